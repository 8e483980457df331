// Storage of the bodies and their spheres: one array per property (structure of arrays), bodies
// contiguous in space after `sort_spatially`, spheres of a body contiguous and in body order.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "dem/records.h"

namespace dem {

/// Shape of a body: one sphere, or two equal spheres `centre_distance` apart along its axis.
struct BodyShape {
  double sphere_radius = 0.0;    ///< [m]
  double centre_distance = 0.0;  ///< 0 for a sphere; 0.5 d = r for the paper's clumps [m]
  bool is_clump() const { return centre_distance > 0.0; }
};

class Particles {
 public:
  /// Adds a body at rest and returns its index. `orientation` maps the body x axis (the clump
  /// axis) to the world. Mass properties use the union of the spheres; `density` in kg/m^3.
  int add_body(const BodyShape& shape, double density, const Eigen::Vector3d& position,
               const Eigen::Quaterniond& orientation = Eigen::Quaterniond::Identity());

  int num_bodies() const { return static_cast<int>(position.size()); }
  int num_spheres() const { return static_cast<int>(sphere_radius.size()); }
  bool has_clumps() const { return num_spheres() != num_bodies(); }

  /// Places every sphere from its body's position and orientation.
  void update_sphere_positions();

  /// What is inconsistent in the arrays (empty if nothing): every body array one entry per body,
  /// every sphere array one per sphere, each body's spheres inside the sphere arrays and pointing
  /// back at it, positions and velocities finite, masses, inertias, volumes and radii positive and
  /// finite. A state read back from a file (a checkpoint someone edited) is checked with it
  /// before any index is followed.
  std::string check() const;

  /// Orders bodies (and their spheres) by the cell of a grid of spacing `cell_size` they lie in,
  /// so that neighbours sit close in memory. Returns, for each old sphere index, its new index.
  std::vector<int> sort_spatially(double cell_size);

  ParticleRecord record(int body) const;

  // ---- body arrays (index: body) ----
  std::vector<std::int64_t> id;              ///< stable id, the insertion order
  std::vector<Eigen::Vector3d> position;     ///< centroid [m]
  std::vector<Eigen::Vector3d> velocity;     ///< at the half step t - dt/2 [m/s]
  std::vector<Eigen::Quaterniond> orientation;
  std::vector<Eigen::Vector3d> angular_momentum;  ///< world frame, at t - dt/2 [kg m^2/s]
  std::vector<Eigen::Vector3d> angular_velocity;  ///< world frame, at t - dt/2 [rad/s]
  std::vector<Eigen::Vector3d> force;        ///< net contact force of this step [N]
  std::vector<Eigen::Vector3d> torque;       ///< net contact torque about the centroid [N m]
  std::vector<double> mass;                  ///< [kg], density scaling included
  std::vector<double> inertia_axial;         ///< [kg m^2]
  std::vector<double> inertia_transverse;    ///< [kg m^2]
  std::vector<double> volume;                ///< solid volume [m^3]
  std::vector<int> first_sphere;             ///< spheres of body b: first_sphere[b] + {0, 1}
  std::vector<std::int8_t> num_body_spheres; ///< 1 or 2

  // ---- sphere arrays (index: sphere) ----
  std::vector<Eigen::Vector3d> sphere_position;  ///< [m]
  std::vector<double> sphere_radius;             ///< [m]
  std::vector<double> sphere_offset;  ///< signed distance from the centroid along the axis [m]
  std::vector<int> sphere_body;

 private:
  template <typename T>
  static void permute(std::vector<T>& values, const std::vector<int>& new_to_old);
};

}  // namespace dem
