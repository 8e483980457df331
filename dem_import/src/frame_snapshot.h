// Internal: one snapshot of the run file from an atoms frame and a contacts frame of the same
// timestep (docs/import.md, "What each file must hold").
#pragma once

#include <array>
#include <string>

#include "dem_import/description.h"
#include "dem_import/dump_file.h"
#include "runfile/run_file.h"

namespace dem_import::internal {

/// The snapshot's bodies, spheres, contacts and periodic cell; step, time and axial strain are the
/// caller's. The cell's lengths are `cell_length`, the series row's (full precision: LIGGGHTS
/// writes the dumps' box bounds with 6 digits), which the atoms frame's bounds must agree with to
/// their precision. `atoms_name` and `contacts_name` name the dumps in messages. Throws
/// std::runtime_error naming the dump, the frame's timestep and the row at fault.
runfile::Snapshot snapshot_from_frames(const DumpFrame& atoms, const DumpFrame& contacts,
                                       const std::array<double, 3>& cell_length,
                                       const ImportDescription& description,
                                       const std::string& atoms_name,
                                       const std::string& contacts_name);

}  // namespace dem_import::internal
