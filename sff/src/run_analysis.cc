#include "sff/run_analysis.h"

#include "sff/directional.h"
#include "sff/run_snapshot.h"
#include "sff/statistics.h"

namespace sff {
namespace {

// The columns of the rose table, one row per sector of a snapshot, each declared once with its
// value (as the SFF and check tables' in analysis.cc).
template <typename Column>
void rose_table_columns(int snapshot, double axial_strain, const RoseSector& r, Column&& column) {
  column("snapshot", static_cast<double>(snapshot));
  column("axial_strain", axial_strain);
  column("psi_low_deg", r.psi_low_deg);
  column("psi_high_deg", r.psi_high_deg);
  column("fraction", r.fraction);
  column("normal_force", r.normal_force);
}

}  // namespace

RunTables analyse_run(const runfile::RunFile& file, const CheckOptions& options,
                      const SnapshotReport& report) {
  const runfile::RunPhysics physics = file.metadata().physics;
  RunTables t;
  const std::vector<std::string> key = {"snapshot", "step", "axial_strain"};
  t.sff_columns = t.check_columns = key;
  t.sff_columns.insert(t.sff_columns.end(), analysis_columns().begin(), analysis_columns().end());
  t.check_columns.insert(t.check_columns.end(), check_columns().begin(), check_columns().end());
  rose_table_columns(0, 0.0, RoseSector(),
                     [&](const char* name, double) { t.rose_columns.push_back(name); });
  const int num_snapshots = file.num_snapshots();
  for (int k = 0; k < num_snapshots; ++k) {
    const runfile::Snapshot s = file.read_snapshot(k);
    const SnapshotInput in = snapshot_input(s, physics);
    SnapshotAnalysis a;
    SnapshotChecks checks;
    std::vector<RoseSector> rose;
    try {
      a = analyse_snapshot(in);
      checks = check_snapshot(in, a, options);
      rose = rose_diagram(in.contacts, ForceScale{in.youngs_modulus, in.solid_volume / in.num_bodies});
    } catch (const StatisticsError& e) {
      if (report) report(s, nullptr, e.what());
      continue;
    }
    const std::vector<double> head = {static_cast<double>(k), static_cast<double>(s.step),
                                      s.axial_strain};
    t.sff_rows.push_back(head);
    for (double v : analysis_row(a)) t.sff_rows.back().push_back(v);
    t.check_rows.push_back(head);
    for (double v : check_row(checks)) t.check_rows.back().push_back(v);
    for (const RoseSector& r : rose) {
      t.rose_rows.emplace_back();
      rose_table_columns(k, s.axial_strain, r,
                         [&](const char*, double value) { t.rose_rows.back().push_back(value); });
    }
    t.analysed.push_back(a);
    t.axial_strain.push_back(s.axial_strain);
    if (report) report(s, &t.analysed.back(), "");
  }
  return t;
}

void store_run_tables(runfile::RunFile& file, const RunTables& t, const CheckOptions& options) {
  file.write_table("sff", t.sff_columns, t.sff_rows);
  file.write_table("sff_checks", t.check_columns, t.check_rows);
  file.write_table("sff_rose", t.rose_columns, t.rose_rows);
  // The bootstrap columns of sff_checks depend on these: kept so the tables can be reproduced.
  file.write_note("sff_bootstrap", "resamples " + std::to_string(options.resamples) + ", seed " +
                                       std::to_string(options.seed));
}

}  // namespace sff
