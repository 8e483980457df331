#include "dem/contact_law.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace dem {
namespace {

TEST(NormalStiffness, FollowsThePaperFormula) {
  EXPECT_DOUBLE_EQ(normal_stiffness(150e6, 2e-5, 150e6, 3e-5),
                   2.0 * 150e6 * 150e6 * 2e-5 * 3e-5 / (150e6 * 2e-5 + 150e6 * 3e-5));
  EXPECT_DOUBLE_EQ(normal_stiffness(150e6, 2e-5, 3e-5), normal_stiffness(150e6, 2e-5, 150e6, 3e-5));
  // Equal spheres: K = E r.
  EXPECT_DOUBLE_EQ(normal_stiffness(1e8, 1e-3, 1e-3), 1e8 * 1e-3);
}

TEST(NormalStiffness, WallIsTheInfiniteRadiusLimit) {
  const double e = 150e6, r = 2e-5;
  EXPECT_NEAR(normal_stiffness(e, r, 7e9, 1e6) / wall_normal_stiffness(e, r), 1.0, 1e-9);
}

TEST(TangentialRotation, RigidRotationCarriesTheForceAlong) {
  // A contact frame spinning rigidly at omega: after many steps the stored force must be the
  // rotated initial force with its magnitude intact.
  const Eigen::Vector3d omega = Eigen::Vector3d(0.3, -1.0, 0.5).normalized() * 2.0;  // rad/s
  const double dt = 1e-4;
  Eigen::Vector3d n(0.0, 0.0, 1.0);
  const Eigen::Vector3d f0(0.7, -0.2, 0.0);
  Eigen::Vector3d f = f0;
  const int steps = 5000;  // total angle 1 rad
  const Eigen::Matrix3d step_rotation = Eigen::AngleAxisd(omega.norm() * dt, omega.normalized())
                                            .toRotationMatrix();
  for (int k = 0; k < steps; ++k) {
    const Eigen::Vector3d n_new = step_rotation * n;
    f = rotate_with_contact_frame(f, n, n_new, dt * omega.dot(n_new));
    n = n_new;
  }
  const Eigen::Matrix3d total =
      Eigen::AngleAxisd(omega.norm() * dt * steps, omega.normalized()).toRotationMatrix();
  // Each step rescales to the stored magnitude: only round-off accumulates (<= 1 ulp a step).
  EXPECT_NEAR(f.norm(), f0.norm(), steps * 2.2e-16 * f0.norm());
  EXPECT_LT((f - total * f0).norm(), 1e-3 * f0.norm());
  EXPECT_NEAR(f.dot(n), 0.0, 1e-13);
}

TEST(TangentialRotation, TiltAloneIsTheMinimalRotation) {
  const Eigen::Vector3d n0(0.0, 0.0, 1.0);
  const Eigen::Vector3d n1 = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) * n0;
  const Eigen::Vector3d f(0.0, 1.0, 0.0);  // in the plane of the tilt
  const Eigen::Vector3d g = rotate_with_contact_frame(f, n0, n1, 0.0);
  EXPECT_LT((g - Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()) * f).norm(), 1e-14);
  const Eigen::Vector3d h(1.0, 0.0, 0.0);  // along the tilt axis: unchanged
  EXPECT_LT((rotate_with_contact_frame(h, n0, n1, 0.0) - h).norm(), 1e-14);
}

TEST(CoulombLimit, ReturnsRadiallyOntoTheCone) {
  Eigen::Vector3d f(3.0, 4.0, 0.0);
  EXPECT_TRUE(apply_coulomb_limit(f, 2.5));
  EXPECT_NEAR(f.norm(), 2.5, 1e-15);
  EXPECT_NEAR(f.x() / f.y(), 0.75, 1e-15);
  Eigen::Vector3d g(0.3, 0.4, 0.0);
  EXPECT_FALSE(apply_coulomb_limit(g, 2.5));
  EXPECT_EQ(g, Eigen::Vector3d(0.3, 0.4, 0.0));
}

TEST(ContactParameters, NamesTheBadParameter) {
  ContactParameters p;
  EXPECT_TRUE(p.validate().empty());
  p.friction = -0.1;
  EXPECT_NE(p.validate().find("friction"), std::string::npos);
  p = ContactParameters{};
  p.youngs_modulus = 0.0;
  EXPECT_NE(p.validate().find("youngs_modulus"), std::string::npos);
}

}  // namespace
}  // namespace dem
