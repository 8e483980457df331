#include "sff_command.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "dem/run_config.h"
#include "dem/run_file.h"
#include "sff/analysis.h"
#include "sff/statistics.h"

namespace sffcal {
namespace {

double box_volume(const std::vector<dem::WallRecord>& walls) {
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  int found = 0;
  for (const dem::WallRecord& w : walls) {
    (w.upper ? hi : lo)[w.axis] = w.position;
    ++found;
  }
  if (found != 6) throw std::runtime_error("the snapshot does not hold a box of six walls");
  return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
}

// Solid volume from the spheres: a body's two spheres give its centre distance.
double solid_volume(const dem::Snapshot& s) {
  std::map<std::int64_t, std::vector<std::size_t>> spheres_of;
  for (std::size_t k = 0; k < s.spheres.size(); ++k) spheres_of[s.sphere_body[k]].push_back(k);
  double total = 0.0;
  for (const auto& [body, list] : spheres_of) {
    const auto& a = s.spheres[list.front()];
    double distance = 0.0;
    if (list.size() == 2) {
      const auto& b = s.spheres[list.back()];
      distance = std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                           (a[2] - b[2]) * (a[2] - b[2]));
    }
    total += sff::clump_volume(a[3], distance);
  }
  return total;
}

}  // namespace

int sff_command(const std::vector<std::string>& run_paths, const std::string& csv_folder) {
  for (const std::string& path : run_paths) {
    dem::RunFile file = dem::RunFile::open(path, true);
    const dem::RunConfig config =
        dem::parse_run_config(file.metadata().config_text, path + " (stored config)");
    std::vector<std::string> columns = {"snapshot", "step", "axial_strain"};
    for (const std::string& c : sff::analysis_columns()) columns.push_back(c);
    std::vector<std::vector<double>> rows;
    const auto start = std::chrono::steady_clock::now();
    std::printf("%s: %d snapshots\n%8s %8s %7s %7s %7s %7s %7s %8s %8s %8s\n", path.c_str(),
                file.num_snapshots(), "eps_a", "eta", "eta_sff", "eta_dec", "a_c", "a_n", "m",
                "Z", "sff_err", "R_b/sig");
    for (int k = 0; k < file.num_snapshots(); ++k) {
      const dem::Snapshot s = file.read_snapshot(k);
      sff::SnapshotInput in;
      in.contacts = sff::ContactSpan(s.contacts);
      in.volume = box_volume(s.walls);
      in.solid_volume = solid_volume(s);
      in.num_bodies = static_cast<int>(s.particles.size());
      in.youngs_modulus = config.contact.youngs_modulus;
      in.friction = config.contact.friction;
      try {
        const sff::SnapshotAnalysis a = sff::analyse_snapshot(in);
        std::vector<double> row = {static_cast<double>(k), static_cast<double>(s.step), s.axial_strain};
        for (double v : sff::analysis_row(a)) row.push_back(v);
        rows.push_back(row);
        std::printf("%8.4f %8.3f %7.3f %7.3f %7.3f %7.3f %7.3f %8.3f %8.3f %8.3f\n", s.axial_strain,
                    a.eta, a.eta_sff, a.eta_decoupled, a.a_c, a.a_n, a.m, a.coordination,
                    a.sff_error, a.branch_ratio);
      } catch (const sff::StatisticsError& e) {
        std::printf("%8.4f  skipped: %s\n", s.axial_strain, e.what());
      }
    }
    file.write_table("sff", columns, rows);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::string csv = path + ".sff.csv";
    if (!csv_folder.empty()) {
      std::filesystem::create_directories(csv_folder);
      csv = csv_folder + "/" + std::filesystem::path(path).filename().string() + ".sff.csv";
    }
    std::ofstream out(csv);
    if (!out) throw std::runtime_error("cannot write " + csv);
    out.precision(10);
    for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
    out << "\n";
    for (const auto& row : rows) {
      for (std::size_t c = 0; c < row.size(); ++c) out << (c ? "," : "") << row[c];
      out << "\n";
    }
    std::printf("table: %s:/analysis/sff and %s (%.2f s)\n", path.c_str(), csv.c_str(), seconds);
  }
  return 0;
}

}  // namespace sffcal
