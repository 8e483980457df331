#include "sff_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "csv_table.h"
#include "dem/run_file.h"
#include "sff/analysis.h"
#include "sff/run_snapshot.h"
#include "sff/statistics.h"

namespace sffcal {
namespace {

// Peak and last-snapshot values, and the worst errors, of one analysed run.
void print_summary(const std::vector<sff::SnapshotAnalysis>& all, const std::vector<double>& strains) {
  std::size_t peak = 0;
  double worst_sff = 0.0, worst_eta = 0.0, worst_wall = 0.0;
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (all[k].eta > all[peak].eta) peak = k;
    worst_sff = std::max(worst_sff, all[k].sff_error);
    if (all[k].eta > 0.1) worst_eta = std::max(worst_eta, std::abs(all[k].eta_sff - all[k].eta) / all[k].eta);
    worst_wall = std::max(worst_wall, all[k].wall_stress_error);
  }
  auto line = [&](const char* name, std::size_t k) {
    const sff::SnapshotAnalysis& a = all[k];
    std::printf("  %-8s eps_a %.3f  eta %.3f (walls %.3f)  a_c %.3f  a_n %.3f  m %.3f  eta_sff %.3f  "
                "eta_decoupled %.3f = %.3f (fabric+force) + %.3f (mobilisation)\n",
                name, strains[k], a.eta, a.wall_eta, a.a_c, a.a_n, a.m, a.eta_sff, a.eta_decoupled,
                0.4 * (a.a_c + a.a_n), a.eta_decoupled - 0.4 * (a.a_c + a.a_n));
  };
  std::printf("summary:\n");
  line("peak", peak);
  line("last", all.size() - 1);
  std::printf("  worst |sigma_SFF - sigma|/|sigma| %.4f, worst |eta_SFF - eta|/eta %.4f (eta > 0.1), "
              "worst |sigma(particle form) - sigma(walls)| %.4f p\n",
              worst_sff, worst_eta, worst_wall);
}

}  // namespace

int sff_command(const std::vector<std::string>& run_paths, const SffCommandOptions& options) {
  for (const std::string& path : run_paths) {
    dem::RunFile file = dem::RunFile::open(path, true);
    const dem::RunConfig config = sff::stored_config(file);
    const std::vector<std::string> key = {"snapshot", "step", "axial_strain"};
    std::vector<std::string> columns = key, check_columns = key;
    for (const std::string& c : sff::analysis_columns()) columns.push_back(c);
    for (const std::string& c : sff::check_columns()) check_columns.push_back(c);
    const std::vector<std::string> rose_columns = {"snapshot", "axial_strain", "psi_low_deg",
                                                   "psi_high_deg", "fraction", "normal_force"};
    std::vector<std::vector<double>> rows, check_rows, rose_rows;
    std::vector<sff::SnapshotAnalysis> analysed;
    std::vector<double> strains;
    sff::CheckOptions check_options;
    check_options.resamples = options.resamples;
    check_options.seed = options.seed;
    const auto start = std::chrono::steady_clock::now();
    std::printf("%s: %d snapshots, bootstrap %d resamples (seed %llu)\n%8s %8s %7s %7s %7s %7s %7s "
                "%7s %8s %8s %8s\n",
                path.c_str(), file.num_snapshots(), options.resamples,
                static_cast<unsigned long long>(options.seed), "eps_a", "eta", "eta_sff", "eta_dec",
                "a_c", "a_n", "m", "Z", "sff_err", "R_b/sig", "wall_err");
    for (int k = 0; k < file.num_snapshots(); ++k) {
      const dem::Snapshot s = file.read_snapshot(k);
      const sff::SnapshotInput in = sff::snapshot_input(s, config);
      try {
        const sff::SnapshotAnalysis a = sff::analyse_snapshot(in);
        const sff::SnapshotChecks checks = sff::check_snapshot(in, a, check_options);
        const std::vector<double> head = {static_cast<double>(k), static_cast<double>(s.step), s.axial_strain};
        rows.push_back(head);
        for (double v : sff::analysis_row(a)) rows.back().push_back(v);
        check_rows.push_back(head);
        for (double v : sff::check_row(checks)) check_rows.back().push_back(v);
        const sff::ForceScale scale{in.youngs_modulus, in.solid_volume / in.num_bodies};
        for (const sff::RoseSector& r : sff::rose_diagram(in.contacts, scale))
          rose_rows.push_back({static_cast<double>(k), s.axial_strain, r.psi_low_deg, r.psi_high_deg,
                               r.fraction, r.normal_force});
        analysed.push_back(a);
        strains.push_back(s.axial_strain);
        std::printf("%8.4f %8.3f %7.3f %7.3f %7.3f %7.3f %7.3f %7.3f %8.3f %8.3f %8.3f\n", s.axial_strain,
                    a.eta, a.eta_sff, a.eta_decoupled, a.a_c, a.a_n, a.m, a.coordination,
                    a.sff_error, a.branch_ratio, a.wall_stress_error);
      } catch (const sff::StatisticsError& e) {
        std::printf("%8.4f  skipped: %s\n", s.axial_strain, e.what());
      }
    }
    file.write_table("sff", columns, rows);
    file.write_table("sff_checks", check_columns, check_rows);
    file.write_table("sff_rose", rose_columns, rose_rows);
    // The bootstrap columns of sff_checks depend on these: kept so the tables can be reproduced.
    file.write_note("sff_bootstrap", "resamples " + std::to_string(options.resamples) + ", seed " +
                                         std::to_string(options.seed));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::string stem = path;
    if (!options.csv_folder.empty()) {
      std::filesystem::create_directories(options.csv_folder);
      stem = options.csv_folder + "/" + std::filesystem::path(path).filename().string();
    }
    write_csv(stem + ".sff.csv", columns, rows);
    write_csv(stem + ".sff_checks.csv", check_columns, check_rows);
    write_csv(stem + ".sff_rose.csv", rose_columns, rose_rows);
    if (!analysed.empty()) print_summary(analysed, strains);
    std::printf("tables: %s:/analysis/{sff,sff_checks,sff_rose} and %s.{sff,sff_checks,sff_rose}.csv "
                "(%.2f s)\n",
                path.c_str(), stem.c_str(), seconds);
  }
  return 0;
}

}  // namespace sffcal
