// Gravity deposition at a loading angle: the first stage of an inherently anisotropic specimen.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "dem/specimen.h"

namespace dem {

/// Bodies settled under gravity and cut to a box, ready for isotropic compaction.
struct Deposit {
  Particles bodies;                ///< the kept bodies, tilted so that the bedding normal is at α
  Eigen::Vector3d lo, hi;          ///< the cut box [m]
  int deposited = 0;               ///< bodies settled before the cut
  std::int64_t steps = 0;          ///< time steps of the settling
};

/// Settles a wide, shallow bed of bodies under gravity along -Z between fixed walls, then keeps
/// the bodies inside a cube cut from its interior (away from the walls and the free surface,
/// whose ordering would otherwise dominate the fabric), rotated by the loading angle about X so
/// that the bedding normal goes from Z to (0, -sin α, cos α). The cube is the smallest that holds
/// config.num_bodies; the bed is sized for it from the grain volume.
Deposit deposit_at_loading_angle(const RunConfig& config, const SimulationOptions& options,
                                 const ContactParameters& law, const ProgressLog& log);

}  // namespace dem
