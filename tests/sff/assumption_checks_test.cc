// T2 and the statistical checks of sff-theory.md §6 on synthetic contact sets whose answers are
// known: weighted views, second/fourth-order fits on direction cells, the binned-weight fallback,
// the Guo & Zhao convention, correlations, independence, coaxiality, the strong/weak split and
// the seeded bootstrap.
#include "sff/assumption_checks.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "sff/analysis.h"
#include "sff/bootstrap.h"
#include "sff/direction_weight.h"
#include "sff/directional.h"
#include "sff/guo_zhao.h"
#include "sff/tensors.h"
#include "synthetic_contacts.h"
#include "sffcal/constants.h"

namespace sff {
namespace {

const ForceScale kUnitScale{0.5, 1.0};  // f_hat = f for l = n
using sffcal::kPi;

using testing::legendre_normals;
using testing::make_contact;
using testing::random_unit;

TEST(ParticleStress, EqualsTheContactFormPlusTheWallTerms) {  // T2
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const int bodies = 40;
  std::vector<Eigen::Vector3d> centroids;
  for (int b = 0; b < bodies; ++b) centroids.emplace_back(unit(rng), unit(rng), unit(rng));
  std::vector<ContactRecord> contacts;
  for (int k = 0; k < 300; ++k) {
    const bool wall = k % 5 == 0;
    const auto a = static_cast<std::int64_t>(k % bodies), b = static_cast<std::int64_t>((7 * k + 3) % bodies);
    if (!wall && a == b) continue;
    const Eigen::Vector3d n = random_unit(rng), ft(unit(rng), unit(rng), unit(rng));
    ContactRecord c = make_contact(n, 1.0 + unit(rng), ft - ft.dot(n) * n);
    c.body_a = wall ? -1 : a;
    c.body_b = b;
    c.wall = wall ? k % 6 : -1;
    const Eigen::Vector3d point = 0.5 * (centroids[a] + centroids[b]) + 0.1 * random_unit(rng);
    const Eigen::Vector3d branch = wall ? Eigen::Vector3d::Zero() : Eigen::Vector3d(centroids[b] - centroids[a]);
    for (int i = 0; i < 3; ++i) c.point[i] = point[i], c.branch[i] = branch[i];
    contacts.push_back(c);
  }
  const double volume = 8.0;
  const Eigen::Matrix3d particle = particle_stress(contacts, centroids, volume);
  const Eigen::Matrix3d split = contact_stress(contacts, volume) + wall_contact_stress(contacts, centroids, volume);
  EXPECT_LT((particle - split).norm(), 1e-13 * particle.norm());
  EXPECT_GT(wall_contact_stress(contacts, centroids, volume).norm(), 0.01 * particle.norm());
  centroids.pop_back();  // a contact now names a body without a centroid
  EXPECT_THROW(particle_stress(contacts, centroids, volume), StatisticsError);
}

TEST(WeightedContacts, MultiplicitiesAndSubsetsAreWeightedMeans) {
  std::mt19937_64 rng(12);
  std::vector<ContactRecord> all, subset;
  std::vector<double> weights, doubled;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector3d n = random_unit(rng);
    all.push_back(make_contact(n, 1.0 + n.z() * n.z(), 0.1 * n.unitOrthogonal()));
    const bool keep = k % 3 != 0;
    weights.push_back(keep ? 1.0 : 0.0);
    doubled.push_back(2.0);
    if (keep) subset.push_back(all.back());
  }
  const ContactSpan span(all);
  const DirectionalTensors whole = directional_tensors(span, kUnitScale, 0.5);
  const DirectionalTensors twice = directional_tensors(span.weighted(doubled), kUnitScale, 0.5);
  const DirectionalTensors part = directional_tensors(span.weighted(weights), kUnitScale, 0.5);
  const DirectionalTensors direct = directional_tensors(subset, kUnitScale, 0.5);
  EXPECT_LT((whole.fabric - twice.fabric).norm(), 1e-13);
  EXPECT_LT((whole.normal - twice.normal).norm(), 1e-13);
  EXPECT_LT((whole.mobilisation - twice.mobilisation).norm(), 1e-13);
  EXPECT_LT((part.fabric - direct.fabric).norm(), 1e-13);
  EXPECT_LT((part.normal - direct.normal).norm(), 1e-13);
  EXPECT_LT((part.tangential - direct.tangential).norm(), 1e-13);
  EXPECT_NEAR(part.lambda, direct.lambda, 1e-13);
  EXPECT_THROW(span.weighted(std::vector<double>(3, 1.0)), std::invalid_argument);
}

TEST(Correlation, PearsonAndSpearmanOnKnownSamples) {
  const std::vector<double> x = {1, 2, 3, 4, 5, 6};
  std::vector<double> cubic, reversed;
  for (double v : x) cubic.push_back(v * v * v), reversed.push_back(-v);
  EXPECT_NEAR(spearman_correlation(x, cubic), 1.0, 1e-15);  // monotone: rank correlation 1
  EXPECT_LT(pearson_correlation(x, cubic), 0.99);           // but not linear
  EXPECT_NEAR(pearson_correlation(x, reversed), -1.0, 1e-15);
  // Ties get their mean rank: ranks of {1, 1, 2} are {0.5, 0.5, 2}.
  EXPECT_NEAR(spearman_correlation({1, 1, 2}, {0.5, 0.5, 2}), 1.0, 1e-15);
  EXPECT_EQ(pearson_correlation({1, 1, 1}, {1, 2, 3}), 0.0);  // no spread: defined as 0
}

TEST(BranchCheck, MeasuresTheAngleBetweenBranchAndNormal) {
  std::mt19937_64 rng(13);
  std::vector<ContactRecord> contacts;
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector3d n = random_unit(rng);
    const Eigen::Vector3d tilted = std::cos(kPi / 6) * n + std::sin(kPi / 6) * n.unitOrthogonal();
    const double length = 1.0 + 0.001 * k;
    contacts.push_back(make_contact(n, 2.0 * length, Eigen::Vector3d::Zero(), length * tilted));
  }
  const BranchCheck check = branch_check(contacts);
  EXPECT_NEAR(check.mean_angle_deg, 30.0, 1e-9);
  EXPECT_NEAR(check.p95_angle_deg, 30.0, 1e-9);
  EXPECT_NEAR(check.pearson_length_force, 1.0, 1e-12);  // f_n proportional to l.n
  EXPECT_NEAR(check.spearman_length_force, 1.0, 1e-12);
}

