#include "dem/wall.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace dem {

std::string ServoParameters::validate() const {
  std::ostringstream error;
  if (!(gain > 0.0 && gain <= 1.0)) error << "servo gain must lie in (0, 1] (got " << gain << "); ";
  if (!(max_speed > 0.0 && std::isfinite(max_speed)))
    error << "servo max_speed must be positive (got " << max_speed << " m/s); ";
  if (!(blend > 0.0 && blend <= 1.0))
    error << "servo blend must lie in (0, 1] (got " << blend << "); ";
  return error.str();
}

double servo_displacement(const ServoParameters& servo, double force, double target_force,
                          double stiffness, double previous_displacement, double dt) {
  const double cap = servo.max_speed * dt;
  // With no contact the wall has nothing to push against: advance at the capped speed.
  double move = stiffness > 0.0 ? servo.gain * (target_force - force) / stiffness
                                 : (target_force > 0.0 ? cap : 0.0);
  move = std::clamp(move, -cap, cap);
  return servo.blend * move + (1.0 - servo.blend) * previous_displacement;
}

}  // namespace dem
