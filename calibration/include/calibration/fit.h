// Calibration of the ACST model (acst_model.h) to DEM triaxial tests: the test data, the staged
// and joint Ceres fits, the SFF strength relation and the outputs. docs/calibration.md describes
// the stages, the objective (weights, residuals, units), the bounds and the outputs.
//
// Conventions: compression positive (strains, stresses); stresses in Pa; strains as fractions.
// The model fabric is F = A_DEM / a_cs (acst-model.md), so the DEM's triaxial anisotropy
// a_c = A_zz - (A_xx + A_yy)/2 is compared with a_cs (F_zz - (F_xx + F_yy)/2).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "calibration/test_data.h"
#include "model/acst_model.h"
#include "model/material_point.h"

namespace ceres {
class Problem;
}

namespace calibration {

// The ACST model's names (model/acst_model.h, model/material_point.h) as the fits use them.
using model::acst::cast_parameters;
using model::acst::cast_state;
using model::acst::Control;
using model::acst::DriverOptions;
using model::acst::IntegrationOptions;
using model::acst::is_admissible_void_ratio;
using model::acst::isotropic_state;
using model::acst::kAtmosphericPressure;
using model::acst::kParameterFields;
using model::acst::kSqrtTwoThirds;
using model::acst::make_record;
using model::acst::mixed_increment;
using model::acst::ParameterAnnotation;
using model::acst::Parameters;
using model::acst::PathResult;
using model::acst::PathStep;
using model::acst::read_parameters_json;
using model::acst::State;
using model::acst::Tensor;
using model::acst::to_string;
using model::acst::triaxial_deviator;
using model::acst::update_state;
using model::acst::UpdateStatus;
using model::acst::value_of;
using model::acst::write_parameters_json;

/// The fitted vector: the 18 model parameters (order of Parameters) and a_cs, the critical-state
/// norm of the DEM fabric tensor A (F = A/a_cs).
inline constexpr int kNumFitParameters = 19;
using FitVector = std::array<double, kNumFitParameters>;
inline constexpr int kAcsIndex = 18;
/// Names as in the parameter file, then "a_cs".
const std::array<const char*, kNumFitParameters>& fit_parameter_names();
/// Index of a name in FitVector; throws for an unknown name.
int fit_parameter_index(const std::string& name);
FitVector to_fit_vector(const Parameters<double>& par, double a_cs);
Parameters<double> model_parameters(const FitVector& x);

enum class Loss { kNone, kHuber, kCauchy };
enum class Stage { kCsl, kElastic, kFabric, kPlastic, kJoint };
const char* to_string(Stage stage);
/// "all" or one stage name; throws std::runtime_error for another word.
std::vector<Stage> parse_stages(const std::string& text);
Loss parse_loss(const std::string& text);

struct FitOptions {
  std::vector<Stage> stages = {Stage::kCsl, Stage::kElastic, Stage::kFabric, Stage::kPlastic,
                               Stage::kJoint};
  int starts = 3;            ///< starts of the plastic and joint stages (1 = staged values only)
  std::uint64_t seed = 1;    ///< seed of the extra starts
  Loss loss = Loss::kNone;
  double loss_scale = 1.0;   ///< in units of the normalised residual
  /// Residual scales: each residual is (model - DEM) / scale (docs/calibration.md).
  double eta_scale = 0.05;          ///< q/p
  double volumetric_scale = 0.005;  ///< volumetric strain
  double fabric_scale = 0.05;       ///< a_c
  /// Mean stress on the undrained paths, relative to max(p0, p_DEM): their response to the
  /// volume constraint, in place of the volumetric strain (docs/calibration.md, "Objective").
  double mean_stress_scale = 0.05;
  int max_points = 60;              ///< series rows per test used in the fit (evenly subsampled)
  /// Largest axial-strain increment of the fit's path: longer gaps between its rows are split
  /// (0: the rows and snapshots only). The lateral stress is held at the increments' ends only, so
  /// the path's error in q/p falls with the square of the step: on the stored dense 100 kPa run,
  /// 2.0e-2 with the 60 rows alone, 3.6e-3 at 0.0025, 9.1e-4 at 0.001 (docs/calibration.md).
  /// 0.0005 by default (issue 19: within 1e-3 of a converged path; 1.6e-3 at 0.001 with the
  /// stored calibration's parameters).
  double fit_max_strain_step = 5e-4;
  /// The same for the reported errors and curves after the fit (TestErrors, the CSV curves):
  /// every series row and at most this step, within 1e-3 in q/p of a converged path.
  double report_max_strain_step = 5e-4;
  int max_iterations = 60;          ///< Ceres iterations per start
  /// Ceres stops a start when an iteration lowers the cost by less than this fraction. The
  /// objective carries the integration noise of the fit tolerance, and on the DEM matrix the
  /// iterations past 1e-5 crept (3183.8 -> 3183.4 per 6 s iteration).
  double function_tolerance = 1e-5;
  double critical_window = 0.1;     ///< axial-strain window at the end that defines the DEM critical state
  /// Integration for the fit: the curves need ~1e-6, not the 1e-9 of the driver's default.
  DriverOptions driver = fit_driver_options();
  /// Integration for the reported errors (TestErrors) after the fit: tighter than the fit's.
  DriverOptions report_driver = report_driver_options();
  /// Threads over tests within one evaluation (OpenMP). Ceres runs single-threaded and every
  /// test is computed independently, so the result is the same for any thread count.
  int threads = 1;
  /// Receives one line per stage start and end and per Ceres iteration (stage, start,
  /// iteration, cost, seconds since the stage began); empty: silent.
  std::function<void(const std::string&)> progress;
  FitVector initial = default_initial();  ///< start values (a_cs is measured, this is a fallback)
  FitVector lower = default_lower(), upper = default_upper();
  /// Never fitted: m (acst-model.md: fixed 0.01). c is held too when no test is an extension.
  std::vector<std::string> fixed = {"m"};
  bool verbose = false;  ///< Ceres progress to stdout

