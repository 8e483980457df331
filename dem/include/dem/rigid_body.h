// Mass properties and free rotation of the bodies the DEM supports: spheres and rigid clumps of
// two equal spheres. Both are axisymmetric (symmetric tops), which the rotation update exploits.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace dem {

/// Mass properties about the centroid, in the body frame whose x axis is the clump axis.
struct MassProperties {
  double volume = 0.0;              ///< solid volume [m^3]
  double mass = 0.0;                ///< [kg]
  double inertia_axial = 0.0;       ///< principal moment about the body axis [kg m^2]
  double inertia_transverse = 0.0;  ///< principal moment about any transverse axis [kg m^2]
};

/// Union of two equal spheres of radius r whose centres are `centre_distance` apart
/// (0 <= s < 2r), the overlap lens counted once. s = 0 gives a single sphere.
/// Closed form from integrating circular slices along the axis.
MassProperties two_sphere_union_properties(double radius, double centre_distance, double density);

/// A single sphere.
MassProperties sphere_properties(double radius, double density);

/// Exact torque-free motion of a symmetric top over a time `dt` at constant world-frame angular
/// momentum L: a rotation about L at rate |L|/I_t composed with a spin about the body axis at
/// rate (L·e)(1/I_a - 1/I_t). Conserves |L| and the kinetic energy to round-off, which is what
/// makes the leapfrog rotation update symplectic for our bodies.
Eigen::Quaterniond rotate_symmetric_top(const Eigen::Quaterniond& orientation,
                                        const Eigen::Vector3d& angular_momentum,
                                        double inertia_axial, double inertia_transverse,
                                        double dt);

/// World-frame angular velocity of a symmetric top with body axis `axis` (unit, world frame).
inline Eigen::Vector3d symmetric_top_angular_velocity(const Eigen::Vector3d& angular_momentum,
                                                      const Eigen::Vector3d& axis,
                                                      double inertia_axial,
                                                      double inertia_transverse) {
  const double inv_t = 1.0 / inertia_transverse;
  return inv_t * angular_momentum +
         (1.0 / inertia_axial - inv_t) * angular_momentum.dot(axis) * axis;
}

/// The body axis (body-frame x) in the world frame.
inline Eigen::Vector3d body_axis(const Eigen::Quaterniond& q) {
  // First column of the rotation matrix, written out to avoid building the matrix.
  return {1.0 - 2.0 * (q.y() * q.y() + q.z() * q.z()), 2.0 * (q.x() * q.y() + q.w() * q.z()),
          2.0 * (q.x() * q.z() - q.w() * q.y())};
}

}  // namespace dem