// The cells of the §6 checks about z (the axis of these synthetic fields).
const DirectionCells kCellsAboutZ(41);

// A density with a known fourth-order term: the moments give back |b4| / |b2|, and the
// second-order form from A fits only as well as b4 allows.
TEST(Truncation, TheDensityGivesBackItsFourthOrderRatio) {
  for (const double b4 : {0.0, 0.3}) {
    std::vector<ContactRecord> contacts;
    for (const auto& n : legendre_normals(0.6, 400'000, 14, b4)) contacts.push_back(make_contact(n, 1.0));
    const DirectionalTensors t = directional_tensors(contacts, kUnitScale, 0.5);
    const TruncationCheck check =
        truncation_check(contacts, kUnitScale, t.fabric, t.lambda, t.normal, kCellsAboutZ);
    EXPECT_NEAR(check.density.fourth_order_ratio, b4 / 0.6, 0.03) << "b4 " << b4;
    if (b4 == 0.0) {
      EXPECT_GT(check.density.r_squared, 0.995);
      EXPECT_LT(check.density.chi2_per_dof, 2.0);  // consistent with counting noise
    } else {
      EXPECT_LT(check.density.r_squared, 0.9);
      EXPECT_GT(check.density.chi2_per_dof, 20.0);
    }
  }
}

// Forces that are exactly second order in the direction: f_n = Lambda (1 + n.F n) and the
// Ouadfel-Rothenburg tangential field Lambda (G n - (n.G n) n) fit with R^2 ~ 1, no 4th order;
// a normal force with a P4 term has the fourth-order ratio of its Legendre series.
TEST(Truncation, SecondOrderForceFieldsFitExactly) {
  std::mt19937_64 rng(15);
  const Eigen::Matrix3d f0 = Eigen::Vector3d(-0.3, -0.3, 0.6).asDiagonal();
  const Eigen::Matrix3d g0 = Eigen::Vector3d(-0.1, -0.1, 0.2).asDiagonal();
  const double lambda0 = 2.0;
  std::vector<ContactRecord> contacts, fourth;
  for (int k = 0; k < 200'000; ++k) {
    const Eigen::Vector3d n = random_unit(rng);
    const Eigen::Vector3d gn = g0 * n;
    const double p2 = 1.5 * n.z() * n.z() - 0.5;
    const double p4 = (35.0 * std::pow(n.z(), 4) - 30.0 * n.z() * n.z() + 3.0) / 8.0;
    contacts.push_back(make_contact(n, lambda0 * (1.0 + n.dot(f0 * n)), lambda0 * (gn - n.dot(gn) * n)));
    fourth.push_back(make_contact(n, lambda0 * (1.0 + 0.4 * p2 + 0.1 * p4)));
  }
  const DirectionalTensors t = directional_tensors(contacts, kUnitScale, 0.5);
  const TruncationCheck check = truncation_check(contacts, kUnitScale, t.fabric, t.lambda, t.normal, kCellsAboutZ);
  // The fourth-order ratios' sampling noise at this N is about 0.02 per component.
  EXPECT_GT(check.normal_force.r_squared, 0.9999);
  EXPECT_LT(check.normal_force.fourth_order_ratio, 0.05);
  EXPECT_GT(check.tangential_force.r_squared, 0.9999);
  EXPECT_LT(check.tangential_force.fourth_order_ratio, 0.05);
  const DirectionalTensors t4 = directional_tensors(fourth, kUnitScale, 0.5);
  const TruncationCheck check4 = truncation_check(fourth, kUnitScale, t4.fabric, t4.lambda, t4.normal, kCellsAboutZ);
  EXPECT_NEAR(check4.normal_force.fourth_order_ratio, 0.25, 0.06);
  EXPECT_LT(check4.normal_force.r_squared, 0.99);
}

// sff-theory.md §6.2 general form: an axisymmetric fabric and force field tilted by 45 degrees
// fits as well as untilted, with cells about the stress's principal axes (the old bands about z
// could not describe a tilted fabric).
TEST(Truncation, ATiltedFabricFitsAsWellAsAnUntiltedOne) {
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.25 * kPi, Eigen::Vector3d(1.0, 0.3, 0.0).normalized()).toRotationMatrix();
  std::vector<ContactRecord> upright, tilted;
  std::mt19937_64 rng(19);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (const auto& n : legendre_normals(0.8, 100'000, 20)) {
    const double fn = 1.0 + 0.5 * (1.5 * n.z() * n.z() - 0.5) + noise(rng);
    const Eigen::Vector3d ft = 0.2 * (Eigen::Vector3d::UnitZ() - n.z() * n) * n.z();
    upright.push_back(make_contact(n, fn, ft));
    tilted.push_back(make_contact(r * n, fn, r * ft));
  }
  TruncationCheck checks[2];
  for (int k = 0; k < 2; ++k) {
    const std::vector<ContactRecord>& set = k == 0 ? upright : tilted;
    const DirectionalTensors t = directional_tensors(set, kUnitScale, 0.5);
    const DirectionCells cells = DirectionCells::principal(41, contact_stress(set, 1.0));
    checks[k] = truncation_check(set, kUnitScale, t.fabric, t.lambda, t.normal, cells);
  }
  EXPECT_GT(checks[0].density.r_squared, 0.99);
  EXPECT_GT(checks[0].normal_force.r_squared, 0.99);
  for (const auto member : {&TruncationCheck::density, &TruncationCheck::normal_force,
                            &TruncationCheck::tangential_force}) {
    const TruncationFit& a = checks[0].*member;
    const TruncationFit& b = checks[1].*member;
    EXPECT_NEAR(a.r_squared, b.r_squared, 1e-9);
    EXPECT_NEAR(a.relative_l2, b.relative_l2, 1e-9);
    EXPECT_NEAR(a.chi2_per_dof, b.chi2_per_dof, 1e-9 * a.chi2_per_dof);
    EXPECT_NEAR(a.fourth_order_ratio, b.fourth_order_ratio, 1e-9);
  }
}

// sff-theory.md §8: where 1 + n.A.n comes near 0 the second-order weight is unusable; the
// estimators flag it (binned_weights, for the report's warning) and use the binned density, and
// still give back the normal-force field. At b = -1 (no normal along z at all) they stay finite;
// the force along z, where there are no contacts, is then an extrapolation no estimator makes.
TEST(DirectionWeights, AVeryStrongFabricFallsBackToBinnedWeights) {
  const Eigen::Matrix3d f0 = Eigen::Vector3d(-0.2, -0.2, 0.4).asDiagonal();
  for (const double b : {-0.95, -1.0}) {
    std::vector<ContactRecord> contacts;
    for (const auto& n : legendre_normals(b, 200'000, 21)) contacts.push_back(make_contact(n, 2.0 * (1.0 + n.dot(f0 * n))));
    const DirectionalTensors t = directional_tensors(contacts, kUnitScale, 0.5);
    EXPECT_TRUE(t.binned_weights) << b;
    EXPECT_NEAR(t.min_density, 1.0 + b, 0.01) << b;  // A = b diag(-1/2, -1/2, 1)
    EXPECT_TRUE(t.normal.allFinite() && t.tangential.allFinite()) << b;
    if (b == -1.0) continue;
    EXPECT_NEAR(t.lambda, 2.0, 0.01);
    EXPECT_LT((t.normal - f0).norm(), 0.02);
  }
  std::vector<ContactRecord> mild;
  for (const auto& n : legendre_normals(-0.5, 20'000, 22)) mild.push_back(make_contact(n, 1.0));
  EXPECT_FALSE(directional_tensors(mild, kUnitScale, 0.5).binned_weights);
}

// Guo & Zhao (2013): a constant normal force with a direction-dependent branch length has no
// normal-force anisotropy a^n, while this project's a_n (of f_hat ~ f_n l) takes that of l.
TEST(GuoZhao, BranchLengthAnisotropyIsSeparatedFromTheForces) {
  std::mt19937_64 rng(23);
  const Eigen::Matrix3d b0 = Eigen::Vector3d(-0.1, -0.1, 0.2).asDiagonal();
  const Eigen::Matrix3d g0 = Eigen::Vector3d(-0.05, 0.15, -0.1).asDiagonal();
  std::vector<ContactRecord> contacts;
  for (int k = 0; k < 200'000; ++k) {
    const Eigen::Vector3d n = random_unit(rng);
    const double length = 1.0 + n.dot(b0 * n);
    const Eigen::Vector3d gn = g0 * n;
    contacts.push_back(make_contact(n, 2.0, 2.0 * (gn - n.dot(gn) * n), length * n));
  }
  const DirectionalTensors t = directional_tensors(contacts, kUnitScale, 0.5);
  const GuoZhaoAnisotropy g = guo_zhao_anisotropy(contacts, DirectionWeight(contacts, t.fabric));
  EXPECT_NEAR(g.mean_normal_force, 2.0, 0.005);
  EXPECT_NEAR(g.mean_branch_length, 1.0, 0.005);
  EXPECT_LT(g.normal.norm(), 0.01);                   // a_n(Guo & Zhao) = 0
  EXPECT_LT((g.branch - b0).norm(), 0.01);            // a^l = B
  EXPECT_NEAR(triaxial(t.normal), triaxial(g.branch), 0.01);  // a_n(today) ~ a_l
  EXPECT_LT((g.tangential - g0).norm(), 0.02);        // Ouadfel-Rothenburg a^t
  EXPECT_THROW(guo_zhao_anisotropy(std::vector<ContactRecord>{}, DirectionWeight({}, t.fabric)),
               StatisticsError);
}

TEST(Rose, SectorsShareTheContactsAndFollowTheDensity) {
  std::vector<ContactRecord> contacts;
  for (const auto& n : legendre_normals(1.0, 200'000, 16)) contacts.push_back(make_contact(n, 1.0 + n.z() * n.z()));
  const std::vector<RoseSector> rose = rose_diagram(contacts, kUnitScale, 36);
  double total = 0.0;
  for (const RoseSector& s : rose) total += s.fraction;
  EXPECT_NEAR(total, 1.0, 1e-12);
  // More contacts, and larger forces, towards the loading axis (psi = 90 deg) than across it.
  EXPECT_GT(rose[17].fraction, 1.3 * rose[0].fraction);
  EXPECT_GT(rose[17].normal_force, 1.3 * rose[0].normal_force);
}

TEST(Independence, SeparatesIndependentFromCoupledMobilisation) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double mu = 0.5;
  std::vector<ContactRecord> independent, coupled;
  for (int k = 0; k < 100'000; ++k) {
    const Eigen::Vector3d n = random_unit(rng), meridian = Eigen::Vector3d::UnitZ() - n.z() * n;
    if (meridian.norm() < 1e-6) continue;
    // Towards the loading axis from either hemisphere: sym(tau n) has a non-zero mean.
    const Eigen::Vector3d tau = (n.z() >= 0.0 ? 1.0 : -1.0) * meridian.normalized();
    const double fn = 0.1 + unit(rng);
    const double xi = unit(rng);
    independent.push_back(make_contact(n, fn, xi * mu * fn * tau));
    coupled.push_back(make_contact(n, fn, (fn / 1.1) * mu * fn * tau));  // xi grows with f_n
  }
  for (const auto* set : {&independent, &coupled}) {
    const DirectionalTensors t = directional_tensors(*set, kUnitScale, mu);
    const IndependenceCheck check = independence_check(*set, mu, kUnitScale, t.lambda, t.normal,
                                                       t.weighted_mobilisation, t.mobilisation,
                                                       kCellsAboutZ);
    if (set == &independent) {
      EXPECT_LT(std::abs(check.mean_spearman), 0.02);
      EXPECT_LT(check.coupling_error, 0.03);
    } else {
      EXPECT_GT(check.mean_spearman, 0.99);
      EXPECT_GT(check.coupling_error, 0.1);
    }
  }
}

TEST(Coaxiality, MeasuresTheAngleBetweenMajorAxes) {
  const Eigen::Matrix3d axial = Eigen::Vector3d(-0.5, -0.5, 1.0).asDiagonal();
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Matrix3d tilted = r * axial * r.transpose();
  const Eigen::Matrix3d bedding = r * Eigen::Vector3d(1.0, 0.2, -1.2).asDiagonal() * r.transpose();
  const CoaxialityCheck check = coaxiality_check(axial + Eigen::Matrix3d::Identity(), tilted, axial,
                                                 axial, bedding);
  EXPECT_NEAR(check.fabric_deg, 0.3 * 180.0 / kPi, 1e-9);
  EXPECT_NEAR(check.normal_deg, 0.0, 1e-9);
  // bedding has its major axis along x: 90 deg from the stress axis.
  EXPECT_NEAR(check.mobilisation_deg, 90.0, 1e-6);
  EXPECT_NEAR(principal_axis(tilted).tilt_deg, 0.3 * 180.0 / kPi, 1e-9);
}

TEST(StrongWeak, SplitsByTheMeanNormalForce) {
  // Normals along z carry force 3, along x force 1: mean 2, so z contacts are the strong ones.
  std::vector<ContactRecord> contacts;
  for (int k = 0; k < 10; ++k) {
    contacts.push_back(make_contact(Eigen::Vector3d::UnitZ(), 3.0));
    contacts.push_back(make_contact(Eigen::Vector3d::UnitX(), 1.0));
  }
  const StrongWeakSplit split = strong_weak_split(contacts, kUnitScale, 1.0);
  EXPECT_DOUBLE_EQ(split.strong_fraction, 0.5);
  EXPECT_NEAR(split.a_c_strong, 7.5, 1e-12);   // all normals along z: A = 7.5 dev(e_z e_z)
  EXPECT_NEAR(split.a_c_weak, -3.75, 1e-12);   // all along x
  EXPECT_NEAR(split.strong_q_share, 3.0 / (3.0 - 0.5), 1e-12);  // q = 30 - 10/2 of which 30
  EXPECT_NEAR(split.weak_p_share, 10.0 / 40.0, 1e-12);
}

// Isotropic normals: a_c has standard deviation 1.5 x 2.24 / sqrt(N); the 95 % interval must have
// about 3.92 of those as width, cover 0, and not depend on the thread count.
TEST(Bootstrap, IntervalsHaveTheSamplingWidthAndAreReproducible) {
  std::mt19937_64 rng(18);
  const int n = 20'000;
  std::vector<ContactRecord> contacts;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d normal = random_unit(rng);
    contacts.push_back(make_contact(normal, 1.0, 0.2 * normal.unitOrthogonal()));
  }
  const BootstrapIntervals b = bootstrap_coefficients(contacts, kUnitScale, 0.5, 200, 42);
  const double sd = 1.5 * std::sqrt(7.5 * 7.5 * 4.0 / 45.0) / std::sqrt(n);
  EXPECT_NEAR(b.a_c.high - b.a_c.low, 3.92 * sd, 0.2 * 3.92 * sd);
  EXPECT_LT(b.a_c.low, 0.0);
  EXPECT_GT(b.a_c.high, 0.0);
  EXPECT_LE(b.a_c.low, b.a_c.estimate);
  EXPECT_GE(b.a_c.high, b.a_c.estimate);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const BootstrapIntervals serial = bootstrap_coefficients(contacts, kUnitScale, 0.5, 200, 42);
  omp_set_num_threads(threads);
  EXPECT_EQ(serial.a_c.low, b.a_c.low);
  EXPECT_EQ(serial.m.high, b.m.high);
  const BootstrapIntervals other = bootstrap_coefficients(contacts, kUnitScale, 0.5, 200, 43);
  EXPECT_NE(other.a_c.low, b.a_c.low);
}

}  // namespace
}  // namespace sff
