// Specimen preparation and configuration: deposition fabric, the void-ratio search, CSV packings,
// and the config parser's errors.
#include "dem/specimen.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <utility>

#include "dem/run_config.h"
#include "sffcal/constants.h"

namespace dem {
namespace {

RunConfig small_config(int bodies) {
  RunConfig config = parse_run_config(default_run_config_text());
  config.num_bodies = bodies;
  return config;
}

TEST(RunConfig, DefaultTextGivesTheDefaults) {
  const RunConfig parsed = parse_run_config(default_run_config_text());
  const RunConfig defaults;
  EXPECT_EQ(parsed.num_bodies, defaults.num_bodies);
  EXPECT_EQ(parsed.seed, defaults.seed);
  EXPECT_EQ(parsed.grains.min_diameter, defaults.grains.min_diameter);
  EXPECT_EQ(parsed.grains.max_diameter, defaults.grains.max_diameter);
  EXPECT_EQ(parsed.grains.centre_distance_ratio, defaults.grains.centre_distance_ratio);
  EXPECT_EQ(parsed.contact.youngs_modulus, defaults.contact.youngs_modulus);
  EXPECT_EQ(parsed.contact.friction, defaults.contact.friction);
  EXPECT_EQ(parsed.contact.stiffness_ratio, defaults.contact.stiffness_ratio);
  EXPECT_EQ(parsed.engine.time_step_safety, defaults.engine.time_step_safety);
  EXPECT_EQ(parsed.engine.skin_ratio, defaults.engine.skin_ratio);
  EXPECT_EQ(parsed.engine.servo.max_speed, defaults.engine.servo.max_speed);
  EXPECT_EQ(parsed.preparation.pressure, defaults.preparation.pressure);
  EXPECT_EQ(parsed.preparation.deposition_gravity, defaults.preparation.deposition_gravity);
  EXPECT_EQ(parsed.preparation.deposition_damping, defaults.preparation.deposition_damping);
  EXPECT_EQ(parsed.preparation.compaction.max_steps, defaults.preparation.compaction.max_steps);
  EXPECT_EQ(parsed.triaxial.confining_stress, defaults.triaxial.confining_stress);
  EXPECT_EQ(parsed.triaxial.strain_rate, defaults.triaxial.strain_rate);
  EXPECT_EQ(parsed.triaxial.max_axial_strain, defaults.triaxial.max_axial_strain);
}

void expect_error(const std::string& toml, const std::string& fragment) {
  try {
    parse_run_config(toml, "t.toml");
    FAIL() << "accepted: " << toml;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(RunConfig, BadInputNamesTheKey) {
  expect_error("bodys = 10\n", "unknown key 'bodys'");
  expect_error("[grains]\nmin_diamter = 1e-5\n", "unknown key 'grains.min_diamter'");
  expect_error("[grains]\nmin_diameter = -1e-5\n", "grains.min_diameter");
  expect_error("[contact]\nfriction = -0.2\n", "friction");
  expect_error("bodies = \"ten\"\n", "bodies must be an integer");
  // A float beyond the integers is refused as a float, never cast (undefined behaviour: UBSan,
  // SFFCAL_SANITIZE, stops here without the check; found by fuzz/config_fuzzer.cc).
  expect_error("bodies = 1e118\n", "bodies must be an integer");
  expect_error("bodies = 1\n", "bodies must be in [2, 10000000] (got 1)");
  // Range-checked before narrowing to int: 2^32 + 80 must not run 80 bodies, 2^32 + 1 threads one.
  expect_error("bodies = 4294967376\n", "bodies must be in [2, 10000000] (got 4294967376)");
  expect_error("bodies = 2147483648\n", "bodies must be in");
  expect_error("threads = 4294967297\n", "threads must be in [0, 1024]");
  expect_error("[engine]\nsort_every_builds = 4294967296\n", "engine.sort_every_builds must be in");
  expect_error("[preparation]\nmethod = \"pour\"\n", "preparation.method");
  expect_error("[triaxial]\nstrain_rate = 0\n", "strain_rate");
  expect_error("[engine]\ntime_step_safety = 1.5\n", "time_step_safety");
  expect_error("[preparation]\ndeposition_damping = 1.0\n", "preparation.deposition_damping");
  expect_error("[grains\n", "TOML syntax error at line 1");
}

TEST(Preparation, LowerFrictionIsDenserAndTheSearchHitsATarget) {
  RunConfig config = small_config(120);
  config.preparation.target_void_ratio = 0.68;
  config.preparation.void_ratio_tolerance = 0.01;
  PreparationReport report;
  const Simulation sim = prepare_specimen(config, &report);
  EXPECT_NEAR(report.void_ratio, 0.68, 0.01) << report.describe();
  EXPECT_GE(report.friction_trials, 2);
  EXPECT_GT(report.compaction_friction, 0.0);
  EXPECT_LT(report.compaction_friction, 1.0);
  EXPECT_TRUE(report.compaction.converged);
  // A target denser than frictionless compaction can reach is refused with the reachable value.
  config.preparation.target_void_ratio = 0.2;
  try {
    prepare_specimen(config, nullptr);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("densest"), std::string::npos) << e.what();
  }
}

TEST(Preparation, DepositionOrientsTheFabricByTheLoadingAngle) {
  // 90 degrees: the bedding normal moves from Z (the deposition direction) to Y. The 250 bodies
  // are cut from the interior of a settled bed of about 2,500 (docs/dem.md).
  RunConfig config = small_config(250);
  config.preparation.method = PreparationMethod::kDeposition;
  config.preparation.loading_angle_deg = 90.0;
  config.preparation.compaction_friction = 0.15;
  PreparationReport report;
  const Simulation sim = prepare_specimen(config, &report);
  EXPECT_EQ(sim.particles().num_bodies(), config.num_bodies) << report.describe();
  const Eigen::Vector3d normal = bedding_normal(90.0), in_plane = Eigen::Vector3d::UnitZ();
  // Elongated grains settle lying in the bedding plane: the clump-axis fabric's minor direction
  // is its normal.
  EXPECT_GT(std::abs(report.axis_minor.dot(normal)), std::cos(20.0 / sffcal::kDegreesPerRadian)) << report.describe();
  // Contacts gather on the grains' long sides, so the contact-normal fabric is largest along the
  // bedding normal, of the three axes it and the bedding plane define. (At this size its principal
  // direction scatters by tens of degrees; docs/dem.md has the directions on 1000 bodies.)
  const Eigen::Matrix3d fabric = contact_normal_fabric(sim);
  const double along_normal = normal.dot(fabric * normal);
  EXPECT_GT(along_normal, fabric(0, 0)) << fabric;
  EXPECT_GT(along_normal, in_plane.dot(fabric * in_plane)) << fabric;
}

TEST(Preparation, LoadsACsvPackingAndNamesBadLines) {
  const std::string path = ::testing::TempDir() + "/sffcal_pack_" + std::to_string(getpid()) + ".csv";
  {
    std::ofstream out(path);
    out << "# two clumps and a sphere-sized gap\n# box: 0 0 0 4e-4 4e-4 4e-4\n"
        << "x,y,z,axis_x,axis_y,axis_z,diameter\n"
        << "1e-4,1e-4,1e-4,1,0,0,5e-5\n"
        << "3e-4,3e-4,3e-4,0,0.6,0.8,4e-5,0.01,0,0\n";
  }
  Eigen::Vector3d lo, hi;
  const Particles p = load_csv_packing(path, GrainSpec{}, &lo, &hi);
  ASSERT_EQ(p.num_bodies(), 2);
  EXPECT_EQ(p.num_spheres(), 4);
  EXPECT_NEAR(p.sphere_radius[2], 2e-5, 1e-18);
  EXPECT_NEAR((p.sphere_position[3] - p.sphere_position[2]).normalized().dot(Eigen::Vector3d(0, 0.6, 0.8)), 1.0, 1e-12);
  EXPECT_EQ(p.velocity[1].x(), 0.01);
  EXPECT_EQ(hi, Eigen::Vector3d(4e-4, 4e-4, 4e-4));
  {
    std::ofstream out(path);
    out << "# box: 0 0 0 4e-4 4e-4 4e-4\nx,y,z,axis_x,axis_y,axis_z,diameter\n1e-4,1e-4,abc,1,0,0,5e-5\n";
  }
  try {
    load_csv_packing(path, GrainSpec{}, &lo, &hi);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(":3: 'abc' is not a number"), std::string::npos) << e.what();
  }
  // A cell must be one whole number.
  for (const std::string cell : {"5e-05abc", "6e-05 7e-05", "nan", "inf", ""}) {
    {
      std::ofstream out(path);
      out << "# box: 0 0 0 4e-4 4e-4 4e-4\nx,y,z,axis_x,axis_y,axis_z,diameter\n1e-4," << cell
          << ",1e-4,1,0,0,5e-5\n";
    }
    try {
      load_csv_packing(path, GrainSpec{}, &lo, &hi);
      FAIL() << "the cell '" << cell << "' was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(":3: '" + cell + "' is not"), std::string::npos) << e.what();
    }
  }
  // A control character in a cell is shown escaped (a raw carriage return would overwrite the
  // message on the terminal).
  {
    std::ofstream out(path);
    out << "# box: 0 0 0 4e-4 4e-4 4e-4\nx,y,z,axis_x,axis_y,axis_z,diameter\n1e-4,1\r2,1e-4,1,0,0,5e-5\n";
  }
  try {
    load_csv_packing(path, GrainSpec{}, &lo, &hi);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(":3: '1\\x0d2' is not a number"), std::string::npos) << e.what();
  }
  {
    std::ofstream out(path);
    out << "# box: 0 0 0 4e-4 4e-4 4e-4\nx,y,z,axis_x,axis_y,axis_z,diameter\n1e-4,1e-4,1e-4,1,0,0,5e-5,\n";
  }
  try {
    load_csv_packing(path, GrainSpec{}, &lo, &hi);
    FAIL() << "a row ending with a comma was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(":3: the row ends with an empty cell"), std::string::npos) << e.what();
  }
  // Overlapping a wall as loaded wall contacts do (10 % of the radius) is accepted, a third of
  // the radius is refused naming the body, the wall and the overlap.
  for (const double overlap : {0.1, 0.33}) {
    {
      std::ofstream out(path);
      out << "# box: 0 0 0 4e-4 4e-4 4e-4\nx,y,z,axis_x,axis_y,axis_z,diameter\n"
          << "2e-4,2e-4,2e-4,1,0,0,5e-5\n"
          << "2e-4,2e-4," << 4e-4 - (1.0 - overlap) * 2.5e-5 << ",1,0,0,5e-5\n";
    }
    if (overlap < 0.25) {
      EXPECT_EQ(load_csv_packing(path, GrainSpec{}, &lo, &hi).num_bodies(), 2);
      continue;
    }
    try {
      load_csv_packing(path, GrainSpec{}, &lo, &hi);
      FAIL() << "an overlap of " << overlap << " radii was accepted";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("body 1 (data row 2) overlaps the z upper wall of the box by 0.33"),
                std::string::npos) << what;
    }
  }
  std::remove(path.c_str());
}

