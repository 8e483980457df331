// sffcal: the project's command-line front end. Each subcommand is one stage of the pipeline.
#include <CLI/CLI.hpp>
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <exception>

#include "dem/compaction.h"
#include "dem/packing.h"

namespace {

struct CompactArgs {
  int bodies = 500;
  bool spheres = false;
  double friction = 0.3;
  double pressure_kpa = 100.0;
  std::uint64_t seed = 1;
  int threads = 0;
};

int run_compact(const CompactArgs& args) {
  if (args.threads > 0) omp_set_num_threads(args.threads);
  dem::GrainSpec grains;
  grains.centre_distance_ratio = args.spheres ? 0.0 : 0.5;
  dem::Particles particles = dem::random_lattice_packing(args.bodies, grains, args.seed);
  Eigen::Vector3d lo, hi;
  dem::bounding_box(particles, lo, hi);
  dem::ContactParameters law;
  law.friction = args.friction;
  dem::SimulationOptions options;
  options.local_damping = 0.7;
  options.servo.max_speed = 0.5;
  dem::Simulation sim(std::move(particles), dem::box_walls(lo, hi), law, options);
  std::printf("sffcal compact: %d %s, d in [%.3g, %.3g] mm, friction %.3g, p'0 %.4g kPa, seed %llu, "
              "%d threads\n",
              args.bodies, args.spheres ? "spheres" : "two-sphere clumps", grains.min_diameter * 1e3,
              grains.max_diameter * 1e3, args.friction, args.pressure_kpa,
              static_cast<unsigned long long>(args.seed), omp_get_max_threads());
  std::printf("time step %.4g s (critical %.4g s)\n", sim.time_step(), sim.critical_time_step());
  dem::CompactionOptions compaction;
  compaction.target_stress = args.pressure_kpa * 1e3;
  const auto start = std::chrono::steady_clock::now();
  const dem::CompactionResult result = dem::compact_isotropically(sim, compaction);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const dem::MacroRecord m = sim.macro_record();
  double solid = 0.0;
  for (double v : sim.particles().volume) solid += v;
  const Eigen::Matrix3d sigma = sim.contact_stress(true);
  std::printf("%s\n", result.summary().c_str());
  std::printf("void ratio           %.4f\n", sim.box_volume() / solid - 1.0);
  std::printf("coordination number  %.3f\n", m.coordination_number);
  std::printf("contact stress [kPa] xx %.2f  yy %.2f  zz %.2f (particle form, walls included)\n",
              sigma(0, 0) / 1e3, sigma(1, 1) / 1e3, sigma(2, 2) / 1e3);
  std::printf("wall stress [kPa]    x %.2f  y %.2f  z %.2f\n", m.wall_force[1] / sim.wall_area(1) / 1e3,
              m.wall_force[3] / sim.wall_area(3) / 1e3, m.wall_force[5] / sim.wall_area(5) / 1e3);
  std::printf("wall clock %.2f s, %.3g body-steps/s\n", seconds,
              static_cast<double>(args.bodies) * static_cast<double>(result.steps) / seconds);
  return result.converged ? 0 : 2;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"sffcal: from grain-scale DEM to a calibrated fabric-based soil model"};
  app.require_subcommand(1);
  CompactArgs compact;
  CLI::App* cmd = app.add_subcommand("compact", "Prepare a specimen by isotropic compaction");
  cmd->add_option("-n,--bodies", compact.bodies, "number of bodies")->check(CLI::Range(2, 10000000));
  cmd->add_flag("--spheres", compact.spheres, "plain spheres instead of two-sphere clumps");
  cmd->add_option("--friction", compact.friction, "inter-grain friction during compaction")
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--pressure", compact.pressure_kpa, "target isotropic stress p'0 [kPa]")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--seed", compact.seed, "random seed");
  cmd->add_option("--threads", compact.threads, "OpenMP threads (0: all)")->check(CLI::NonNegativeNumber);
  CLI11_PARSE(app, argc, argv);
  try {
    if (cmd->parsed()) return run_compact(compact);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sffcal: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
