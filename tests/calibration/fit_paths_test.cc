// The fit's model path on every axisymmetric loading path of the DEM (issue 19): the constraint
// each path holds, agreement with the library's drivers, exact parameter derivatives through the
// lateral Newton solve, and c and the undrained response fitted back from model data.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "calibration/fit.h"
#include "fit_path.h"
#include "fit_solve.h"
#include "synthetic_test.h"
#include "toyoura.h"

namespace calibration {
namespace {

using testing::scientific;
using testing::synthetic_test;

constexpr TestPath kPaths[] = {TestPath::kDrainedCompression, TestPath::kDrainedExtension,
                               TestPath::kConstantPCompression, TestPath::kUndrainedCompression,
                               TestPath::kUndrainedExtension};

// Toyoura-like parameters with a Lode dependence (c = 0.75) and a_cs = 0.8.
FitVector toyoura_vector() {
  FitVector x = to_fit_vector(testing::toyoura(), 0.8);
  x[fit_parameter_index("c")] = 0.75;
  return x;
}

TEST(FitPaths, EachPathHoldsItsConstraintAndAgreesWithTheDrivers) {
  const FitVector x = toyoura_vector();
  const DriverOptions report = FitOptions::report_driver_options();  // Newton to 1e-8 p
  const Parameters<double> par = model_parameters(x);
  for (TestPath path : kPaths) {
    const std::string name = to_string(path);
    const TestData t = synthetic_test(name, x, 0.70, 0.1, 0.0, 1, path, 0.1);
    const ModelCurves c = simulate_test(t, x, report);
    const std::size_t n = t.axial_strain.size();
    ASSERT_EQ(c.rows_reached, static_cast<int>(n)) << name;
    EXPECT_GT(axial_direction(path) * c.eta.back(), 0.5) << name << ": q/p takes the path's sign";
    double worst = 0.0;  // the constraint's residual over the rows
    for (std::size_t k = 0; k < n; ++k) {
      if (holds_lateral_stress(path))  // sigma_3 = p - q/3 = p (1 - eta/3) held at p0
        worst = std::max(worst, std::abs(c.p[k] * (1.0 - c.eta[k] / 3.0) - t.p0) / t.p0);
      else if (path == TestPath::kConstantPCompression)
        worst = std::max(worst, std::abs(c.p[k] - t.p0) / t.p0);
      else
        worst = std::max(worst, std::abs(c.volumetric_strain[k]));
    }
    EXPECT_LT(worst, is_undrained(path) ? 1e-15 : 1e-7) << name;
    // The library's drivers on the same increments: the undrained one takes the same strain
    // increments (the same updates to rounding), the drained one solves the same lateral
    // condition with the general mixed-control Newton.
    if (path == TestPath::kConstantPCompression) continue;
    const State<double> s0 = isotropic_state(
        t.p0, t.e0, triaxial_deviator(kSqrtTwoThirds * t.a_c0 / x[kAcsIndex]));
    const double end = t.axial_strain.back();
    const int increments = static_cast<int>(n) - 1;
    const PathResult<double> driver = is_undrained(path)
                                          ? undrained_triaxial(par, s0, end, increments, report)
                                          : drained_triaxial(par, s0, end, increments, report);
    ASSERT_EQ(driver.rows.size(), n) << name;
    double difference = 0.0;
    for (std::size_t k = 0; k < n; ++k)
      difference = std::max(difference, std::abs(driver.rows[k].eta - c.eta[k]));
    std::printf("%s: constraint residual %.1e, max |q/p - the driver's| %.1e\n", name.c_str(),
                worst, difference);
    EXPECT_LT(difference, is_undrained(path) ? 1e-12 : 1e-6) << name;
  }
}

// The Jacobian of the fit's residuals (Jets through the lateral Newton solve by the implicit
// function theorem, fit_path.h) against centred differences of the same discrete path, on every
// path, past the peak of the drained compression.
TEST(FitPaths, ParameterDerivativesThroughEachPathMatchCentredDifferences) {
  using Jet = ceres::Jet<double, 6>;
  const FitVector x = toyoura_vector();
  const std::array<const char*, 6> names = {"G0", "M_c", "c", "h0", "n_d", "k_F"};
  DriverOptions smooth;  // one implicit step per increment: smooth in the parameters
  smooth.integration = IntegrationOptions();
  smooth.stress_tolerance = 1e-12;
  smooth.max_newton_iterations = 50;
  const fit_detail::ResidualSpec spec;
  double worst_overall = 0.0;
  for (TestPath path : kPaths) {
    const std::string name = to_string(path);
    const TestData t = synthetic_test(name, x, 0.70, 0.1, 0.2, 3, path, 0.1);
    const fit_detail::Grid g = fit_detail::make_grid(t, 21, 1e-3);  // 100 increments
    const int n = fit_detail::count_residuals(t, g, spec);
    std::array<Jet, kNumFitParameters> v;
    for (int i = 0; i < kNumFitParameters; ++i) v[i] = Jet(x[i]);
    for (int j = 0; j < 6; ++j) v[fit_parameter_index(names[j])].v[j] = 1.0;
    const PathResult<Jet> jet_path = fit_detail::run_test(t, g, v, smooth);
    // kUnreliable (a step's error estimate above max_step_error, the dense specimen's first
    // loading) still is a discrete path whose derivatives the Jets must give.
    ASSERT_NE(jet_path.status, UpdateStatus::kFailed) << name;
    std::vector<Jet> r(static_cast<std::size_t>(n));
    fit_detail::path_residuals(t, g, spec, v[kAcsIndex], jet_path, r.data());
    if (path == TestPath::kDrainedCompression) {
      double peak = 0.0;
      for (const auto& row : jet_path.rows) peak = std::max(peak, row.eta.a);
      ASSERT_LT(jet_path.rows.back().eta.a, 0.97 * peak) << "the path must end past the peak";
    }
    auto residuals_at = [&](int j, double factor) {
      FitVector y = x;
      y[fit_parameter_index(names[j])] *= factor;
      const PathResult<double> p = fit_detail::run_test(t, g, y, smooth);
      EXPECT_EQ(p.status, jet_path.status) << name;
      std::vector<double> out(static_cast<std::size_t>(n));
      fit_detail::path_residuals(t, g, spec, y[kAcsIndex], p, out.data());
      return out;
    };
    for (int j = 0; j < 6; ++j) {
      const double h = 1e-5 * x[fit_parameter_index(names[j])];
      const std::vector<double> plus = residuals_at(j, 1.0 + 1e-5);
      const std::vector<double> minus = residuals_at(j, 1.0 - 1e-5);
      // Relative to the largest derivative of this parameter over the residuals.
      double scale = 0.0, error = 0.0;
      for (int k = 0; k < n; ++k) scale = std::max(scale, std::abs(plus[k] - minus[k]) / (2 * h));
      for (int k = 0; k < n; ++k)
        error = std::max(error, std::abs(r[k].v[j] - (plus[k] - minus[k]) / (2 * h)));
      if (std::string(names[j]) == "c" && axial_direction(path) > 0.0) {
        EXPECT_LT(error, 1e-6) << name << ": c has no effect in compression";
        continue;
      }
      ASSERT_GT(scale, 0.0) << name << " " << names[j];
      worst_overall = std::max(worst_overall, error / scale);
      EXPECT_LT(error / scale, 1e-5) << name << " " << names[j];
    }
  }
  RecordProperty("worst_relative_error", scientific(worst_overall));
  std::printf("worst relative error of the Jacobian: %.2e\n", worst_overall);
}

// c is measured by the csl stage from the extension tests' ends (M_e / M_c) and refined by the
// joint stage; the undrained test's mean stress enters as a residual. Model data with noise.
TEST(FitPaths, CAndTheUndrainedResponseAreFittedBackFromModelData) {
  FitVector truth = toyoura_vector();
  truth[fit_parameter_index("h0")] = 5.0;
  truth[fit_parameter_index("n_d")] = 2.0;
  const std::vector<TestData> tests = {
      synthetic_test("compression", truth, 0.80, 0.1, 0.2, 31),
      synthetic_test("extension", truth, 0.80, 0.1, 0.2, 32, TestPath::kDrainedExtension),
      synthetic_test("undrained", truth, 0.85, 0.1, 0.2, 33, TestPath::kUndrainedCompression,
                     0.05)};
  FitOptions options;
  options.stages = {Stage::kCsl, Stage::kJoint};
  options.starts = 1;
  options.max_points = 25;
  options.initial = truth;
  options.fixed = {"G0", "nu", "m", "c_h", "e_A", "e_gamma", "lambda_c", "xi", "a_cs", "k_F",
                   "n_b", "A0", "n_G", "n_F"};
  const char* free[] = {"M_c", "c", "h0", "n_d"};
  const double distant[] = {1.3, 1.25, 2.0, 2.0};  // c starts at 0.94
  for (int j = 0; j < 4; ++j) options.initial[fit_parameter_index(free[j])] *= distant[j];
  const CalibrationResult r = calibrate(tests, options);
  ASSERT_EQ(r.stages.size(), 1u);
  EXPECT_EQ(r.stages[0].free_parameters, 4);
  EXPECT_EQ(r.estimates[fit_parameter_index("c")].stage, "joint");
  for (const char* name : free) {
    const int i = fit_parameter_index(name);
    const ParameterEstimate& e = r.estimates[i];
    std::printf("%s: fitted %.4f +- %.4f, truth %.4f\n", name, e.value, e.standard_error, truth[i]);
    ASSERT_GT(e.standard_error, 0.0) << name;
    EXPECT_LT(std::abs(e.value - truth[i]), 3.0 * e.standard_error) << name;
  }
  // The undrained test's errors are those of its effective stress path.
  ASSERT_EQ(r.errors.size(), 3u);
  EXPECT_EQ(r.errors[2].path, "undrained_compression");
  EXPECT_LT(r.errors[2].rms_p_ratio, 0.05);
  EXPECT_EQ(r.errors[2].rms_volumetric, 0.0);
  // Without an extension test c is held, and said.
  const CalibrationResult compression_only = calibrate({tests[0]}, options);
  EXPECT_EQ(compression_only.stages[0].free_parameters, 3);
  EXPECT_TRUE(compression_only.estimates[fit_parameter_index("c")].fixed);
  bool said = false;
  for (const std::string& note : compression_only.notes) said = said || note.find("c held") == 0;
  EXPECT_TRUE(said);
}

// solve_stage's check (the fit keeps a set the report can integrate): an end point the check
// refuses gives way to the newest earlier iterate it accepts; a check that accepts everything
// changes nothing, bit for bit; one that refuses everything keeps the end point and says so.
TEST(FitStageCheck, ARefusedEndPointGivesWayToTheNewestAcceptedIterate) {
  const FitVector truth = toyoura_vector();
  const int h0 = fit_parameter_index("h0");
  const std::vector<TestData> tests = {synthetic_test("dense", truth, 0.70, 0.1, 0.2, 5)};
  FitOptions options;
  const std::vector<fit_detail::Grid> grids = {
      fit_detail::make_grid(tests[0], options.max_points, options.fit_max_strain_step)};
  FitVector start = truth;
  start[h0] = 3.0 * truth[h0];
  auto solve = [&](const fit_detail::SetCheck& check) {
    return fit_detail::solve_stage(tests, grids, fit_detail::ResidualSpec(), start, {h0}, options,
                                   options.lower, options.upper, 1, 1, "check", check);
  };
  const fit_detail::StageResult plain = solve({});
  ASSERT_TRUE(std::isfinite(plain.final_cost));
  ASSERT_LT(std::abs(plain.x[h0] / truth[h0] - 1.0), 0.05);  // fitted back near the truth

  const fit_detail::StageResult all = solve([](const FitVector&) { return std::string(); });
  EXPECT_EQ(all.x, plain.x);
  EXPECT_EQ(all.final_cost, plain.final_cost);
  EXPECT_TRUE(all.note.empty()) << all.note;

  // Refuse the neighbourhood of the truth, where the fit ends.
  int calls = 0;
  auto near_truth = [&](const FitVector& x) {
    ++calls;
    return std::abs(x[h0] / truth[h0] - 1.0) < 0.1 ? std::string("near the truth") : std::string();
  };
  const fit_detail::StageResult guarded = solve(near_truth);
  EXPECT_GE(std::abs(guarded.x[h0] / truth[h0] - 1.0), 0.1);
  EXPECT_GT(guarded.final_cost, plain.final_cost);
  EXPECT_NE(guarded.note.find("refused (near the truth)"), std::string::npos) << guarded.note;
  EXPECT_NE(guarded.note.find("kept iteration"), std::string::npos) << guarded.note;
  EXPECT_LE(calls, 8);  // going back 1, 2, 4, ... iterations, not one by one
  ::testing::Test::RecordProperty("h0_guarded_over_truth", scientific(guarded.x[h0] / truth[h0]));
  ::testing::Test::RecordProperty("checks", calls);

  const fit_detail::StageResult none =
      solve([](const FitVector&) { return std::string("never"); });
  EXPECT_EQ(none.x, plain.x);
  EXPECT_NE(none.note.find("no earlier iterate was accepted"), std::string::npos) << none.note;
}

}  // namespace
}  // namespace calibration
