#include "calibrate_command.h"

#include <chrono>
#include <cstdio>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>
#include <omp.h>

#include "calibration/any_model_fit.h"
#include "calibration/fit.h"
#include "calibration/network_fit.h"
#include "model/descriptor.h"

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

std::vector<calibration::TestData> read_tests(const std::vector<std::string>& paths,
                                              const char* role) {
  std::vector<calibration::TestData> tests;
  for (const std::string& path : paths) {
    tests.push_back(calibration::read_run_file(path));
    const calibration::TestData& t = tests.back();
    std::printf("read %s (%s): %zu rows, %zu snapshots, p0 = %.0f Pa, e0 = %.4f, a_c0 = %.4f, "
                "mu = %.4f\n",
                path.c_str(), role, t.axial_strain.size(), t.a_c.size(), t.p0, t.e0, t.a_c0,
                t.friction);
  }
  return tests;
}

void refuse_shared_runs(const std::vector<calibration::TestData>& tests,
                        const std::vector<calibration::TestData>& held_out) {
  for (const calibration::TestData& h : held_out)
    for (const calibration::TestData& t : tests)
      if (h.source == t.source)
        throw std::runtime_error("'" + h.source + "' is both fitted and held out");
}

// The contact-network fit's first start: the parameter file's values (those it lacks at their
// value_if_absent, the model before them), or the default start placed by the tests.
model::network::Parameters<double> network_start(
    const std::string& path, const std::vector<calibration::TestData>& tests) {
  namespace net = calibration::network;
  if (path.empty()) return net::default_start(tests);
  double youngs_modulus = net::kDemYoungsModulus;
  const model::network::Parameters<double> start =
      model::network::read_parameters_json(path, &youngs_modulus);
  if (youngs_modulus != net::kDemYoungsModulus)
    throw std::runtime_error("--start " + path + ": its youngs_modulus " +
                             std::to_string(youngs_modulus) + " Pa is not the DEM's " +
                             std::to_string(net::kDemYoungsModulus) +
                             " Pa, which normalises Lambda in the fit");
  std::printf("first start from %s\n", path.c_str());
  return start;
}

int calibrate_network(const std::vector<std::string>& run_paths,
                      const CalibrateCommandOptions& options, const std::string& command_line) {
  namespace net = calibration::network;
  net::FitOptions fit;
  fit.starts = options.starts;
  fit.seed = options.seed;
  fit.threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  fit.held = options.held_parameters;
  fit.first_stage = !options.predicted_only;
  fit.progress = progress_printer();
  std::vector<calibration::TestData> tests = read_tests(run_paths, "fitted");
  std::vector<calibration::TestData> held_out = read_tests(options.held_out, "held out");
  refuse_shared_runs(tests, held_out);
  calibration::check_unique_names(tests, held_out);
  for (auto* list : {&tests, &held_out})
    for (calibration::TestData& t : *list) {
      net::initial_state(t);  // names a test without Z
      t = net::with_closing_normal_anisotropy(std::move(t));
    }
  const net::Parameters<double> first = network_start(options.start_file, tests);
  const auto start = std::chrono::steady_clock::now();
  const net::FitResult result = net::fit(tests, first, fit);
  if (options.verbose) std::printf("%s\n", result.report.c_str());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string summary = net::write_fit_outputs(options.output_folder, tests, held_out,
                                                     result, fit, SFFCAL_VERSION, command_line);
  std::string runs;
  for (const auto* list : {&run_paths, &options.held_out})
    for (const std::string& path : *list) runs += " " + path;
  std::printf("\n%s\ncalibrated in %.1f s; outputs in %s (plot: scripts/plot_network.py %s%s -o "
              "network.png)\n",
              summary.c_str(), seconds, options.output_folder.c_str(),
              options.output_folder.c_str(), runs.c_str());
  return 0;
}

// Any other registered model, fitted over its description (calibration/any_model_fit.h).
int calibrate_any_model(const std::vector<std::string>& run_paths,
                        const CalibrateCommandOptions& options, const std::string& command_line) {
  const model::ModelDescription& description = model::find_model(options.model);
  calibration::AnyModelFitOptions fit;
  fit.max_points = options.max_points;
  const std::vector<calibration::TestData> tests = read_tests(run_paths, "fitted");
  const std::vector<calibration::TestData> held_out = read_tests(options.held_out, "held out");
  refuse_shared_runs(tests, held_out);
  calibration::check_unique_names(tests, held_out);
  const auto start = std::chrono::steady_clock::now();
  const calibration::AnyModelFitResult result =
      calibration::fit_any_model(description, tests, held_out, fit);
  if (options.verbose) std::printf("%s\n", result.termination.c_str());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string summary = calibration::write_any_model_fit_outputs(
      options.output_folder, description, tests, held_out, result, fit, SFFCAL_VERSION,
      command_line);
  std::printf("\n%s\ncalibrated in %.1f s; outputs in %s\n", summary.c_str(), seconds,
              options.output_folder.c_str());
  return result.usable ? 0 : 1;
}

}  // namespace

