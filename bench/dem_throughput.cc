// Throughput of the DEM engine on a dense, jammed packing of the reference grains.
//
// For each N and body kind (two-sphere clumps, plain spheres of the same diameters) it prepares
// a packing by isotropic compaction to 100 kPa (compaction friction 0.1: dense), then times a
// fixed number of steps with friction tan 30, walls held by the servo, local damping 0.7, and
// prints body-steps/s, sphere-steps/s and contact-steps/s per core for each thread count, with
// the share of the time spent in detection, forces and integration.
//
//   dem_throughput [--bodies 2000,10000] [--steps 2000] [--threads 1,2] [--seed 1]
//                  [--skin 0.1] [--cache out/bench]   (prepared packings are kept and reused)
//                  [--features 1]   (instead: the cost of each scene feature, one thread)
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "dem/compaction.h"
#include "dem/packing.h"
#include "dem/run_file_io.h"
#include "list_argument.h"

namespace {

dem::Simulation jammed_packing(int bodies, bool clumps, std::uint64_t seed,
                               const std::string& cache_folder) {
  // Preparing 10,000 bodies takes minutes: keep the packing in a specimen file and reuse it.
  const std::string cache = cache_folder + "/packing_" + std::to_string(bodies) +
                            (clumps ? "_clumps_" : "_spheres_") + std::to_string(seed) + ".h5";
  if (std::filesystem::exists(cache)) {
    dem::RunFile file = dem::RunFile::open(cache);
    dem::ContactParameters law;
    law.friction = 0.1;
    dem::SimulationOptions options;
    options.local_damping = 0.7;
    std::fprintf(stderr, "  packing from %s\n", cache.c_str());
    return dem::Simulation(dem::read_checkpoint(file, nullptr), law, options);
  }
  dem::GrainSpec grains;
  grains.centre_distance_ratio = clumps ? 0.5 : 0.0;
  dem::Particles particles = dem::random_lattice_packing(bodies, grains, seed);
  Eigen::Vector3d lo, hi;
  dem::bounding_box(particles, lo, hi);
  dem::ContactParameters law;
  law.friction = 0.1;
  dem::SimulationOptions options;
  options.local_damping = 0.7;
  options.servo.max_speed = 1.0;
  dem::Simulation sim(std::move(particles), dem::box_walls(lo, hi), law, options);
  dem::CompactionOptions compaction;
  compaction.stress_tolerance = 0.02;
  compaction.max_unbalanced_force = 1e-2;
  compaction.check_every = 500;
  const dem::CompactionResult result = dem::compact_isotropically(sim, compaction);
  std::fprintf(stderr, "  prepared %d %s: %s\n", bodies, clumps ? "clumps" : "spheres",
               result.summary().c_str());
  std::filesystem::create_directories(cache_folder);
  dem::RunFile file = dem::RunFile::create(cache, {"specimen", "dem_throughput", seed, ""}, {});
  dem::write_checkpoint(file, sim.state(), {});
  return sim;
}

// One timed run of `steps` steps from `prepared` with the given law and options; returns the
// sphere-steps/s per core.
double sphere_rate(const dem::Simulation& prepared, const dem::ContactParameters& law,
                   const dem::SimulationOptions& options, int steps, int threads) {
  omp_set_num_threads(threads);
  dem::Simulation sim(prepared.particles(), prepared.walls(), law, options);
  sim.run(50);
  const auto start = std::chrono::steady_clock::now();
  sim.run(steps);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sim.particles().num_spheres() * static_cast<double>(steps) / seconds / threads;
}

// The cost of each feature a scene may declare: the same packing run with one feature switched
// on or off at a time (one thread), relative to the plain frictionless scene.
void feature_table(const dem::Simulation& prepared, const char* kind, int steps) {
  dem::ContactParameters base_law = prepared.contact_parameters();
  base_law.friction = 0.0;
  dem::SimulationOptions base = prepared.options();
  base.local_damping = 0.0;
  struct Variant {
    const char* name;
    dem::ContactParameters law;
    dem::SimulationOptions options;
  };
  std::vector<Variant> variants;
  variants.push_back({"frictionless, no damping, no gravity", base_law, base});
  auto with = [&](const char* name, auto&& change) {
    Variant v{name, base_law, base};
    change(v);
    variants.push_back(v);
  };
  with("+ grain friction (tan 30)", [](Variant& v) { v.law.friction = 0.5773502691896257; });
  with("+ wall friction (0.3)", [](Variant& v) { v.law.wall_friction = 0.3; });
  with("+ gravity", [](Variant& v) { v.options.gravity = {0.0, 0.0, -9.81}; });
  with("+ local damping (0.7)", [](Variant& v) { v.options.local_damping = 0.7; });
  with("+ contact viscous damping (0.1)", [](Variant& v) { v.law.normal_damping_ratio = 0.1; });
  with("all of the above", [](Variant& v) {
    v.law.friction = 0.5773502691896257;
    v.law.wall_friction = 0.3;
    v.options.gravity = {0.0, 0.0, -9.81};
    v.options.local_damping = 0.7;
    v.law.normal_damping_ratio = 0.1;
  });
  double reference = 0.0;
  for (const Variant& v : variants) {
    const double rate = sphere_rate(prepared, v.law, v.options, steps, 1);
    if (reference == 0.0) reference = rate;
    std::printf("| %d | %s | %s | %.3g | %.2f |\n", prepared.particles().num_bodies(), kind, v.name,
                rate, rate / reference);
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> body_counts = {2000, 10000}, thread_counts = {1, 2};
  int steps = 2000;
  std::uint64_t seed = 1;
  std::string cache_folder = "out/bench";
  double skin_ratio = dem::SimulationOptions{}.skin_ratio;
  bool features = false;
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string flag = argv[k], value = argv[k + 1];
    if (flag == "--bodies") body_counts = bench::parse_int_list(value);
    else if (flag == "--threads") thread_counts = bench::parse_int_list(value);
    else if (flag == "--steps") steps = std::atoi(value.c_str());
    else if (flag == "--seed") seed = std::strtoull(value.c_str(), nullptr, 10);
    else if (flag == "--cache") cache_folder = value;
    else if (flag == "--skin") skin_ratio = std::atof(value.c_str());
    else if (flag == "--features") features = value == "1";
    else {
      std::fprintf(stderr, "unknown option %s\n", flag.c_str());
      return 1;
    }
  }
  if (features) {
    std::printf("| bodies | kind | scene | sphere-steps/s (1 thread) | relative |\n|---|---|---|---|---|\n");
    for (int bodies : body_counts)
      for (bool clumps : {false, true})
        feature_table(jammed_packing(bodies, clumps, seed, cache_folder), clumps ? "clumps" : "spheres", steps);
    return 0;
  }
  std::printf("| bodies | kind | threads | contacts | candidates | steps | wall s | body-steps/s/core | "
              "sphere-steps/s/core | contact-steps/s/core | detect %% | forces %% | integrate %% | list builds |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int bodies : body_counts) {
    for (bool clumps : {true, false}) {
      omp_set_num_threads(omp_get_num_procs());
      const dem::Simulation prepared = jammed_packing(bodies, clumps, seed, cache_folder);
      for (int threads : thread_counts) {
        omp_set_num_threads(threads);
        dem::Particles particles = prepared.particles();
        dem::ContactParameters law = prepared.contact_parameters();
        law.friction = 0.5773502691896257;
        dem::SimulationOptions options = prepared.options();
        options.skin_ratio = skin_ratio;
        dem::Simulation sim(std::move(particles), prepared.walls(), law, options);
        sim.run(50);  // build the lists and warm the caches
        const dem::PhaseTimings before = sim.timings();
        const std::int64_t builds_before = sim.contacts().num_builds();
        const auto start = std::chrono::steady_clock::now();
        sim.run(steps);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const dem::PhaseTimings& after = sim.timings();
        const double detect = after.detection - before.detection;
        const double forces = after.forces - before.forces;
        const double integrate = after.integration - before.integration;
        const double total = detect + forces + integrate;
        const double contacts = sim.num_touching_pairs();
        const double per_core = static_cast<double>(steps) / seconds / threads;
        std::printf("| %d | %s | %d | %.0f | %d | %d | %.2f | %.3g | %.3g | %.3g | %.1f | %.1f | %.1f | %lld |\n",
                    bodies, clumps ? "clumps" : "spheres", threads, contacts, sim.contacts().num_pairs(),
                    steps, seconds,
                    bodies * per_core, sim.particles().num_spheres() * per_core,
                    contacts * per_core, 100 * detect / total, 100 * forces / total,
                    100 * integrate / total,
                    static_cast<long long>(sim.contacts().num_builds() - builds_before));
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
