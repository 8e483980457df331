// Numerical stability under stress (issue 8): energy conservation from far below the critical
// time step to 0.3 of it, and up to it with friction (above it: TimeStep.* in packing_test.cc),
// the wall servo at 10 kPa and 1 MPa, extreme inputs, and deterministic replay of a run file.
// Each scene is small (≤ 150 clumps) so the file stays quick; the long servo runs are
// bench/stress/.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <random>
#include <vector>

#include "dem/compaction.h"
#include "dem/critical_step.h"
#include "dem/packing.h"
#include "dem/run_config.h"
#include "dem/run_file_io.h"
#include "dem/simulation.h"
#include "dem/specimen.h"
#include "dem/triaxial.h"
#include "specimen_fixture.h"

namespace dem {
namespace {

constexpr int kBodies = 150;

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "/sffcal_stability_" + std::to_string(getpid()) + "_" + name;
}

// A dense specimen (frictionless compaction) at 100 kPa, shared by most tests below.
const Simulation& dense_specimen() {
  static const Simulation specimen = [] {
    Simulation sim = testing::loose_specimen(kBodies, 0.0, 21);
    CompactionOptions compaction;
    compaction.max_unbalanced_force = 1e-2;
    if (!compact_isotropically(sim, compaction).converged)
      throw std::runtime_error("dense specimen: compaction did not settle");
    return sim;
  }();
  return specimen;
}

// ---- time step: energy of a frictionless, undamped packing ----

// Elastic energy of the normal springs, 0.5 f_n overlap per contact (frictionless, no dashpot).
double elastic_energy(const Simulation& sim) {
  double e = 0.0;
  for (const ContactRecord& c : sim.contact_records(true)) e += 0.5 * c.normal_force * c.overlap;
  return e;
}

// A jammed frictionless packing at 100 kPa in a fixed box, given seeded random velocities with as
// much kinetic as elastic energy, then run without damping at `time_step` (0: `safety` x dt_c).
struct EnergyScene {
  SimulationState state;
  ContactParameters law;
  SimulationOptions options;
};

EnergyScene jammed_scene_with_velocities(std::uint64_t velocity_seed) {
  const Simulation& sim = dense_specimen();
  EnergyScene s{sim.state(), sim.contact_parameters(), sim.options()};
  s.law.friction = 0.0;
  s.law.wall_friction = 0.0;
  s.options.local_damping = 0.0;
  for (Wall& w : s.state.walls) {
    w.mode = WallMode::kVelocity;
    w.velocity = 0.0;
  }
  set_random_velocities(s.state.particles, elastic_energy(sim), velocity_seed);
  return s;
}

const EnergyScene& frictionless_jammed_scene() {
  static const EnergyScene scene = jammed_scene_with_velocities(5);
  return scene;
}

// |E - E0| / E0 at `samples` instants spread over `duration` seconds. The energy at step t pairs
// the elastic energy at x(t) with the mean of the kinetic energies at t -/+ dt/2 (leapfrog).
std::vector<double> energy_errors(Simulation& sim, double duration, int samples) {
  const auto steps = static_cast<std::int64_t>(std::ceil(duration / sim.time_step()));
  const std::int64_t between = std::max<std::int64_t>(1, steps / samples - 1);
  std::vector<double> errors;
  double e0 = 0.0;
  for (int k = 0; k < samples; ++k) {
    const double before = sim.kinetic_energy();
    sim.step();
    const double e = elastic_energy(sim) + 0.5 * (before + sim.kinetic_energy());
    if (k == 0) e0 = e;
    errors.push_back(std::abs(e - e0) / e0);
    sim.run(between);
  }
  return errors;
}

double largest(const std::vector<double>& v, std::size_t from, std::size_t to) {
  return *std::max_element(v.begin() + static_cast<std::ptrdiff_t>(from),
                           v.begin() + static_cast<std::ptrdiff_t>(to));
}

Simulation energy_scene_at(double safety, double time_step = 0.0,
                           const EnergyScene& scene = frictionless_jammed_scene()) {
  SimulationOptions options = scene.options;
  options.time_step_safety = safety;
  options.time_step = time_step;
  return Simulation(scene.state, scene.law, options);
}

TEST(TimeStepSweep, EnergyErrorIsSmallAndSecondOrderBelowTheCriticalStep) {
  // The same physical time, 500 critical steps (about 160 periods of the stiffest mode: dt_c =
  // 2/omega_max), at each safety factor, from 0.03 to 0.3 of the limit (0.05 to 0.5 of the
  // per-body estimate of earlier versions). The grains rattle (as much kinetic as elastic
  // energy), so a run is chaotic and its largest error one sample, and the compacted specimen is
  // itself the end of a chaotic run: a one-bit change of the contact normals (another specimen)
  // raised the errors by 30-60 % and the observed order 0.05 -> 0.1 fell to 1.68 with one
  // velocity seed (issue 16). The error is the mean over three velocity seeds (orders 2.26, 1.87
  // and 2.10 here; 2.01-2.03 at the earlier factors).
  const std::vector<EnergyScene> scenes = {jammed_scene_with_velocities(5),
                                           jammed_scene_with_velocities(6),
                                           jammed_scene_with_velocities(7)};
  const double dt_c = energy_scene_at(1.0).critical_time_step();
  const std::vector<double> safety = {0.03, 0.06, 0.12, 0.3};
  std::vector<double> error;
  for (double s : safety) {
    double sum = 0.0;
    for (const EnergyScene& scene : scenes) {
      Simulation sim = energy_scene_at(s, 0.0, scene);
      const std::vector<double> e = energy_errors(sim, 500.0 * dt_c, 50);
      sum += largest(e, 0, e.size());
      EXPECT_LT(largest(e, 0, e.size()), 0.01) << "safety " << s;
    }
    error.push_back(sum / static_cast<double>(scenes.size()));
    std::printf("safety %.2f: largest energy error over 500 dt_c, mean of %zu runs %.2e\n", s,
                scenes.size(), error.back());
  }
  // Leapfrog is second order: the error falls as dt^2 between successive safety factors.
  for (std::size_t k = 1; k < safety.size(); ++k) {
    const double order = std::log(error[k] / error[k - 1]) / std::log(safety[k] / safety[k - 1]);
    EXPECT_GT(order, 1.7) << "safety " << safety[k - 1] << " -> " << safety[k];
    EXPECT_LT(order, 2.3) << "safety " << safety[k - 1] << " -> " << safety[k];
  }
}

// Elastic energy of the tangential springs, 0.5 |f_t|^2 / k_t per contact with k_t = xi k_n and
// k_n = f_n / overlap (no dashpot).
double tangential_energy(const Simulation& sim) {
  const double xi = sim.contact_parameters().stiffness_ratio;
  double e = 0.0;
  for (const ContactRecord& c : sim.contact_records(true)) {
    if (!(c.normal_force > 0.0)) continue;
    const Eigen::Vector3d ft(c.tangential_force.data());
    e += 0.5 * ft.squaredNorm() * c.overlap / (xi * c.normal_force);
  }
  return e;
}

TEST(TimeStepSweep, AFrictionalJammedPackingOnlyLosesEnergyUpToSafetyOne) {
  // The scene above with friction (tan 30 deg between grains): slip dissipates, so the total
  // energy (kinetic + normal + tangential springs) may only fall; a step past the stable limit
  // makes it grow. 2000 critical steps at each safety factor of the stiffness-based estimate,
  // which is refreshed as the contacts change.
  const EnergyScene& scene = frictionless_jammed_scene();
  ContactParameters law = scene.law;
  law.friction = ContactParameters{}.friction;
  for (double safety : {0.3, 0.5, 0.7, 1.0}) {
    SimulationOptions options = scene.options;
    options.time_step_safety = safety;
    Simulation sim(scene.state, law, options);
    // As energy_errors: the springs at x(t) with the mean kinetic energy at t -/+ dt/2.
    auto total = [&] {
      const double before = sim.kinetic_energy();
      sim.step();
      return 0.5 * (before + sim.kinetic_energy()) + elastic_energy(sim) + tangential_energy(sim);
    };
    const double e0 = total();
    double previous = e0, largest_rise = 0.0;
    const int samples = 100;
    const auto between = static_cast<std::int64_t>(2000.0 / safety / samples);
    for (int k = 0; k < samples; ++k) {
      sim.run(between);
      const double e = total();
      largest_rise = std::max(largest_rise, (e - previous) / e0);
      previous = e;
    }
    std::printf("safety %.1f: largest rise between samples %.2e E0, final %.4f E0, dt %.3g s "
                "(one-contact limit %.3g s)\n",
                safety, largest_rise, previous / e0, sim.time_step(),
                one_contact_time_step(sim.particles(), law, options.density_scaling));
    EXPECT_LT(largest_rise, 1e-3) << "safety " << safety;
    EXPECT_LT(previous, e0) << "safety " << safety;
  }
}

// ---- the wall servo at 10 kPa and 1 MPa ----

double wall_stress_error(const Simulation& sim, int w, double target) {
  return std::abs(sim.wall_forces()[w] / sim.wall_area(w) - target) / target;
}

// Re-consolidates the shared specimen to `pressure`, then shears it to 0.5 % axial strain,
// sampling the wall speeds at every acceptance check and series row (Servo.NeverExceedsItsSpeedCap
// covers every step).
void check_servo_at(double pressure) {
  Simulation sim(dense_specimen().state(), dense_specimen().contact_parameters(),
                 dense_specimen().options());
  const double cap = sim.options().servo.max_speed;
  double fastest = 0.0;
  auto record_wall_speeds = [&] {
    for (const Wall& w : sim.walls()) fastest = std::max(fastest, std::abs(w.velocity));
  };
  CompactionOptions compaction;
  compaction.target_stress = pressure;
  compaction.max_unbalanced_force = 1e-2;
  const CompactionResult result =
      compact_isotropically(sim, compaction, [&](const CompactionResult&) {
        record_wall_speeds();
      });
  ASSERT_TRUE(result.converged) << result.summary();
  for (int w = 0; w < 6; ++w)
    EXPECT_LE(wall_stress_error(sim, w, pressure), compaction.stress_tolerance) << "wall " << w;
  EXPECT_LE(fastest, cap * (1.0 + 1e-12));
  EXPECT_GT(fastest, 0.0);

  Simulation shear = testing::shearing_copy(sim);
  TriaxialOptions options;
  options.confining_stress = pressure;
  // Quasi-static at every pressure: I = rate d sqrt(rho / p) about 5e-4.
  options.strain_rate = 60.0 * std::sqrt(pressure / 100e3);
  options.max_axial_strain = 0.005;
  options.output_strain_interval = 2.5e-4;
  options.critical_min_strain = 1.0;
  TriaxialTest test(shear, options);
  fastest = 0.0;
  int lateral_walls_moving_out = 0;
  const TriaxialSummary summary = test.run(nullptr, [&](const TriaxialProgress&) {
    for (int axis = 0; axis < 2; ++axis)
      for (bool upper : {false, true}) {
        const Wall& w = shear.walls()[shear.box_wall(axis, upper)];
        fastest = std::max(fastest, std::abs(w.velocity));
        lateral_walls_moving_out += (upper ? w.velocity : -w.velocity) > 0.0;
      }
  });
  EXPECT_LT(summary.max_inertial_number, 1e-3) << summary.describe();
  EXPECT_LT(summary.worst_lateral_error, 0.05) << summary.describe();
  EXPECT_LE(fastest, cap * (1.0 + 1e-12));
  EXPECT_GT(lateral_walls_moving_out, 0);  // the servo did act: the specimen bulges
}

TEST(Servo, HoldsTenKilopascal) { check_servo_at(10e3); }
TEST(Servo, HoldsOneMegapascal) { check_servo_at(1e6); }

// ---- extreme inputs ----

TEST(ExtremeInputs, SoftGrainsStopWithAMessageNamingTheStiffness) {
  // E / p = 15: the contacts of a packing at p overlap by about a quarter of the radius.
  ContactParameters law = dense_specimen().contact_parameters();
  law.youngs_modulus = 1.5e6;
  Simulation sim(dense_specimen().state(), law, dense_specimen().options());
  try {
    compact_isotropically(sim, CompactionOptions{});
    FAIL() << "grains this soft were compacted without complaint";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("too soft"), std::string::npos) << what;
    EXPECT_NE(what.find("E / stress"), std::string::npos) << what;
    EXPECT_NE(what.find("bodies "), std::string::npos) << what;
    EXPECT_NE(what.find("preparation.servo_max_speed"), std::string::npos) << what;
  }
}

