// ParaView output: one VTU file per snapshot (spheres as points with their radius, body id and
// velocity; contacts as lines between body centroids with their normal force) and a PVD
// collection that orders them in time.
#pragma once

#include <string>
#include <vector>

#include "dem/run_file_io.h"

namespace dem {

/// Writes `<stem>_spheres.vtu` and `<stem>_contacts.vtu` for one snapshot.
void write_snapshot_vtu(const Snapshot& snapshot, const std::string& stem);

/// Writes every snapshot of `run` into `folder` (created if needed) with `spheres.pvd` and
/// `contacts.pvd` collections; returns the number of snapshots written.
int export_run_to_vtk(const RunFile& run, const std::string& folder);

}  // namespace dem
