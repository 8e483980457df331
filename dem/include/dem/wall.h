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

/// The wall servo: a proportional-integral controller on the wall's normal force, in the
/// velocity form that carries the wall's speed from step to step (feed-forward).
///
/// The proportional part is the servo of the paper: the force error over the wall's contact
/// stiffness times a gain. Alone it must lag a specimen that pushes the wall at a speed v by a
/// force error of about K v dt / gain (K the wall's stiffness), which grows with the time step,
/// the specimen width and the strain rate. The integral part accumulates the corrections into the
/// wall's own speed, so the steady error behind a steadily moving specimen is zero; its time
/// constant is counted in critical steps because the specimen's response time is (a shorter one
/// makes the loop oscillate with the grains behind the wall, docs/dem.md). The move is capped at
/// max_speed, and the integral is held while the cap binds (anti-windup).
struct ServoParameters {
  double gain = 0.8;              ///< fraction of the stiffness-estimated correction per step
  double max_speed = 0.5;         ///< cap on the wall speed [m/s]
  double blend = 0.5;             ///< weight of this step's move against the previous one
  /// Integral time constant in critical steps (T_i = integral_time x the critical step); 0 turns
  /// the integral action off (the purely proportional servo of the first versions).
  double integral_time = 10.0;

  /// The reasons these settings are refused ("" if none), at a time step of `step_ratio` critical
  /// steps: each value in its range, and the loop stable (servo_spectral_radius < 1; with the
  /// integral action that needs blend > kappa / (1 + kappa), kappa = step_ratio / integral_time).
  std::string validate(double step_ratio = 1.0) const;
};

/// The spectral radius of the servo loop against a spring (the force error's amplification per
/// step, the specimen at rest; < 1: the error decays): the largest |z| over the roots of
///   (z - 1)^2 (z - (1 - b)) + b g z ((1 + kappa) z - 1),   kappa = step_ratio / integral_time,
/// from d_{n+1} = d_n - m_n, I_n = I_{n-1} + kappa g d_n, m_n = b (g d_n + I_n) + (1 - b) m_{n-1}
/// (d the force error over the stiffness, m the wall's move; servo_displacement without the cap);
/// without integral action the quadratic (z - 1)(z - (1 - b)) + b g z. For g in (0, 1] it passes
/// 1 at b = kappa / (1 + kappa) (docs/dem.md, "The servo's stable range").
double servo_spectral_radius(const ServoParameters& servo, double step_ratio);

/// What the servo carries from one step to the next, per wall.
struct ServoState {
  double last_move = 0.0;  ///< the previous step's displacement along the inward normal [m]
  double integral = 0.0;   ///< accumulated correction per step, the learned speed x dt [m]
};

/// Displacement of a stress-controlled wall along its inward normal for this step [m]
/// (positive: towards the bodies), and the servo state updated. `force` is the compressive
/// normal force the bodies put on the wall, `stiffness` the sum of the normal stiffnesses of its
/// contacts (0 when it has none: the wall then advances at the capped speed towards a positive
/// target), `critical_step` the engine's critical time step [s].
double servo_displacement(const ServoParameters& servo, double force, double target_force,
                          double stiffness, double dt, double critical_step, ServoState& state);

}  // namespace dem
