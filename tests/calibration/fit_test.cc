// The calibration: identifiability on model-generated data, the SFF relation, the covariance
// scaling, bad inputs, and a fit to the committed reduced DEM test.
#include "calibration/fit.h"

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "dem/loading_path.h"
#include "dem/run_config.h"
#include "runfile/run_file.h"
#include "synthetic_test.h"
#include "toyoura.h"
#include "sffcal/constants.h"

namespace calibration {
namespace {

using testing::scientific;

using testing::synthetic_test;

// Every named parameter free, inside its bounds, with a standard error, and within 3 standard
// errors of the truth (a 99.7 % interval per parameter); the fits are recorded.
void expect_fitted_back(const CalibrationResult& r, const FitVector& truth,
                        std::initializer_list<const char*> names) {
  for (const char* name : names) {
    const int i = fit_parameter_index(name);
    const ParameterEstimate& e = r.estimates[i];
    ::testing::Test::RecordProperty(std::string(name) + "_fit", scientific(e.value));
    ::testing::Test::RecordProperty(std::string(name) + "_se", scientific(e.standard_error));
    EXPECT_FALSE(e.fixed) << name;
    EXPECT_FALSE(e.at_bound) << name;
    ASSERT_GT(e.standard_error, 0.0) << name;
    EXPECT_LT(std::abs(e.value - truth[i]), 3.0 * e.standard_error)
        << name << ": fitted " << e.value << " +- " << e.standard_error << ", truth " << truth[i];
  }
}

// The Toyoura-like parameters with a_cs = 0.8, and `changes` (name, value) applied: the truth
// the identifiability tests make their synthetic data from.
FitVector toyoura_truth(std::initializer_list<std::pair<const char*, double>> changes) {
  FitVector truth = to_fit_vector(testing::toyoura(), 0.8);
  for (const auto& [name, value] : changes) truth[fit_parameter_index(name)] = value;
  return truth;
}

// The joint stage alone, one start from the truth, with `held` fixed there.
FitOptions joint_fit_from(const FitVector& truth, std::vector<std::string> held) {
  FitOptions options;
  options.stages = {Stage::kJoint};
  options.starts = 1;
  options.initial = truth;
  options.fixed = std::move(held);
  return options;
}

TEST(FitIdentifiability, ModelDataAreFittedBackFromADistantStart) {
  const FitVector truth = toyoura_truth({{"h0", 5.0}, {"n_d", 2.0}, {"k_F", 8.0}});
  // Noise of 0.2 residual scales: q/p +-0.01, eps_v +-0.001, a_c +-0.01.
  const std::vector<TestData> tests = {synthetic_test("dense", truth, 0.70, 0.1, 0.2, 11),
                                       synthetic_test("loose", truth, 0.88, 0.1, 0.2, 12)};
  // Free: M_c, h0, n_b, A0, n_d, k_F (the others are fixed at the truth).
  FitOptions options = joint_fit_from(truth, {"G0", "nu", "c", "m", "c_h", "e_A", "e_gamma",
                                              "lambda_c", "xi", "a_cs", "n_b_loose", "n_G",
                                              "n_F"});
  const std::initializer_list<const char*> free = {"M_c", "h0", "n_b", "A0", "n_d", "k_F"};
  const double distant[] = {1.5, 2.5, 2.0, 0.5, 2.0, 0.4};  // start = truth x factor
  int j = 0;
  for (const char* name : free) options.initial[fit_parameter_index(name)] *= distant[j++];
  const CalibrationResult r = calibrate(tests, options);
  ASSERT_EQ(r.stages.size(), 1u);
  EXPECT_LT(r.stages[0].final_cost, 1e-2 * r.stages[0].initial_cost);
  // Noise level 0.2 in normalised units: s^2 should be close to 0.04.
  RecordProperty("s2", scientific(r.covariance_scale));
  EXPECT_GT(r.covariance_scale, 0.02);
  EXPECT_LT(r.covariance_scale, 0.08);
  expect_fitted_back(r, truth, free);
}

// n_b_loose acts where psi > 0 only: fitted back from a test that starts looser than the
// critical state line (toyoura: e_c = 0.915 at 100 kPa), held with a note where none does.
TEST(FitIdentifiability, TheLooseSlopeIsFittedBackOnlyWhereATestStartsLoose) {
  const FitVector truth = toyoura_truth({{"h0", 5.0}, {"n_b_loose", 6.0}});
  const TestData dense = synthetic_test("dense", truth, 0.70, 0.1, 0.2, 31);
  const TestData loose = synthetic_test("loose", truth, 0.95, 0.1, 0.2, 32);
  FitOptions options =
      joint_fit_from(truth, {"G0", "nu", "c", "m", "c_h", "e_A", "e_gamma", "lambda_c", "xi",
                             "a_cs", "A0", "n_d", "k_F", "M_c", "n_G", "n_F"});
  options.initial[fit_parameter_index("h0")] = 10.0;
  options.initial[fit_parameter_index("n_b")] = 2.0;
  options.initial[fit_parameter_index("n_b_loose")] = 0.0;  // DM04's one slope
  const CalibrationResult r = calibrate({dense, loose}, options);
  expect_fitted_back(r, truth, {"h0", "n_b", "n_b_loose"});
  // The dense test alone: n_b_loose stays where it started, and the notes say why.
  const CalibrationResult d = calibrate({dense}, options);
  EXPECT_EQ(d.values[fit_parameter_index("n_b_loose")], 0.0);
  bool noted = false;
  for (const std::string& note : d.notes) noted = noted || note.find("n_b_loose held") == 0;
  EXPECT_TRUE(noted);
}

// n_G, the pressure exponent of the moduli, from a drained and an undrained test (whose p' path
// follows K(p)), started from DM04's 1/2.
TEST(FitIdentifiability, TheElasticExponentIsFittedBack) {
  const FitVector truth = toyoura_truth({{"h0", 5.0}, {"n_G", 0.2}});
  const std::vector<TestData> tests = {
      synthetic_test("dense", truth, 0.70, 0.1, 0.2, 41),
      synthetic_test("undrained", truth, 0.80, 0.1, 0.2, 42, TestPath::kUndrainedCompression,
                     0.05)};
  FitOptions options =
      joint_fit_from(truth, {"nu", "c", "m", "c_h", "e_A", "e_gamma", "lambda_c", "xi", "a_cs",
                             "A0", "n_d", "k_F", "M_c", "n_b", "n_b_loose", "n_F"});
  options.initial[fit_parameter_index("G0")] = 80.0;
  options.initial[fit_parameter_index("n_G")] = 0.5;
  const CalibrationResult r = calibrate(tests, options);
  expect_fitted_back(r, truth, {"G0", "h0", "n_G"});
}

// n_F, the state exponent of the fabric rate, from a dense and a loose test's a_c histories
// (psi < 0 and > 0), started from LD12's constant rate: the fabric stage alone fits it with k_F.
TEST(FitIdentifiability, TheFabricRatesStateExponentIsFittedBack) {
  const FitVector truth = toyoura_truth({{"h0", 5.0}, {"k_F", 8.0}, {"n_F", 6.0}});
  const std::vector<TestData> tests = {synthetic_test("dense", truth, 0.70, 0.1, 0.2, 51),
                                       synthetic_test("loose", truth, 0.95, 0.1, 0.2, 52)};
  FitOptions options;
  options.stages = {Stage::kFabric};
  options.initial = truth;
  options.initial[fit_parameter_index("k_F")] = 20.0;
  options.initial[fit_parameter_index("n_F")] = 0.0;
  options.fixed = {"a_cs"};
  const CalibrationResult r = calibrate(tests, options);
  expect_fitted_back(r, truth, {"k_F", "n_F"});
}

TEST(FitThreads, SameResultForAnyThreadCountAndHeldOutTestsArePredicted) {
  const FitVector truth = toyoura_truth({});
  const std::vector<TestData> tests = {synthetic_test("dense", truth, 0.70, 0.1, 0.2, 21),
                                       synthetic_test("loose", truth, 0.88, 0.1, 0.2, 22)};
  FitOptions options =
      joint_fit_from(truth, {"G0", "nu", "c", "m", "c_h", "e_A", "e_gamma", "lambda_c", "xi",
                             "a_cs", "k_F", "n_b_loose", "n_G", "n_F"});
  options.max_iterations = 6;
  options.initial[fit_parameter_index("h0")] *= 2.0;
  options.initial[fit_parameter_index("n_d")] *= 0.6;
  std::vector<std::string> lines;
  options.progress = [&](const std::string& line) { lines.push_back(line); };
  options.threads = 1;
  const CalibrationResult one = calibrate(tests, options);
  options.threads = 2;
  const CalibrationResult two = calibrate(tests, options);
  ASSERT_EQ(one.stages.size(), 1u);
  EXPECT_LT(one.stages[0].final_cost, one.stages[0].initial_cost);
  for (int i = 0; i < kNumFitParameters; ++i)
    EXPECT_EQ(one.values[i], two.values[i]) << fit_parameter_names()[i];  // bit for bit
  EXPECT_EQ(one.stages[0].final_cost, two.stages[0].final_cost);
  // Progress: a line at the stage start, per iteration and at the end.
  ASSERT_GE(lines.size(), 3u);
  EXPECT_NE(lines.front().find("stage joint"), std::string::npos) << lines.front();
  EXPECT_NE(lines[1].find("iteration 0"), std::string::npos) << lines[1];
  int done = 0;
  for (const std::string& line : lines) done += line.find("stage joint done") != std::string::npos;
  EXPECT_EQ(done, 2);  // one per calibrate call (lines holds both runs)
  EXPECT_GT(one.stages[0].timing.jacobian_evaluations, 0);
  EXPECT_GT(one.stages[0].timing.substeps_per_step, 1.0);
  // A held-out test is predicted at the fitted values, the same errors as test_errors.
  CalibrationResult predicted = one;
  predict({tests[1]}, options, predicted);
  ASSERT_EQ(predicted.predictions.size(), 1u);
  EXPECT_EQ(predicted.predictions[0].rms_eta, one.errors[1].rms_eta);
  TestData bad = tests[0];
  bad.eta[3] = std::nan("");
  EXPECT_THROW(predict({bad}, options, predicted), std::runtime_error);
}

TEST(FitSffRelation, RecoversKnownCoefficients) {
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 0.005);
  TestData t;
  t.friction = 0.5;
  const double c1 = 0.38, c2 = 0.45, c3 = 0.7;
  for (int k = 0; k < 60; ++k) {
    const double a = 1.6 * u(random), f = 1.6 * u(random), m = 0.7 * u(random);
    t.a_c.push_back(a);
    t.a_n.push_back(f);
    t.mobilisation.push_back(m);
    t.snapshot_eta.push_back(c1 * a + c2 * f + c3 * 0.5 * m + gauss(random));
  }
  const SffRelationFit fit = fit_sff_relation({t});
  ASSERT_TRUE(fit.available);
  EXPECT_EQ(fit.snapshots, 60);
  const double truth[] = {c1, c2, c3};
  for (int j = 0; j < 3; ++j) {
    EXPECT_GT(fit.standard_errors[j], 0.0);
    EXPECT_LT(std::abs(fit.coefficients[j] - truth[j]), 3.0 * fit.standard_errors[j]) << j;
  }
  EXPECT_NEAR(fit.rms, 0.005, 0.0015);
  EXPECT_NEAR(fit.distance,
              std::sqrt(std::pow(fit.coefficients[0] - 0.4, 2) + std::pow(fit.coefficients[1] - 0.4, 2) +
                        std::pow(fit.coefficients[2] - 0.6, 2)),
              1e-12);
  // Without friction the relation is not fitted, and says why.
  t.friction = 0.0;
  const SffRelationFit none = fit_sff_relation({t});
  EXPECT_FALSE(none.available);
  EXPECT_FALSE(none.note.empty());
}

struct Line {
  Line(double x, double y) : x_(x), y_(y) {}
  template <typename T>
  bool operator()(const T* ab, T* r) const {
    r[0] = y_ - (ab[0] + ab[1] * x_);
    return true;
  }
  double x_, y_;
};

TEST(FitCovariance, ScaledStandardErrorsEqualOrdinaryLeastSquares) {
  // y = a + b x + noise (sd 0.3): the scaled Ceres errors equal the textbook OLS errors
  // s sqrt((X^T X)^-1), with s^2 = RSS/(n - 2); unscaled they would be smaller by s.
  std::mt19937_64 random(3);
  std::normal_distribution<double> gauss(0.0, 0.3);
  const int n = 50;
  std::vector<double> x(n), y(n);
  double ab[2] = {0.0, 0.0};
  ceres::Problem problem;
  for (int k = 0; k < n; ++k) {
    x[k] = 0.1 * k;
    y[k] = 1.0 + 2.0 * x[k] + gauss(random);
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Line, 1, 2>(new Line(x[k], y[k])),
                             nullptr, ab);
  }
  ceres::Solver::Options o;
  ceres::Solver::Summary s;
  ceres::Solve(o, &problem, &s);
  std::vector<double> errors;
  double s2 = 0.0;
  ASSERT_TRUE(scaled_standard_errors(problem, ab, 2, s.final_cost, n, 2, errors, &s2));
  double sx = 0, sxx = 0, rss = 0;
  for (int k = 0; k < n; ++k) {
    sx += x[k];
    sxx += x[k] * x[k];
    rss += std::pow(y[k] - ab[0] - ab[1] * x[k], 2);
  }
  const double det = n * sxx - sx * sx;
  const double ols_s2 = rss / (n - 2);
  EXPECT_NEAR(s2, ols_s2, 1e-10 * ols_s2);
  EXPECT_NEAR(errors[0], std::sqrt(ols_s2 * sxx / det), 1e-6 * errors[0]);
  EXPECT_NEAR(errors[1], std::sqrt(ols_s2 * n / det), 1e-6 * errors[1]);
  EXPECT_NEAR(std::sqrt(s2), 0.3, 0.1);
  // Not more residuals than free parameters: no errors.
  EXPECT_FALSE(scaled_standard_errors(problem, ab, 2, s.final_cost, 2, 2, errors));
}