// Compacts `bodies` random bodies of `grains` to 100 kPa in a box (friction 0.3, damped), checks
// every wall reached it, and returns the specimen.
Simulation compacted_box(int bodies, const GrainSpec& grains, std::uint64_t seed,
                         const ContactParameters& law, SimulationOptions options) {
  Particles p = random_lattice_packing(bodies, grains, seed);
  Eigen::Vector3d lo, hi;
  bounding_box(p, lo, hi);
  options.local_damping = 0.7;
  Simulation sim(std::move(p), box_walls(lo, hi), law, options);
  CompactionOptions compaction;
  compaction.max_unbalanced_force = 1e-2;
  const CompactionResult result = compact_isotropically(sim, compaction);
  EXPECT_TRUE(result.converged) << result.summary();
  for (int w = 0; w < 6; ++w)
    EXPECT_LE(wall_stress_error(sim, w, compaction.target_stress), compaction.stress_tolerance);
  return sim;
}

TEST(ExtremeInputs, StiffGrainsCompactWithTinyOverlaps) {
  // E / p = 1.5e5 (100 x the paper's stiffness), a small specimen; the faster servo cap keeps the
  // wall travel per step at the paper's setting, since the step is 10 x shorter.
  GrainSpec grains;
  ContactParameters law;
  law.youngs_modulus = 1.5e10;
  law.friction = 0.3;
  SimulationOptions options;
  options.servo.max_speed = 5.0;
  const Simulation sim = compacted_box(40, grains, 8, law, options);
  // Mean overlap of a packing ~ 3.5 p / E of the radius: about 2e-5 here.
  double worst = 0.0;
  for (const ContactRecord& c : sim.contact_records(false)) worst = std::max(worst, c.overlap);
  EXPECT_LT(worst / (0.5 * grains.min_diameter), 1e-3);
}

