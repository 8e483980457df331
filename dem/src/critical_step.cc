#include "dem/critical_step.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "dem/parallel.h"

namespace dem {
namespace {

double largest_eigenvalue(const Eigen::Matrix3d& m) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(m, Eigen::EigenvaluesOnly);
  return solver.eigenvalues()[2];
}

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& l) {
  Eigen::Matrix3d m;
  m << 0.0, -l.z(), l.y(), l.z(), 0.0, -l.x(), -l.y(), l.x(), 0.0;
  return m;
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

// A uniform number in [-1, 1] from (key, dof) (splitmix64): the start vector depends on the
// bodies' stable ids only, not on the thread count or the bodies' order in memory.
double hashed_unit(std::int64_t key, int dof) {
  std::uint64_t z = static_cast<std::uint64_t>(key) * 6u + static_cast<std::uint64_t>(dof) +
                    0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-52 - 1.0;
}

// One spring per candidate contact, in the frame of the list's last build.
struct Spring {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  Eigen::Vector3d lever_a = Eigen::Vector3d::Zero(), lever_b = Eigen::Vector3d::Zero();  // to c
  double k_n = 0.0, k_t = 0.0;
  double c_n = 0.0;              // the normal dashpot's coefficient [N s/m]
  int body_a = -1, body_b = -1;  // body_a = -1 for a wall (fixed)
};

// The assembled system M^-1/2 K M^-1/2 of the bodies on their candidate springs.
class SpringSystem {
 public:
  SpringSystem(const Particles& P, const std::vector<Wall>& walls, const ContactList& C,
               const ContactParameters& law, double density_scaling, int min_parallel_items)
      : P_(P), C_(C), parallel_(min_parallel_items) {
    const int nb = P.num_bodies(), np = C.num_pairs();
    centroid_.resize(nb);
    inv_sqrt_mass_.resize(nb);
    inv_sqrt_inertia_.resize(nb);
#pragma omp parallel for schedule(static) if (nb >= parallel_)
    for (int b = 0; b < nb; ++b) {
      Eigen::Vector3d axis;
      build_frame(P, C, b, centroid_[b], axis);
      inv_sqrt_mass_[b] = 1.0 / std::sqrt(density_scaling * P.mass[b]);
      // J^-1/2 in the world frame: the axial and transverse inertias about the body axis.
      const Eigen::Matrix3d axial = axis * axis.transpose();
      inv_sqrt_inertia_[b] =
          (Eigen::Matrix3d::Identity() - axial) /
              std::sqrt(density_scaling * P.inertia_transverse[b]) +
          axial / std::sqrt(density_scaling * P.inertia_axial[b]);
    }
    // A tangential spring acts only where there is friction (the engine skips it otherwise).
    const double young = law.youngs_modulus;
    const double xi_pair = law.friction > 0.0 ? law.stiffness_ratio : 0.0;
    const double xi_wall = law.wall_friction > 0.0 ? law.stiffness_ratio : 0.0;
    // The dashpots as the force loop has them: 2 beta sqrt(m k_n), m the pair's reduced mass or
    // the body's own against a wall.
    const double beta = law.normal_damping_ratio;
    auto mass = [&](int body) { return density_scaling * P.mass[body]; };
    const int ns = C.num_slots();
    springs_.resize(ns);
#pragma omp parallel for schedule(static) if (ns >= parallel_)
    for (int slot = 0; slot < ns; ++slot) {
      Spring& k = springs_[slot];
      int sphere;
      if (slot < np) {
        sphere = C.pair_i[slot];
        const int other = C.pair_j[slot];
        k.normal = C.build_position[other] - C.build_position[sphere];
        const double length = k.normal.norm();
        if (!(length > 0.0)) continue;  // coincident centres: no direction, left out (k = 0)
        k.normal /= length;
        k.k_n = normal_stiffness(young, P.sphere_radius[sphere], P.sphere_radius[other]);
        k.k_t = xi_pair * k.k_n;
        k.body_a = P.sphere_body[sphere];
        k.body_b = P.sphere_body[other];
        const double m_a = mass(k.body_a), m_b = mass(k.body_b);
        k.c_n = 2.0 * beta * std::sqrt(m_a * m_b / (m_a + m_b) * k.k_n);
      } else {
        // The wall is held fixed over a step: the sphere is body b, pushed along the inward normal.
        sphere = C.wall_sphere[slot - np];
        k.normal = walls[C.wall_index[slot - np]].inward_normal();
        k.k_n = wall_normal_stiffness(young, P.sphere_radius[sphere]);
        k.k_t = xi_wall * k.k_n;
        k.body_b = P.sphere_body[sphere];
        k.c_n = 2.0 * beta * std::sqrt(mass(k.body_b) * k.k_n);
      }
      const Eigen::Vector3d contact =
          C.build_position[sphere] +
          (slot < np ? 1.0 : -1.0) * P.sphere_radius[sphere] * k.normal;
      if (k.body_a >= 0) k.lever_a = contact - centroid_[k.body_a];
      k.lever_b = contact - centroid_[k.body_b];
    }
  }

  int size() const { return 6 * P_.num_bodies(); }

  // y = M^-1/2 K M^-1/2 x: the displacements d = M^-1/2 x stretch each spring by delta =
  // (u_b + theta_b x l_b) - (u_a + theta_a x l_a); its force f = K_c delta pushes back on b by
  // (f, l_b x f) and on a by -(f, l_a x f) (the gradient of 1/2 delta^T K_c delta); y = M^-1/2 of
  // each body's sum, gathered in the fixed order of the incidence lists.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) {
    const int nb = P_.num_bodies(), ns = C_.num_slots();
    set_displacement(x);
    force_.resize(ns);
#pragma omp parallel for schedule(static) if (ns >= parallel_)
    for (int slot = 0; slot < ns; ++slot) {
      const Spring& k = springs_[slot];
      const Eigen::Vector3d delta = stretch(k);
      force_[slot] = k.k_t * delta + (k.k_n - k.k_t) * k.normal.dot(delta) * k.normal;
    }
    y.resize(6 * nb);
#pragma omp parallel for schedule(static) if (nb >= parallel_)
    for (int b = 0; b < nb; ++b) {
      Eigen::Vector3d f = Eigen::Vector3d::Zero(), t = Eigen::Vector3d::Zero();
      const int s_end = P_.first_sphere[b] + P_.num_body_spheres[b];
      for (int s = P_.first_sphere[b]; s < s_end; ++s)
        for (int e = C_.incidence_offset[s]; e < C_.incidence_offset[s + 1]; ++e) {
          const int slot = C_.incidence[e] >> 1;
          const Spring& k = springs_[slot];
          if (k.body_b == b) {
            f += force_[slot];
            t += k.lever_b.cross(force_[slot]);
          } else {
            f -= force_[slot];
            t -= k.lever_a.cross(force_[slot]);
          }
        }
      y.segment<3>(6 * b) = inv_sqrt_mass_[b] * f;
      y.segment<3>(6 * b + 3) = inv_sqrt_inertia_[b] * t;
    }
  }

  // The damping ratio of the mode x (a vector of M^1/2 d, as multiply takes it) at angular
  // frequency omega: zeta = d^T C d / (2 omega d^T M d) = omega d^T C d / (2 d^T K d) with
  // omega^2 = d^T K d / d^T M d, C the normal dashpots on the springs' normal stretches.
  double damping_ratio(const Eigen::VectorXd& x, double omega) {
    set_displacement(x);
    const Eigen::Vector2d sums = deterministic_sum(
        C_.num_slots(), Eigen::Vector2d(Eigen::Vector2d::Zero()), [&](int from, int to) {
          Eigen::Vector2d part = Eigen::Vector2d::Zero();
          for (int slot = from; slot < to; ++slot) {
            const Spring& k = springs_[slot];
            const Eigen::Vector3d delta = stretch(k);
            const double normal = k.normal.dot(delta);
            part[0] += k.c_n * normal * normal;
            part[1] += k.k_t * delta.squaredNorm() + (k.k_n - k.k_t) * normal * normal;
          }
          return part;
        });
    return sums[1] > 0.0 ? omega * sums[0] / (2.0 * sums[1]) : 0.0;
  }

  double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
    return deterministic_sum(P_.num_bodies(), 0.0, [&](int from, int to) {
      return a.segment(6 * from, 6 * (to - from)).dot(b.segment(6 * from, 6 * (to - from)));
    });
  }

  // Each body's own blocks: lower = the largest eigenvalue of a translational or rotational 3x3
  // block, upper = max(lambda_t, lambda_r) + |coupling|_F, bounding its 6x6 block from above.
  // `weight` is each body's largest 3x3 eigenvalue (0 for a body without candidates).
  void body_bounds(double& lower, double& upper, std::vector<double>& weight) const {
    const int nb = P_.num_bodies();
    weight.assign(nb, 0.0);
    double lo = 0.0, up = 0.0;
#pragma omp parallel for schedule(static) reduction(max : lo, up) if (nb >= parallel_)
    for (int b = 0; b < nb; ++b) {
      Eigen::Matrix3d tt = Eigen::Matrix3d::Zero(), tr = Eigen::Matrix3d::Zero(),
                      rr = Eigen::Matrix3d::Zero();
      bool any = false;
      const int s_end = P_.first_sphere[b] + P_.num_body_spheres[b];
      for (int s = P_.first_sphere[b]; s < s_end; ++s)
        for (int e = C_.incidence_offset[s]; e < C_.incidence_offset[s + 1]; ++e) {
          const Spring& k = springs_[C_.incidence[e] >> 1];
          if (k.body_b < 0) continue;
          const Eigen::Vector3d& lever = k.body_b == b ? k.lever_b : k.lever_a;
          // delta = u - [l]x theta with K_c = k_t I + (k_n - k_t) n n^T: K_tt = K_c,
          // K_tr = -K_c [l]x = -k_t [l]x - (k_n - k_t) n (n x l)^T, K_rr = [l]x^T K_c [l]x =
          // k_t (|l|^2 I - l l^T) + (k_n - k_t) (l x n)(l x n)^T (n^T [l]x = (n x l)^T).
          const double k_diff = k.k_n - k.k_t;
          const Eigen::Vector3d l_x_n = lever.cross(k.normal);
          tt.diagonal().array() += k.k_t;
          tt.noalias() += k_diff * k.normal * k.normal.transpose();
          tr -= k.k_t * cross_matrix(lever);
          tr.noalias() += k_diff * k.normal * l_x_n.transpose();
          rr.diagonal().array() += k.k_t * lever.squaredNorm();
          rr.noalias() += k_diff * l_x_n * l_x_n.transpose() - k.k_t * lever * lever.transpose();
          any = true;
        }
      if (!any) continue;
      const double m = inv_sqrt_mass_[b];
      const Eigen::Matrix3d& j = inv_sqrt_inertia_[b];
      const double lambda_t = largest_eigenvalue(m * m * tt);
      const double lambda_r = largest_eigenvalue(j * rr * j);
      const double coupling = (m * tr * j).norm();
      weight[b] = std::max(lambda_t, lambda_r);
      lo = std::max(lo, weight[b]);
      up = std::max(up, weight[b] + coupling);
    }
    lower = lo;
    upper = up;
  }

 private:
  // displacement_ = M^-1/2 x.
  void set_displacement(const Eigen::VectorXd& x) {
    const int nb = P_.num_bodies();
    displacement_.resize(6 * nb);
#pragma omp parallel for schedule(static) if (nb >= parallel_)
    for (int b = 0; b < nb; ++b) {
      displacement_.segment<3>(6 * b) = inv_sqrt_mass_[b] * x.segment<3>(6 * b);
      displacement_.segment<3>(6 * b + 3) = inv_sqrt_inertia_[b] * x.segment<3>(6 * b + 3);
    }
  }

  // The spring's stretch under displacement_: (u_b + theta_b x l_b) - (u_a + theta_a x l_a).
  Eigen::Vector3d stretch(const Spring& k) const {
    if (k.body_b < 0) return Eigen::Vector3d::Zero();
    Eigen::Vector3d delta = displacement_.segment<3>(6 * k.body_b) +
                            displacement_.segment<3>(6 * k.body_b + 3).cross(k.lever_b);
    if (k.body_a >= 0)
      delta -= displacement_.segment<3>(6 * k.body_a) +
               displacement_.segment<3>(6 * k.body_a + 3).cross(k.lever_a);
    return delta;
  }

  const Particles& P_;
  const ContactList& C_;
  int parallel_;
  std::vector<Eigen::Vector3d> centroid_;
  std::vector<double> inv_sqrt_mass_;
  std::vector<Eigen::Matrix3d> inv_sqrt_inertia_;
  std::vector<Spring> springs_;
  Eigen::VectorXd displacement_;
  std::vector<Eigen::Vector3d> force_;
};

