// A whole calibration (calibrate.h).
#include "calibration/calibrate.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace calibration {
namespace {

std::vector<TestData> read_tests(const std::vector<std::string>& paths, const char* role,
                                 const FitSettings& settings) {
  std::vector<TestData> tests;
  for (const std::string& path : paths) {
    tests.push_back(read_run_file(path));
    const TestData& t = tests.back();
    if (!settings.progress) continue;
    char line[512];
    std::snprintf(line, sizeof line,
                  "read %s (%s): %zu rows, %zu snapshots, p0 = %.0f Pa, e0 = %.4f, a_c0 = %.4f, "
                  "mu = %.4f",
                  path.c_str(), role, t.axial_strain.size(), t.a_c.size(), t.p0, t.e0, t.a_c0,
                  t.friction);
    settings.progress(line);
  }
  return tests;
}

void refuse_shared_runs(const std::vector<TestData>& tests, const std::vector<TestData>& held_out) {
  for (const TestData& h : held_out)
    for (const TestData& t : tests)
      if (h.source == t.source)
        throw std::runtime_error("'" + h.source + "' is both fitted and held out");
}

// A setting the caller gave that the model's fit does not read, refused by name.
void refuse_unread_settings(const ModelFit& fit, const CalibrationRequest& request) {
  const auto spell = [&](const std::string& name) {
    return request.spell ? request.spell(name) : name;
  };
  const std::vector<std::string> reads = fit.reads();
  for (const std::string& name : request.given)
    if (std::find(reads.begin(), reads.end(), name) == reads.end()) {
      // Every fit reads the output folder and the held-out runs besides its settings.
      std::string listed = spell("output") + ", " + spell("hold-out");
      for (const std::string& r : reads) listed += ", " + spell(r);
      throw std::invalid_argument(spell(name) + " does not apply to " + spell("model") + " " +
                                  fit.model() + " (its fit reads " + listed + ")");
    }
}

}  // namespace

CalibrationOutcome calibrate(const CalibrationRequest& request) {
  const std::unique_ptr<ModelFit> fit = make_fit(request.model, request.settings);
  refuse_unread_settings(*fit, request);
  std::vector<TestData> tests = read_tests(request.runs, "fitted", request.settings);
  std::vector<TestData> held_out = read_tests(request.held_out, "held out", request.settings);
  tests.insert(tests.end(), request.tests.begin(), request.tests.end());
  held_out.insert(held_out.end(), request.held_out_tests.begin(), request.held_out_tests.end());
  refuse_shared_runs(tests, held_out);
  check_unique_names(tests, held_out);
  for (auto* list : {&tests, &held_out})
    for (TestData& t : *list) t = fit->prepare(std::move(t));
  const auto start = std::chrono::steady_clock::now();
  fit->fit(tests);
  fit->predict(held_out);
  CalibrationOutcome outcome;
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outcome.report = fit->report();
  outcome.summary =
      fit->write_outputs(request.output_folder, request.program_version, request.command_line);
  outcome.plot_hint = fit->plot_hint(request.output_folder, request.runs);
  outcome.usable = fit->usable();
  return outcome;
}

}  // namespace calibration
