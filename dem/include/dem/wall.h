// Planar, axis-aligned rigid walls, and the servo that holds a wall at a target stress.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>

namespace dem {

/// How a wall moves: at a prescribed velocity, or servo-controlled to a target normal stress.
enum class WallMode { kVelocity, kStress };

/// A plane normal to `axis` (0 = x, 1 = y, 2 = z). A lower wall (`upper == false`) pushes the
/// bodies towards +axis, an upper wall towards -axis. Walls extend without bound in the plane.
struct Wall {
  int axis = 0;
  bool upper = false;
  double position = 0.0;       ///< coordinate of the plane along `axis` [m]
  double velocity = 0.0;       ///< along +axis [m/s], used in kVelocity mode
  WallMode mode = WallMode::kVelocity;
  double target_stress = 0.0;  ///< compressive normal stress to hold in kStress mode [Pa]

  /// Unit normal pointing from the wall into the box.
  Eigen::Vector3d inward_normal() const {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    n[axis] = upper ? -1.0 : 1.0;
    return n;
  }
};

/// The servo of the paper: estimate the wall's stiffness from its contacts, move it by the
/// force error over that stiffness times a gain, cap the speed, and blend with the last move.
struct ServoParameters {
  double gain = 0.5;              ///< fraction of the stiffness-estimated correction per step
  double max_speed = 0.5;         ///< cap on the wall speed [m/s]
  double blend = 0.5;             ///< weight of this step's move against the previous one

  std::string validate() const;
};

/// Displacement of a stress-controlled wall along its inward normal for this step [m]
/// (positive: towards the bodies). `force` is the compressive normal force the bodies put on the
/// wall, `stiffness` the sum of the normal stiffnesses of its contacts (0 when it has none).
double servo_displacement(const ServoParameters& servo, double force, double target_force,
                          double stiffness, double previous_displacement, double dt);

}  // namespace dem
