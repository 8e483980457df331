// Isotropic compaction of a specimen by six servo-controlled walls.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "dem/simulation.h"

namespace dem {

struct CompactionOptions {
  double target_stress = 100e3;        ///< p'0 on every wall [Pa]
  double stress_tolerance = 0.01;      ///< accepted |sigma_wall - p'0| / p'0 on every wall
  double max_unbalanced_force = 1e-3;  ///< accepted unbalanced-force ratio
  std::int64_t max_steps = 2'000'000;
  int check_every = 200;               ///< steps between checks of the acceptance criteria
};

struct CompactionResult;
/// Called after every check with the state so far (for progress displays).
using CompactionProgress = std::function<void(const CompactionResult&)>;

struct CompactionResult {
  bool converged = false;
  std::int64_t steps = 0;
  double worst_stress_error = 0.0;     ///< max over walls of |sigma - p'0| / p'0
  double unbalanced_force_ratio = 0.0;
  std::string summary() const;
};

/// Puts the six walls of the box under stress control at `target_stress` and steps until the
/// state is accepted (every wall within tolerance and the unbalanced-force ratio below its
/// threshold, at two consecutive checks) or max_steps pass.
CompactionResult compact_isotropically(Simulation& simulation, const CompactionOptions& options,
                                       const CompactionProgress& progress = nullptr);

}  // namespace dem