TEST(ExtremeInputs, DampedContactsCompactAtAnyDampingRatio) {
  // Contact dashpots at 0.35-1 of critical: the servo reads the dashpot's force per step of wall
  // travel as stiffness (without it these did not settle in 2 million steps, the walls
  // alternately losing their contacts and pressing twice the target). compacted_box checks that
  // the compaction converged with every wall at p'0.
  for (double ratio : {0.35, 0.5, 1.0}) {
    SCOPED_TRACE("damping ratio " + std::to_string(ratio));
    ContactParameters law;
    law.friction = 0.15;
    law.normal_damping_ratio = ratio;
    compacted_box(100, GrainSpec{}, 1, law, SimulationOptions{});
  }
}

TEST(ExtremeInputs, WideSizeRatioCompactsAndDetectsEveryOverlap) {
  GrainSpec grains;
  grains.min_diameter = 0.01e-3;  // size ratio 10
  grains.max_diameter = 0.1e-3;
  ContactParameters law;
  law.friction = 0.3;
  const Simulation sim = compacted_box(60, grains, 4, law, SimulationOptions{});
  // Every sphere, the smallest included, is still inside the box.
  const Particles& q = sim.particles();
  for (int s = 0; s < q.num_spheres(); ++s)
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_GT(q.sphere_position[s][axis], sim.walls()[sim.box_wall(axis, false)].position);
      EXPECT_LT(q.sphere_position[s][axis], sim.walls()[sim.box_wall(axis, true)].position);
    }
  // The cell grid, sized by the largest spheres, misses no overlap of the smallest.
  int brute = 0;
  for (int i = 0; i < q.num_spheres(); ++i)
    for (int j = i + 1; j < q.num_spheres(); ++j) {
      const double reach = q.sphere_radius[i] + q.sphere_radius[j];
      brute += q.sphere_body[i] != q.sphere_body[j] &&
               (q.sphere_position[i] - q.sphere_position[j]).squaredNorm() < reach * reach;
    }
  Simulation next = sim;
  next.step();
  EXPECT_EQ(next.num_touching_pairs(), brute);
  EXPECT_GT(brute, 60);
}

