#include "snapshot_check.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace runfile {
namespace {

[[noreturn]] void refuse(const std::string& what) {
  throw std::runtime_error("the snapshot is not consistent: " + what);
}

template <typename Values>
void require_finite(const Values& values, const std::string& what) {
  for (double v : values)
    if (!std::isfinite(v)) refuse(what + " holds a value that is not finite (" + std::to_string(v) + ")");
}

std::string record(const char* kind, std::size_t index) {
  return std::string(kind) + " " + std::to_string(index);
}

}  // namespace

void check_snapshot(const Snapshot& s, std::size_t sphere_values, std::size_t cell_values) {
  if (cell_values != 0 || !s.periodic_cell.empty()) {
    if (cell_values != 6 && !(cell_values == 0 && s.periodic_cell.size() == 2))
      refuse("'periodic_cell' has " + std::to_string(cell_values) +
             " values, not 6 (the lower and upper corners)");
    for (const auto& corner : s.periodic_cell) require_finite(corner, "'periodic_cell'");
    for (int a = 0; a < 3; ++a)
      if (!(s.periodic_cell[1][a] > s.periodic_cell[0][a]))
        refuse("'periodic_cell' has an upper corner not above its lower one");
    if (!s.walls.empty()) refuse("a periodic snapshot also has walls");
  }
  if (sphere_values % 4 != 0)
    refuse("'spheres' has " + std::to_string(sphere_values) + " values, not 4 per sphere");
  if (s.sphere_body.size() != s.spheres.size())
    refuse("'sphere_body' has " + std::to_string(s.sphere_body.size()) + " entries for " +
           std::to_string(s.spheres.size()) + " spheres");
  if (!std::isfinite(s.time) || !std::isfinite(s.axial_strain))
    refuse("its time or axial strain is not finite");

  const std::size_t n = s.particles.size();
  std::vector<bool> held(n, false);
  for (std::size_t k = 0; k < n; ++k) {
    const ParticleRecord& p = s.particles[k];
    if (p.id < 0 || static_cast<std::size_t>(p.id) >= n)
      refuse(record("particle", k) + " has id " + std::to_string(p.id) + " outside 0.." +
             std::to_string(n - 1));
    if (held[static_cast<std::size_t>(p.id)])
      refuse(record("particle", k) + " repeats body id " + std::to_string(p.id));
    held[static_cast<std::size_t>(p.id)] = true;
    if (p.num_spheres != 1 && p.num_spheres != 2)
      refuse(record("particle", k) + " has " + std::to_string(p.num_spheres) + " spheres");
    if (!(p.sphere_diameter > 0.0) || !std::isfinite(p.sphere_diameter))
      refuse(record("particle", k) + " has a sphere diameter that is not positive and finite");
    const std::string name = record("particle", k);
    require_finite(p.position, name);
    require_finite(p.orientation, name);
    require_finite(p.velocity, name);
    require_finite(p.angular_velocity, name);
  }
  auto holds = [&](std::int64_t id) { return id >= 0 && static_cast<std::size_t>(id) < n; };

  for (std::size_t k = 0; k < s.spheres.size(); ++k) {
    require_finite(s.spheres[k], record("sphere", k));
    if (!(s.spheres[k][3] > 0.0)) refuse(record("sphere", k) + " has a radius that is not positive");
    if (!holds(s.sphere_body[k]))
      refuse(record("sphere", k) + " refers to body " + std::to_string(s.sphere_body[k]) +
             ", which the snapshot does not hold");
  }
  for (std::size_t k = 0; k < s.walls.size(); ++k) {
    const WallRecord& w = s.walls[k];
    if (w.axis < 0 || w.axis > 2) refuse(record("wall", k) + " has axis " + std::to_string(w.axis));
    require_finite(std::vector<double>{w.position, w.velocity, w.normal_force, w.target_stress},
                   record("wall", k));
  }
  for (std::size_t k = 0; k < s.contacts.size(); ++k) {
    const ContactRecord& c = s.contacts[k];
    const bool wall_contact = c.body_a < 0;
    if (!holds(c.body_b) || (!wall_contact && !holds(c.body_a)))
      refuse(record("contact", k) + " refers to body " +
             std::to_string(holds(c.body_b) ? c.body_a : c.body_b) +
             ", which the snapshot does not hold");
    if (wall_contact && (c.wall < 0 || static_cast<std::size_t>(c.wall) >= s.walls.size()))
      refuse(record("contact", k) + " refers to wall " + std::to_string(c.wall) + " of " +
             std::to_string(s.walls.size()));
    const std::string name = record("contact", k);
    require_finite(c.point, name);
    require_finite(c.normal, name);
    require_finite(c.branch, name);
    require_finite(c.tangential_force, name);
    require_finite(std::vector<double>{c.overlap, c.normal_force}, name);
  }
}

}  // namespace runfile