TestData small_valid_test() {
  FitVector x = to_fit_vector(testing::toyoura(), 0.8);
  TestData t = synthetic_test("valid", x, 0.75, 0.0, 0.0, 1);
  return t;
}

// Residuals correlated along a curve (the DEM's excursions: lag-1 autocorrelation 0.7-0.95 in
// the matrix fits) make s^2 (J^T J)^-1 too small. A straight line through AR(1) noise (rho 0.8),
// 2000 replicates: the robust (Newey-West) standard error against the spread of the estimates.
TEST(FitCovariance, RobustStandardErrorsFollowTheSpreadUnderCorrelatedNoise) {
  const int n = 60, replicates = 2000;
  const double rho = 0.8, sigma = 0.1;
  std::mt19937_64 random(5);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<double> jacobian(2 * n);  // rows (1, x_i), row-major
  for (int i = 0; i < n; ++i) {
    jacobian[2 * i] = 1.0;
    jacobian[2 * i + 1] = static_cast<double>(i) / (n - 1);
  }
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>> J(
      jacobian.data(), n, 2);
  const Eigen::Matrix2d inverse = (J.transpose() * J).inverse();
  double sum = 0.0, sum2 = 0.0, robust2 = 0.0, independent2 = 0.0, robust_split2 = 0.0;
  for (int k = 0; k < replicates; ++k) {
    Eigen::VectorXd y(n);
    double e = sigma * gauss(random);
    for (int i = 0; i < n; ++i) {
      y(i) = 1.0 + 2.0 * J(i, 1) + e;
      e = rho * e + sigma * std::sqrt(1.0 - rho * rho) * gauss(random);
    }
    const Eigen::Vector2d b = inverse * (J.transpose() * y);
    const Eigen::VectorXd r = y - J * b;
    std::vector<double> robust, split;
    ASSERT_TRUE(
        autocorrelation_robust_standard_errors(jacobian.data(), 2, 2, r.data(), {n}, robust));
    // The same residuals cut into two series: no correlation counted across the cut.
    ASSERT_TRUE(autocorrelation_robust_standard_errors(jacobian.data(), 2, 2, r.data(),
                                                       {n / 2, n / 2}, split));
    sum += b(1);
    sum2 += b(1) * b(1);
    robust2 += robust[1] * robust[1];
    robust_split2 += split[1] * split[1];
    independent2 += r.squaredNorm() / (n - 2) * inverse(1, 1);
  }
  const double spread = std::sqrt((sum2 - sum * sum / replicates) / (replicates - 1));
  const double robust = std::sqrt(robust2 / replicates);
  const double independent = std::sqrt(independent2 / replicates);
  std::printf("slope: spread %.4f, robust SE %.4f, independent SE %.4f, robust over two series "
              "%.4f\n", spread, robust, independent, std::sqrt(robust_split2 / replicates));
  RecordProperty("spread_over_robust", scientific(spread / robust));
  RecordProperty("spread_over_independent", scientific(spread / independent));
  // The independent errors hide the correlation (2.9 measured). The robust ones recover much of
  // it, less the kernel estimate's small-sample bias (1.7 measured: the fit's residuals are
  // orthogonal to J, which takes the slowest part of the noise out of them; prewhitening with
  // the AR(1) coefficient brought it to 1.15 here but made the errors 2-4 times the refit spread
  // on the DEM matrix, docs/calibration.md).
  EXPECT_GT(spread / independent, 2.5);
  EXPECT_LT(spread / robust, 1.9);
  EXPECT_GT(robust / independent, 1.5);
  // Two series of 30: only the lags across the cut are dropped (0.0673 against 0.0671 measured).
  EXPECT_NEAR(std::sqrt(robust_split2 / replicates) / robust, 1.0, 0.2);
  // Uncorrelated residuals: the robust error is the plain one (Andrews' bandwidth near 0).
  std::vector<double> white(n), robust_white;
  for (double& v : white) v = sigma * gauss(random);
  double bandwidth = -1.0;
  ASSERT_TRUE(autocorrelation_robust_standard_errors(jacobian.data(), 2, 2, white.data(), {n},
                                                     robust_white, &bandwidth));
  EXPECT_LE(bandwidth, 3.0);
  // Too few residuals, or a singular J^T J, give no errors.
  std::vector<double> none;
  EXPECT_FALSE(
      autocorrelation_robust_standard_errors(jacobian.data(), 2, 2, white.data(), {2}, none));
  std::vector<double> singular(2 * n, 1.0);
  EXPECT_FALSE(
      autocorrelation_robust_standard_errors(singular.data(), 2, 2, white.data(), {n}, none));
  EXPECT_TRUE(none.empty());
}

