// What the engine writes into a run file through runfile's API, and reads back: snapshots of the
// grain-scale state and checkpoints of the full engine state (their layout is defined here).
#pragma once

#include "dem/simulation.h"
#include "runfile/run_file.h"

namespace dem {

using runfile::CheckpointExtras;
using runfile::RunFile;
using runfile::Snapshot;

/// Collects the snapshot of the simulation's current state.
Snapshot take_snapshot(const Simulation& simulation, double axial_strain);

/// Replaces the file's checkpoint with this state; series and snapshots written so far are kept.
void write_checkpoint(RunFile& file, const SimulationState& state, const CheckpointExtras& extras);

/// Reads and validates the file's checkpoint (errors name the file and the array). When the file
/// is open for writing, the series rows and snapshots written after the checkpoint are dropped,
/// so the resumed run continues the file exactly where the checkpoint left it.
SimulationState read_checkpoint(RunFile& file, CheckpointExtras* extras);

}  // namespace dem
