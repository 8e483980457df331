#include "dem_commands.h"

#include <omp.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "dem/run_config.h"
#include "dem/run_file_io.h"
#include "dem/specimen.h"
#include "dem/triaxial.h"
#include "dem/vtk_writer.h"
#include "csv_table.h"
#include "output_guard.h"
#include "progress.h"
#include "sffcal/output_file.h"

namespace sffcal {
namespace {

runfile::RunMetadata metadata(const char* kind, const dem::RunConfig& config) {
  return dem::run_metadata(kind, config, SFFCAL_VERSION);
}

void use_threads(const dem::RunConfig& config) {
  if (config.threads > 0) omp_set_num_threads(config.threads);
}

std::string format_seconds(double s) {
  char text[32];
  if (s >= 3600) std::snprintf(text, sizeof(text), "%.1f h", s / 3600);
  else if (s >= 60) std::snprintf(text, sizeof(text), "%.1f min", s / 60);
  else std::snprintf(text, sizeof(text), "%.0f s", s);
  return text;
}

dem::TriaxialSummary shear(dem::Simulation& sim, const dem::RunConfig& config, runfile::RunFile& file,
                           const runfile::CheckpointExtras* resumed) {
  dem::TriaxialTest test(sim, config.triaxial);
  ProgressLine line;
  const dem::TriaxialSummary summary = test.run(&file, [&](const dem::TriaxialProgress& p) {
    if (!p.warning.empty()) {
      line.finish();
      std::fflush(stdout);
      std::fprintf(stderr, "sffcal: warning: %s\n", p.warning.c_str());
    }
    char text[200];
    std::snprintf(text, sizeof(text), "axial strain %.4f / %.3f  q/p %.3f  %.0f steps/s  %s left",
                  p.axial_strain, p.target_strain, p.eta, p.steps_per_second,
                  format_seconds(p.seconds_left).c_str());
    line.update(p.axial_strain / p.target_strain, text);
  }, resumed);
  line.finish();
  const std::string csv = file.path() + ".series.csv";
  write_series_csv(file, csv);
  std::printf("%s\nrun file: %s (series also in %s)\n", summary.describe().c_str(),
              file.path().c_str(), csv.c_str());
  return summary;
}

// Prepares a specimen and saves it as a specimen file (snapshot + checkpoint).
void prepare_and_save(const dem::RunConfig& config, const std::string& out_path) {
  use_threads(config);
  std::printf("preparing %d %s (d in [%.3g, %.3g] mm), p'0 %.4g kPa, seed %llu, %d threads\n",
              config.num_bodies, config.grains.centre_distance_ratio > 0 ? "two-sphere clumps" : "spheres",
              config.grains.min_diameter * 1e3, config.grains.max_diameter * 1e3,
              config.preparation.pressure / 1e3, static_cast<unsigned long long>(config.seed),
              omp_get_max_threads());
  dem::PreparationReport report;
  std::fflush(stdout);
  ProgressLine line;  // off a terminal the log gets one line per compaction instead
  const dem::Simulation sim = dem::prepare_specimen(
      config, &report,
      [&](const std::string& msg) {
        line.finish();
        std::printf("  %s\n", msg.c_str());
        std::fflush(stdout);
      },
      [&](const dem::CompactionResult& r) {
        char text[160];
        std::snprintf(text, sizeof(text),
                      "compacting: step %lld, worst wall stress error %.2f %%, unbalanced force %.2e",
                      static_cast<long long>(r.steps), 100.0 * r.worst_stress_error,
                      r.unbalanced_force_ratio);
        line.update(-1.0, text);
      });
  line.finish();
  runfile::RunFile file = runfile::RunFile::create(out_path, metadata("specimen", config), {});
  file.write_snapshot(dem::take_snapshot(sim, 0.0));
  dem::write_checkpoint(file, sim.state(), {{"pressure", config.preparation.pressure},
                                            {"void_ratio", report.void_ratio},
                                            {"compaction_friction", report.compaction_friction}});
  file.write_note("preparation", report.describe());
  std::printf("%s\nspecimen file: %s\n", report.describe().c_str(), out_path.c_str());
}

}  // namespace

int print_default_config(const std::string& out_path) {
  if (out_path.empty()) {
    std::printf("%s", dem::default_run_config_text().c_str());
    return 0;
  }
  write_text_file(out_path, dem::default_run_config_text());
  std::printf("wrote %s\n", out_path.c_str());
  return 0;
}

int prepare_command(const std::string& config_path, const RunFileTarget& out) {
  const dem::RunConfig config = dem::load_run_config(config_path);
  out.make([&](const std::string& path) { prepare_and_save(config, path); });
  return 0;
}

namespace {

// The triaxial test of `config` on the specimen, written to out_path.
int run_triaxial(const dem::RunConfig& config, const std::string& specimen_path,
                 const std::string& out_path) {
  use_threads(config);
  runfile::CheckpointExtras specimen_extras;
  dem::SimulationState state = [&] {
    runfile::RunFile specimen = runfile::RunFile::open(specimen_path);
    if (specimen.metadata().kind != "specimen")
      throw std::runtime_error(specimen_path + " is a " + specimen.metadata().kind +
                               " run file, not a specimen (`sffcal prepare` writes one; `sffcal "
                               "triaxial --resume` continues a test)");
    // The bodies' masses are the specimen's: a config of another grain density would be recorded
    // in /physics and not applied (the results were those of the specimen's density).
    const double density = specimen.metadata().physics.grain_density;
    if (density > 0.0 && std::abs(config.grains.density - density) > 1e-12 * density)
      throw std::runtime_error("the config's grains.density " + std::to_string(config.grains.density) +
                               " kg/m^3 differs from the specimen's " + std::to_string(density) +
                               " kg/m^3 (" + specimen_path + "), whose bodies carry their masses: "
                               "give the specimen's density");
    return dem::read_checkpoint(specimen, &specimen_extras);
  }();
  const double sigma3 = config.triaxial.confining_stress;
  const double p0 = specimen_extras.count("pressure") ? specimen_extras.at("pressure") : sigma3;
  if (std::abs(p0 - sigma3) > config.preparation.compaction.stress_tolerance * sigma3) {
    // A specimen prepared at another pressure is first brought isotropically to sigma_3.
    std::printf("re-consolidating the specimen from %.4g to %.4g kPa\n", p0 / 1e3, sigma3 / 1e3);
    state = dem::reconsolidate(std::move(state), config, sigma3);
  }
  dem::Simulation sim(std::move(state), config.contact, config.engine);
  std::printf("triaxial compression: sigma_3 %.4g kPa, strain rate %.3g /s, %d bodies, time step "
              "%.3g s (critical %.3g s), density scaling %.3g, %d threads\n  scene: %s\n",
              sigma3 / 1e3, config.triaxial.strain_rate, sim.particles().num_bodies(),
              sim.time_step(), sim.critical_time_step(), config.engine.density_scaling,
              omp_get_max_threads(), sim.features().describe().c_str());
  runfile::RunFile file = runfile::RunFile::create(out_path, metadata("triaxial", config),
                                           dem::triaxial_series_names());
  file.write_note("specimen", specimen_path);
  shear(sim, config, file, nullptr);
  return 0;
}

}  // namespace

int triaxial_command(const std::string& config_path, const std::string& specimen_path,
                     const RunFileTarget& out) {
  const dem::RunConfig config = dem::load_run_config(config_path);
  out.make([&](const std::string& path) { run_triaxial(config, specimen_path, path); });
  return 0;
}

int resume_command(const std::string& run_path) {
  runfile::RunFile file = runfile::RunFile::open(run_path, true);
  if (file.metadata().kind != "triaxial")
    throw std::runtime_error(run_path + " is a " + file.metadata().kind +
                             " file, not a triaxial run: --resume continues a killed triaxial "
                             "test (shear a specimen with: sffcal triaxial -c CONFIG -s " +
                             run_path + " -o RUN.h5)");
  const dem::RunConfig config = dem::parse_run_config(file.metadata().config_text, run_path + " (stored config)");
  use_threads(config);
  if (!file.has_checkpoint()) throw std::runtime_error(run_path + " has no checkpoint to resume from");
  runfile::CheckpointExtras extras;
  dem::SimulationState state = dem::read_checkpoint(file, &extras);
  dem::Simulation sim(std::move(state), config.contact, config.engine);
  std::printf("resuming %s at step %lld\n", run_path.c_str(), static_cast<long long>(sim.step_count()));
  shear(sim, config, file, &extras);
  return 0;
}

int dem_command(const std::string& config_path, const RunFileTarget& specimen,
                const RunFileTarget& out) {
  const dem::RunConfig config = dem::load_run_config(config_path);  // read once for both stages
  specimen.make([&](const std::string& path) { prepare_and_save(config, path); });
  out.make([&](const std::string& path) { run_triaxial(config, specimen.path(), path); });
  return 0;
}

int vtk_command(const std::string& run_path, const std::string& folder) {
  const runfile::RunFile file = runfile::RunFile::open(run_path);
  const int n = dem::export_run_to_vtk(file, folder);
  std::printf("wrote %d snapshots to %s (open spheres.pvd in ParaView; Glyph by 'radius')\n", n,
              folder.c_str());
  return 0;
}

int info_command(const std::string& run_path) {
  const runfile::RunFile file = runfile::RunFile::open(run_path);
  const runfile::RunMetadata m = file.metadata();
  std::printf("%s: %s run, program version %s, seed %llu, schema %lld\n", run_path.c_str(),
              m.kind.c_str(), m.program_version.c_str(), static_cast<unsigned long long>(m.seed),
              static_cast<long long>(m.schema_version));
  std::printf("physics: E %.4g Pa, k_t/k_n %.3g, friction %.6g (walls %.3g), grain density %.5g "
              "kg/m^3, density scaling %.3g%s\n",
              m.physics.youngs_modulus, m.physics.stiffness_ratio, m.physics.friction,
              m.physics.wall_friction, m.physics.grain_density, m.physics.density_scaling,
              m.schema_version < 2 ? " (from the stored config)" : "");
  if (!m.loading.path.empty()) {
    std::printf("loading: %s\n", m.loading.path.c_str());
    for (int axis = 0; axis < 3; ++axis)
      std::printf("  %c: %s\n", "xyz"[axis], m.loading.axis_control[axis].c_str());
  } else if (m.kind == "triaxial") {
    std::printf("loading: drained_compression (a file from before /loading was written)\n");
  }
  std::printf("series: %zu rows of %zu columns; snapshots: %d; checkpoint: %s\n",
              file.series_length(), file.series_names().size(), file.num_snapshots(),
              file.has_checkpoint() ? "yes" : "no");
  for (const char* note : {"import", "preparation", "specimen", "summary"}) {  // schema 1 kept a summary note
    const std::string text = file.read_note(note);
    if (!text.empty()) std::printf("%s: %s\n", note, text.c_str());
  }
  if (file.has_summary()) std::printf("summary: %s\n", file.read_summary().describe().c_str());
  return 0;
}

}  // namespace sffcal