// Shears a copy of the dense specimen to 2 % axial strain with grain friction `mu`; returns the
// peak q/p and checks the contact law on the way.
double shear_with_friction(double mu) {
  ContactParameters law = dense_specimen().contact_parameters();
  law.friction = mu;
  SimulationOptions options = dense_specimen().options();
  options.local_damping = 0.0;
  Simulation sim(dense_specimen().state(), law, options);
  TriaxialOptions triaxial;
  triaxial.strain_rate = 100.0;
  triaxial.max_axial_strain = 0.02;
  triaxial.output_strain_interval = 0.002;
  triaxial.critical_min_strain = 1.0;
  TriaxialTest test(sim, triaxial);
  int at_the_limit = 0;
  const TriaxialSummary summary = test.run(nullptr, [&](const TriaxialProgress&) {
    if (mu == 0.0) {
      // The force is along the normal: its tangential part is the round-off of f - (f.n) n.
      for (const ContactRecord& c : sim.contact_records(true)) {
        const Eigen::Vector3d ft(c.tangential_force[0], c.tangential_force[1],
                                 c.tangential_force[2]);
        EXPECT_LE(ft.norm(), 1e-14 * c.normal_force);
        EXPECT_FALSE(c.sliding);
      }
    } else {
      const double u = sim.max_friction_utilisation();
      EXPECT_LE(u, 1.0 + 1e-12);
      at_the_limit += u > 1.0 - 1e-9;
    }
  });
  if (mu > 0.0) {
    EXPECT_GT(at_the_limit, 0) << "no contact reached the Coulomb limit";
  }
  EXPECT_TRUE(std::isfinite(summary.peak_eta));
  return summary.peak_eta;
}

