#include "calibrate_command.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>
#include <omp.h>

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

// A setting given on the command line that the model's fit does not read, refused by name.
void refuse_unread_settings(const calibration::ModelFit& fit, const std::vector<std::string>& given) {
  const std::vector<std::string> reads = fit.reads();
  for (const std::string& name : given)
    if (std::find(reads.begin(), reads.end(), name) == reads.end()) {
      std::string listed;
      for (const std::string& r : reads) listed += (listed.empty() ? "--" : ", --") + r;
      throw std::invalid_argument("--" + name + " does not apply to --model " + fit.model() +
                                  " (its fit reads -o, --hold-out, " + listed + ")");
    }
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
  calibration::FitSettings settings = options.settings;
  settings.threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  settings.progress = progress_printer();
  const std::unique_ptr<calibration::ModelFit> fit =
      calibration::make_fit(options.model, settings);
  refuse_unread_settings(*fit, options.given);
  std::vector<calibration::TestData> tests = read_tests(run_paths, "fitted");
  std::vector<calibration::TestData> held_out = read_tests(options.held_out, "held out");
  refuse_shared_runs(tests, held_out);
  calibration::check_unique_names(tests, held_out);
  for (auto* list : {&tests, &held_out})
    for (calibration::TestData& t : *list) t = fit->prepare(std::move(t));
  const auto start = std::chrono::steady_clock::now();
  fit->fit(tests);
  fit->predict(held_out);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options.settings.verbose && !fit->report().empty()) std::printf("%s\n", fit->report().c_str());
  const std::string summary = fit->write_outputs(options.output_folder, SFFCAL_VERSION, command_line);
  std::printf("\n%s\ncalibrated in %.1f s; outputs in %s (plot: %s)\n", summary.c_str(), seconds,
              options.output_folder.c_str(),
              fit->plot_hint(options.output_folder, run_paths).c_str());
  return fit->usable() ? 0 : 1;
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
