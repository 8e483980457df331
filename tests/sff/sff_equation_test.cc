// The test ideas T9, T10 and T12-T14 of sff-theory.md.
#include "sff/sff_equation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sff/tensors.h"
#include "synthetic_contacts.h"
#include "sffcal/constants.h"

namespace sff {
namespace {

using sffcal::kPi;

Eigen::Matrix3d random_traceless(std::mt19937_64& rng, double scale) {
  std::normal_distribution<double> gauss;
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = gauss(rng);
  return scale * dev(sym(m)).normalized();
}

Eigen::Matrix3d axisymmetric(double t) {  // t(T) = t, traceless, about z
  return t * Eigen::Vector3d(-1.0 / 3.0, -1.0 / 3.0, 2.0 / 3.0).asDiagonal().toDenseMatrix();
}

TEST(SffEquation, ProductTermsMatchQuadrature) {  // T9
  std::mt19937_64 rng(9);
  const Eigen::Matrix3d a = random_traceless(rng, 0.6), f = random_traceless(rng, 0.8);
  // (1/4 pi) int (1 + n.A.n)(1 + n.F.n) n n dOmega on an 800 x 1600 midpoint grid.
  const int nt = 800, np = 1600;
  Eigen::Matrix3d integral = Eigen::Matrix3d::Zero();
  for (int i = 0; i < nt; ++i) {
    const double theta = (i + 0.5) * kPi / nt;
    const double weight = std::sin(theta) * (kPi / nt) * (2.0 * kPi / np) / (4.0 * kPi);
    for (int j = 0; j < np; ++j) {
      const double phi = (j + 0.5) * 2.0 * kPi / np;
      const Eigen::Vector3d n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                              std::cos(theta));
      integral += weight * (1.0 + n.dot(a * n)) * (1.0 + n.dot(f * n)) * n * n.transpose();
    }
  }
  SffState state;
  state.youngs_modulus = 1.0;
  state.coordination = 1.0;
  state.lambda = 1.0;
  state.fabric = a;
  state.normal = f;
  EXPECT_LT((sff_stress(state) - integral).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(SffEquation, ConciseFormEqualsTheTensorFormForAxisymmetricStates) {  // T10
  for (const auto& [a, f, t] : {std::tuple{0.3, 0.5, 0.02}, {-0.2, 0.4, -0.01}, {0.8, 0.9, 0.05}}) {
    SffState state;
    state.coordination = 5.5;
    state.void_ratio = 0.6;
    state.lambda = 5.7e-4;
    state.fabric = axisymmetric(a);
    state.normal = axisymmetric(f);
    state.tangential = axisymmetric(t);
    const StressInvariants inv = triaxial_invariants(sff_stress(state));
    EXPECT_NEAR(inv.eta, concise_eta(a, f, t), 1e-13);
  }
}

TEST(SffEquation, TheConciseNormalAnisotropyInvertsTheConciseForm) {
  // In compression and extension, with fabric and tangential anisotropies of either sign.
  for (const auto& [a, f, t] : {std::tuple{0.98, 1.74, 0.125}, {-1.1, -1.35, -0.06},
                                 {0.2, -0.1, 0.0}, {1.6, 2.2, 0.14}}) {
    const double eta = concise_eta(a, f, t);
    EXPECT_NEAR(concise_normal_anisotropy(a, t, eta), f, 1e-13) << a << " " << f << " " << t;
    // A larger stress ratio at the same fabric needs a larger normal-force anisotropy.
    EXPECT_GT(concise_normal_anisotropy(a, t, eta + 0.05), f);
  }
  // The coefficient of f vanishes at eta = (2/5 + 8a/105) / (4a/45): no f reaches it.
  const double a = 2.0, unreachable = (0.4 + 16.0 / 105.0) / (8.0 / 45.0);
  EXPECT_THROW(concise_normal_anisotropy(a, 0.0, unreachable), StatisticsError);
  EXPECT_THROW(concise_normal_anisotropy(0.5, 0.0, std::nan("")), StatisticsError);
}

using testing::make_contact;

TEST(SffEquation, ExactDecoupledFormReproducesTheStressWithoutTheBranchTerm) {  // T12
  std::mt19937_64 rng(12);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double mu = 0.5, volume = 1e-9;
  const ForceScale scale{150e6, 1e-13};
  std::vector<ContactRecord> contacts;
  for (int k = 0; k < 5000; ++k) {
    const Eigen::Vector3d n = Eigen::Vector3d(gauss(rng), gauss(rng), 1.5 * gauss(rng)).normalized();
    const double fn = 1e-3 * (0.2 + unit(rng));
    Eigen::Vector3d t = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
    t = (t - t.dot(n) * n).normalized();
    const Eigen::Vector3d ft = mu * fn * unit(rng) * t;
    // Clump-like branches: not parallel to the normal.
    const Eigen::Vector3d branch = 5e-5 * (n + 0.3 * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)));
    contacts.push_back(make_contact(n, fn, ft, branch));
  }
  const Eigen::Matrix3d a = fabric_anisotropy(fabric_tensor(contacts));
  const NormalForceStatistics nf = normal_force_statistics(contacts, a, scale);
  const Mobilisation mob = mobilisation(contacts, a, nf.lambda, mu, scale);
  // F^t = mu T_m exactly.
  EXPECT_LT((tangential_force_tensor(contacts, nf.lambda, scale) - mu * mob.weighted).norm(),
            1e-12 * mob.weighted.norm());
  const Eigen::Matrix3d sigma = contact_stress(contacts, volume) - branch_remainder(contacts, volume);
  EXPECT_NEAR(exact_decoupled_eta(contacts, mu, nf.lambda, mob.weighted, scale),
              triaxial_invariants(sigma).eta, 1e-12);
}

TEST(SffEquation, AllSlidingContactsGiveAFrictionTermLinearInMu) {  // T13
  const ForceScale scale{0.5, 1.0};
  auto build = [&](double mu) {  // the same normals for every mu
    std::mt19937_64 rng(13);
    std::normal_distribution<double> g;
    std::vector<ContactRecord> contacts;
    for (int k = 0; k < 20000; ++k) {
      const Eigen::Vector3d n = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
      // A fixed axisymmetric shear field tau ~ S n - (n.S n) n, S = diag(-1/2, -1/2, 1).
      const Eigen::Vector3d sn(-0.5 * n.x(), -0.5 * n.y(), n.z());
      Eigen::Vector3d t = sn - n.dot(sn) * n;
      if (t.squaredNorm() < 1e-12) continue;
      t.normalize();
      contacts.push_back(make_contact(n, 1.0, mu * 1.0 * t, n));  // xi = 1 everywhere
    }
    return contacts;
  };
  double previous_ratio = 0.0;
  for (double mu : {0.2, 0.4, 0.8}) {
    const std::vector<ContactRecord> contacts = build(mu);
    const Eigen::Matrix3d a = fabric_anisotropy(fabric_tensor(contacts));
    const NormalForceStatistics nf = normal_force_statistics(contacts, a, scale);
    const Mobilisation mob = mobilisation(contacts, a, nf.lambda, mu, scale);
    EXPECT_NEAR(mob.sliding_fraction, 1.0, 1e-12);
    const double friction_term = mu * nf.lambda * triaxial(mob.weighted);
    if (previous_ratio != 0.0) {
      EXPECT_NEAR(friction_term / mu, previous_ratio, 1e-12 * std::abs(previous_ratio));
    }
    previous_ratio = friction_term / mu;
  }
  EXPECT_GT(std::abs(previous_ratio), 0.01);
}

TEST(SffEquation, MobilisationFieldGivesBackItsTensor) {  // T14
  Eigen::Matrix3d m0;
  m0 << 0.2, 0.0, 0.1, 0.0, 0.2, 0.0, 0.1, 0.0, -0.4;  // |m(n)| <= 1: xi stays in [0, 1]
  std::mt19937_64 rng(14);
  std::normal_distribution<double> gauss;
  const double mu = 0.5;
  std::vector<ContactRecord> contacts;
  for (int k = 0; k < 1'000'000; ++k) {
    const Eigen::Vector3d n = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const Eigen::Vector3d m = m0 * n - n.dot(m0 * n) * n;  // xi tau
    contacts.push_back(make_contact(n, 1.0, mu * 1.0 * m, n));
  }
  const ForceScale scale{0.5, 1.0};
  const Eigen::Matrix3d a = fabric_anisotropy(fabric_tensor(contacts));
  const NormalForceStatistics nf = normal_force_statistics(contacts, a, scale);
  const Mobilisation mob = mobilisation(contacts, a, nf.lambda, mu, scale);
  EXPECT_LT((mob.tensor - m0).cwiseAbs().maxCoeff(), 5e-3) << mob.tensor;
  EXPECT_NEAR(triaxial(mob.tensor), triaxial(m0), 5e-3);
}

}  // namespace
}  // namespace sff