  static DriverOptions fit_driver_options();
  static DriverOptions report_driver_options();
  static FitVector default_initial();
  static FitVector default_lower();
  static FitVector default_upper();
};

/// Sets the fit's search range of one parameter from "NAME=LOW:HIGH" (`sffcal calibrate
/// --range`): NAME as in the parameter file, or a_cs; LOW < HIGH, both finite and physical for
/// the parameter (docs/model.md's table; a_cs > 0). The start value is moved into the range
/// (the stages start from it). Throws std::runtime_error naming what is wrong.
void set_search_range(FitOptions& options, const std::string& range);

struct ParameterEstimate {
  double value = 0.0, lower = 0.0, upper = 0.0;
  /// From the covariance of the last stage that freed it, robust to residuals correlated along
  /// each curve (autocorrelation_robust_standard_errors); < 0: not estimated (fixed, or no
  /// covariance).
  double standard_error = -1.0;
  /// The same covariance as if the residuals were independent (s^2 (J^T J)^-1,
  /// scaled_standard_errors): smaller by the factor the correlation hides (docs/calibration.md).
  double standard_error_independent = -1.0;
  bool fixed = true;             ///< not a free parameter of any stage
  bool at_bound = false;         ///< within 1e-4 of the range of a bound (covariance ignores bounds)
  std::string stage;             ///< the stage that set it ("" = initial value)
};

/// Errors of the model against one test over every series row and snapshot (q/p and a_c where
/// the DEM specimen has not liquefied, kLiquefiedMeanStress).
struct TestErrors {
  std::string name;
  int rows = 0, snapshots = 0;
  std::string path;  ///< the loading path (to_string(TestPath))
  double rms_eta = 0.0, rms_volumetric = 0.0, rms_void_ratio = 0.0, rms_a_c = 0.0;
  double rms_p_ratio = 0.0;  ///< RMS of (p_model - p_DEM)/p0
  double max_abs_eta = 0.0;
  double rms_normalised = 0.0;  ///< RMS of all normalised residuals of the joint objective
  std::string status;           ///< model status along the path
};

/// Where the time of a Ceres stage went (summed over its starts; docs/calibration.md, "Speed").
struct StageTiming {
  double seconds = 0.0;  ///< wall time of the stage, covariance included
  double cpu_seconds = 0.0;  ///< processor time of the process (all threads) in the stage
  int iterations = 0;    ///< Levenberg-Marquardt iterations
  /// Evaluations of all tests at one point: values only, or values with the Jacobian (Jets).
  int cost_evaluations = 0, jacobian_evaluations = 0;
  double cost_seconds = 0.0, jacobian_seconds = 0.0;  ///< wall time in those evaluations
  /// Mean integration substeps (attempted) per grid step of a test in one evaluation, over all
  /// updates of the step (lateral Newton iterations and the Jet update).
  double substeps_per_step = 0.0;
  double max_substeps_per_step = 0.0;  ///< the largest of those means over the evaluations
};

struct StageReport {
  std::string stage;
  int free_parameters = 0, residuals = 0, starts = 0;
  double initial_cost = 0.0, final_cost = 0.0;
  std::string message;
  StageTiming timing;
};

/// eta = c1 a_c + c2 a_n + c3 mu m over all snapshots (linear least squares).
struct SffRelationFit {
  bool available = false;
  int snapshots = 0;
  std::array<double, 3> coefficients{}, standard_errors{};
  double rms = 0.0;        ///< of eta - fit
  double distance = 0.0;   ///< || c - (2/5, 2/5, 3/5) ||
  std::string note;
};

struct CriticalStatePoint {
  std::string test;
  double p = 0.0, void_ratio = 0.0, eta = 0.0, a_c = 0.0;
};

struct CalibrationResult {
  FitVector values{};
  std::array<ParameterEstimate, kNumFitParameters> estimates{};
  double covariance_scale = 0.0;  ///< s^2 = 2 cost / (n - p) of the last Ceres stage
  /// Mean Bartlett bandwidth (in residuals) of the last stage's robust standard errors.
  double mean_bandwidth = 0.0;
  std::vector<CriticalStatePoint> critical_states;
  std::vector<StageReport> stages;
  std::vector<TestErrors> errors;
  SffRelationFit sff;
  std::vector<std::string> notes;  ///< decisions taken (fixed parameters and why)
  /// Errors on tests held back from the fit and predicted with the fitted values (predict()).
  std::vector<TestErrors> predictions;
};

/// The staged and joint calibration of options.stages over all tests (docs/calibration.md).
/// Throws std::runtime_error for invalid data or options.
CalibrationResult calibrate(const std::vector<TestData>& tests, const FitOptions& options);

/// Model curves of a test at x, on the strains of the test's series rows and snapshots.
struct ModelCurves {
  std::vector<double> axial_strain, eta, volumetric_strain, void_ratio;  ///< at the series rows
  std::vector<double> p;  ///< mean stress [Pa] at the series rows
  std::vector<double> a_c;                                              ///< at the snapshots
  UpdateStatus status = UpdateStatus::kOk;
  int rows_reached = 0;  ///< series rows reached before a failure
  /// Undrained: the axial strain from which the model, liquefied, was held at its last state
  /// (fit_path.h); NaN where it was not.
  double liquefied_at = std::numeric_limits<double>::quiet_NaN();
};
ModelCurves simulate_test(const TestData& test, const FitVector& x, const DriverOptions& driver,
                          double max_strain_step = 0.0);

/// Errors of x against a test (every series row and snapshot).
TestErrors test_errors(const TestData& test, const FitVector& x, const FitOptions& options);

/// Predicts tests that were held back from the fit: validates them and appends their errors at
/// result.values (report integration, every row and snapshot) to result.predictions.
void predict(const std::vector<TestData>& held_out, const FitOptions& options,
             CalibrationResult& result);

/// The SFF strength relation over all snapshots with a known friction (and a_c, a_n, m finite).
SffRelationFit fit_sff_relation(const std::vector<TestData>& tests);

/// Standard errors of `size` parameters from a solved Ceres problem's covariance, scaled by
/// s^2 = 2 cost / (n_residuals - n_free) (Ceres assumes unit residual variance). Entries of
/// constant (manifold) coordinates are 0. Returns false (errors untouched) if the covariance is
/// rank deficient or n_residuals <= n_free.
bool scaled_standard_errors(ceres::Problem& problem, double* block, int size, double cost,
                            int n_residuals, int n_free, std::vector<double>& errors,
                            double* scale = nullptr);

/// Standard errors of a least-squares estimate whose residuals are correlated along each of
/// their series (heteroscedasticity and autocorrelation consistent; Newey & West 1987): the
/// sandwich (J^T J)^-1 M (J^T J)^-1 with M = sum over series s of sum_ij w_ij r_i r_j J_i^T J_j,
/// Bartlett weights w_ij = 1 - |i - j|/(L_s + 1) inside a series and 0 across series, the
/// bandwidth L_s by Andrews' (1991) AR(1) plug-in rule from the series' lag-1 autocorrelation
/// (docs/calibration.md, "Uncertainty": how it compares with refits on other seeds).
/// jacobian: n rows of `stride` doubles, the first k used; series_lengths sum to n (a series:
/// residuals that are neighbours in strain). Returns false (errors untouched) if J^T J is
/// singular; *mean_bandwidth receives the mean L_s over the series.
bool autocorrelation_robust_standard_errors(const double* jacobian, int stride, int k,
                                            const double* residuals,
                                            const std::vector<int>& series_lengths,
                                            std::vector<double>& errors,
                                            double* mean_bandwidth = nullptr);

/// Writes the outputs into folder (created if needed): parameters.json (the parameter file,
/// readable by read_parameters_json, with bounds, standard errors, at_bound flags and
/// provenance), <test>_curves.csv and <test>_fabric.csv (model against DEM) for the fitted and
/// the held-out tests, summary.md. Returns the summary table (Markdown) that summary.md holds.
std::string write_calibration_outputs(const std::string& folder,
                                      const std::vector<TestData>& tests,
                                      const CalibrationResult& result, const FitOptions& options,
                                      const std::string& program_version,
                                      const std::string& command_line,
                                      const std::vector<TestData>& held_out = {});

/// The summary table of errors per test and of the SFF relation (Markdown).
std::string summary_markdown(const CalibrationResult& result);

}  // namespace calibration
