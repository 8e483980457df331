#include "runfile/stored_physics.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>

namespace runfile {

RunPhysics physics_from_config_text(const std::string& text, const std::string& source) {
  toml::table table;
  try {
    table = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << source << ": TOML syntax error at line " << e.source().begin.line << ", column "
        << e.source().begin.column << ": " << e.description();
    throw std::runtime_error(msg.str());
  }
  auto value = [&](const char* section, const char* key, double schema1_default) {
    const toml::node* node = table[section][key].node();
    if (!node) return schema1_default;
    const std::optional<double> v = node->value<double>();  // integers convert too
    if (!v || !std::isfinite(*v))
      throw std::runtime_error(source + ": " + section + "." + key + " is not a finite number");
    return *v;
  };
  // The defaults of sffcal 0.1 (docs/config.md of that version).
  RunPhysics physics;
  physics.youngs_modulus = value("contact", "youngs_modulus", 150e6);
  physics.stiffness_ratio = value("contact", "stiffness_ratio", 0.5);
  physics.friction = value("contact", "friction", 0.5773502691896257);  // tan 30 deg
  physics.wall_friction = value("contact", "wall_friction", 0.0);
  physics.grain_density = value("grains", "density", 2650.0);
  physics.density_scaling = value("engine", "density_scaling", 1.0);
  return physics;
}

}  // namespace runfile
