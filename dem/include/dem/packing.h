// Loose initial packings and the box around them.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "dem/particles.h"
#include "dem/wall.h"

namespace dem {

/// The grains of a specimen: sphere diameters uniform in [min, max], and the clump's centre
/// distance as a fraction of the diameter (0.5 for the paper's clumps, 0 for plain spheres).
struct GrainSpec {
  double min_diameter = 0.03e-3;       ///< [m]
  double max_diameter = 0.07e-3;       ///< [m]
  double centre_distance_ratio = 0.5;  ///< s / d; 0 gives spheres
  double density = 2650.0;             ///< [kg/m^3]
};

/// Random insertion without overlap: bodies at the sites of a cubic lattice whose spacing is the
/// longest body (plus `gap_ratio` of it), each with a random diameter, a uniformly random
/// orientation and a small random shift that keeps it inside its site. The lattice is centred on
/// the origin, with `height_ratio` times as many sites along z as along x and y (1: a cube).
/// Same seed, same packing.
Particles random_lattice_packing(int num_bodies, const GrainSpec& grains, std::uint64_t seed,
                                 double gap_ratio = 0.05, double height_ratio = 1.0);

/// Sets the bodies moving for a stability or energy test: seeded Gaussian velocity components,
/// no spin, scaled so that they carry `kinetic_energy` [J] (with their unscaled masses).
void set_random_velocities(Particles& particles, double kinetic_energy, std::uint64_t seed);

/// Smallest axis-aligned box holding every sphere, [lo, hi] per axis.
void bounding_box(const Particles& particles, Eigen::Vector3d& lo, Eigen::Vector3d& hi);

/// Six walls on the faces of [lo, hi], at rest, in velocity mode; order -x, +x, -y, +y, -z, +z.
std::vector<Wall> box_walls(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

}  // namespace dem
