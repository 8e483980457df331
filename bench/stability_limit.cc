// The stability limit on prepared specimens: (1) the Lanczos estimate of omega_max after k
// iterations against a converged one, its brackets, and its cost against one step of the engine;
// (2) with --safeties, the energy of the jammed packing set rattling, run at each safety factor
// of the limit, and past it.
//
// Each specimen file (from `sffcal prepare`) is restored with the shearing law (friction tan 30,
// frictionless walls, no damping, the default options). Table 1, for each iteration count:
// 2/omega_max, its ratio to the converged limit (`--reference` iterations), the guaranteed step
// 2/omega_upper, the single-body step 2/omega_lower and the converged limit of the touching
// contacts alone (the candidates that do not touch left out), and the wall time of one estimate
// in steps of the engine (the mean of `--steps` steps on the same packing). Table 2: the walls are
// held still and the bodies given seeded random velocities with as much kinetic energy as the
// springs hold; the run goes on for `--duration` critical steps at each safety factor, and the
// total energy E (kinetic at the mean of the half steps, normal and tangential springs) may only
// fall through slip: the table gives the largest rise between samples and the final E / E0.
// A factor above 1 is the step of safety 1 on bodies whose masses and inertias are then divided
// by its square (the step is kept until the next list build, which would correct it).
//
//   stability_limit SPECIMEN.h5 [SPECIMEN.h5 ...] [--iterations 4,8,16,32] [--reference 400]
//                   [--steps 200] [--threads 1] [--safeties 0.5,0.7,1.0,1.1] [--duration 2000]
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "dem/critical_step.h"
#include "dem/packing.h"
#include "dem/run_file_io.h"
#include "dem/simulation.h"
#include "list_argument.h"

namespace {

template <typename F>
double seconds(F&& f, int repeat) {
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < repeat; ++k) f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / repeat;
}

// Kinetic energy at the mean of the half steps around the next step, plus the springs' energy
// after it: 0.5 f_n overlap and 0.5 |f_t|^2 / k_t per contact (no dashpot).
double total_energy(dem::Simulation& sim) {
  const double before = sim.kinetic_energy();
  sim.step();
  const double xi = sim.contact_parameters().stiffness_ratio;
  double e = 0.5 * (before + sim.kinetic_energy());
  for (const dem::ContactRecord& c : sim.contact_records(true)) {
    if (!(c.normal_force > 0.0)) continue;
    e += 0.5 * c.normal_force * c.overlap;
    const Eigen::Vector3d ft(c.tangential_force.data());
    e += 0.5 * ft.squaredNorm() * c.overlap / (xi * c.normal_force);
  }
  return e;
}

// The specimen rattling in its fixed box at `safety` of the limit (past 1: see the header).
void energy_row(const dem::SimulationState& specimen, double safety, double duration) {
  dem::SimulationState state = specimen;
  for (dem::Wall& w : state.walls) {
    w.mode = dem::WallMode::kVelocity;
    w.velocity = 0.0;
  }
  dem::ContactParameters law;
  dem::SimulationOptions options;
  options.time_step_safety = std::min(safety, 1.0);
  double elastic = 0.0;
  {
    dem::Simulation at_rest(state, law, options);
    at_rest.step();  // a restored state holds no contact forces until its first step
    for (const dem::ContactRecord& c : at_rest.contact_records(true))
      elastic += 0.5 * c.normal_force * c.overlap;
  }
  dem::set_random_velocities(state.particles, elastic, 5);
  dem::Simulation sim(state, law, options);
  const double dt_c = sim.critical_time_step();
  if (safety > 1.0) {
    const double f2 = safety * safety;
    for (int b = 0; b < sim.particles().num_bodies(); ++b) {
      sim.particles().mass[b] /= f2;
      sim.particles().inertia_axial[b] /= f2;
      sim.particles().inertia_transverse[b] /= f2;
    }
  }
  const std::int64_t builds = sim.contacts().num_builds();
  const double e0 = total_energy(sim);
  double previous = e0, largest_rise = 0.0;
  const int samples = 100;
  const auto between = static_cast<std::int64_t>(duration / std::min(safety, 1.0) / samples);
  bool finite = true;
  try {
    for (int k = 0; k < samples && finite; ++k) {
      sim.run(between);
      const double e = total_energy(sim);
      finite = std::isfinite(e);
      largest_rise = std::max(largest_rise, (e - previous) / e0);
      previous = e;
    }
  } catch (const std::exception& e) {
    finite = false;
  }
  std::printf("| %d | %.2f | %.4g | %.4g | %s | %s | %lld |\n", sim.particles().num_bodies(),
              safety, dt_c, sim.time_step(), finite ? std::to_string(largest_rise).c_str() : "unstable",
              finite ? std::to_string(previous / e0).c_str() : "stopped",
              static_cast<long long>(sim.contacts().num_builds() - builds));
}

