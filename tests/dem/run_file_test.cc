#include "dem/run_file_io.h"

#include <gtest/gtest.h>
#include <omp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "dem/triaxial.h"
#include "specimen_fixture.h"

namespace dem {
namespace {

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "/sffcal_" + std::to_string(getpid()) + "_" + name;
}

// Resumes the killed run in `path` from its checkpoint with the engine settings of `whole`;
// `builds` receives the list builds the checkpoint had seen.
Simulation resume(const std::string& path, const Simulation& whole, const TriaxialOptions& options,
                  std::int64_t* builds = nullptr) {
  RunFile file = RunFile::open(path, true);
  CheckpointExtras extras;
  SimulationState state = read_checkpoint(file, &extras);
  if (builds) *builds = state.contacts.num_builds();
  Simulation sim(std::move(state), whole.contact_parameters(), whole.options());
  TriaxialTest test(sim, options);
  test.run(&file, nullptr, &extras);
  return sim;
}

// The resumed run equals the uninterrupted one bit for bit: every series but the wall time,
// the snapshots, the summary's step count and strain, the final positions. Removes both files.
void expect_same_run(const std::string& whole_path, const Simulation& whole,
                     const std::string& resumed_path, const Simulation& resumed) {
  {
    const RunFile a = RunFile::open(whole_path), b = RunFile::open(resumed_path);
    for (const std::string& name : triaxial_series_names()) {
      if (name == "time") continue;
      EXPECT_EQ(a.series(name), b.series(name)) << name;
    }
    EXPECT_EQ(a.num_snapshots(), b.num_snapshots());
    // The summary counts the test's steps, the resumed run's before the kill included.
    EXPECT_EQ(a.read_summary().steps, b.read_summary().steps);
    EXPECT_EQ(a.read_summary().axial_strain, b.read_summary().axial_strain);
    ASSERT_EQ(whole.particles().num_bodies(), resumed.particles().num_bodies());
    for (int k = 0; k < whole.particles().num_bodies(); ++k)
      ASSERT_EQ(whole.particles().position[k], resumed.particles().position[k]);
  }
  std::remove(whole_path.c_str());
  std::remove(resumed_path.c_str());
}

TEST(RunFile, RoundTripsSeriesSnapshotsAndMetadata) {
  const Simulation sim = testing::compacted_specimen(60, 0.3, 5);
  const std::string path = temp_path("roundtrip.h5");
  const runfile::RunMetadata meta{"test", "[dem]\nbodies = 60\n", 5, "0.1.0"};
  const Snapshot written = take_snapshot(sim, 0.125);
  {
    RunFile file = RunFile::create(path, meta, {"a", "b"});
    file.append_series({1.0, 2.0});
    file.append_series({3.0, 4.5});
    file.write_snapshot(written);
  }
  const RunFile file = RunFile::open(path);
  EXPECT_EQ(file.metadata().config_text, meta.config_text);
  EXPECT_EQ(file.metadata().seed, 5u);
  EXPECT_EQ(file.series("b"), (std::vector<double>{2.0, 4.5}));
  ASSERT_EQ(file.num_snapshots(), 1);
  const Snapshot read = file.read_snapshot(0);
  EXPECT_EQ(read.step, written.step);
  EXPECT_EQ(read.axial_strain, 0.125);
  ASSERT_EQ(read.contacts.size(), written.contacts.size());
  ASSERT_GT(read.contacts.size(), 60u);
  for (std::size_t k = 0; k < read.contacts.size(); ++k) {
    EXPECT_EQ(read.contacts[k].body_a, written.contacts[k].body_a);
    EXPECT_EQ(read.contacts[k].normal, written.contacts[k].normal);
    EXPECT_EQ(read.contacts[k].normal_force, written.contacts[k].normal_force);
    EXPECT_EQ(read.contacts[k].tangential_force, written.contacts[k].tangential_force);
    EXPECT_EQ(read.contacts[k].branch, written.contacts[k].branch);
  }
  ASSERT_EQ(read.particles.size(), 60u);
  EXPECT_EQ(read.particles[7].orientation, written.particles[7].orientation);
  EXPECT_EQ(read.spheres, written.spheres);
  ASSERT_EQ(read.walls.size(), 6u);
  EXPECT_EQ(read.walls[5].normal_force, written.walls[5].normal_force);
  std::remove(path.c_str());
}

TEST(RunFile, ClearErrorsForMissingFilesAndSeries) {
  try {
    RunFile::open(temp_path("does_not_exist.h5"));
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("does_not_exist.h5"), std::string::npos) << e.what();
  }
  const std::string path = temp_path("series.h5");
  RunFile file = RunFile::create(path, {}, {"a"});
  try {
    file.series("nope");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("nope"), std::string::npos) << e.what();
  }
  EXPECT_THROW(file.append_series({1.0, 2.0}), std::invalid_argument);
  std::remove(path.c_str());
}