void expect_error(const std::function<void()>& f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no error (expected one containing '" << needle << "')";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(FitInputs, BadDataGiveClearErrors) {
  TestData empty = small_valid_test();
  empty.axial_strain.clear();
  expect_error([&] { validate_test_data(empty); }, "fewer than 3 series rows");
  TestData nan = small_valid_test();
  nan.volumetric_strain[4] = std::nan("");
  expect_error([&] { validate_test_data(nan); }, "series 'volumetric_strain' row 4 is not finite");
  expect_error([&] { calibrate({nan}, FitOptions{}); }, "not finite");
  TestData nan_fabric = small_valid_test();
  nan_fabric.a_c[2] = std::nan("");
  expect_error([&] { validate_test_data(nan_fabric); }, "SFF column 'a_c' snapshot 2");
  TestData short_eta = small_valid_test();
  short_eta.eta.pop_back();
  expect_error([&] { validate_test_data(short_eta); }, "series 'eta' has");
  TestData no_snapshot = small_valid_test();
  for (std::vector<double>* column :
       {&no_snapshot.snapshot_axial_strain, &no_snapshot.a_c, &no_snapshot.a_n,
        &no_snapshot.mobilisation, &no_snapshot.snapshot_eta})
    column->clear();
  expect_error([&] { validate_test_data(no_snapshot); }, "no snapshot in the SFF table");
  expect_error([&] { calibrate({}, FitOptions{}); }, "no tests");
  FitOptions out_of_bounds;
  out_of_bounds.initial[fit_parameter_index("nu")] = 0.6;
  expect_error([&] { calibrate({small_valid_test()}, out_of_bounds); },
               "initial value of 'nu'");
  expect_error([] { parse_stages("warm"); }, "unknown stage 'warm'");
  expect_error([] { parse_loss("l1"); }, "unknown loss 'l1'");
}

