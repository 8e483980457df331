// The SFF analysis of a whole run file, as `sffcal sff` stores it: every snapshot analysed with
// the run's physics, the §6 checks and the rose diagram, as three tables.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "runfile/run_file.h"
#include "sff/analysis.h"

namespace sff {

/// One row per analysed snapshot (/analysis/sff and /analysis/sff_checks, each led by snapshot,
/// step and axial strain) and one row per rose sector (/analysis/sff_rose).
struct RunTables {
  std::vector<std::string> sff_columns, check_columns, rose_columns;
  std::vector<std::vector<double>> sff_rows, check_rows, rose_rows;
  std::vector<SnapshotAnalysis> analysed;  ///< one per row of sff_rows
  std::vector<double> axial_strain;        ///< of each analysed snapshot
};

/// Called once per snapshot with its analysis, or with null and why it was skipped.
using SnapshotReport =
    std::function<void(const runfile::Snapshot&, const SnapshotAnalysis*, const std::string& skipped)>;

/// Analyses every snapshot of `file`. A snapshot where a statistic is undefined (StatisticsError:
/// no contacts, no force) is skipped and reported, not stored.
RunTables analyse_run(const runfile::RunFile& file, const CheckOptions& options,
                      const SnapshotReport& report = {});

/// Stores the tables in /analysis/{sff,sff_checks,sff_rose}, replacing earlier ones, with the
/// bootstrap settings they depend on (the note "sff_bootstrap").
void store_run_tables(runfile::RunFile& file, const RunTables& tables, const CheckOptions& options);

}  // namespace sff
