#include "dem/wall.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace dem {

double servo_spectral_radius(const ServoParameters& servo, double step_ratio) {
  const double b = servo.blend, g = servo.gain;
  if (servo.integral_time == 0.0) {  // z^2 + (b g - 2 + b) z + (1 - b)
    Eigen::Matrix2d companion;
    companion << -(b * g - 2.0 + b), -(1.0 - b), 1.0, 0.0;
    return companion.eigenvalues().cwiseAbs().maxCoeff();
  }
  const double kappa = step_ratio / servo.integral_time;
  // (z - 1)^2 (z - (1 - b)) + b g z ((1 + kappa) z - 1) = z^3 + c2 z^2 + c1 z + c0
  const double c2 = -(3.0 - b) + b * g * (1.0 + kappa);
  const double c1 = 1.0 + 2.0 * (1.0 - b) - b * g;
  const double c0 = -(1.0 - b);
  Eigen::Matrix3d companion;
  companion << -c2, -c1, -c0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0;
  return companion.eigenvalues().cwiseAbs().maxCoeff();
}

std::string ServoParameters::validate(double step_ratio) const {
  std::ostringstream error;
  if (!(gain > 0.0 && gain <= 1.0)) error << "servo gain must lie in (0, 1] (got " << gain << "); ";
  if (!(max_speed > 0.0 && std::isfinite(max_speed)))
    error << "servo max_speed must be positive (got " << max_speed << " m/s); ";
  if (!(blend > 0.0 && blend <= 1.0))
    error << "servo blend must lie in (0, 1] (got " << blend << "); ";
  if (!(integral_time == 0.0 || (integral_time >= 1.0 && std::isfinite(integral_time))))
    error << "servo integral_time must be 0 (off) or >= 1 critical step (got " << integral_time
          << "); ";
  if (!error.str().empty()) return error.str();
  const double radius = servo_spectral_radius(*this, step_ratio);
  if (!(radius < 1.0 - 1e-12)) {
    error << "servo gain " << gain << ", blend " << blend << " and integral_time " << integral_time
          << " make the wall's loop unstable at a time step of " << step_ratio
          << " critical steps (it amplifies a force error by " << radius << " per step)";
    if (integral_time > 0.0) {
      const double kappa = step_ratio / integral_time;
      error << ": the blend must exceed " << kappa / (1.0 + kappa)
            << "; raise servo.blend or servo.integral_time";
    }
    error << "; ";
  }
  return error.str();
}

double servo_displacement(const ServoParameters& servo, double force, double target_force,
                          double stiffness, double dt, double critical_step, ServoState& state) {
  const double cap = servo.max_speed * dt;
  if (!(stiffness > 0.0)) {
    // No contact: nothing to push against, and nothing learned about the specimen's speed.
    state.integral = 0.0;
    state.last_move = target_force > 0.0 ? cap : 0.0;
    return state.last_move;
  }
  const double correction = servo.gain * (target_force - force) / stiffness;
  // Integral time 0 is the proportional servo: no integral, not even one carried in a state.
  double integral = 0.0;
  if (servo.integral_time > 0.0)
    integral = state.integral + dt / (servo.integral_time * critical_step) * correction;
  integral = std::clamp(integral, -cap, cap);
  double move = servo.blend * (correction + integral) + (1.0 - servo.blend) * state.last_move;
  if (std::abs(move) > cap) {
    move = std::clamp(move, -cap, cap);
    // Anti-windup: while the cap binds, do not accumulate further in its direction.
    if (servo.integral_time > 0.0 && (integral - state.integral) * move > 0.0)
      integral = std::clamp(state.integral, -cap, cap);
  }
  state.integral = integral;
  state.last_move = move;
  return move;
}

}  // namespace dem