// `sffcal calibrate --range NAME=LOW:HIGH`: the range replaces the default, the start moves into
// it, and every malformed or non-physical range is refused by name.
TEST(FitInputs, SearchRangesAreSetByNameAndBadOnesAreNamed) {
  FitOptions options;
  const int n_d = fit_parameter_index("n_d");
  set_search_range(options, "n_d=0:60");
  EXPECT_EQ(options.lower[n_d], 0.0);
  EXPECT_EQ(options.upper[n_d], 60.0);
  set_search_range(options, "n_d=5:10");  // the default start, 3.5, lies below
  EXPECT_EQ(options.initial[n_d], 5.0);
  set_search_range(options, "a_cs=0.5:1.5");
  EXPECT_EQ(options.upper[kAcsIndex], 1.5);
  expect_error([&] { set_search_range(options, "n_d=20"); }, "expected NAME=LOW:HIGH");
  expect_error([&] { set_search_range(options, "n_x=0:1"); }, "unknown parameter 'n_x'");
  expect_error([&] { set_search_range(options, "n_d=0:1e3x"); }, "'1e3x' is not a finite number");
  expect_error([&] { set_search_range(options, "n_d=:1"); }, "'' is not a finite number");
  expect_error([&] { set_search_range(options, "n_d=0:inf"); }, "'inf' is not a finite number");
  expect_error([&] { set_search_range(options, "n_d=3:1"); }, "LOW must be below HIGH");
  expect_error([&] { set_search_range(options, "nu=0:0.6"); },
               "is not physical for 'nu': it must be in (-1, 0.5)");
  expect_error([&] { set_search_range(options, "a_cs=0:1"); }, "not physical for 'a_cs'");
  EXPECT_EQ(options.upper[n_d], 10.0);  // a refused range changes nothing
}

