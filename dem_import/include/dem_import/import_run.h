// `sffcal import`: another code's run (its dumps, series table and import.toml) as a run file of
// the current schema, written by runfile/ as every run file is (docs/import.md).
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include "dem_import/description.h"

namespace dem_import {

struct ImportReport {
  int snapshots = 0;
  std::size_t series_rows = 0;
  std::size_t bodies = 0, spheres = 0;
  std::size_t contacts = 0;    ///< in the last snapshot
  double solid_volume = 0.0;   ///< of the first snapshot's bodies [m^3]
  double initial_void_ratio = 0.0;
};

/// The run-file series that an import writes, in order; then the source's other columns as
/// `source_<name>`.
const std::vector<std::string>& imported_series_names();

/// Reads the description's files and writes the run file at `output` (which the caller has
/// checked; made in one go). `progress` is called with a line after each snapshot. Throws
/// std::runtime_error naming the file, the timestep and the row at fault: the dumps' frames not
/// pairing up by timestep, a snapshot's timestep not a step of the series, a missing column, a
/// cell that changes its kind, a body count that changes between frames.
/// `program_version` is sffcal's, stored as every run file's.
ImportReport import_run(const ImportDescription& description, const std::string& output,
                        const std::string& program_version,
                        const std::function<void(const std::string&)>& progress);

}  // namespace dem_import
