// Checks on small packings: compaction, stress, friction limit, detection, determinism,
// stability diagnostics.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <memory>

#include "dem/compaction.h"
#include "dem/packing.h"
#include "dem/simulation.h"
#include "specimen_fixture.h"

namespace dem {
namespace {

constexpr int kBodies = 150;
constexpr std::uint64_t kSeed = 7;

Simulation loose_specimen(double friction, std::uint64_t seed = kSeed,
                          double centre_distance_ratio = 0.5) {
  return testing::loose_specimen(kBodies, friction, seed, centre_distance_ratio);
}

// One compacted specimen shared by the tests that only read or copy it.
class CompactedSpecimen : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    specimen_ = std::make_unique<Simulation>(loose_specimen(0.3));
    CompactionOptions options;
    options.target_stress = 100e3;
    options.max_unbalanced_force = 1e-4;
    result_ = compact_isotropically(*specimen_, options);
  }
  static void TearDownTestSuite() { specimen_.reset(); }
  static std::unique_ptr<Simulation> specimen_;
  static CompactionResult result_;
};
std::unique_ptr<Simulation> CompactedSpecimen::specimen_;
CompactionResult CompactedSpecimen::result_;

TEST_F(CompactedSpecimen, ReachesTheTargetStressAndRest) {
  ASSERT_TRUE(result_.converged) << result_.summary();
  for (int w = 0; w < 6; ++w)
    EXPECT_NEAR(specimen_->wall_forces()[w] / specimen_->wall_area(w), 100e3, 1e3);
  // A jammed frictional packing: once the rattlers (bodies held by fewer than two contacts,
  // walls included) are removed, each body has at least d + 1 = 4 contacts on average.
  const std::vector<ContactRecord> contacts = specimen_->contact_records(true);
  std::vector<int> count(kBodies, 0);
  std::vector<bool> rattler(kBodies, false);
  for (bool changed = true; changed;) {
    std::fill(count.begin(), count.end(), 0);
    for (const ContactRecord& c : contacts) {
      const bool a_active = c.body_a < 0 || !rattler[c.body_a];
      if (!a_active || rattler[c.body_b]) continue;
      ++count[c.body_b];
      if (c.body_a >= 0) ++count[c.body_a];
    }
    changed = false;
    for (int b = 0; b < kBodies; ++b)
      if (!rattler[b] && count[b] < 2) rattler[b] = changed = true;
  }
  int bodies = 0, pairs = 0;
  for (int b = 0; b < kBodies; ++b) bodies += !rattler[b];
  for (const ContactRecord& c : contacts)
    pairs += c.body_a >= 0 && !rattler[c.body_a] && !rattler[c.body_b];
  ASSERT_GT(bodies, kBodies / 2);
  EXPECT_GE(2.0 * pairs / bodies, 4.0) << bodies << " bodies without rattlers";
}

TEST_F(CompactedSpecimen, LoveWeberStressEqualsTheWallStress) {
  ASSERT_TRUE(result_.converged) << result_.summary();
  const Simulation& sim = *specimen_;
  const Eigen::Matrix3d with_walls = sim.contact_stress(true);
  const Eigen::Matrix3d bodies_only = sim.contact_stress(false);
  for (int a = 0; a < 3; ++a) {
    const double wall_stress =
        0.5 * (sim.wall_forces()[2 * a] / sim.wall_area(2 * a) +
               sim.wall_forces()[2 * a + 1] / sim.wall_area(2 * a + 1));
    // Particle form: equal to the boundary stress up to the unbalanced force (1e-4 here).
    EXPECT_NEAR(with_walls(a, a), wall_stress, 5e-3 * wall_stress);
    // Contact form: lower by the wall layer, about 2 r / L for this ~10-grain box.
    const double length = sim.walls()[2 * a + 1].position - sim.walls()[2 * a].position;
    const double layer = 2.0 * 0.025e-3 / length;
    EXPECT_LT(bodies_only(a, a), wall_stress);
    EXPECT_GT(bodies_only(a, a), (1.0 - 2.0 * layer) * wall_stress);
  }
  // Off-diagonal terms need not vanish: a frictionless wall still carries a moment through an
  // uneven pressure. Torque balance keeps the particle form symmetric, which sym() would hide,
  // so it is not asserted here.
}

TEST_F(CompactedSpecimen, DetectionFindsEveryOverlap) {
  const Simulation& sim = *specimen_;
  const Particles& p = sim.particles();
  // Every overlapping pair of spheres of different bodies, by brute force.
  int brute = 0;
  for (int i = 0; i < p.num_spheres(); ++i)
    for (int j = i + 1; j < p.num_spheres(); ++j) {
      if (p.sphere_body[i] == p.sphere_body[j]) continue;
      const double reach = p.sphere_radius[i] + p.sphere_radius[j];
      if ((p.sphere_position[i] - p.sphere_position[j]).squaredNorm() < reach * reach) ++brute;
    }
  // The next step computes its forces on exactly these positions.
  Simulation next = sim;
  next.step();
  EXPECT_EQ(next.num_touching_pairs(), brute);
  EXPECT_GT(brute, kBodies);
}

TEST_F(CompactedSpecimen, TangentialForceNeverExceedsCoulomb) {
  Simulation sim = *specimen_;
  // Shear it: platens in at a strain rate of ~20 /s, lateral walls held by the servo.
  const double height = sim.walls()[5].position - sim.walls()[4].position;
  sim.walls()[4].mode = sim.walls()[5].mode = WallMode::kVelocity;
  sim.walls()[4].velocity = 10.0 * height;
  sim.walls()[5].velocity = -10.0 * height;
  double worst = 0.0;
  int sliding_checks = 0;
  for (int k = 0; k < 40; ++k) {
    sim.run(250);
    const double u = sim.max_friction_utilisation();
    worst = std::max(worst, u);
    sliding_checks += u > 1.0 - 1e-9;
  }
  EXPECT_LE(worst, 1.0 + 1e-12);
  EXPECT_GT(sliding_checks, 0);  // contacts did reach the limit: the check is not vacuous
}