TEST(ExtremeInputs, FrictionZeroAndOne) {
  const double frictionless = shear_with_friction(0.0);
  const double rough = shear_with_friction(1.0);
  EXPECT_GT(frictionless, 0.0);
  EXPECT_GT(rough, frictionless + 0.1);
}

TEST(ExtremeInputs, TwoBodiesInALargeBoxFlyAndBounce) {
  // Two clumps 2.3 mm apart in a 2.5 mm box (50 diameters): a sparse grid, no contacts, then
  // frictionless wall bounces. Kinetic energy and |momentum| per axis are kept.
  Particles p;
  p.add_body({2.5e-5, 2.5e-5}, 2650.0, {1e-4, 1e-4, 1e-4});
  p.add_body({2.5e-5, 2.5e-5}, 2650.0, {2.4e-3, 2.4e-3, 2.4e-3});
  p.velocity[0] = {2.0, 0.5, -1.0};
  p.velocity[1] = {-1.0, 2.0, 0.5};
  ContactParameters law;
  law.friction = 0.0;
  // A lone bounce lasts pi sqrt(m / k), about 2.2 steps at the default 0.7 dt_c (dt_c = 2/omega
  // = 2 sqrt(m / k) for a body on one wall), where leapfrog returns the kinetic energy only to a
  // few per cent; 0.1 dt_c resolves it to 1e-3 (docs/dem.md).
  SimulationOptions options;
  options.time_step_safety = 0.1;
  Simulation sim(std::move(p), box_walls({0, 0, 0}, {2.5e-3, 2.5e-3, 2.5e-3}), law, options);
  const double energy = sim.kinetic_energy();
  sim.run(20000);  // 0.45 ms: each body crosses part of the box and meets walls
  for (int b = 0; b < 2; ++b) ASSERT_TRUE(sim.particles().position[b].allFinite());
  EXPECT_NEAR(sim.kinetic_energy(), energy, 1e-3 * energy);
  for (int b = 0; b < 2; ++b)
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_GT(sim.particles().position[b][axis], 0.0);
      EXPECT_LT(sim.particles().position[b][axis], 2.5e-3);
    }
}