// A small triaxial run file with the series calibration reads and, when `with_sff`, an SFF table.
void write_small_run(const std::string& path, const runfile::RunMetadata& meta, bool with_sff) {
  std::filesystem::remove(path);
  runfile::RunFile file = runfile::RunFile::create(
      path, meta, {"axial_strain", "volumetric_strain", "p", "q", "eta", "void_ratio", "sigma_3"});
  for (int k = 0; k < 5; ++k) file.append_series({0.01 * k, 0.0, 1e5, 1e4 * k, 0.1 * k, 0.7, 1e5});
  if (with_sff)
    file.write_table("sff", {"axial_strain", "p", "q", "eta", "void_ratio", "a_c", "a_n", "m"},
                     {{0.0, 1e5, 0.0, 0.0, 0.7, 0.0, 0.0, 0.0},
                      {0.02, 1e5, 5e4, 0.5, 0.7, 0.5, 0.4, 0.3}});
}

TEST(FitInputs, RunFileWithoutSffTableIsNamed) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "calibration_fit_test_no_sff.h5").string();
  runfile::RunMetadata meta;
  meta.kind = "triaxial";
  meta.physics.friction = 0.5;
  write_small_run(path, meta, false);
  expect_error([&] { read_run_file(path); }, "has no SFF table /analysis/sff");
  // With the table it reads, and the friction is the run's.
  write_small_run(path, meta, true);
  const TestData t = read_run_file(path);
  EXPECT_EQ(t.a_c.size(), 2u);
  EXPECT_DOUBLE_EQ(t.friction, 0.5);
  EXPECT_DOUBLE_EQ(t.p0, 1e5);
  std::filesystem::remove(path);
}

