// The run file as a contract: physics and summary round trips, checkpoints written through the
// generic state API, the schema-1 files committed as reference data, and the errors a reader
// meets, each naming the file and the object.
#include "runfile/run_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "runfile/dem_test.h"
#include "runfile/stored_physics.h"
#include "sffcal/constants.h"

namespace runfile {
namespace {

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "/sffcal_runfile_" + std::to_string(getpid()) + "_" + name;
}

template <typename F>
void expect_error(F&& f, const std::vector<std::string>& fragments) {
  try {
    f();
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    for (const std::string& fragment : fragments)
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)
          << "'" << fragment << "' not in: " << e.what();
  }
}

RunMetadata sample_metadata() {
  RunMetadata m;
  m.kind = "triaxial";
  m.config_text = "[contact]\nfriction = 0.25\n";
  m.seed = 42;
  m.program_version = "test";
  m.physics = {2.5e8, 0.4, 0.25, 0.1, 2500.0, 10.0};
  return m;
}

const std::vector<std::string> kTestSeries = {"axial_strain", "volumetric_strain", "p", "q",
                                              "eta", "void_ratio", "sigma_3"};

TEST(RunFileContract, PhysicsAndSummaryAreStoredAsTypedAttributes) {
  const std::string path = temp_path("physics.h5");
  TestSummary summary;
  summary.reached_critical_state = true;
  summary.axial_strain = 0.3;
  summary.peak_eta = 1.1;
  summary.peak_eta_strain = 0.04;
  summary.critical_eta = 0.9;
  summary.initial_void_ratio = 0.6;
  summary.final_void_ratio = 0.7;
  summary.worst_lateral_error = 0.01;
  summary.max_inertial_number = 2e-4;
  summary.steps = 123456;
  summary.wall_seconds = 7.5;
  {
    RunFile file = RunFile::create(path, sample_metadata(), kTestSeries);
    EXPECT_FALSE(file.has_summary());
    file.write_summary(summary);
  }
  const RunFile file = RunFile::open(path);
  const RunMetadata m = file.metadata();
  EXPECT_EQ(m.schema_version, kSchemaVersion);
  EXPECT_EQ(m.physics.youngs_modulus, 2.5e8);
  EXPECT_EQ(m.physics.stiffness_ratio, 0.4);
  EXPECT_EQ(m.physics.friction, 0.25);
  EXPECT_EQ(m.physics.wall_friction, 0.1);
  EXPECT_EQ(m.physics.grain_density, 2500.0);
  EXPECT_EQ(m.physics.density_scaling, 10.0);
  ASSERT_TRUE(file.has_summary());
  const TestSummary read = file.read_summary();
  EXPECT_TRUE(read.reached_critical_state);
  EXPECT_EQ(read.peak_eta, 1.1);
  EXPECT_EQ(read.critical_eta, 0.9);
  EXPECT_EQ(read.steps, 123456);
  EXPECT_EQ(read.describe(), summary.describe());
  std::remove(path.c_str());
}

// The physics of a schema-1 file is its stored config read with that schema's defaults: a config
// without [contact] sheared at tan 30 deg (the latent bug of issue 15 gave 0 there).
TEST(RunFileContract, SchemaOnePhysicsComesFromTheStoredConfigWithItsDefaults) {
  const RunPhysics defaults = physics_from_config_text("bodies = 100\n", "x");
  EXPECT_EQ(defaults.friction, 0.5773502691896257);
  EXPECT_NEAR(defaults.friction, std::tan(sffcal::kPi / 6.0), 1e-16);
  EXPECT_EQ(defaults.youngs_modulus, 150e6);
  EXPECT_EQ(defaults.grain_density, 2650.0);
  EXPECT_EQ(defaults.density_scaling, 1.0);
  const RunPhysics set = physics_from_config_text(
      "[contact]\nfriction = 0.5\nyoungs_modulus = 3e8\n[grains]\ndensity = 2000\n", "x");
  EXPECT_EQ(set.friction, 0.5);
  EXPECT_EQ(set.youngs_modulus, 3e8);
  EXPECT_EQ(set.grain_density, 2000.0);  // an integer reads as a number
  expect_error([] { physics_from_config_text("[contact]\nfriction = = 0.5\n", "run.h5 (stored config)"); },
               {"run.h5 (stored config)", "line 2"});
  expect_error([] { physics_from_config_text("[contact]\nfriction = \"high\"\n", "cfg"); },
               {"cfg", "contact.friction"});
}