TEST(ExtremeInputs, TwoBodiesCompactOrReportWhyNot) {
  Particles p;
  p.add_body({2.5e-5, 2.5e-5}, 2650.0, {1e-4, 1e-4, 1e-4});
  p.add_body({2.0e-5, 2.0e-5}, 2650.0, {1.6e-4, 1.7e-4, 1.5e-4},
             Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 1, 0).normalized())));
  ContactParameters law;
  law.friction = 0.3;
  SimulationOptions options;
  options.local_damping = 0.7;
  Simulation sim(std::move(p), box_walls({0, 0, 0}, {2.5e-4, 2.5e-4, 2.5e-4}), law, options);
  CompactionOptions compaction;
  compaction.max_steps = 100000;
  const CompactionResult result = compact_isotropically(sim, compaction);
  for (int b = 0; b < 2; ++b) ASSERT_TRUE(sim.particles().position[b].allFinite());
  if (result.converged) {
    for (int w = 0; w < 6; ++w)
      EXPECT_LE(wall_stress_error(sim, w, compaction.target_stress), compaction.stress_tolerance);
  } else {
    EXPECT_NE(result.summary().find("NOT accepted"), std::string::npos);
  }
}

// Writes a CSV packing of two clumps whose first spheres are `gap` apart (negative: overlap).
std::string two_clump_csv(const std::string& name, double gap) {
  const std::string path = temp_path(name);
  std::ofstream out(path);
  const double d = 5e-5;
  out << "# box: 0 0 0 4e-4 4e-4 4e-4\nx,y,z,axis_x,axis_y,axis_z,diameter\n"
      << "2e-4,1.5e-4,2e-4,0,1,0,5e-5\n"
      << "2e-4," << 1.5e-4 + 1.5 * d + gap << ",2e-4,0,1,0,5e-5\n";  // spheres at +-d/4
  return path;
}

RunConfig csv_config(const std::string& path) {
  RunConfig config = parse_run_config(default_run_config_text());
  config.preparation.method = PreparationMethod::kCsv;
  config.preparation.csv_path = path;
  return config;
}

TEST(ExtremeInputs, DeeplyOverlappingInputBodiesAreRefusedByName) {
  // The facing spheres of two clumps overlap by 0.4 of their radius.
  const std::string path = two_clump_csv("deep.csv", -0.4 * 2.5e-5);
  try {
    prepare_specimen(csv_config(path), nullptr);
    FAIL() << "overlapping input bodies were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bodies 0 and 1 overlap by 0.4"), std::string::npos)
        << e.what();
  }
  std::remove(path.c_str());
}

TEST(ExtremeInputs, ShallowInputOverlapsArePushedApart) {
  // 0.1 of the radius: accepted, and released without making energy (damped, no gravity).
  const std::string path = two_clump_csv("shallow.csv", -0.1 * 2.5e-5);
  Eigen::Vector3d lo, hi;
  Particles p = load_csv_packing(path, GrainSpec{}, &lo, &hi);
  std::remove(path.c_str());
  SimulationOptions options;
  options.local_damping = 0.7;
  Simulation sim(std::move(p), box_walls(lo, hi), ContactParameters{}, options);
  const double overlap0 = 0.1 * 2.5e-5;
  const double stored = 0.5 * normal_stiffness(ContactParameters{}.youngs_modulus, 2.5e-5, 2.5e-5) *
                        overlap0 * overlap0;
  double deepest = 0.0;
  for (int k = 0; k < 100; ++k) {
    sim.run(200);
    for (int b = 0; b < 2; ++b) ASSERT_TRUE(sim.particles().position[b].allFinite());
    for (const ContactRecord& c : sim.contact_records(false))
      deepest = std::max(deepest, c.overlap);
    EXPECT_LT(sim.kinetic_energy(), stored);
  }
  EXPECT_LT(deepest, overlap0);
}