// Issue 15's latent bug: a DEM config without [contact] shears at the DEM's default friction
// (tan 30 deg), and calibration must read that, not 0 (which skipped the SFF strength fit). The
// DEM's parser decides the friction once and the run file stores it in /physics.
TEST(FitInputs, FrictionIsTheOneTheDemShearedWith) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "calibration_fit_test_friction.h5").string();
  const dem::RunConfig without_contact = dem::parse_run_config("bodies = 100\n");
  write_small_run(path, dem::run_metadata("triaxial", without_contact, "test"), true);
  EXPECT_EQ(read_run_file(path).friction, without_contact.contact.friction);
  EXPECT_NEAR(read_run_file(path).friction, std::tan(sffcal::kPi / 6.0), 1e-15);
  const dem::RunConfig with_contact = dem::parse_run_config("[contact]\nfriction = 0.3\n");
  write_small_run(path, dem::run_metadata("triaxial", with_contact, "test"), true);
  EXPECT_EQ(read_run_file(path).friction, 0.3);
  std::filesystem::remove(path);
}

// The loading path is read from the run file (issue 19); true triaxial, which the fit's
// axisymmetric path cannot follow, is refused by its name, and the strains must move in the
// path's direction.
TEST(FitInputs, TheLoadingPathIsReadAndTrueTriaxialIsRefusedByName) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "calibration_fit_test_path.h5").string();
  const dem::RunConfig undrained =
      dem::parse_run_config("[triaxial]\npath = \"undrained_compression\"\n");
  write_small_run(path, dem::run_metadata("triaxial", undrained, "test"), true);
  EXPECT_EQ(read_run_file(path).path, TestPath::kUndrainedCompression);
  const dem::RunConfig true_triaxial =
      dem::parse_run_config("[triaxial]\npath = \"true_triaxial\"\nb = 0.5\n");
  write_small_run(path, dem::run_metadata("triaxial", true_triaxial, "test"), true);
  expect_error([&] { read_run_file(path); },
               "loading path true_triaxial: the calibration follows axisymmetric paths only");
  // write_small_run's strains rise: not an extension test.
  const dem::RunConfig extension =
      dem::parse_run_config("[triaxial]\npath = \"drained_extension\"\n");
  write_small_run(path, dem::run_metadata("triaxial", extension, "test"), true);
  expect_error([&] { read_run_file(path); },
               "axial_strain does not decrease at row 1 (path drained_extension)");
  std::filesystem::remove(path);
  expect_error([] { parse_test_path("sideways"); }, "unknown loading path 'sideways'");
  // The spellings are the DEM's (the run file's /loading path): each DEM path is read back under
  // its own name, or refused by it (true triaxial).
  for (const std::string& name : dem::loading_path_names()) {
    if (name == "true_triaxial") continue;
    EXPECT_EQ(to_string(parse_test_path(name)), name);
  }
}

TEST(FitInputs, MissingCsvColumnIsNamed) {
  const auto dir = std::filesystem::temp_directory_path();
  const std::string series = (dir / "calibration_fit_test_series.csv").string();
  const std::string sff = (dir / "calibration_fit_test_sff.csv").string();
  std::ofstream(series) << "axial_strain,eta,volumetric_strain,void_ratio,p\n0,0,0,0.7,1e5\n"
                           "0.01,0.5,0.001,0.7,1.1e5\n0.02,0.8,0.0,0.7,1.2e5\n";
  std::ofstream(sff) << "axial_strain,a_n,m,eta\n0,0,0,0\n0.02,0.5,0.3,0.8\n";
  expect_error([&] { read_csv_pair(series, sff, "x", 0.5); }, "missing column 'a_c'");
  std::filesystem::remove(series);
  std::filesystem::remove(sff);
}

