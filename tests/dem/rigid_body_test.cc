#include "dem/rigid_body.h"
#include "sffcal/clump_geometry.h"
#include "sffcal/constants.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace dem {
namespace {

using sffcal::kPi;

TEST(TwoSphereUnion, MatchesReferenceValuesForPaperClump) {
  // Sphere radius r, centre distance s = r (total length 1.5 d): reference values from
  // architecture.md.
  const double r = 0.7, rho = 2.0;
  const MassProperties p = two_sphere_union_properties(r, r, rho);
  const double r3 = r * r * r, r5 = r3 * r * r;
  EXPECT_NEAR(p.volume, 9.0 * kPi * r3 / 4.0, 1e-14 * r3);
  EXPECT_NEAR(p.mass, rho * 9.0 * kPi * r3 / 4.0, 1e-13 * r3);
  EXPECT_NEAR(p.inertia_axial, 153.0 / 160.0 * kPi * rho * r5, 1e-13 * r5);
  EXPECT_NEAR(p.inertia_transverse, 531.0 / 320.0 * kPi * rho * r5, 1e-13 * r5);
}

TEST(TwoSphereUnion, ZeroDistanceIsOneSphere) {
  const double r = 1.3, rho = 3.0;
  const MassProperties p = sphere_properties(r, rho);
  const double mass = rho * 4.0 / 3.0 * kPi * r * r * r;
  EXPECT_NEAR(p.mass, mass, 1e-12 * mass);
  EXPECT_NEAR(p.inertia_axial, 0.4 * mass * r * r, 1e-12 * mass * r * r);
  EXPECT_NEAR(p.inertia_transverse, 0.4 * mass * r * r, 1e-12 * mass * r * r);
}

TEST(TwoSphereUnion, AgreesWithMonteCarloAtAnotherSpacing) {
  const double r = 1.0, s = 1.4, rho = 1.0;
  const MassProperties p = two_sphere_union_properties(r, s, rho);
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> ux(-(s / 2 + r), s / 2 + r), uyz(-r, r);
  const int n = 2'000'000;
  double inside = 0.0, axial = 0.0, transverse = 0.0;
  for (int k = 0; k < n; ++k) {
    const double x = ux(rng), y = uyz(rng), z = uyz(rng);
    const double dx = std::abs(x) - s / 2;
    if (dx * dx + y * y + z * z > r * r) continue;
    inside += 1.0;
    axial += y * y + z * z;
    transverse += x * x + z * z;
  }
  const double box = (s + 2 * r) * 4 * r * r;
  const double volume = box * inside / n;
  // Relative standard errors are about 1e-3 at this sample size; 5e-3 is five of them.
  EXPECT_NEAR(p.volume / volume, 1.0, 5e-3);
  EXPECT_NEAR(p.inertia_axial / (box * axial / n), 1.0, 5e-3);
  EXPECT_NEAR(p.inertia_transverse / (box * transverse / n), 1.0, 5e-3);
  // Summing the two spheres instead would overstate the volume: the lens is counted once.
  EXPECT_LT(p.volume, 2.0 * 4.0 / 3.0 * kPi);
}

// The one clump volume (common/): the slice integral the DEM's mass properties use equals the
// closed form 8 pi r^3 / 3 - pi (4r + s)(2r - s)^2 / 12 the SFF analysis had, to round-off, from
// one sphere (s = 0) to touching spheres (s -> 2r).
TEST(TwoSphereUnion, VolumeIsTheClosedFormAndTheMassPropertiesOne) {
  const double r = 0.3e-3;
  for (const double s : {0.0, 0.1 * r, 0.5 * r, r, 1.5 * r, 1.999 * r}) {
    const double closed =
        8.0 * kPi * r * r * r / 3.0 - kPi * (4.0 * r + s) * (2.0 * r - s) * (2.0 * r - s) / 12.0;
    EXPECT_NEAR(sffcal::two_sphere_union_volume(r, s), closed, 1e-14 * closed) << "s = " << s;
    EXPECT_EQ(sffcal::two_sphere_union_volume(r, s), two_sphere_union_properties(r, s, 2650.0).volume);
  }
  EXPECT_NEAR(sffcal::two_sphere_union_volume(r, 0.0), 4.0 * kPi * r * r * r / 3.0, 1e-15 * r * r * r);
}

TEST(TwoSphereUnion, RejectsNonPhysicalInput) {
  EXPECT_THROW(two_sphere_union_properties(-1.0, 0.5, 1.0), std::invalid_argument);
  EXPECT_THROW(two_sphere_union_properties(1.0, 2.0, 1.0), std::invalid_argument);
  EXPECT_THROW(two_sphere_union_properties(1.0, 0.5, 0.0), std::invalid_argument);
}

TEST(SymmetricTop, FreeRotationConservesMomentumAndEnergy) {
  const double ia = 0.3, it = 0.8;
  const Eigen::Vector3d L(0.2, -0.5, 0.9);
  Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  auto energy = [&](const Eigen::Quaterniond& qq) {
    const Eigen::Vector3d w = symmetric_top_angular_velocity(L, body_axis(qq), ia, it);
    return 0.5 * L.dot(w);
  };
  const double e0 = energy(q);
  const double axial0 = L.dot(body_axis(q));
  for (int k = 0; k < 10000; ++k) q = rotate_symmetric_top(q, L, ia, it, 1e-2);
  EXPECT_NEAR(energy(q), e0, 1e-12 * e0);
  EXPECT_NEAR(L.dot(body_axis(q)), axial0, 1e-12);
}

TEST(SymmetricTop, SmallStepsFollowTheAngularVelocity) {
  // Over a tiny step the rotation must equal exp(omega dt) applied to the orientation.
  const double ia = 0.3, it = 0.8, dt = 1e-6;
  const Eigen::Vector3d L(0.4, 0.1, -0.3);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(1.1, Eigen::Vector3d(0, 1, 1).normalized()));
  const Eigen::Vector3d w = symmetric_top_angular_velocity(L, body_axis(q), ia, it);
  const Eigen::Quaterniond expected =
      Eigen::Quaterniond(Eigen::AngleAxisd(w.norm() * dt, w.normalized())) * q;
  const Eigen::Quaterniond got = rotate_symmetric_top(q, L, ia, it, dt);
  EXPECT_LT(got.angularDistance(expected), 1e-10);
}

