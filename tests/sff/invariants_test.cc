// The general form of the SFF tensors (issue 18): invariants against their closed forms, and a
// DEM snapshot rotated by 45 degrees analysed to the same invariants and §6 statistics (they do
// not depend on the frame, as the triaxial scalars about z do).
#include "sff/invariants.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "../dem/specimen_fixture.h"
#include "dem/run_file_io.h"
#include "dem/triaxial.h"
#include "sff/analysis.h"
#include "sff/run_snapshot.h"
#include "sff/tensors.h"
#include "sffcal/constants.h"

namespace sff {
namespace {

TEST(Invariants, ClosedFormsOfAxisymmetricAndMidwayTensors) {
  // Triaxial compression: q = sigma_1 - sigma_3, Lode angle 0.
  const TensorInvariants compression = tensor_invariants(Eigen::Vector3d(1, 1, 3).asDiagonal());
  EXPECT_NEAR(compression.mean, 5.0 / 3.0, 1e-15);
  EXPECT_NEAR(compression.magnitude, 2.0, 1e-14);
  EXPECT_NEAR(compression.lode_deg, 0.0, 1e-6);
  EXPECT_EQ(compression.values, Eigen::Vector3d(3, 1, 1));
  EXPECT_NEAR(std::abs(compression.directions.col(0).z()), 1.0, 1e-15);
  // Triaxial extension: Lode angle 60; b = 1/2: 30.
  EXPECT_NEAR(tensor_invariants(Eigen::Vector3d(3, 3, 1).asDiagonal()).lode_deg, 60.0, 1e-6);
  EXPECT_NEAR(tensor_invariants(Eigen::Vector3d(0, 1, 2).asDiagonal()).lode_deg, 30.0, 1e-12);
  // About z the triaxial scalar is t(); about x of an extension, the extension's magnitude.
  const Eigen::Matrix3d t = Eigen::Vector3d(1, 2, 5).asDiagonal();
  EXPECT_EQ(triaxial_about(t, Eigen::Vector3d::UnitZ()), triaxial(t));
  EXPECT_EQ(alignment(t, 2.0 * t + Eigen::Matrix3d::Identity()), 1.0);
  EXPECT_EQ(alignment(t, Eigen::Matrix3d::Identity()), 0.0);
}

// One snapshot of a sheared 60-clump specimen, and the same snapshot turned by 45 degrees about
// x (every position, normal, branch and force vector rotated).
TEST(Invariants, ARotatedSnapshotHasTheSameInvariants) {
  dem::Simulation sim =
      dem::testing::shearing_copy(dem::testing::compacted_specimen(60, 0.0, 8));
  dem::TriaxialOptions options;
  options.max_axial_strain = 0.02;
  dem::TriaxialTest(sim, options).run(nullptr, nullptr);
  const runfile::Snapshot snapshot = dem::take_snapshot(sim, 0.02);
  runfile::Snapshot turned = snapshot;
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.25 * sffcal::kPi, Eigen::Vector3d::UnitX())
                                .toRotationMatrix();
  auto rotate = [&](runfile::Vec3Record& v) {
    Eigen::Map<Eigen::Vector3d> x(v.data());
    x = (r * x).eval();
  };
  for (runfile::ContactRecord& c : turned.contacts) {
    rotate(c.point);
    rotate(c.normal);
    rotate(c.branch);
    rotate(c.tangential_force);
  }
  for (runfile::ParticleRecord& p : turned.particles) rotate(p.position);
  runfile::RunPhysics physics;
  physics.youngs_modulus = sim.contact_parameters().youngs_modulus;
  physics.friction = sim.contact_parameters().friction;
  SnapshotInput in = snapshot_input(snapshot, physics), in_turned = snapshot_input(turned, physics);
  in.centroids.clear();  // the wall terms hold axis-aligned walls: not part of the comparison
  in_turned.centroids.clear();
  const SnapshotAnalysis a = analyse_snapshot(in), b = analyse_snapshot(in_turned);
  ASSERT_GT(a.eta, 0.3);  // sheared: the deviators are not small
  const Eigen::Matrix3d* tensors_a[] = {&a.stress, &a.fabric, &a.normal, &a.tangential, &a.mobilisation};
  const Eigen::Matrix3d* tensors_b[] = {&b.stress, &b.fabric, &b.normal, &b.tangential, &b.mobilisation};
  const char* names[] = {"stress", "fabric", "normal", "tangential", "mobilisation"};
  for (int k = 0; k < 5; ++k) {
    const TensorInvariants ia = tensor_invariants(*tensors_a[k]), ib = tensor_invariants(*tensors_b[k]);
    const double scale = ia.values.cwiseAbs().maxCoeff();
    EXPECT_NEAR(ia.mean, ib.mean, 1e-12 * scale) << names[k];
    EXPECT_NEAR(ia.magnitude, ib.magnitude, 1e-12 * scale) << names[k];
    EXPECT_NEAR(ia.lode_deg, ib.lode_deg, 1e-6) << names[k];  // acos near 0 loses digits
    for (int v = 0; v < 3; ++v) EXPECT_NEAR(ia.values[v], ib.values[v], 1e-12 * scale) << names[k];
    EXPECT_NEAR(alignment(*tensors_a[k], a.stress), alignment(*tensors_b[k], b.stress), 1e-12)
        << names[k];
    // The triaxial scalar about the stress's major axis turns with the snapshot; about z not.
    EXPECT_NEAR(triaxial_about(*tensors_a[k], a.stress_axis.axis),
                triaxial_about(*tensors_b[k], b.stress_axis.axis), 1e-12 * scale)
        << names[k];
  }
  EXPECT_GT(std::abs(triaxial(a.fabric) - triaxial(b.fabric)), 0.05 * std::abs(triaxial(a.fabric)));
  // The Guo & Zhao tensors' invariants, and the §6 statistics on cells about the stress's
  // principal axes, turn with the snapshot too.
  for (const auto member : {&GuoZhaoAnisotropy::normal, &GuoZhaoAnisotropy::tangential,
                            &GuoZhaoAnisotropy::branch})
    EXPECT_NEAR(tensor_invariants(a.guo_zhao.*member).magnitude,
                tensor_invariants(b.guo_zhao.*member).magnitude, 1e-12);
  EXPECT_NEAR(a.guo_zhao.mean_normal_force, b.guo_zhao.mean_normal_force, 1e-12 * a.guo_zhao.mean_normal_force);
  CheckOptions no_bootstrap;
  no_bootstrap.resamples = 0;
  const SnapshotChecks ca = check_snapshot(in, a, no_bootstrap);
  const SnapshotChecks cb = check_snapshot(in_turned, b, no_bootstrap);
  for (const auto fit : {&TruncationCheck::density, &TruncationCheck::normal_force,
                         &TruncationCheck::tangential_force}) {
    const TruncationFit &fa = ca.truncation.*fit, &fb = cb.truncation.*fit;
    EXPECT_NEAR(fa.r_squared, fb.r_squared, 1e-12);
    EXPECT_NEAR(fa.relative_l2, fb.relative_l2, 1e-12);
    EXPECT_NEAR(fa.chi2_per_dof, fb.chi2_per_dof, 1e-12 * fa.chi2_per_dof);
    EXPECT_NEAR(fa.fourth_order_ratio, fb.fourth_order_ratio, 1e-12);
  }
  EXPECT_GT(ca.truncation.density.r_squared, 0.0);  // a real comparison, not an empty one
  EXPECT_NEAR(ca.independence.mean_spearman, cb.independence.mean_spearman, 1e-12);
  EXPECT_NEAR(ca.independence.coupling_error, cb.independence.coupling_error, 1e-12);
  EXPECT_NEAR(ca.coaxiality.fabric_deg, cb.coaxiality.fabric_deg, 1e-6);
  EXPECT_NEAR(ca.coaxiality.normal_deg, cb.coaxiality.normal_deg, 1e-6);
  EXPECT_NEAR(ca.branch.mean_angle_deg, cb.branch.mean_angle_deg, 1e-9);
}

}  // namespace
}  // namespace sff
