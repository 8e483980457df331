// Internal: one snapshot of the run file from an atoms frame and a contacts frame of the same
// timestep (docs/import.md, "What each file must hold").
#pragma once

#include <array>
#include <string>

#include "dem_import/description.h"
#include "dem_import/dump_file.h"
#include "runfile/run_file.h"

namespace dem_import::internal {

/// Where the specimen's boundary is at a frame's step, from the series row of that step (full
/// precision: LIGGGHTS writes the dumps' box bounds with 6 digits).
struct FrameBox {
  std::array<double, 3> length{};  ///< the cell's lengths, or the gaps between opposite walls [m]
  std::array<double, 3> lower{};   ///< walls only: the lower walls' positions [m]
};

/// The walls' names in the run file's order (index 2 axis + upper), as the atoms dump's roles
/// name them: <wall>_fx, <wall>_fy, <wall>_fz, the force of the wall on the sphere [N].
inline constexpr const char* kWallNames[6] = {"xlo", "xhi", "ylo", "yhi", "zlo", "zhi"};

/// Throws std::runtime_error naming `where` unless the atoms frame's box is of the kind that the
/// description's [test] boundary says: periodic along all three axes, or along none (walls); and
/// orthogonal.
void check_box_kind(const DumpFrame& atoms, const ImportDescription& description,
                    const std::string& where);

/// The snapshot's bodies, spheres and contacts, and its periodic cell or its six walls (as the
/// description's [test] boundary says; the dump's box must say the same); step, time and axial
/// strain are the caller's. A periodic cell's lengths are `box.length`, which the atoms frame's
/// bounds must agree with to their precision. `atoms_name` and `contacts_name` name the dumps in
/// messages. Throws std::runtime_error naming the dump, the frame's timestep and the row at fault.
runfile::Snapshot snapshot_from_frames(const DumpFrame& atoms, const DumpFrame& contacts,
                                       const FrameBox& box, const ImportDescription& description,
                                       const std::string& atoms_name,
                                       const std::string& contacts_name);

}  // namespace dem_import::internal