// The list's touching candidates only (after a step, whose touching flags they are).
dem::ContactList touching_only(const dem::ContactList& list, int num_spheres) {
  dem::ContactList t;
  t.build_position = list.build_position;
  for (int p = 0; p < list.num_pairs(); ++p)
    if (list.pair_touching[p]) {
      t.pair_i.push_back(list.pair_i[p]);
      t.pair_j.push_back(list.pair_j[p]);
    }
  for (int k = 0; k < list.num_wall_candidates(); ++k)
    if (list.wall_touching[k]) {
      t.wall_sphere.push_back(list.wall_sphere[k]);
      t.wall_index.push_back(list.wall_index[k]);
    }
  t.restore(list.skin(), list.num_builds(), num_spheres);
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> specimens;
  std::vector<int> iterations = {4, 8, 16, 32};
  int reference = 400, steps = 200, threads = 1;
  std::vector<double> safeties;
  double duration = 2000.0;
  const bool parsed = bench::parse_arguments(
      argc, argv, specimens, [&](const std::string& arg, const std::string& value) {
        if (arg == "--iterations") iterations = bench::parse_int_list(value);
        else if (arg == "--reference") reference = std::atoi(value.c_str());
        else if (arg == "--steps") steps = std::atoi(value.c_str());
        else if (arg == "--threads") threads = std::atoi(value.c_str());
        else if (arg == "--safeties") safeties = bench::parse_double_list(value);
        else if (arg == "--duration") duration = std::atof(value.c_str());
        else return false;
        return true;
      });
  if (!parsed) return 1;

  if (specimens.empty()) {
    std::fprintf(stderr, "usage: stability_limit SPECIMEN.h5 [...] [--iterations 4,8,16,32] "
                         "[--reference 400] [--steps 200] [--threads 1] "
                         "[--safeties 0.5,0.7,1.0,1.1] [--duration 2000]\n");
    return 1;
  }
  omp_set_num_threads(threads);
  std::printf("| clumps | candidates | iterations | 2/omega_max [s] | / converged | 2/omega_upper / "
              "converged | 2/omega_lower / converged | touching only / converged | estimate [steps] |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& path : specimens) {
    dem::RunFile specimen = dem::RunFile::open(path);
    const dem::SimulationState state = dem::read_checkpoint(specimen, nullptr);
    dem::ContactParameters law;  // the shearing law
    dem::Simulation sim(state, law, dem::SimulationOptions{});
    const dem::ContactList& list = sim.contacts();
    const auto limit = [&](int k) {
      return dem::stability_limit(sim.particles(), sim.walls(), list, law, 1.0,
                                  sim.options().min_parallel_items, k);
    };
    const dem::StabilityLimit converged = limit(reference);
    const double step_seconds = seconds([&] { sim.step(); }, steps);
    const dem::StabilityLimit touching =
        dem::stability_limit(sim.particles(), sim.walls(),
                             touching_only(list, sim.particles().num_spheres()), law, 1.0,
                             sim.options().min_parallel_items, reference);
    for (int k : iterations) {
      dem::StabilityLimit estimate;
      const double cost = seconds([&] { estimate = limit(k); }, 3);
      std::printf("| %d | %d | %d | %.4g | %.4f | %.4f | %.4f | %.4f | %.1f |\n",
                  sim.particles().num_bodies(), list.num_slots(), estimate.iterations,
                  estimate.time_step(), estimate.time_step() / converged.time_step(),
                  converged.guaranteed_time_step() / converged.time_step(),
                  2.0 / converged.omega_lower / converged.time_step(),
                  touching.time_step() / converged.time_step(), cost / step_seconds);
    }
    std::printf("| %d | %d | %d (converged) | %.4g | 1 | | | | |\n", sim.particles().num_bodies(),
                list.num_slots(), converged.iterations, converged.time_step());
  }
  if (safeties.empty()) return 0;
  std::printf("\n| clumps | safety | critical step [s] | time step [s] | largest rise / E0 | final E / E0 "
              "| list builds |\n|---|---|---|---|---|---|---|\n");
  for (const std::string& path : specimens) {
    dem::RunFile specimen = dem::RunFile::open(path);
    const dem::SimulationState state = dem::read_checkpoint(specimen, nullptr);
    for (double safety : safeties) energy_row(state, safety, duration);
  }
  return 0;
}
