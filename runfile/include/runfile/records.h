// Plain records of the grain-scale data a run file stores: the DEM writes them, every later stage
// (sff, vtk, the Python readers) reads them. HDF5 compound types mirror them field for field.
//
// Units: SI throughout (m, kg, s, N, Pa).
// Sign convention (stated once, here): a contact joins body A to body B; its unit normal
// points from A towards B; `force` is the force that A exerts on B, so a compressive contact
// has normal_force = force·normal > 0. Stresses built from these records are compression
// positive. For a wall contact, A is the wall and the normal points from the wall into the body.
#pragma once

#include <array>
#include <cstdint>

namespace runfile {

using Vec3Record = std::array<double, 3>;

/// One contact between two spheres of different bodies, or between a wall and a sphere.
struct ContactRecord {
  std::int64_t body_a = -1;     ///< body id of A, or -1 when A is a wall
  std::int64_t body_b = -1;     ///< body id of B
  std::int32_t wall = -1;       ///< wall index when A is a wall, else -1
  std::int32_t sliding = 0;     ///< 1 when the tangential force sits on the Coulomb limit
  Vec3Record point{};           ///< contact point [m]
  Vec3Record normal{};          ///< unit normal from A to B
  Vec3Record branch{};          ///< centroid of B minus centroid of A [m] (zero for walls)
  double overlap = 0.0;         ///< normal overlap [m]
  double normal_force = 0.0;    ///< force·normal on B [N], > 0 in compression
  Vec3Record tangential_force{};///< tangential part of the force on B [N]
};

/// State of one rigid body (a sphere or a two-sphere clump).
struct ParticleRecord {
  std::int64_t id = 0;          ///< stable body id (survives spatial re-sorting)
  std::int32_t num_spheres = 1; ///< 1 for a sphere, 2 for a clump
  double sphere_diameter = 0.0; ///< diameter of each of its spheres [m]
  Vec3Record position{};        ///< centroid of the union of its spheres [m]
  std::array<double, 4> orientation{{1.0, 0.0, 0.0, 0.0}}; ///< unit quaternion (w, x, y, z)
  Vec3Record velocity{};        ///< [m/s]
  Vec3Record angular_velocity{};///< world frame [rad/s]
};

/// State of one planar wall.
struct WallRecord {
  std::int32_t axis = 0;           ///< 0 = x, 1 = y, 2 = z
  std::int32_t upper = 0;          ///< 1 for the wall at the upper end of its axis
  std::int32_t stress_controlled = 0;  ///< 1 when servo-controlled to target_stress
  std::int32_t padding = 0;
  double position = 0.0;           ///< [m]
  double velocity = 0.0;           ///< along +axis [m/s]
  double normal_force = 0.0;       ///< compressive force of the bodies on the wall [N]
  double target_stress = 0.0;      ///< [Pa]
};

}  // namespace runfile