TEST(ExtremeInputs, AWallDrivenIntoABodyStopsWithAMessageNamingBoth) {
  // One sphere just fitting between the z walls; the top wall comes down at 1 m/s, faster than
  // the sphere can be pushed aside (it cannot: the bottom wall holds it). Its overlap with the
  // walls passes the limit, which is reported like a pair's, naming the body and the wall.
  Particles p;
  const double r = 2.5e-5;
  p.add_body({r, 0.0}, 2650.0, Eigen::Vector3d(2e-4, 2e-4, r), Eigen::Quaterniond::Identity());
  std::vector<Wall> walls = box_walls(Eigen::Vector3d::Zero(), Eigen::Vector3d(4e-4, 4e-4, 2.0 * r));
  for (Wall& w : walls)
    if (w.axis == 2 && w.upper) w.velocity = -1.0;
  ContactParameters law;
  law.friction = 0.0;
  Simulation sim(std::move(p), walls, law, SimulationOptions{});
  try {
    sim.run(100000);
    FAIL() << "a wall went through a body without complaint";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("unstable run at step"), std::string::npos) << what;
    EXPECT_NE(what.find("body 0 and wall "), std::string::npos) << what;
    EXPECT_NE(what.find("limit max_overlap_ratio 0.25"), std::string::npos) << what;
  }
}

// ---- deterministic replay ----

// Prepares a 40-clump specimen from the config's seed and shears it to 0.5 % into a run file.
std::string replay(const std::string& name) {
  RunConfig config = parse_run_config(default_run_config_text());
  config.seed = 3;
  config.num_bodies = 40;
  config.preparation.compaction.max_unbalanced_force = 1e-2;
  config.triaxial.strain_rate = 100.0;
  config.triaxial.max_axial_strain = 0.005;
  config.triaxial.output_strain_interval = 0.001;
  config.triaxial.snapshot_strain_interval = 0.0025;
  Simulation sim = prepare_specimen(config, nullptr);
  Simulation shear(sim.state(), config.contact, config.engine);
  const std::string path = temp_path(name);
  {
    RunFile file = RunFile::create(path, {"triaxial", config.text, config.seed, "test"},
                                   triaxial_series_names());
    TriaxialTest(shear, config.triaxial).run(&file, nullptr);
  }
  return path;
}

void expect_identical_run_files(const std::string& path_a, const std::string& path_b) {
  const RunFile a = RunFile::open(path_a), b = RunFile::open(path_b);
  ASSERT_GT(a.series_length(), 5u);
  for (const std::string& name : triaxial_series_names())
    EXPECT_EQ(a.series(name), b.series(name)) << name;
  ASSERT_EQ(a.num_snapshots(), b.num_snapshots());
  for (int k = 0; k < a.num_snapshots(); ++k) {
    const Snapshot x = a.read_snapshot(k), y = b.read_snapshot(k);
    EXPECT_EQ(x.spheres, y.spheres);
    ASSERT_EQ(x.contacts.size(), y.contacts.size());
    for (std::size_t c = 0; c < x.contacts.size(); ++c) {
      EXPECT_EQ(x.contacts[c].normal_force, y.contacts[c].normal_force);
      EXPECT_EQ(x.contacts[c].tangential_force, y.contacts[c].tangential_force);
    }
  }
}

// One thread and two give bit-identical runs (packing_test.cc,
// CompactedSpecimen.RunsAreBitIdenticalForAnyThreadCount), so they agree statistically a
// fortiori; not repeated here.
TEST(Replay, SameSeedGivesAnIdenticalRunFile) {
  const std::string first = replay("first.h5"), again = replay("again.h5");
  expect_identical_run_files(first, again);
  for (const std::string& path : {first, again}) std::remove(path.c_str());
}

}  // namespace
}  // namespace dem