// A short test to 5 % axial strain with frequent rows, snapshots and checkpoints.
TriaxialOptions short_test(double checkpoint_strain_interval) {
  TriaxialOptions options;
  options.strain_rate = 100.0;
  options.max_axial_strain = 0.05;
  options.output_strain_interval = 0.0025;
  options.snapshot_strain_interval = 0.02;
  options.checkpoint_strain_interval = checkpoint_strain_interval;
  return options;
}

struct Killed : std::runtime_error {
  Killed() : std::runtime_error("killed") {}
};

// Runs `options` on the specimen whole, and again killed past 3.7 % and resumed from its file:
// the two runs must be the same, bit for bit.
void expect_resume_gives_the_uninterrupted_run(const Simulation& specimen,
                                               const TriaxialOptions& options) {
  const runfile::RunMetadata meta{"triaxial", "", 9, "test"};

  const std::string whole_path = temp_path("whole.h5");
  Simulation whole = testing::shearing_copy(specimen);
  {
    RunFile file = RunFile::create(whole_path, meta, triaxial_series_names());
    TriaxialTest(whole, options).run(&file, nullptr);
  }

  const std::string killed_path = temp_path("killed.h5");
  {
    Simulation sim = testing::shearing_copy(specimen);
    RunFile file = RunFile::create(killed_path, meta, triaxial_series_names());
    EXPECT_THROW(TriaxialTest(sim, options).run(&file, [](const TriaxialProgress& p) {
      if (p.axial_strain > 0.037) throw Killed();
    }),
                 Killed);
  }
  const Simulation resumed = resume(killed_path, whole, options);
  expect_same_run(whole_path, whole, killed_path, resumed);
}

TEST(RunFile, ResumeAfterAKillGivesTheUninterruptedRun) {
  expect_resume_gives_the_uninterrupted_run(testing::compacted_specimen(80, 0.2, 9),
                                            short_test(0.015));
}

// sigma_x = sigma_y at constant volume reads the lateral walls' forces of the last step, which a
// restored engine has not got: the checkpoint carries them.
TEST(RunFile, ResumeOfAnUndrainedRunWithEqualLateralStressesGivesTheUninterruptedRun) {
  TriaxialOptions options = short_test(0.015);
  options.path = LoadingPath::kUndrainedCompression;
  options.undrained_lateral = UndrainedLateral::kEqualStresses;
  expect_resume_gives_the_uninterrupted_run(testing::compacted_specimen(80, 0.2, 9), options);
}