TEST(Compaction, LowerFrictionGivesDenserPacking) {
  auto void_ratio = [](double friction) {
    Simulation sim = loose_specimen(friction);
    CompactionOptions options;
    EXPECT_TRUE(compact_isotropically(sim, options).converged);
    double solid = 0.0;
    for (double v : sim.particles().volume) solid += v;
    return sim.box_volume() / solid - 1.0;
  };
  EXPECT_LT(void_ratio(0.0), void_ratio(0.5) - 0.03);
}

// Shears a copy of the compacted specimen for a few hundred steps on `threads` threads, with
// every loop parallel however small the scene.
Simulation sheared_copy(const Simulation& specimen, int threads) {
  omp_set_num_threads(threads);
  SimulationOptions options = specimen.options();
  options.min_parallel_items = 1;
  Particles particles = specimen.particles();
  Simulation sim(std::move(particles), specimen.walls(), specimen.contact_parameters(), options);
  sim.walls()[4].mode = sim.walls()[5].mode = WallMode::kVelocity;
  sim.walls()[4].velocity = 0.02;
  sim.walls()[5].velocity = -0.02;
  sim.run(600);
  omp_set_num_threads(omp_get_num_procs());
  return sim;
}

TEST_F(CompactedSpecimen, RunsAreBitIdenticalForAnyThreadCount) {
  const Simulation one = sheared_copy(*specimen_, 1);
  const Simulation two = sheared_copy(*specimen_, 2);
  ASSERT_GT(one.num_touching_pairs(), kBodies);
  for (int k = 0; k < one.particles().num_bodies(); ++k) {
    ASSERT_EQ(one.particles().position[k], two.particles().position[k]);
    ASSERT_EQ(one.particles().angular_momentum[k], two.particles().angular_momentum[k]);
  }
  EXPECT_EQ(one.contact_stress(), two.contact_stress());
  EXPECT_NE(one.particles().position[0], specimen_->particles().position[0]);  // it did move
}

TEST(Determinism, SameSeedSameRunOtherSeedOtherRun) {
  auto run = [](std::uint64_t seed) {
    Simulation sim = loose_specimen(0.5, seed);
    for (Wall& w : sim.walls()) {
      w.mode = WallMode::kStress;
      w.target_stress = 100e3;
    }
    sim.run(3000);
    return sim;
  };
  const Simulation a = run(kSeed), b = run(kSeed), c = run(kSeed + 1);
  for (int k = 0; k < a.particles().num_bodies(); ++k)
    ASSERT_EQ(a.particles().position[k], b.particles().position[k]);
  EXPECT_NE(a.particles().position[0], c.particles().position[0]);
}

TEST(TimeStep, AboveTheCriticalStepIsRefused) {
  Particles p = random_lattice_packing(8, GrainSpec{}, 1);
  Simulation probe(p, {}, ContactParameters{}, SimulationOptions{});
  // dt_c is leapfrog's limit 2/omega_max of the packing's springs: any step past it, by 1 % or
  // more, is refused before the run.
  for (double factor : {1.01, 1.8, 2.5}) {
    SimulationOptions options;
    options.time_step = factor * probe.critical_time_step();
    try {
      Simulation sim(p, {}, ContactParameters{}, options);
      FAIL() << "a time step of " << factor << " critical steps was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("exceeds the critical step"), std::string::npos) << e.what();
    }
  }
  SimulationOptions at_limit;
  at_limit.time_step = probe.critical_time_step();
  EXPECT_NO_THROW(Simulation(p, {}, ContactParameters{}, at_limit));
}

TEST(TimeStep, AJammedPackingAtTheCriticalStepRunsOnStably) {
  // The largest accepted step (safety 1, following the contacts) on a compacted frictional,
  // damped packing at rest: 20,000 steps without the overlap limit being reached (runtime
  // instability stops a run with "unstable run":
  // ExtremeInputs.SoftGrainsStopWithAMessageNamingTheStiffness).
  Simulation reference = loose_specimen(0.3);
  CompactionOptions compaction;
  compaction.max_unbalanced_force = 1e-2;
  ASSERT_TRUE(compact_isotropically(reference, compaction).converged);
  SimulationOptions options = reference.options();
  options.time_step_safety = 1.0;
  Particles p = reference.particles();
  for (int b = 0; b < p.num_bodies(); ++b) p.velocity[b].setZero();
  Simulation sim(std::move(p), reference.walls(), reference.contact_parameters(), options);
  EXPECT_NO_THROW(sim.run(20000));
  EXPECT_LT(sim.unbalanced_force_ratio(), 0.1);
}

TEST(Scene, DeclaresOnlyTheFeaturesItUses) {
  Simulation spheres = loose_specimen(0.0, kSeed, 0.0);
  EXPECT_FALSE(spheres.features().clumps);
  EXPECT_FALSE(spheres.features().friction);
  EXPECT_FALSE(spheres.features().rotation());
  EXPECT_FALSE(spheres.features().gravity);
  Simulation clumps = loose_specimen(0.5);
  EXPECT_TRUE(clumps.features().clumps);
  EXPECT_TRUE(clumps.features().friction);
  EXPECT_TRUE(clumps.features().local_damping);
  EXPECT_EQ(spheres.features().describe(), "spheres, local damping, no rotation");
}

}  // namespace
}  // namespace dem