// Finite numbers that make no finite packing are refused by line (found by
// fuzz/csv_packing_fuzzer.cc): a box from -1e308 to 1e308 (an infinite size, compacted for
// thousands of steps before), a diameter whose mass overflows (1e150 m) or underflows (1e-300 m)
// (refused later by the engine, naming no file or line).
TEST(Preparation, ACsvPackingOfNoFiniteSizeOrMassIsRefusedByLine) {
  const std::string path = ::testing::TempDir() + "/sffcal_pack_" + std::to_string(getpid()) + ".csv";
  const std::pair<std::string, std::string> cases[] = {
      {"# box: -1e308 0 0 1e308 4e-4 4e-4\nx,y,z,axis_x,axis_y,axis_z,diameter\n"
       "0,2e-4,2e-4,1,0,0,5e-5\n",
       ":1: the box must have a finite size"},
      {"# box: 0 0 0 1e200 1e200 1e200\nx,y,z,axis_x,axis_y,axis_z,diameter\n"
       "5e199,5e199,5e199,1,0,0,1e150\n",
       ":3: a body of diameter 1e+150 m has a mass or inertia that is not"},
      {"# box: 0 0 0 4e-4 4e-4 4e-4\nx,y,z,axis_x,axis_y,axis_z,diameter\n"
       "2e-4,2e-4,2e-4,1,0,0,1e-300\n",
       ":3: a body of diameter 1e-300 m has a mass or inertia that is not"}};
  for (const auto& [text, fragment] : cases) {
    {
      std::ofstream out(path);
      out << text;
    }
    Eigen::Vector3d lo, hi;
    try {
      load_csv_packing(path, GrainSpec{}, &lo, &hi);
      ADD_FAILURE() << "accepted:\n" << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace dem

namespace dem {
namespace {

// The example configs are read by users and scripts: each must load, and the fast preset must
// carry the settings bench/RESULTS.md measured ("Run time against error").
TEST(RunConfig, ExampleConfigsLoad) {
  const std::string examples = std::string(SFFCAL_SOURCE_DIR) + "/examples/";
  for (const char* name : {"quick_triaxial.toml", "fast_triaxial.toml"}) {  // not the pipeline scenes
    EXPECT_NO_THROW(load_run_config(examples + name)) << name;
  }
  const RunConfig fast = load_run_config(examples + "fast_triaxial.toml");
  EXPECT_EQ(fast.engine.time_step_safety, 1.0);
  EXPECT_EQ(fast.triaxial.strain_rate, 200.0);
  EXPECT_EQ(parse_run_config(default_run_config_text()).triaxial.strain_rate, 100.0);
}

// A config file that sets nothing (empty, or comments only) is refused: it would silently run
// every default (1000 bodies), which a truncated or wrong file is more likely to mean.
TEST(RunConfig, AnEmptyConfigFileIsRefused) {
  const std::string path = ::testing::TempDir() + "/sffcal_empty_" + std::to_string(getpid()) + ".toml";
  std::ofstream(path) << "# only a comment\n\n";
  try {
    load_run_config(path);
    FAIL() << "an empty config was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sets no key"), std::string::npos) << e.what();
  }
  std::ofstream(path) << "bodies = 50\n";
  EXPECT_EQ(load_run_config(path).num_bodies, 50);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace dem