// The reference data committed before schema 2 still reads: metadata, physics, series, SFF table.
TEST(RunFileContract, CommittedSchemaOneFilesStillRead) {
  const std::string dir = std::string(SFFCAL_SOURCE_DIR) + "/tests/data/reference/";
  const std::string with_snapshots = dir + "iso_dense_100kPa_reduced.h5";  // keeps 3 snapshots
  std::vector<std::string> paths = {with_snapshots};
  for (const auto& entry : std::filesystem::directory_iterator(dir + "matrix"))
    if (entry.path().extension() == ".h5") paths.push_back(entry.path().string());
  ASSERT_EQ(paths.size(), 20u);
  for (const std::string& path : paths) {
    SCOPED_TRACE(path);
    const DemTest test = read_dem_test(path);
    EXPECT_EQ(test.metadata.schema_version, 1);
    EXPECT_EQ(test.metadata.kind, "triaxial");
    EXPECT_EQ(test.metadata.physics.friction, 0.5773502691896257);
    EXPECT_EQ(test.metadata.physics.youngs_modulus, 1.5e8);
    EXPECT_GT(test.series.axial_strain.size(), 50u);
    EXPECT_EQ(test.series.sigma_3.size(), test.series.axial_strain.size());
    ASSERT_TRUE(test.analysed);
    EXPECT_GE(test.sff.a_c.size(), 2u);
    EXPECT_EQ(test.sff.m.size(), test.sff.axial_strain.size());
    // The contact-network model's state columns (optional in the reader, present here).
    EXPECT_EQ(test.sff.coordination.size(), test.sff.axial_strain.size());
    EXPECT_EQ(test.sff.lambda.size(), test.sff.axial_strain.size());
    EXPECT_EQ(test.sff.a_t.size(), test.sff.axial_strain.size());
    EXPECT_GT(test.sff.lambda.front(), 0.0);
    const RunFile file = RunFile::open(path);
    EXPECT_FALSE(file.has_summary());  // schema 1 kept it as a note
    EXPECT_FALSE(file.read_note("summary").empty());
    EXPECT_EQ(file.num_snapshots(), path == with_snapshots ? 3 : 0);  // the matrix files: no /snapshots
  }
}

TEST(RunFileContract, ADemTestNamesWhatIsMissing) {
  const std::string path = temp_path("dem_test.h5");
  {
    RunFile file = RunFile::create(path, sample_metadata(),
                                   {"axial_strain", "volumetric_strain", "p", "eta", "void_ratio", "sigma_3"});
    file.append_series({0.0, 0.0, 1e5, 0.0, 0.7, 1e5});
  }
  expect_error([&] { read_dem_test(path); }, {path, "/series/q"});
  std::remove(path.c_str());
  {
    RunFile file = RunFile::create(path, sample_metadata(), kTestSeries);
    for (int k = 0; k < 3; ++k) file.append_series({0.01 * k, 0.0, 1e5, 1e4 * k, 0.1 * k, 0.7, 1e5});
  }
  DemTest test = read_dem_test(path);
  EXPECT_FALSE(test.analysed);
  EXPECT_EQ(test.name, "sffcal_runfile_" + std::to_string(getpid()) + "_dem_test");
  EXPECT_EQ(test.series.q, (std::vector<double>{0.0, 1e4, 2e4}));
  EXPECT_EQ(test.metadata.physics.friction, 0.25);
  {
    RunFile file = RunFile::open(path, true);
    file.write_table("sff", {"axial_strain", "a_c"}, {{0.0, 0.1}, {0.02, 0.2}});
  }
  expect_error([&] { read_dem_test(path); }, {path, "/analysis/sff", "'p'"});
  {  // the required columns without the optional coordination, lambda and a_t: read, left empty
    RunFile file = RunFile::open(path, true);
    file.write_table("sff", {"axial_strain", "p", "q", "eta", "void_ratio", "a_c", "a_n", "m",
                             "lambda"},
                     {{0.0, 1e5, 0.0, 0.0, 0.7, 0.0, 0.0, 0.0, 1e-3}});
  }
  test = read_dem_test(path);
  EXPECT_TRUE(test.analysed);
  EXPECT_EQ(test.sff.a_c.size(), 1u);
  EXPECT_TRUE(test.sff.lambda.empty());  // all three or none
  EXPECT_TRUE(test.sff.coordination.empty());
  std::remove(path.c_str());
}

