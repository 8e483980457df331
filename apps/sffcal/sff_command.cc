#include "sff_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "csv_table.h"
#include "runfile/run_file.h"
#include "sff/run_analysis.h"
#include "sff/sff_equation.h"

namespace sffcal {
namespace {

// Peak and last-snapshot values, and the worst errors, of one analysed run (sheared at `friction`).
// The peak is the largest |eta| (an extension run's stress ratio is negative).
void print_summary(const std::vector<sff::SnapshotAnalysis>& all, const std::vector<double>& strains,
                   double friction) {
  std::size_t peak = 0;
  double worst_sff = 0.0, worst_eta = 0.0, worst_wall = 0.0;
  for (std::size_t k = 0; k < all.size(); ++k) {
    const double magnitude = std::abs(all[k].eta);
    if (magnitude > std::abs(all[peak].eta)) peak = k;
    worst_sff = std::max(worst_sff, all[k].sff_error);
    if (magnitude > 0.1)
      worst_eta = std::max(worst_eta, std::abs(all[k].eta_sff - all[k].eta) / magnitude);
    worst_wall = std::max(worst_wall, all[k].wall_stress_error);
  }
  // An imported periodic run has no walls: their columns hold 0 ("unknown", docs/sff.md).
  const bool walls = std::any_of(all.begin(), all.end(),
                                 [](const sff::SnapshotAnalysis& a) { return a.wall_eta != 0.0; });
  auto line = [&](const char* name, std::size_t k) {
    const sff::SnapshotAnalysis& a = all[k];
    const sff::DecoupledTerms terms = sff::decoupled_terms(a.a_c, a.a_n, friction, a.m);
    char wall_eta[32] = " (no walls)";
    if (walls) std::snprintf(wall_eta, sizeof wall_eta, " (walls %.3f)", a.wall_eta);
    std::printf("  %-8s eps_a %.3f  eta %.3f%s  a_c %.3f  a_n %.3f  m %.3f  eta_sff %.3f  "
                "eta_decoupled %.3f = %.3f (fabric+force) + %.3f (mobilisation)\n"
                "  %-8s Guo & Zhao: a_n %.3f  a_l %.3f  a_t %.3f  eta_gz %.3f\n",
                name, strains[k], a.eta, wall_eta, a.a_c, a.a_n, a.m, a.eta_sff, a.eta_decoupled,
                terms.fabric + terms.normal_force, terms.mobilisation, "", a.a_n_gz,
                a.a_l, a.a_t_gz, a.eta_gz);
  };
  std::printf("summary:\n");
  line("peak", peak);
  line("last", all.size() - 1);
  std::printf("  worst |sigma_SFF - sigma|/|sigma| %.4f, worst |eta_SFF - eta|/|eta| %.4f (|eta| > 0.1)",
              worst_sff, worst_eta);
  if (walls) std::printf(", worst |sigma(particle form) - sigma(walls)| %.4f p", worst_wall);
  std::printf("\n");
}

}  // namespace

int sff_command(const std::vector<std::string>& run_paths, const SffCommandOptions& options) {
  sff::CheckOptions check_options;
  check_options.resamples = options.resamples;
  check_options.seed = options.seed;
  for (const std::string& path : run_paths) {
    runfile::RunFile file = runfile::RunFile::open(path, true);
    const auto start = std::chrono::steady_clock::now();
    std::printf("%s: %d snapshots, bootstrap %d resamples (seed %llu)\n%8s %8s %7s %7s %7s %7s %7s "
                "%7s %8s %8s %8s\n",
                path.c_str(), file.num_snapshots(), options.resamples,
                static_cast<unsigned long long>(options.seed), "eps_a", "eta", "eta_sff", "eta_dec",
                "a_c", "a_n", "m", "Z", "sff_err", "R_b/sig", "wall_err");
    const sff::RunTables tables = sff::analyse_run(
        file, check_options,
        [](const runfile::Snapshot& s, const sff::SnapshotAnalysis* a, const std::string& skipped) {
          if (!a) {
            std::printf("%8.4f  skipped: %s\n", s.axial_strain, skipped.c_str());
            return;
          }
          std::printf("%8.4f %8.3f %7.3f %7.3f %7.3f %7.3f %7.3f %7.3f %8.3f %8.3f %8.3f\n",
                      s.axial_strain, a->eta, a->eta_sff, a->eta_decoupled, a->a_c, a->a_n, a->m,
                      a->coordination, a->sff_error, a->branch_ratio, a->wall_stress_error);
          if (a->binned_weights)
            std::printf("         warning: 1 + lambda_min(A) = %.3f <= %.1f, too anisotropic for "
                        "second-order weights: binned direction weights used\n",
                        a->min_density, sff::DirectionWeight::kMinSecondOrderDensity);
        });
    sff::store_run_tables(file, tables, check_options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::string stem = path;
    if (!options.csv_folder.empty()) {
      std::filesystem::create_directories(options.csv_folder);
      stem = options.csv_folder + "/" + std::filesystem::path(path).filename().string();
    }
    write_csv(stem + ".sff.csv", tables.sff_columns, tables.sff_rows);
    write_csv(stem + ".sff_checks.csv", tables.check_columns, tables.check_rows);
    write_csv(stem + ".sff_rose.csv", tables.rose_columns, tables.rose_rows);
    if (!tables.analysed.empty()) print_summary(tables.analysed, tables.axial_strain, file.metadata().physics.friction);
    std::printf("tables: %s:/analysis/{sff,sff_checks,sff_rose} and %s.{sff,sff_checks,sff_rose}.csv "
                "(%.2f s)\n",
                path.c_str(), stem.c_str(), seconds);
  }
  return 0;
}

}  // namespace sffcal