FitKind fit_kind(const std::string& model) {
  if (model == "acst") return FitKind::kAcst;
  if (model == "network" || model == "contact_network") return FitKind::kNetwork;
  model::find_model(model);  // throws, listing the registered names
  return FitKind::kAnyModel;
}

int calibrate_command(const std::vector<std::string>& run_paths,
                      const CalibrateCommandOptions& options, const std::string& command_line) {
  const FitKind kind = fit_kind(options.model);
  if (kind == FitKind::kNetwork) return calibrate_network(run_paths, options, command_line);
  if (kind == FitKind::kAnyModel) return calibrate_any_model(run_paths, options, command_line);
  if (!options.held_parameters.empty())
    throw std::invalid_argument("--hold applies to --model network (ACST: --range)");
  if (options.predicted_only)
    throw std::invalid_argument("--predicted-only applies to --model network (ACST: --stages)");
  if (!options.start_file.empty())
    throw std::invalid_argument("--start applies to --model network (ACST: --range)");
  calibration::FitOptions fit;
  fit.stages = calibration::parse_stages(options.stages);
  fit.loss = calibration::parse_loss(options.loss);
  fit.starts = options.starts;
  fit.seed = options.seed;
  fit.max_points = options.max_points;
  fit.fit_max_strain_step = options.max_strain_step;
  fit.verbose = options.verbose;
  fit.threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  for (const std::string& range : options.ranges) calibration::set_search_range(fit, range);
  fit.progress = progress_printer();
  const std::vector<calibration::TestData> tests = read_tests(run_paths, "fitted");
  const std::vector<calibration::TestData> held_out = read_tests(options.held_out, "held out");
  refuse_shared_runs(tests, held_out);
  const auto start = std::chrono::steady_clock::now();
  calibration::CalibrationResult result = calibration::calibrate(tests, fit);
  calibration::predict(held_out, fit, result);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string summary = calibration::write_calibration_outputs(
      options.output_folder, tests, result, fit, SFFCAL_VERSION, command_line, held_out);
  std::printf("\n%s\ncalibrated in %.1f s; outputs in %s (plot: scripts/plot_calibration.py %s)\n",
              summary.c_str(), seconds, options.output_folder.c_str(),
              options.output_folder.c_str());
  return 0;
}

void add_calibrate_options(CLI::App& calibrate, CalibrateCommandOptions& options) {
  calibrate
      .add_option("--model", options.model,
                  "acst: the ACST model's staged fit; network (or contact_network): the "
                  "contact-network model (docs/network-model.md; its runs need Z, Lambda and a_t "
                  "in /analysis/sff; it reads --starts, --seed, --threads, --hold-out, --hold, "
                  "--predicted-only, --start, -v); any other registered model, e.g. "
                  "linear_elastic: fitted over its description to drained compression runs "
                  "(docs/model-interface.md; it reads --hold-out, --points, -v)")
      ->check([](const std::string& name) {
        try {
          fit_kind(name);
          return std::string();
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
      })
      ->capture_default_str();
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
  calibrate.add_option("--hold", options.held_parameters,
                       "--model network: a parameter held at its starting value, e.g. c_t (at 1: "
                       "no Lode dependence), c_l (at 0), n_kappa (at 1) or n_ra (at 0: the fit's "
                       "last stage, which frees it, skipped); repeatable");
  calibrate.add_flag("--predicted-only", options.predicted_only,
                     "--model network: fit on the predicted paths from each start directly, "
                     "without the first stage along the DEM's strain paths (faster where an "
                     "undrained run makes that stage slow; docs/network-model.md)");
  calibrate
      .add_option("--start", options.start_file,
                  "--model network: a contact-network parameter file (an earlier fit's "
                  "parameters.json) whose values are the first start, the others drawn about it; "
                  "parameters it lacks start as the model before them (e.g. d_psi = 0)")
      ->check(CLI::ExistingFile);
  calibrate.add_option("--range", options.ranges,
                       "NAME=LOW:HIGH: the fit's search range of a parameter instead of the "
                       "default (docs/calibration.md, \"Bounds\"), e.g. n_d=0:60; repeatable");
}

}  // namespace sffcal