// A checkpoint is written beside the previous one and swapped in at commit: a writer that dies
// before committing leaves the previous checkpoint whole.
TEST(RunFileContract, AnUncommittedCheckpointLeavesThePreviousOne) {
  const std::string path = temp_path("checkpoint.h5");
  RunFile file = RunFile::create(path, sample_metadata(), {"a"});
  file.append_series({1.0});
  const std::vector<double> x = {1.0, 2.0, 3.0, 4.0, 5.0, 6.0};
  const std::vector<std::int32_t> i = {7, -8};
  const std::vector<std::int64_t> l = {1LL << 40};
  const std::vector<std::uint8_t> b = {0, 1, 1};
  {
    StateWriter out = file.begin_checkpoint();
    out.attribute("time", 0.5);
    out.attribute("step_count", std::int64_t{99});
    out.extras({{"height0", 0.01}});
    out.array("x", x.data(), 2, 3);
    out.array("i", i.data(), i.size());
    out.array("l", l.data(), l.size());
    out.array("b", b.data(), b.size());
    out.walls({WallRecord{}});
    out.commit();
  }
  file.append_series({2.0});
  {
    StateWriter out = file.begin_checkpoint();
    out.attribute("time", 9.0);
    // destroyed without commit(): a run killed while writing
  }
  ASSERT_TRUE(file.has_checkpoint());
  {
    const StateReader in = file.read_checkpoint();
    EXPECT_EQ(in.real("time"), 0.5);
    EXPECT_EQ(in.integer("step_count"), 99);
    EXPECT_EQ(in.extras().at("height0"), 0.01);
    EXPECT_EQ(in.array<double>("x"), x);
    EXPECT_EQ(in.array<std::int32_t>("i"), i);
    EXPECT_EQ(in.array<std::int64_t>("l"), l);
    EXPECT_EQ(in.array<std::uint8_t>("b"), b);
    EXPECT_EQ(in.walls().size(), 1u);
    EXPECT_TRUE(in.has("x"));
    EXPECT_FALSE(in.has("y"));
    expect_error([&] { in.array<double>("y"); }, {path, "checkpoint", "y"});
  }
  EXPECT_EQ(file.series_length(), 2u);
  file.rewind_to_checkpoint();  // the row written after the checkpoint goes
  EXPECT_EQ(file.series("a"), (std::vector<double>{1.0}));
  std::remove(path.c_str());
}

TEST(RunFileContract, ANonHdf5FileIsRefusedByName) {
  const std::string path = temp_path("text.h5");
  { std::FILE* f = std::fopen(path.c_str(), "w"); std::fputs("not hdf5\n", f); std::fclose(f); }
  expect_error([&] { RunFile::open(path); }, {path, "not an HDF5 file"});
  expect_error([&] { read_dem_test(path); }, {path});
  std::remove(path.c_str());
}

