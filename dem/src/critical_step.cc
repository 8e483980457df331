#include "dem/critical_step.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace dem {
namespace {

double largest_eigenvalue(const Eigen::Matrix3d& m) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(m, Eigen::EigenvaluesOnly);
  return solver.eigenvalues()[2];
}

// The centroid and axis of body b at the list's last build, from its spheres' build positions.
void build_frame(const Particles& P, const ContactList& C, int b, Eigen::Vector3d& centroid,
                 Eigen::Vector3d& axis) {
  const int s0 = P.first_sphere[b];
  if (P.num_body_spheres[b] == 1) {
    centroid = C.build_position[s0];
    axis = Eigen::Vector3d::UnitX();
    return;
  }
  const int s1 = s0 + 1;
  const double span = P.sphere_offset[s1] - P.sphere_offset[s0];
  if (span == 0.0) {
    centroid = 0.5 * (C.build_position[s0] + C.build_position[s1]);
    axis = Eigen::Vector3d::UnitX();
    return;
  }
  axis = (C.build_position[s1] - C.build_position[s0]) / span;
  centroid = C.build_position[s0] - P.sphere_offset[s0] * axis;
  axis.normalize();
}

}  // namespace

double stiffness_critical_step(const Particles& P, const std::vector<Wall>& walls,
                               const ContactList& C, const ContactParameters& law,
                               double density_scaling, int min_parallel_items) {
  if (static_cast<int>(C.build_position.size()) != P.num_spheres() ||
      static_cast<int>(C.incidence_offset.size()) != P.num_spheres() + 1)
    throw std::logic_error("stiffness_critical_step: the contact list does not fit the bodies");
  const int nb = P.num_bodies(), np = C.num_pairs();
  // A tangential spring acts only where there is friction (the engine skips it otherwise).
  const double young = law.youngs_modulus;
  const double xi_pair = law.friction > 0.0 ? law.stiffness_ratio : 0.0;
  const double xi_wall = law.wall_friction > 0.0 ? law.stiffness_ratio : 0.0;
  double largest = 0.0;  // the largest squared angular frequency over the bodies [1/s^2]
#pragma omp parallel for schedule(static) reduction(max : largest) if (nb >= min_parallel_items)
  for (int b = 0; b < nb; ++b) {
    Eigen::Vector3d centroid, axis;
    build_frame(P, C, b, centroid, axis);
    Eigen::Matrix3d k_translation = Eigen::Matrix3d::Zero(), k_rotation = Eigen::Matrix3d::Zero();
    bool any = false;
    const int s_end = P.first_sphere[b] + P.num_body_spheres[b];
    for (int s = P.first_sphere[b]; s < s_end; ++s) {
      const double r = P.sphere_radius[s];
      for (int e = C.incidence_offset[s]; e < C.incidence_offset[s + 1]; ++e) {
        const int slot = C.incidence[e] >> 1;
        Eigen::Vector3d n;  // from this sphere towards the other body or the wall
        double k_n, xi;
        if (slot < np) {
          const int other = C.pair_i[slot] == s ? C.pair_j[slot] : C.pair_i[slot];
          n = C.build_position[other] - C.build_position[s];
          const double length = n.norm();
          if (!(length > 0.0)) continue;
          n /= length;
          k_n = normal_stiffness(young, r, P.sphere_radius[other]);
          xi = xi_pair;
        } else {
          n = -walls[C.wall_index[slot - np]].inward_normal();
          k_n = wall_normal_stiffness(young, r);
          xi = xi_wall;
        }
        const double k_t = xi * k_n;
        const Eigen::Vector3d lever = C.build_position[s] + r * n - centroid;
        const Eigen::Vector3d l_x_n = lever.cross(n);
        k_translation.diagonal().array() += k_t;
        k_translation.noalias() += (k_n - k_t) * n * n.transpose();
        k_rotation.diagonal().array() += k_t * lever.squaredNorm();
        k_rotation.noalias() += (k_n - k_t) * l_x_n * l_x_n.transpose() - k_t * lever * lever.transpose();
        any = true;
      }
    }
    if (!any) continue;
    const double mass = density_scaling * P.mass[b];
    // J^-1/2 in the world frame: the axial and transverse inertias about the body axis.
    const double ia = density_scaling * P.inertia_axial[b];
    const double it = density_scaling * P.inertia_transverse[b];
    const Eigen::Matrix3d axial = axis * axis.transpose();
    const Eigen::Matrix3d root_inverse =
        (Eigen::Matrix3d::Identity() - axial) / std::sqrt(it) + axial / std::sqrt(ia);
    const double omega2 =
        std::max(largest_eigenvalue(k_translation) / mass,
                 largest_eigenvalue(root_inverse * k_rotation * root_inverse));
    largest = std::max(largest, omega2);
  }
  return largest > 0.0 ? 1.0 / std::sqrt(largest) : std::numeric_limits<double>::infinity();
}

double one_contact_critical_step(const Particles& P, const ContactParameters& law,
                                 double density_scaling) {
  double step = std::numeric_limits<double>::infinity();
  for (int b = 0; b < P.num_bodies(); ++b) {
    const int s = P.first_sphere[b];
    const double r = P.sphere_radius[s];
    const double lever = std::abs(P.sphere_offset[s]) + r;
    const double m_eff = density_scaling * std::min({P.mass[b],
                                                     P.inertia_transverse[b] / (lever * lever),
                                                     P.inertia_axial[b] / (r * r)});
    step = std::min(step, std::sqrt(m_eff / wall_normal_stiffness(law.youngs_modulus, r)));
  }
  return step;
}

}  // namespace dem
