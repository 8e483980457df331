#include "dem/particles.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "dem/rigid_body.h"

namespace dem {

int Particles::add_body(const BodyShape& shape, double density, const Eigen::Vector3d& pos,
                        const Eigen::Quaterniond& q) {
  const MassProperties props =
      two_sphere_union_properties(shape.sphere_radius, shape.centre_distance, density);
  const int body = num_bodies();
  id.push_back(body);
  position.push_back(pos);
  velocity.push_back(Eigen::Vector3d::Zero());
  orientation.push_back(q.normalized());
  angular_momentum.push_back(Eigen::Vector3d::Zero());
  angular_velocity.push_back(Eigen::Vector3d::Zero());
  force.push_back(Eigen::Vector3d::Zero());
  torque.push_back(Eigen::Vector3d::Zero());
  mass.push_back(props.mass);
  inertia_axial.push_back(props.inertia_axial);
  inertia_transverse.push_back(props.inertia_transverse);
  volume.push_back(props.volume);
  first_sphere.push_back(num_spheres());
  const int n = shape.is_clump() ? 2 : 1;
  num_body_spheres.push_back(static_cast<std::int8_t>(n));
  const Eigen::Vector3d axis = body_axis(orientation.back());
  for (int k = 0; k < n; ++k) {
    const double offset = n == 1 ? 0.0 : (k == 0 ? -0.5 : 0.5) * shape.centre_distance;
    sphere_offset.push_back(offset);
    sphere_radius.push_back(shape.sphere_radius);
    sphere_body.push_back(body);
    sphere_position.push_back(pos + offset * axis);
  }
  return body;
}

void Particles::update_sphere_positions() {
  const int nb = num_bodies();
  for (int b = 0; b < nb; ++b) {
    const int s0 = first_sphere[b];
    if (num_body_spheres[b] == 1) {
      sphere_position[s0] = position[b];
      continue;
    }
    const Eigen::Vector3d axis = body_axis(orientation[b]);
    for (int s = s0; s < s0 + num_body_spheres[b]; ++s)
      sphere_position[s] = position[b] + sphere_offset[s] * axis;
  }
}

template <typename T>
void Particles::permute(std::vector<T>& values, const std::vector<int>& new_to_old) {
  std::vector<T> out;
  out.reserve(values.size());
  for (int old : new_to_old) out.push_back(values[old]);
  values.swap(out);
}

std::vector<int> Particles::sort_spatially(double cell_size) {
  const int nb = num_bodies();
  if (nb == 0) return {};
  Eigen::Vector3d lo = position[0];
  for (const auto& p : position) lo = lo.cwiseMin(p);
  // Key: cell indices interleaved bit by bit (Morton order) keep neighbouring cells close.
  auto spread = [](std::uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  std::vector<std::uint64_t> key(nb);
  for (int b = 0; b < nb; ++b) {
    const Eigen::Vector3d c = (position[b] - lo) / cell_size;
    key[b] = spread(static_cast<std::uint64_t>(c.x())) |
             spread(static_cast<std::uint64_t>(c.y())) << 1 |
             spread(static_cast<std::uint64_t>(c.z())) << 2;
  }
  std::vector<int> order(nb);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });

  std::vector<int> sphere_new_to_old;
  sphere_new_to_old.reserve(num_spheres());
  for (int old_body : order)
    for (int k = 0; k < num_body_spheres[old_body]; ++k)
      sphere_new_to_old.push_back(first_sphere[old_body] + k);

  permute(id, order);
  permute(position, order);
  permute(velocity, order);
  permute(orientation, order);
  permute(angular_momentum, order);
  permute(angular_velocity, order);
  permute(force, order);
  permute(torque, order);
  permute(mass, order);
  permute(inertia_axial, order);
  permute(inertia_transverse, order);
  permute(volume, order);
  permute(num_body_spheres, order);
  permute(sphere_position, sphere_new_to_old);
  permute(sphere_radius, sphere_new_to_old);
  permute(sphere_offset, sphere_new_to_old);
  int s = 0;
  for (int b = 0; b < nb; ++b) {
    first_sphere[b] = s;
    for (int k = 0; k < num_body_spheres[b]; ++k) sphere_body[s++] = b;
  }
  std::vector<int> old_to_new(sphere_new_to_old.size());
  for (int n = 0; n < static_cast<int>(sphere_new_to_old.size()); ++n)
    old_to_new[sphere_new_to_old[n]] = n;
  return old_to_new;
}