// Three drained tests whose last window sits at (p_k, e_k): only the critical state line stage.
CalibrationResult fit_critical_state_line(const double (&p)[3], const double (&e)[3]) {
  const FitVector x = to_fit_vector(testing::toyoura(), 0.8);
  std::vector<TestData> tests;
  for (int k = 0; k < 3; ++k) {
    TestData t = synthetic_test("t" + std::to_string(k), x, 0.75, 0.1, 0.0, 0);
    std::fill(t.p.begin() + 1, t.p.end(), p[k]);
    std::fill(t.void_ratio.begin() + 1, t.void_ratio.end(), e[k]);
    tests.push_back(t);
  }
  FitOptions options;
  options.stages = {Stage::kCsl};
  options.starts = 1;
  options.initial = x;
  return calibrate(tests, options);
}

TEST(FitCriticalStateLine, AFallingLineIsFittedAndARisingOneGivesTheMeanAtLambdaZero) {
  const int ig = fit_parameter_index("e_gamma"), il = fit_parameter_index("lambda_c"),
            ix = fit_parameter_index("xi");
  const double p[3] = {100e3, 200e3, 400e3};
  // On the line e_c = 0.9 - 0.05 (p/p_a)^0.7: fitted back (xi by its 0.005 scan).
  double e_line[3];
  for (int k = 0; k < 3; ++k)
    e_line[k] = 0.9 - 0.05 * std::pow(p[k] / kAtmosphericPressure, 0.7);
  const CalibrationResult line = fit_critical_state_line(p, e_line);
  EXPECT_NEAR(line.values[ix], 0.7, 1e-9);
  EXPECT_NEAR(line.values[ig], 0.9, 1e-9);
  EXPECT_NEAR(line.values[il], 0.05, 1e-9);
  // Void ratios that rise with pressure (small DEM specimens far from a critical state): the
  // least-squares line has lambda_c < 0, so lambda_c = 0 and e_gamma is the mean, not the
  // intercept of the rising line (which lies below every point).
  const double e_rising[3] = {0.75, 0.76, 0.78};
  const CalibrationResult rising = fit_critical_state_line(p, e_rising);
  EXPECT_EQ(rising.values[il], 0.0);
  EXPECT_NEAR(rising.values[ig], (0.75 + 0.76 + 0.78) / 3.0, 1e-12);
  bool noted = false;
  for (const std::string& note : rising.notes)
    noted = noted || note.find("rise with pressure") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(FitCriticalStateLine, AnExtensionTestsCriticalStateIsItsLastWindowOfStrain) {
  // Extension runs to negative axial strain: the window is the last critical_window of |eps_a|,
  // as in compression (it was the whole test, the strain "growing" towards its first row).
  const FitVector x = to_fit_vector(testing::toyoura(), 0.8);
  std::vector<TestData> tests = {
      synthetic_test("compression", x, 0.75, 0.1, 0.0, 0),
      synthetic_test("extension", x, 0.75, 0.1, 0.0, 0, TestPath::kDrainedExtension)};
  FitOptions options;
  options.stages = {Stage::kCsl};
  options.starts = 1;
  options.initial = x;
  const CalibrationResult r = calibrate(tests, options);
  ASSERT_EQ(r.critical_states.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const TestData& t = tests[k];
    double eta = 0.0, e = 0.0;
    int rows = 0;
    for (std::size_t i = 0; i < t.axial_strain.size(); ++i)
      if (std::abs(t.axial_strain.back()) - std::abs(t.axial_strain[i]) <= options.critical_window) {
        eta += t.eta[i];
        e += t.void_ratio[i];
        ++rows;
      }
    EXPECT_EQ(rows, 21) << t.name;  // 0.1 of the 0.2 path: rows 20..40
    EXPECT_NEAR(r.critical_states[k].eta, eta / rows, 1e-12) << t.name;
    EXPECT_NEAR(r.critical_states[k].void_ratio, e / rows, 1e-12) << t.name;
  }
  // c = M_e / M_c from the two windows' q/p.
  EXPECT_NEAR(r.values[fit_parameter_index("c")],
              std::abs(r.critical_states[1].eta) / r.critical_states[0].eta, 1e-12);
}

TEST(FitDem, DenseReferenceTestConvergesToItsCriticalStressRatio) {
  const std::string dir = std::string(SFFCAL_SOURCE_DIR) + "/bench/reference/";
  const TestData t = read_csv_pair(dir + "dense_100kPa_2000_series.csv",
                                   dir + "dense_100kPa_2000_sff.csv", "dense_100kPa_2000",
                                   0.5773502691896257);
  FitOptions options;
  options.starts = 1;
  options.max_points = 20;      // small, to keep the suite fast (the CLI default is 60)
  options.max_iterations = 10;  // per stage
  const CalibrationResult r = calibrate({t}, options);
  ASSERT_EQ(r.critical_states.size(), 1u);
  const double eta_cs = r.critical_states[0].eta;
  const double M_c = r.values[fit_parameter_index("M_c")];
  RecordProperty("eta_cs_dem", scientific(eta_cs));
  RecordProperty("M_c", scientific(M_c));
  for (const StageReport& s : r.stages) {
    RecordProperty("cost_" + s.stage, scientific(s.initial_cost) + " -> " + scientific(s.final_cost));
    if (s.stage == "plastic" || s.stage == "joint") {
      EXPECT_LE(s.final_cost, s.initial_cost);
    }
  }
  ASSERT_EQ(r.errors.size(), 1u);
  const TestErrors& e = r.errors[0];
  RecordProperty("rms_eta", scientific(e.rms_eta));
  RecordProperty("rms_volumetric", scientific(e.rms_volumetric));
  RecordProperty("rms_a_c", scientific(e.rms_a_c));
  EXPECT_EQ(e.status, "ok");
  EXPECT_NEAR(M_c, eta_cs, 0.1);
  EXPECT_LT(e.rms_eta, 0.15);
  EXPECT_LT(e.rms_volumetric, 0.02);
  ASSERT_TRUE(r.sff.available);
  RecordProperty("sff_c", scientific(r.sff.coefficients[0]) + " " + scientific(r.sff.coefficients[1]) +
                              " " + scientific(r.sff.coefficients[2]));
  RecordProperty("sff_distance", scientific(r.sff.distance));
  // The DEM obeys the SFF relation closely: the fitted eta within 0.05 RMS.
  EXPECT_LT(r.sff.rms, 0.05);
  // The parameter file is readable by the FE side.
  const std::string folder = (std::filesystem::temp_directory_path() / "calibration_fit_test_out").string();
  write_calibration_outputs(folder, {t}, r, options, "test", "fit_test");
  const Parameters<double> back = read_parameters_json(folder + "/parameters.json");
  EXPECT_DOUBLE_EQ(back.M_c, M_c);
  EXPECT_TRUE(std::filesystem::exists(folder + "/dense_100kPa_2000_curves.csv"));
  std::filesystem::remove_all(folder);
}

// On DEM data: the fabric stage on the committed 500-clump matrix runs (dense 100 and 300 kPa,
// loose 100 kPa), once with n_F free and once held at LD12's 0. The dense fabric turns faster than
// the loose one (docs/model.md Eq. 16), so the state exponent must take a clear part of the a_c
// residual that one k_F leaves (on the nine matrix runs the stage's cost falls by half).
TEST(FitDem, TheFabricRatesStateExponentFollowsTheDenseAndTheLooseFabric) {
  const std::string dir = std::string(SFFCAL_SOURCE_DIR) + "/tests/data/reference/matrix/";
  std::vector<TestData> tests;
  for (const char* name : {"iso_dense_100kPa", "iso_dense_300kPa", "iso_loose_100kPa"})
    tests.push_back(read_run_file(dir + name + ".h5"));
  FitOptions options;
  options.stages = {Stage::kCsl, Stage::kElastic, Stage::kFabric};
  options.max_points = 20;
  auto fabric_cost = [&](bool free_rate_exponent, double* n_F) {
    FitOptions o = options;
    if (!free_rate_exponent) o.fixed = {"n_F"};
    const CalibrationResult r = calibrate(tests, o);
    for (const StageReport& s : r.stages)
      if (s.stage == "fabric") {
        *n_F = r.values[fit_parameter_index("n_F")];
        return s.final_cost;
      }
    ADD_FAILURE() << "no fabric stage";
    return 0.0;
  };
  double n_F_free = 0.0, n_F_held = 0.0;
  const double free_cost = fabric_cost(true, &n_F_free), held_cost = fabric_cost(false, &n_F_held);
  RecordProperty("fabric_cost_n_F_free", scientific(free_cost));
  RecordProperty("fabric_cost_n_F_held_0", scientific(held_cost));
  RecordProperty("n_F", scientific(n_F_free));
  EXPECT_EQ(n_F_held, 0.0);
  EXPECT_GT(n_F_free, 3.0);
  EXPECT_LT(free_cost, 0.7 * held_cost);
}

}  // namespace
}  // namespace calibration
