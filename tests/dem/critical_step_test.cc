// The stability limit 2/omega_max (critical_step.h): analytic frequencies of one and two bodies,
// and the largest eigenvalue of a jammed clump packing against a dense eigensolver on a matrix
// assembled here independently (body by body, from the bodies' positions and orientations).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dem/compaction.h"
#include "dem/critical_step.h"
#include "dem/packing.h"
#include "dem/simulation.h"
#include "specimen_fixture.h"

namespace dem {
namespace {

constexpr double kDensity = 2650.0;

// Two equal spheres just touching (zero overlap) with the given grain friction.
Simulation two_spheres(double friction) {
  const double r = 1e-3;
  Particles p;
  p.add_body({r, 0.0}, kDensity, {-r, 0.0, 0.0});
  p.add_body({r, 0.0}, kDensity, {r, 0.0, 0.0});
  ContactParameters law;
  law.friction = friction;
  return Simulation(std::move(p), {}, law, SimulationOptions{});
}

TEST(StabilityLimit, TwoSpheresOnOneSpringAtTheirPairFrequency) {
  // Normal mode: the spheres move against each other, omega^2 = 2 k_n / m. With friction the
  // tangential spring k_t = xi k_n stretches by u_B - u_A - r (theta_A + theta_B) at the contact:
  // omega^2 = k_t (2/m + 2 r^2 / I) = 7 xi k_n / m for solid spheres (I = 2/5 m r^2).
  for (double friction : {0.0, 0.5}) {
    const Simulation sim = two_spheres(friction);
    const double m = sim.particles().mass[0];
    const double k_n = normal_stiffness(sim.contact_parameters().youngs_modulus, 1e-3, 1e-3);
    const double xi = sim.contact_parameters().stiffness_ratio;
    const double omega2 = (friction > 0.0 ? std::max(2.0, 7.0 * xi) : 2.0) * k_n / m;
    EXPECT_NEAR(sim.critical_time_step(), 2.0 / std::sqrt(omega2),
                1e-12 * sim.critical_time_step())
        << "friction " << friction;
    const StabilityLimit& s = sim.stability();
    EXPECT_LE(s.omega_lower, s.omega_max * (1.0 + 1e-12));
    EXPECT_GE(s.omega_upper, s.omega_max * (1.0 - 1e-12));
  }
  // With friction the coupled mode is above every single-body block: the lower bracket is
  // strictly below it (the per-body estimate of earlier versions would have missed it).
  const StabilityLimit s = two_spheres(0.5).stability();
  EXPECT_LT(s.omega_lower, 0.9 * s.omega_max);
}

TEST(StabilityLimit, ThreeDampedSpheresInALineDampTheirTopModeMoreThanOnePair) {
  // Frictionless spheres touching in a line: the axial modes are (1, 0, -1) at k/m and
  // (1, -2, 1) at 3k/m (nothing else is stiff). The dashpots c = 2 beta sqrt(m/2 k) see the same
  // stretches as the springs, so the top mode's damping ratio is omega c / (2k) = beta sqrt(3/2);
  // one pair alone has beta, and damped_limit_factor takes the larger.
  const double r = 1e-3, beta = 0.5;
  ContactParameters law;
  law.friction = 0.0;
  law.normal_damping_ratio = beta;
  for (int spheres : {2, 3}) {
    Particles p;
    for (int k = 0; k < spheres; ++k) p.add_body({r, 0.0}, kDensity, {2.0 * r * k, 0.0, 0.0});
    const Simulation sim(std::move(p), {}, law, SimulationOptions{});
    const double m = sim.particles().mass[0];
    const double k_n = normal_stiffness(law.youngs_modulus, r, r);
    const double omega2 = (spheres == 2 ? 2.0 : 3.0) * k_n / m;
    const double zeta = spheres == 2 ? beta : beta * std::sqrt(1.5);
    const StabilityLimit& s = sim.stability();
    EXPECT_NEAR(s.omega_max, std::sqrt(omega2), 1e-10 * std::sqrt(omega2)) << spheres;
    EXPECT_NEAR(s.modal_damping_ratio, zeta, 1e-10) << spheres;
    const double limit = 2.0 / std::sqrt(omega2) * damped_limit_factor(0.0, zeta);
    EXPECT_NEAR(sim.critical_time_step(), limit, 1e-9 * limit) << spheres;
  }
}

TEST(StabilityLimit, NoCandidateFallsBackOnTheFirstContactsLimit) {
  Particles p;
  p.add_body({1e-3, 0.0}, kDensity, {0.0, 0.0, 0.0});
  p.add_body({1e-3, 0.0}, kDensity, {0.0, 0.0, 1.0});  // far apart
  Simulation sim(p, {}, ContactParameters{}, SimulationOptions{});
  EXPECT_EQ(sim.stability().omega_max, 0.0);
  EXPECT_TRUE(std::isinf(sim.stability().time_step()));
  EXPECT_EQ(sim.critical_time_step(),
            one_contact_time_step(sim.particles(), sim.contact_parameters(), 1.0));
}

// M^-1/2 K M^-1/2 of the bodies on the candidate springs of sim's list, assembled body block by
// body block: a spring between bodies a and b at point c with K_c acts on delta = G_b x_b -
// G_a x_a, G = [I, -[c - X]x] for the translation and rotation of each body.
Eigen::MatrixXd assembled_system(const Particles& P, const std::vector<Wall>& walls,
                                 const ContactList& C, const ContactParameters& law) {
  const int nb = P.num_bodies(), np = C.num_pairs();
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(6 * nb, 6 * nb);
  auto g_of = [&](int body, const Eigen::Vector3d& c) {
    Eigen::Matrix<double, 3, 6> g;
    const Eigen::Vector3d l = c - P.position[body];
    Eigen::Matrix3d skew;
    skew << 0, -l.z(), l.y(), l.z(), 0, -l.x(), -l.y(), l.x(), 0;
    g << Eigen::Matrix3d::Identity(), -skew;
    return g;
  };
  for (int slot = 0; slot < C.num_slots(); ++slot) {
    Eigen::Vector3d n, c;
    double k_n, xi;
    int a = -1, b;
    if (slot < np) {
      const int i = C.pair_i[slot], j = C.pair_j[slot];
      n = (P.sphere_position[j] - P.sphere_position[i]).normalized();
      c = P.sphere_position[i] + P.sphere_radius[i] * n;
      k_n = normal_stiffness(law.youngs_modulus, P.sphere_radius[i], P.sphere_radius[j]);
      xi = law.friction > 0.0 ? law.stiffness_ratio : 0.0;
      a = P.sphere_body[i];
      b = P.sphere_body[j];
    } else {
      const int s = C.wall_sphere[slot - np];
      n = walls[C.wall_index[slot - np]].inward_normal();
      c = P.sphere_position[s] - P.sphere_radius[s] * n;
      k_n = wall_normal_stiffness(law.youngs_modulus, P.sphere_radius[s]);
      xi = law.wall_friction > 0.0 ? law.stiffness_ratio : 0.0;
      b = P.sphere_body[s];
    }
    const Eigen::Matrix3d spring =
        xi * k_n * Eigen::Matrix3d::Identity() + (1.0 - xi) * k_n * n * n.transpose();
    const Eigen::Matrix<double, 3, 6> gb = g_of(b, c);
    k.block<6, 6>(6 * b, 6 * b) += gb.transpose() * spring * gb;
    if (a < 0) continue;
    const Eigen::Matrix<double, 3, 6> ga = g_of(a, c);
    k.block<6, 6>(6 * a, 6 * a) += ga.transpose() * spring * ga;
    k.block<6, 6>(6 * a, 6 * b) -= ga.transpose() * spring * gb;
    k.block<6, 6>(6 * b, 6 * a) -= gb.transpose() * spring * ga;
  }
  Eigen::MatrixXd scale = Eigen::MatrixXd::Zero(6 * nb, 6 * nb);
  for (int b = 0; b < nb; ++b) {
    const Eigen::Matrix3d r = P.orientation[b].toRotationMatrix();
    const Eigen::Vector3d inertia(P.inertia_axial[b], P.inertia_transverse[b],
                                  P.inertia_transverse[b]);
    scale.block<3, 3>(6 * b, 6 * b) =
        Eigen::Matrix3d::Identity() / std::sqrt(P.mass[b]);
    scale.block<3, 3>(6 * b + 3, 6 * b + 3) =
        r * inertia.cwiseSqrt().cwiseInverse().asDiagonal() * r.transpose();
  }
  return scale * k * scale;
}

TEST(StabilityLimit, MatchesTheLargestEigenvalueOfAJammedClumpPacking) {
  // A compacted 150-clump specimen at 100 kPa with the shearing law (friction tan 30) in its box:
  // the Lanczos estimate (16 iterations) on a list built at the present positions, against all
  // eigenvalues of the assembled 900 x 900 matrix.
  const Simulation sim = testing::shearing_copy(testing::compacted_specimen(150, 0.3, 7));
  const Particles& p = sim.particles();
  ContactList list;
  list.build(p, sim.walls(), 0.1 * 2.0 * *std::max_element(p.sphere_radius.begin(),
                                                          p.sphere_radius.end()));
  const Eigen::MatrixXd a = assembled_system(p, sim.walls(), list, sim.contact_parameters());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(a, Eigen::EigenvaluesOnly);
  const double omega_max = std::sqrt(solver.eigenvalues().maxCoeff());
  const StabilityLimit s =
      stability_limit(p, sim.walls(), list, sim.contact_parameters(), 1.0, 1);
  std::printf("150 clumps, %d candidates: omega_max %.6e (dense) %.6e (%d Lanczos iterations), "
              "brackets %.4f, %.4f\n",
              list.num_slots(), omega_max, s.omega_max, s.iterations, s.omega_lower / omega_max,
              s.omega_upper / omega_max);
  EXPECT_NEAR(s.omega_max, omega_max, 1e-3 * omega_max);
  EXPECT_LE(s.omega_max, omega_max * (1.0 + 1e-9));  // a Ritz value never exceeds it
  EXPECT_LE(s.omega_lower, omega_max * (1.0 + 1e-12));
  EXPECT_GE(s.omega_upper, omega_max * (1.0 - 1e-12));
}

}  // namespace
}  // namespace dem
