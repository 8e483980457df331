#include "dem/packing.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace dem {

Particles random_lattice_packing(int num_bodies, const GrainSpec& grains, std::uint64_t seed,
                                 double gap_ratio, double height_ratio) {
  if (num_bodies <= 0) throw std::invalid_argument("random_lattice_packing: num_bodies <= 0");
  if (!(grains.min_diameter > 0.0 && grains.max_diameter >= grains.min_diameter))
    throw std::invalid_argument("random_lattice_packing: need 0 < min_diameter <= max_diameter");
  if (!(grains.centre_distance_ratio >= 0.0 && grains.centre_distance_ratio < 1.0))
    throw std::invalid_argument("random_lattice_packing: centre_distance_ratio must be in [0, 1)");
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);

  const double longest = grains.max_diameter * (1.0 + grains.centre_distance_ratio);
  const double spacing = longest * (1.0 + gap_ratio);
  if (!(height_ratio > 0.0)) throw std::invalid_argument("random_lattice_packing: height_ratio <= 0");
  const int per_side = std::max(
      1, static_cast<int>(std::ceil(std::cbrt(static_cast<double>(num_bodies) / height_ratio))));
  const int layers = (num_bodies + per_side * per_side - 1) / (per_side * per_side);
  const double half_extent = 0.5 * spacing * per_side, half_height = 0.5 * spacing * layers;

  Particles particles;
  for (int n = 0; n < num_bodies; ++n) {
    const int ix = n % per_side, iy = (n / per_side) % per_side, iz = n / (per_side * per_side);
    const double d =
        grains.min_diameter + (grains.max_diameter - grains.min_diameter) * unit(rng);
    // A uniformly random rotation: a normalised 4D Gaussian.
    Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
    q.normalize();
    const double length = d * (1.0 + grains.centre_distance_ratio);
    const double play = 0.5 * (spacing - length);  // room left in the site on each side
    Eigen::Vector3d centre(-half_extent + spacing * (ix + 0.5), -half_extent + spacing * (iy + 0.5),
                           -half_height + spacing * (iz + 0.5));
    for (int k = 0; k < 3; ++k) centre[k] += play * (2.0 * unit(rng) - 1.0);
    particles.add_body({0.5 * d, grains.centre_distance_ratio * d}, grains.density, centre, q);
  }
  return particles;
}

void bounding_box(const Particles& particles, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  lo = Eigen::Vector3d::Constant(HUGE_VAL);
  hi = -lo;
  for (int s = 0; s < particles.num_spheres(); ++s) {
    const Eigen::Vector3d r = Eigen::Vector3d::Constant(particles.sphere_radius[s]);
    lo = lo.cwiseMin(particles.sphere_position[s] - r);
    hi = hi.cwiseMax(particles.sphere_position[s] + r);
  }
}

std::vector<Wall> box_walls(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::vector<Wall> walls;
  for (int axis = 0; axis < 3; ++axis) {
    Wall lower, upper;
    lower.axis = upper.axis = axis;
    lower.position = lo[axis];
    upper.upper = true;
    upper.position = hi[axis];
    walls.push_back(lower);
    walls.push_back(upper);
  }
  return walls;
}

void set_random_velocities(Particles& p, double kinetic_energy, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  double kinetic = 0.0;
  for (int b = 0; b < p.num_bodies(); ++b) {
    p.velocity[b] = {gauss(rng), gauss(rng), gauss(rng)};
    p.angular_momentum[b].setZero();
    p.angular_velocity[b].setZero();
    kinetic += 0.5 * p.mass[b] * p.velocity[b].squaredNorm();
  }
  for (auto& v : p.velocity) v *= std::sqrt(kinetic_energy / kinetic);
}

}  // namespace dem