ParticleRecord Particles::record(int b) const {
  ParticleRecord r;
  r.id = id[b];
  r.num_spheres = num_body_spheres[b];
  r.sphere_diameter = 2.0 * sphere_radius[first_sphere[b]];
  for (int k = 0; k < 3; ++k) {
    r.position[k] = position[b][k];
    r.velocity[k] = velocity[b][k];
    r.angular_velocity[k] = angular_velocity[b][k];
  }
  const Eigen::Quaterniond& q = orientation[b];
  r.orientation = {q.w(), q.x(), q.y(), q.z()};
  return r;
}

std::string Particles::check() const {
  std::ostringstream e;
  const std::size_t n = id.size(), ns = sphere_radius.size();
  auto sized = [&](std::size_t size, std::size_t expected, const char* name, const char* per) {
    if (size != expected) e << name << " has " << size << " entries, not one per " << per << " (" << expected << "); ";
  };
  sized(position.size(), n, "position", "body");
  sized(velocity.size(), n, "velocity", "body");
  sized(orientation.size(), n, "orientation", "body");
  sized(angular_momentum.size(), n, "angular_momentum", "body");
  sized(angular_velocity.size(), n, "angular_velocity", "body");
  sized(mass.size(), n, "mass", "body");
  sized(inertia_axial.size(), n, "inertia_axial", "body");
  sized(inertia_transverse.size(), n, "inertia_transverse", "body");
  sized(volume.size(), n, "volume", "body");
  sized(first_sphere.size(), n, "first_sphere", "body");
  sized(num_body_spheres.size(), n, "num_body_spheres", "body");
  sized(sphere_position.size(), ns, "sphere_position", "sphere");
  sized(sphere_offset.size(), ns, "sphere_offset", "sphere");
  sized(sphere_body.size(), ns, "sphere_body", "sphere");
  if (!e.str().empty()) return e.str();  // the checks below index the arrays
  auto finite3 = [](const Eigen::Vector3d& v) { return v.allFinite(); };
  auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  for (std::size_t b = 0; b < n; ++b) {
    const int first = first_sphere[b], count = num_body_spheres[b];
    if (count < 1 || count > 2 || first < 0 || static_cast<std::size_t>(first) + count > ns) {
      e << "body " << id[b] << ": spheres [" << first << ", "
        << static_cast<std::int64_t>(first) + count << ") outside the " << ns << " spheres; ";
      return e.str();
    }
    for (int k = first; k < first + count; ++k)
      if (sphere_body[k] != static_cast<int>(b))
        e << "sphere " << k << " belongs to body " << sphere_body[k] << ", not " << b << "; ";
    if (!finite3(position[b]) || !finite3(velocity[b]) || !finite3(angular_momentum[b]) ||
        !finite3(angular_velocity[b]) || !orientation[b].coeffs().allFinite() ||
        !(orientation[b].norm() > 0.5))
      e << "body " << id[b] << ": a position, velocity, orientation or angular momentum is not finite; ";
    if (!positive(mass[b]) || !positive(inertia_axial[b]) || !positive(inertia_transverse[b]) ||
        !positive(volume[b]))
      e << "body " << id[b] << ": mass " << mass[b] << ", inertia or volume " << volume[b]
        << " is not positive and finite; ";
    if (e.tellp() > 2000) return e.str() + "...";
  }
  for (std::size_t k = 0; k < ns; ++k)
    if (!positive(sphere_radius[k]) || !std::isfinite(sphere_offset[k]) ||
        !finite3(sphere_position[k])) {
      e << "sphere " << k << ": radius " << sphere_radius[k] << " or its position is not finite and positive; ";
      break;
    }
  return e.str();
}

}  // namespace dem
