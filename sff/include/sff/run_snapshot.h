// The bridge from a DEM run file's snapshot to the SFF input: box volume and wall stresses from
// the six walls (or the volume of an imported run's periodic cell, without wall stresses), solid volume from the clumps' spheres, centroids by body id, E and mu from the
// run's physics. Kept out of the pure `sff` library (this one links the run-file reader).
#pragma once

#include "runfile/run_file.h"
#include "sff/analysis.h"

namespace sff {

/// The SFF input of a snapshot; its contact span points into `snapshot`, which must outlive it.
/// Throws std::runtime_error when the snapshot has neither a box of six walls nor a periodic cell,
/// or a body id out of range.
SnapshotInput snapshot_input(const runfile::Snapshot& snapshot, const runfile::RunPhysics& physics);

}  // namespace sff
