// Throughput of the DEM engine in triaxial shear (issue 16): list builds, the servo, the series
// rows and the run file included, with the share of each phase.
//
// For each specimen file (from `sffcal prepare`) and thread count it shears the specimen from
// rest with the engine's defaults (friction tan 30, no damping, the PI servo, the default time
// step) for `--strain` of axial strain at `--rate`, writing a run file as `sffcal triaxial` does,
// and prints sphere-steps/s per core with the shares of detection (list builds and the critical
// step), forces, integration (bodies and walls) and the rest (series rows, records, I/O).
//
//   shear_throughput SPECIMEN.h5 [SPECIMEN.h5 ...] [--threads 1,2] [--strain 0.005]
//                    [--rate 100] [--out out/bench/shear]
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "dem/run_file_io.h"
#include "list_argument.h"
#include "dem/triaxial.h"

int main(int argc, char** argv) {
  std::vector<std::string> specimens;
  std::vector<int> thread_counts = {1, 2};
  double strain = 0.005, rate = 100.0;
  std::string out_folder = "out/bench/shear";
  const bool parsed = bench::parse_arguments(
      argc, argv, specimens, [&](const std::string& arg, const std::string& value) {
        if (arg == "--threads") thread_counts = bench::parse_int_list(value);
        else if (arg == "--strain") strain = std::atof(value.c_str());
        else if (arg == "--rate") rate = std::atof(value.c_str());
        else if (arg == "--out") out_folder = value;
        else return false;
        return true;
      });
  if (!parsed) return 1;
  if (specimens.empty()) {
    std::fprintf(stderr, "usage: shear_throughput SPECIMEN.h5 [...] [--threads 1,2] [--strain 0.005] "
                         "[--rate 100] [--out out/bench/shear]\n");
    return 1;
  }
  std::filesystem::create_directories(out_folder);
  std::printf("| clumps | spheres | threads | steps | time step [s] | wall s | sphere-steps/s/core | "
              "detect %% | forces %% | integrate %% | rows, records %% | list builds | steps per build |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& path : specimens) {
    dem::CheckpointExtras extras;
    dem::RunFile specimen = dem::RunFile::open(path);
    const dem::SimulationState state = dem::read_checkpoint(specimen, &extras);
    for (int threads : thread_counts) {
      omp_set_num_threads(threads);
      dem::ContactParameters law;  // the shearing law: friction tan 30, frictionless walls
      dem::Simulation sim(state, law, dem::SimulationOptions{});
      dem::TriaxialOptions options;
      options.confining_stress = extras.count("pressure") ? extras.at("pressure") : 100e3;
      options.strain_rate = rate;
      options.max_axial_strain = strain;
      options.critical_min_strain = 1.0;
      const std::string run_path = out_folder + "/shear_" + std::to_string(threads) + ".h5";
      std::filesystem::remove(run_path);
      dem::RunFile file = dem::RunFile::create(run_path, {"triaxial", "", 0, "shear_throughput"},
                                               dem::triaxial_series_names());
      dem::TriaxialTest test(sim, options);
      const std::int64_t builds_before = sim.contacts().num_builds();
      const auto start = std::chrono::steady_clock::now();
      const dem::TriaxialSummary summary = test.run(&file, nullptr);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const dem::PhaseTimings& t = sim.timings();
      const double rest = std::max(0.0, seconds - t.total());
      const long long builds = static_cast<long long>(sim.contacts().num_builds() - builds_before);
      const int spheres = sim.particles().num_spheres();
      std::printf("| %d | %d | %d | %lld | %.3g | %.1f | %.3g | %.1f | %.1f | %.1f | %.1f | %lld | %.0f |\n",
                  sim.particles().num_bodies(), spheres, threads,
                  static_cast<long long>(summary.steps), sim.time_step(), seconds,
                  spheres * static_cast<double>(summary.steps) / seconds / threads,
                  100 * t.detection / seconds, 100 * t.forces / seconds,
                  100 * t.integration / seconds, 100 * rest / seconds, builds,
                  builds > 0 ? static_cast<double>(summary.steps) / static_cast<double>(builds) : 0.0);
      std::fflush(stdout);
    }
  }
  return 0;
}
