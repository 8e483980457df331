// The model path of a DEM test (fit_path.h) against a converged one: the lateral stress is held at
// the increments' ends only, so the error in q/p falls with the square of the largest increment
// (FitOptions::fit_max_strain_step, report_max_strain_step). Issue 19 asks for 1e-3 in q/p.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "calibration/fit.h"

namespace calibration {
namespace {

const std::string kData = std::string(SFFCAL_SOURCE_DIR) + "/tests/data/reference/";

// The stored calibration's parameters (tests/data/reference/calibration).
FitVector stored_parameters() {
  std::ifstream in(kData + "calibration/parameters.json");
  const nlohmann::json stored = nlohmann::json::parse(in);
  FitVector x{};
  for (int i = 0; i < kNumFitParameters; ++i) {
    const std::string name = fit_parameter_names()[i];
    x[i] = name == "a_cs" ? stored.at("fabric_normalisation").at("a_cs").at("value").get<double>()
                          : stored.at("parameters").at(name).at("value").get<double>();
  }
  return x;
}

// Largest |q/p - q/p of the converged path| over the series rows.
double path_error(const TestData& t, const FitVector& x, double step,
                  const ModelCurves& converged) {
  const ModelCurves c = simulate_test(t, x, FitOptions::report_driver_options(), step);
  double worst = 0.0;
  for (std::size_t i = 0; i < c.eta.size(); ++i)
    worst = std::max(worst, std::abs(c.eta[i] - converged.eta[i]));
  return worst;
}

TEST(FitPath, ErrorFallsWithTheSquareOfTheStepAndTheReportsAreWithin1e3) {
  const FitVector x = stored_parameters();
  const FitOptions defaults;
  const double fit_step = defaults.fit_max_strain_step;
  const double report_step = defaults.report_max_strain_step;
  for (const char* run : {"matrix/iso_dense_100kPa.h5", "matrix/iso_loose_100kPa.h5"}) {
    const TestData t = read_run_file(kData + run);
    const ModelCurves converged = simulate_test(t, x, FitOptions::report_driver_options(), 1e-4);
    ASSERT_EQ(converged.rows_reached, static_cast<int>(t.axial_strain.size())) << run;
    const double rows_only = path_error(t, x, 0.0, converged);
    const double coarse = path_error(t, x, 2.0 * fit_step, converged);
    const double fit = path_error(t, x, fit_step, converged);
    const double report = path_error(t, x, report_step, converged);
    std::printf("%s: max |d(q/p)| against steps of 1e-4: rows only %.2e, steps %.0e %.2e, "
                "%.0e (the fit's) %.2e, %.0e (the reports') %.2e\n",
                run, rows_only, 2.0 * fit_step, coarse, fit_step, fit, report_step, report);
    EXPECT_LE(fit, 1e-3) << run << ": the fit's default step";
    EXPECT_LE(report, 1e-3) << run << ": the reports' default step";
    EXPECT_GT(coarse / fit, 2.5) << run << ": about second order (4 for halving the step)";
    EXPECT_LE(fit, rows_only);
  }
}

}  // namespace
}  // namespace calibration
