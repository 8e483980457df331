// The test ideas T1 and T4-T8 of sff-theory.md, on hand-built and synthetic contact sets.
#include "sff/statistics.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "sff/tensors.h"
#include "synthetic_contacts.h"

namespace sff {
namespace {

// Forces are normalised with factor (l.n) / (2 E v_bar) = 1 for l = n, E = 1/2, v_bar = 1.
const ForceScale kUnitScale{0.5, 1.0};

using testing::make_contact;
using testing::random_unit;

using testing::legendre_normals;

TEST(ContactStress, SimpleCubicLatticeGivesFOverDSquared) {  // T1
  const double d = 2e-3, f = 3.5;
  const int n = 4;  // periodic lattice: every body has six contacts
  std::vector<ContactRecord> contacts;
  for (int body = 0; body < n * n * n; ++body)
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[axis] = 1.0;
      contacts.push_back(make_contact(e, f, Eigen::Vector3d::Zero(), d * e));
    }
  const double volume = std::pow(n * d, 3);
  const Eigen::Matrix3d sigma = contact_stress(contacts, volume);
  EXPECT_LT((sigma - f / (d * d) * Eigen::Matrix3d::Identity()).norm(), 1e-12 * f / (d * d));
  EXPECT_EQ(count_body_contacts(contacts), 3u * n * n * n);  // Z = 2 N_c / N_p = 6
  const StressInvariants inv = triaxial_invariants(sigma);
  EXPECT_NEAR(inv.eta, 0.0, 1e-12);
}

TEST(Fabric, IsotropicNormalsGiveNoAnisotropy) {  // T4
  std::mt19937_64 rng(4);
  std::vector<ContactRecord> contacts;
  for (int k = 0; k < 1'000'000; ++k) contacts.push_back(make_contact(random_unit(rng), 1.0));
  const Eigen::Matrix3d a = fabric_anisotropy(fabric_tensor(contacts));
  EXPECT_NEAR(fabric_tensor(contacts).trace(), 1.0, 1e-12);
  EXPECT_LT(a.cwiseAbs().maxCoeff(), 0.01);  // s.d. of A_zz is 2.24 / sqrt(N) = 0.0022
}

TEST(Fabric, LegendreDensityGivesBackItsCoefficient) {  // T5
  for (double b : {-1.0, 0.5, 2.0}) {
    std::vector<ContactRecord> contacts;
    for (const auto& n : legendre_normals(b, 1'000'000, 5)) contacts.push_back(make_contact(n, 1.0));
    const Eigen::Matrix3d a = fabric_anisotropy(fabric_tensor(contacts));
    const Eigen::Matrix3d expected = b * Eigen::Vector3d(-0.5, -0.5, 1.0).asDiagonal().toDenseMatrix();
    EXPECT_LT((a - expected).cwiseAbs().maxCoeff(), 0.015) << "b = " << b << "\n" << a;
    EXPECT_NEAR(triaxial(a), 1.5 * b, 0.02);
    EXPECT_NEAR(std::abs(signed_invariant(a)), std::abs(1.5 * b), 0.02);
  }
}

TEST(Fabric, RotatingTheNormalsRotatesTheTensor) {  // T6
  std::vector<ContactRecord> contacts, rotated;
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  for (const auto& n : legendre_normals(0.8, 20000, 6)) {
    contacts.push_back(make_contact(n, 1.0));
    rotated.push_back(make_contact(r * n, 1.0));
  }
  const Eigen::Matrix3d a = fabric_anisotropy(fabric_tensor(contacts));
  const Eigen::Matrix3d b = fabric_anisotropy(fabric_tensor(rotated));
  EXPECT_LT((b - r * a * r.transpose()).norm(), 1e-12);
}

TEST(NormalForce, SyntheticDirectionalForcesGiveBackLambdaAndF) {  // T7
  const double lambda0 = 5.7e-4;
  Eigen::Matrix3d f0;
  f0 << -0.2, 0.05, 0.0, 0.05, -0.1, 0.02, 0.0, 0.02, 0.3;  // traceless, not coaxial with A
  std::vector<ContactRecord> contacts;
  for (const auto& n : legendre_normals(0.5, 1'000'000, 7))
    contacts.push_back(make_contact(n, lambda0 * (1.0 + n.dot(f0 * n))));
  const Eigen::Matrix3d a = fabric_anisotropy(fabric_tensor(contacts));
  const NormalForceStatistics s = normal_force_statistics(contacts, a, kUnitScale);
  EXPECT_NEAR(s.lambda / lambda0, 1.0, 5e-3);
  // 0.5 % of the largest component of F0 (measured error 3e-4 at this seed).
  EXPECT_LT((s.anisotropy - f0).cwiseAbs().maxCoeff(), 0.005 * 0.3) << s.anisotropy;
}

TEST(TangentialForce, OuadfelRothenburgFieldGivesAFifth) {  // T8
  const double lambda = 2.0;
  Eigen::Matrix3d at;
  at << 0.1, 0.0, 0.03, 0.0, 0.1, 0.0, 0.03, 0.0, -0.2;
  std::mt19937_64 rng(8);
  std::vector<ContactRecord> contacts;
  for (int k = 0; k < 1'000'000; ++k) {
    const Eigen::Vector3d n = random_unit(rng);
    const Eigen::Vector3d ft = lambda * (at * n - n.dot(at * n) * n);
    contacts.push_back(make_contact(n, lambda, ft));
  }
  const NormalForceStatistics s =
      normal_force_statistics(contacts, fabric_anisotropy(fabric_tensor(contacts)), kUnitScale);
  // Lambda carries the weight 1/(1 + n.A.n) of the sample's small anisotropy A: second order.
  EXPECT_NEAR(s.lambda / lambda, 1.0, 1e-5);
  const Eigen::Matrix3d ft = tangential_force_tensor(contacts, s.lambda, kUnitScale);
  EXPECT_LT((ft - at / 5.0).cwiseAbs().maxCoeff(), 1e-3) << ft;
  EXPECT_NEAR(ft.trace(), 0.0, 1e-12);
}

TEST(Statistics, UndefinedInputIsAnErrorNotANan) {
  const std::vector<ContactRecord> none;
  EXPECT_THROW(fabric_tensor(none), StatisticsError);
  EXPECT_THROW(contact_stress(none, 0.0), StatisticsError);
  std::vector<ContactRecord> zero_force = {make_contact(Eigen::Vector3d::UnitZ(), 0.0)};
  EXPECT_THROW(normal_force_statistics(zero_force, Eigen::Matrix3d::Zero(), kUnitScale),
               StatisticsError);
  // Wall contacts are not part of the body-body statistics.
  ContactRecord wall = make_contact(Eigen::Vector3d::UnitX(), 1.0);
  wall.wall = 2;
  const std::vector<ContactRecord> only_wall = {wall};
  EXPECT_THROW(fabric_tensor(only_wall), StatisticsError);
}

}  // namespace
}  // namespace sff