// The largest eigenvalue of the tridiagonal matrix (alpha on the diagonal, beta beside it) and,
// where `vector` is given, its eigenvector (the Ritz vector's coordinates in the Lanczos basis).
double largest_ritz_value(const std::vector<double>& alpha, const std::vector<double>& beta,
                          Eigen::VectorXd* vector = nullptr) {
  const int k = static_cast<int>(alpha.size());
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(k, k);
  for (int i = 0; i < k; ++i) {
    t(i, i) = alpha[i];
    if (i + 1 < k) t(i, i + 1) = t(i + 1, i) = beta[i];
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(
      t, vector ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly);
  if (vector) *vector = solver.eigenvectors().col(k - 1);
  return solver.eigenvalues()[k - 1];
}

}  // namespace

double StabilityLimit::time_step() const {
  return omega_max > 0.0 ? 2.0 / omega_max : std::numeric_limits<double>::infinity();
}

double StabilityLimit::guaranteed_time_step() const {
  return omega_upper > 0.0 ? 2.0 / omega_upper : std::numeric_limits<double>::infinity();
}

StabilityLimit stability_limit(const Particles& P, const std::vector<Wall>& walls,
                               const ContactList& C, const ContactParameters& law,
                               double density_scaling, int min_parallel_items, int iterations) {
  if (static_cast<int>(C.build_position.size()) != P.num_spheres() ||
      static_cast<int>(C.incidence_offset.size()) != P.num_spheres() + 1)
    throw std::logic_error("stability_limit: the contact list does not fit the bodies");
  SpringSystem system(P, walls, C, law, density_scaling, min_parallel_items);
  StabilityLimit limit;
  double lower = 0.0, upper = 0.0;
  std::vector<double> weight;
  system.body_bounds(lower, upper, weight);
  if (!(lower > 0.0)) return limit;  // no candidate anywhere
  limit.omega_lower = std::sqrt(lower);
  limit.omega_upper = std::sqrt(2.0 * upper);

  // Start where the stiffest bodies are: seeded numbers weighted by (lambda_b / lower)^2, so the
  // Krylov space opens around the regions the largest eigenvalue lives in.
  const int nb = P.num_bodies(), n = system.size();
  Eigen::VectorXd q(n), q_previous = Eigen::VectorXd::Zero(n), w(n);
  for (int b = 0; b < nb; ++b) {
    const double r = weight[b] / lower;
    for (int dof = 0; dof < 6; ++dof) q[6 * b + dof] = r * r * hashed_unit(P.id[b], dof);
  }
  q /= std::sqrt(system.dot(q, q));
  std::vector<double> alpha, beta;
  // With dashpots the basis is kept, to form the top Ritz vector and its damping ratio.
  const bool damped = law.normal_damping_ratio > 0.0;
  std::vector<Eigen::VectorXd> basis;
  double beta_previous = 0.0, ritz = 0.0;
  for (int j = 0; j < iterations; ++j) {
    if (damped) basis.push_back(q);
    system.multiply(q, w);
    const double a = system.dot(q, w);
    w -= a * q + beta_previous * q_previous;
    alpha.push_back(a);
    const double b = std::sqrt(std::max(0.0, system.dot(w, w)));
    ritz = largest_ritz_value(alpha, beta);
    limit.iterations = j + 1;
    if (!(b > 1e-12 * std::abs(a))) break;  // the Krylov space closed: ritz is exact
    beta.push_back(b);
    q_previous.swap(q);
    q = w / b;
    beta_previous = b;
  }
  // The Ritz value never exceeds lambda_max; the block bound is the floor it must reach.
  limit.omega_max = std::sqrt(std::clamp(ritz, lower, 2.0 * upper));
  if (damped) {
    Eigen::VectorXd coordinates;
    largest_ritz_value(alpha, beta, &coordinates);
    Eigen::VectorXd mode = Eigen::VectorXd::Zero(n);
    for (int j = 0; j < static_cast<int>(coordinates.size()); ++j)
      mode += coordinates[j] * basis[j];
    limit.modal_damping_ratio =
        std::max(law.normal_damping_ratio, system.damping_ratio(mode, limit.omega_max));
  }
  return limit;
}

double damped_limit_factor(double local_damping, double damping_ratio) {
  return (std::sqrt(1.0 + damping_ratio * damping_ratio) - damping_ratio) /
         std::sqrt(1.0 + local_damping);
}

double one_contact_time_step(const Particles& P, const ContactParameters& law,
                             double density_scaling) {
  double step = std::numeric_limits<double>::infinity();
  for (int b = 0; b < P.num_bodies(); ++b) {
    const int s = P.first_sphere[b];
    const double r = P.sphere_radius[s];
    const double lever = std::abs(P.sphere_offset[s]) + r;
    const double m_eff = density_scaling * std::min({P.mass[b],
                                                     P.inertia_transverse[b] / (lever * lever),
                                                     P.inertia_axial[b] / (r * r)});
    step = std::min(step,
                    2.0 * std::sqrt(m_eff / (2.0 * wall_normal_stiffness(law.youngs_modulus, r))));
  }
  return step;
}

}  // namespace dem
