#include "dem/contact_law.h"

#include <sstream>

namespace dem {

std::string ContactParameters::validate() const {
  std::ostringstream error;
  if (!(youngs_modulus > 0.0 && std::isfinite(youngs_modulus)))
    error << "youngs_modulus must be positive and finite (got " << youngs_modulus << " Pa); ";
  if (!(stiffness_ratio > 0.0 && stiffness_ratio <= 1.0))
    error << "stiffness_ratio k_t/k_n must lie in (0, 1] (got " << stiffness_ratio << "); ";
  if (!(friction >= 0.0 && friction <= 10.0))
    error << "friction must lie in [0, 10] (got " << friction << "); ";
  if (!(wall_friction >= 0.0 && wall_friction <= 10.0))
    error << "wall_friction must lie in [0, 10] (got " << wall_friction << "); ";
  if (!(normal_damping_ratio >= 0.0 && normal_damping_ratio <= 1.0))
    error << "normal_damping_ratio must lie in [0, 1] (got " << normal_damping_ratio << "); ";
  return error.str();
}

}  // namespace dem