// Two bodies (a sphere on a wall, a clump) with one contact each kind: every reader gets a
// consistent snapshot, and an edited one is refused naming the record at fault.
Snapshot two_body_snapshot() {
  Snapshot s;
  s.step = 10;
  s.time = 1e-6;
  s.particles.resize(2);
  s.particles[0].id = 0;
  s.particles[0].sphere_diameter = 1e-4;
  s.particles[1].id = 1;
  s.particles[1].num_spheres = 2;
  s.particles[1].sphere_diameter = 1e-4;
  s.particles[1].position = {2e-4, 0.0, 0.0};
  s.spheres = {{0.0, 0.0, 0.0, 5e-5}, {1.75e-4, 0.0, 0.0, 5e-5}, {2.25e-4, 0.0, 0.0, 5e-5}};
  s.sphere_body = {0, 1, 1};
  s.walls.resize(6);
  for (int w = 0; w < 6; ++w) s.walls[w].axis = w / 2, s.walls[w].upper = w % 2;
  ContactRecord pair;
  pair.body_a = 0, pair.body_b = 1, pair.normal = {1.0, 0.0, 0.0}, pair.normal_force = 1e-3;
  ContactRecord wall;
  wall.body_b = 0, wall.wall = 0, wall.normal = {1.0, 0.0, 0.0}, wall.normal_force = 2e-3;
  s.contacts = {pair, wall};
  return s;
}

TEST(RunFileContract, AnInconsistentSnapshotIsRefusedNamingTheRecord) {
  const std::string path = temp_path("snapshots.h5");
  std::vector<std::pair<Snapshot, std::string>> cases;
  cases.emplace_back(two_body_snapshot(), "");
  cases.emplace_back(two_body_snapshot(), "contact 0 holds a value that is not finite");
  cases.back().first.contacts[0].normal_force = std::nan("");
  cases.emplace_back(two_body_snapshot(), "contact 1 refers to body 7");
  cases.back().first.contacts[1].body_b = 7;
  cases.emplace_back(two_body_snapshot(), "contact 1 refers to wall 6 of 6");
  cases.back().first.contacts[1].wall = 6;
  cases.emplace_back(two_body_snapshot(), "sphere 2 refers to body 2");
  cases.back().first.sphere_body[2] = 2;
  cases.emplace_back(two_body_snapshot(), "particle 1 repeats body id 0");
  cases.back().first.particles[1].id = 0;
  cases.emplace_back(two_body_snapshot(), "particle 0 holds a value that is not finite");
  cases.back().first.particles[0].velocity[2] = INFINITY;
  cases.emplace_back(two_body_snapshot(), "sphere 1 has a radius that is not positive");
  cases.back().first.spheres[1][3] = 0.0;
  cases.emplace_back(two_body_snapshot(), "wall 3 has axis 5");
  cases.back().first.walls[3].axis = 5;
  cases.emplace_back(two_body_snapshot(), "'sphere_body' has 2 entries for 3 spheres");
  cases.back().first.sphere_body.pop_back();
  // A periodic cell (an imported run) comes without walls, with its upper corner above its lower.
  cases.emplace_back(two_body_snapshot(), "a periodic snapshot also has walls");
  cases.back().first.periodic_cell = {{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}};
  cases.emplace_back(two_body_snapshot(), "'periodic_cell' has an upper corner not above");
  cases.back().first.periodic_cell = {{0.0, 0.0, 0.0}, {1.0, 0.0, 1.0}};
  cases.back().first.walls.clear();
  cases.back().first.contacts.pop_back();
  cases.emplace_back(two_body_snapshot(), "'periodic_cell' has 3 values, not 6");
  cases.back().first.periodic_cell = {{0.0, 0.0, 0.0}};
  cases.back().first.walls.clear();
  cases.back().first.contacts.pop_back();
  {
    RunFile file = RunFile::create(path, sample_metadata(), kTestSeries);
    for (const auto& c : cases) file.write_snapshot(c.first);
  }
  const RunFile file = RunFile::open(path);
  EXPECT_EQ(file.read_snapshot(0).contacts.size(), 2u);
  EXPECT_TRUE(file.read_snapshot(0).periodic_cell.empty());
  for (int k = 1; k < static_cast<int>(cases.size()); ++k)
    expect_error([&] { file.read_snapshot(k); },
                 {path, "snapshot " + std::to_string(k), cases[static_cast<std::size_t>(k)].second});
  std::remove(path.c_str());
}

}  // namespace
}  // namespace runfile