// A saved state that was edited or damaged (the arrays of a checkpoint are plain datasets) is
// refused naming what is wrong, before any index in it is followed: a short mass array, a contact
// index past the spheres, a wall index past the walls, a NaN position (issue 17).
TEST(RunFile, ATamperedStateIsRefusedNamingTheArray) {
  const Simulation specimen = testing::compacted_specimen(40, 0.3, 3);
  const SimulationState good = specimen.state();
  ASSERT_GT(good.contacts.num_pairs(), 0);
  ASSERT_GT(good.contacts.num_wall_candidates(), 0);
  auto expect_refused = [&](SimulationState state, const std::string& fragment) {
    try {
      Simulation sim(std::move(state), specimen.contact_parameters(), specimen.options());
      FAIL() << "accepted a state with a bad " << fragment;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  SimulationState s = good;
  s.particles.mass.pop_back();
  expect_refused(s, "mass has");
  s = good;
  s.contacts.pair_j[0] = s.particles.num_spheres() + 5;
  expect_refused(s, "pair 0");
  s = good;
  s.contacts.wall_index[0] = 6;
  expect_refused(s, "wall candidate 0");
  s = good;
  s.particles.position[3].x() = std::nan("");
  expect_refused(s, "not finite");
  s = good;
  s.particles.first_sphere[2] = s.particles.num_spheres();
  expect_refused(s, "outside the");
  // The untouched state is accepted.
  EXPECT_NO_THROW(Simulation(SimulationState(good), specimen.contact_parameters(), specimen.options()));
}

// A checkpoint the engine cannot run from is refused by read_checkpoint itself, naming what is
// wrong (found by fuzz/checkpoint_fuzzer.cc, each read back by the engine out of bounds or
// wrapping a counter): a list with no build positions and no rebuild due, body arrays one body
// short of the sphere arrays (a sphere of no body), a step count at the largest integer, and a
// body whose sphere range ends past the largest int (named without wrapping).
TEST(RunFile, ACheckpointTheEngineCannotRunFromIsRefusedByName) {
  const Simulation specimen = testing::compacted_specimen(40, 0.3, 3);
  const SimulationState good = specimen.state();
  ASSERT_FALSE(good.rebuild_due);
  const std::string path = temp_path("unrunnable_checkpoint.h5");
  auto expect_refused = [&](const SimulationState& state, const std::string& fragment) {
    {
      RunFile file = RunFile::create(path, runfile::RunMetadata{"specimen", "", 3, "test"}, {});
      write_checkpoint(file, state, {});
    }
    RunFile file = RunFile::open(path);
    try {
      read_checkpoint(file, nullptr);
      ADD_FAILURE() << "read a checkpoint with " << fragment;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  SimulationState s = good;
  s.contacts.build_wall_position.clear();
  expect_refused(s, "has no build positions, and no rebuild is due");
  s = good;
  Particles& p = s.particles;
  for (auto* v : {&p.position, &p.velocity, &p.angular_momentum, &p.angular_velocity}) v->pop_back();
  for (auto* v : {&p.mass, &p.inertia_axial, &p.inertia_transverse, &p.volume}) v->pop_back();
  p.id.pop_back();
  p.orientation.pop_back();
  p.first_sphere.pop_back();
  p.num_body_spheres.pop_back();
  expect_refused(s, "the checkpoint's bodies own 78 spheres of 80");
  s = good;
  s.step_count = std::numeric_limits<std::int64_t>::max();
  expect_refused(s, "step_count");
  s = good;
  s.particles.first_sphere[0] = std::numeric_limits<int>::max();
  expect_refused(s, ": spheres [2147483647, 2147483649) outside the 80 spheres");
  std::remove(path.c_str());
}

// A real kill: a child process shearing with a spatial re-sort at every list build is killed with
// SIGKILL (no destructor, the file never closed) right after a flush, a few checkpoints in; the
// run resumed from its file gives the uninterrupted run bit for bit, series and positions
// (issue 17: the grain totals were summed in the re-sorted order and moved by up to 3 ulp).
TEST(RunFile, ResumeAfterSigkillAndReSortsGivesTheUninterruptedRun) {
  const Simulation specimen = testing::compacted_specimen(80, 0.2, 13);
  const TriaxialOptions options = short_test(0.01);
  const runfile::RunMetadata meta{"triaxial", "", 13, "test"};
  auto sheared = [&] {
    Simulation sim = testing::shearing_copy(specimen);
    SimulationOptions engine = sim.options();
    engine.sort_every_builds = 1;
    return Simulation(sim.state(), sim.contact_parameters(), engine);
  };

  const std::string whole_path = temp_path("sigkill_whole.h5");
  Simulation whole = sheared();
  {
    RunFile file = RunFile::create(whole_path, meta, triaxial_series_names());
    TriaxialTest(whole, options).run(&file, nullptr);
  }

  const std::string killed_path = temp_path("sigkill_killed.h5");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // the child shears and kills itself after the row at 3.5 %
    // One thread: the parent's OpenMP team does not survive fork() (results are the same for any
    // thread count).
    omp_set_num_threads(1);
    Simulation sim = sheared();
    RunFile file = RunFile::create(killed_path, meta, triaxial_series_names());
    TriaxialTest(sim, options).run(&file, [](const TriaxialProgress& p) {
      if (p.axial_strain > 0.035) std::raise(SIGKILL);
    });
    std::_Exit(0);  // not reached
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "status " << status;

  std::int64_t builds = 0;
  const Simulation resumed = resume(killed_path, whole, options, &builds);
  EXPECT_GE(builds, 3) << "re-sorts before the checkpoint";
  expect_same_run(whole_path, whole, killed_path, resumed);
}

}  // namespace
}  // namespace dem
