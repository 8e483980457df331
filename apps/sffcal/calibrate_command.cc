#include "calibrate_command.h"

#include <chrono>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>
#include <omp.h>

#include "calibration/calibrate.h"
#include "calibration/model_fit.h"

namespace sffcal {
namespace {

// Prints a line with the seconds since `begin`.
std::function<void(const std::string&)> progress_printer() {
  const auto begin = std::chrono::steady_clock::now();
  return [begin](const std::string& line) {
    const double t =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    std::printf("[%8.1f s] %s\n", t, line.c_str());
    std::fflush(stdout);
  };
}

}  // namespace

std::vector<std::string> given_settings(const CLI::App& calibrate) {
  std::vector<std::string> given;
  for (const char* name : calibration::kFitSettingNames)
    if (calibrate.count("--" + std::string(name)) > 0) given.push_back(name);
  return given;
}

int calibrate_command(const std::vector<std::string>& run_paths,
                      const CalibrateCommandOptions& options, const std::string& command_line) {
  calibration::CalibrationRequest request;
  request.runs = run_paths;
  request.held_out = options.held_out;
  request.model = options.model;
  request.settings = options.settings;
  request.settings.threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  request.settings.progress = progress_printer();
  request.given = options.given;
  request.spell = [](const std::string& name) {
    return name == "output" ? std::string("-o") : "--" + name;
  };
  request.output_folder = options.output_folder;
  request.program_version = SFFCAL_VERSION;
  request.command_line = command_line;
  const calibration::CalibrationOutcome outcome = calibration::calibrate(request);
  if (options.settings.verbose && !outcome.report.empty()) std::printf("%s\n", outcome.report.c_str());
  std::printf("\n%s\ncalibrated in %.1f s; outputs in %s (plot: %s)\n", outcome.summary.c_str(),
              outcome.seconds, options.output_folder.c_str(), outcome.plot_hint.c_str());
  return outcome.usable ? 0 : 1;
}

void add_calibrate_options(CLI::App& calibrate, CalibrateCommandOptions& options) {
  calibration::FitSettings& s = options.settings;
  calibrate
      .add_option("--model", options.model,
                  "acst: the ACST model's staged fit; network (or contact_network): the "
                  "contact-network model (docs/network-model.md; its runs need Z, Lambda and a_t "
                  "in /analysis/sff); any other registered model, e.g. linear_elastic: fitted "
                  "over its description to drained compression runs (docs/model-interface.md). "
                  "A setting the model's fit does not read is refused by name")
      ->check([](const std::string& name) {
        try {
          calibration::make_fit(name, {});
          return std::string();
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
      })
      ->capture_default_str();
  calibrate.add_option("--stages", s.stages, "ACST: all | csl | elastic | fabric | plastic | joint")
      ->check(CLI::IsMember({"all", "csl", "elastic", "fabric", "plastic", "joint"}))
      ->capture_default_str();
  calibrate
      .add_option("--starts", s.starts,
                  "starts of the multi-start stages (ACST: plastic and joint, the first from the "
                  "staged values; network: the first from the default or --start), the others "
                  "seeded")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  calibrate.add_option("--seed", s.seed, "seed of the extra starts")->capture_default_str();
  calibrate.add_option("--loss", s.loss, "ACST: robust loss: none | huber | cauchy")
      ->check(CLI::IsMember({"none", "huber", "cauchy"}))
      ->capture_default_str();
  calibrate.add_option("--points", s.max_points, "series rows per test used in the fit")
      ->check(CLI::Range(3, 100000))
      ->capture_default_str();
  calibrate
      .add_option("--max-strain-step", s.max_strain_step,
                  "ACST: largest axial-strain increment of the fit's path, splitting longer gaps "
                  "between its rows (0: the rows only; the path error in q/p falls with its "
                  "square, within 1e-3 of a converged path at the default)")
      ->check(CLI::Range(0.0, 0.1))
      ->capture_default_str();
  calibrate.add_flag("-v,--verbose", s.verbose, "print the solver's iterations as well");
  calibrate
      .add_option("--threads", options.threads,
                  "threads over tests (the result does not depend on it); 0: OMP_NUM_THREADS, "
                  "else all cores")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  calibrate
      .add_option("--hold-out", options.held_out,
                  "run files (with /analysis/sff) predicted with the fitted parameters but not "
                  "fitted; their errors and curves are written with the others")
      ->check(CLI::ExistingFile);
  calibrate.add_option("--hold", s.held,
                       "network: a parameter held at its starting value, e.g. c_t (at 1: "
                       "no Lode dependence), c_l (at 0), n_kappa (at 1) or n_ra (at 0: the fit's "
                       "last stage, which frees it, skipped); repeatable");
  calibrate.add_flag("--predicted-only", s.predicted_only,
                     "network: fit on the predicted paths from each start directly, "
                     "without the first stage along the DEM's strain paths (faster where an "
                     "undrained run makes that stage slow; docs/network-model.md)");
  calibrate
      .add_option("--start", s.start_file,
                  "network: a contact-network parameter file (an earlier fit's "
                  "parameters.json) whose values are the first start, the others drawn about it; "
                  "parameters it lacks start as the model before them (e.g. d_psi = 0)")
      ->check(CLI::ExistingFile);
  calibrate.add_option("--range", s.ranges,
                       "ACST: NAME=LOW:HIGH: the fit's search range of a parameter instead of the "
                       "default (docs/calibration.md, \"Bounds\"), e.g. n_d=0:60; repeatable");
}

}  // namespace sffcal