TEST(SymmetricTop, SmallAngleSeriesAgreesWithTheLibmRotationToRoundOff) {
  // rotate_symmetric_top takes sin and cos of half angles up to 1/32 from a Taylor series; the
  // same rotation built with libm (Eigen's AngleAxis) must agree to a few ulps on both sides of
  // that switch, at the tiny angles of a DEM step and at large ones.
  const double ia = 0.3, it = 0.8;
  const Eigen::Vector3d L(0.4, 0.1, -0.3);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(1.1, Eigen::Vector3d(0, 1, 1).normalized()));
  for (double dt : {1e-9, 1e-6, 1e-3, 0.05, 0.1, 0.12, 0.2, 0.5, 2.0}) {
    const Eigen::Vector3d axis = body_axis(q);
    const Eigen::Quaterniond precession(Eigen::AngleAxisd(dt * L.norm() / it, L.normalized()));
    const Eigen::Quaterniond spin(Eigen::AngleAxisd(
        dt * L.dot(axis) * (1.0 / ia - 1.0 / it), Eigen::Vector3d::UnitX()));
    const Eigen::Quaterniond expected = (precession * q * spin).normalized();
    const Eigen::Quaterniond got = rotate_symmetric_top(q, L, ia, it, dt);
    EXPECT_LT((got.coeffs() - expected.coeffs()).cwiseAbs().maxCoeff(), 1e-15) << "dt " << dt;
  }
}

}  // namespace
}  // namespace dem
