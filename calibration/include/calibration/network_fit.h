// The contact-network model (network_model.h) against DEM tests: its state taken from the first
// snapshot, its laws fitted to the micro histories (Z, Lambda, a_c, a_n, a_t) and the stress along
// the DEM's own strain path, and its predictions of drained and undrained triaxial tests
// (docs/network-model.md, "Calibration").
//
// Conventions: compression positive, stresses in Pa, strains as fractions.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "calibration/fit.h"
#include "calibration/network_test_data.h"
#include "model/network_model.h"
#include "model/network_path.h"
#include "model/network_update.h"

namespace calibration::network {

// The contact-network model's names (model/network_model.h) as the fits use them.
using model::network::admissible;
using model::network::axisymmetric;
using model::network::DiagonalTensor;
using model::network::from_array;
using model::network::integrate;
using model::network::kCriticalSlopeIndex;
using model::network::kCriticalVoidRatioIndex;
using model::network::kFabricRateExponentIndex;
using model::network::kInherentFadeIndex;
using model::network::kLambdaExponentIndex;
using model::network::kLambdaGainIndex;
using model::network::kLambdaReference;
using model::network::kLodeFactorIndex;
using model::network::kNumFirstVersionParameters;
using model::network::kNumParameters;
using model::network::kStateDilatancyIndex;
using model::network::kTargetVoidRatioWeightIndex;
using model::network::lateral_component;
using model::network::lower_bounds;
using model::network::map_components;
using model::network::parameter_names;
using model::network::Parameters;
using model::network::rate;
using model::network::read_parameters_json;
using model::network::State;
using model::network::stress;
using model::network::substeps_for;
using model::network::Tensor;
using model::network::to_array;
using model::network::trace;
using model::network::triaxial_part;
using model::network::upper_bounds;
using model::network::validate;
using model::network::write_parameters_json;

/// The model along one test (model/network_path.h), at the union of the DEM's series rows and
/// snapshots in axial strain order; `row` / `snapshot` say which DEM row or snapshot a node is,
/// -1 if none.
using model::network::Curve;

/// The paths' integration (PathOptions: substep_size, max_substeps) and the fit's settings.
struct FitOptions : model::network::PathOptions {
  /// Residual scales: (model - DEM) / scale.
  double eta_scale = 0.05;
  double stress_scale = 0.02;       ///< relative lateral stress (drained) or p/p0 (undrained)
  double volumetric_scale = 0.005;  ///< volumetric strain on the predicted drained path
  double coordination_scale = 0.05;
  double lambda_scale = 0.02;       ///< relative
  double anisotropy_scale = 0.05;   ///< a_c, a_n
  double tangential_scale = 0.005;  ///< a_t
  int max_iterations = 200;
  int threads = 1;
  /// Starts: the first from the given values, the others drawn about them (starting_points);
  /// the lowest cost of the second stage wins.
  int starts = 1;
  std::uint64_t seed = 1;
  /// Parameters held at their start values (parameter_names(); "n_ra" skips the fit's last stage),
  /// besides c_t without an extension test, c_l and n_kappa without an undrained test, lambda_e
  /// when the tests' initial mean stresses span less than a factor 1.5 and r_i without a deposit's
  /// initial fabric, which are always held.
  std::vector<std::string> held;
  /// Fit along the DEM's strain paths first (the first stage), then on the predicted paths from its
  /// result; false: on the predicted paths from each start directly (docs/network-model.md,
  /// "Calibration": faster where an undrained test makes the first stage slow).
  bool first_stage = true;
  /// Called with a line after each stage of each start (for a progress display); may be empty.
  std::function<void(const std::string&)> progress;
};

/// Drives the model along the DEM's measured strain path (axial and volumetric strain, x and y
/// alike) from initial_state: the stress is the model's, the strains the DEM's.
Curve follow_strain_path(const Parameters<double>& par, const TestData& test,
                         const FitOptions& options = {});

/// Predicts the test from initial_state on its own loading path: drained (the lateral stress held
/// at its initial value, the lateral strain found by Newton) or undrained (constant volume), at
/// the DEM's axial strains. Stops with complete = false where an increment cannot be solved.
/// lateral_stress [Pa, compression positive]: the drained path's lateral stress where given (an FE
/// specimen under a confining traction holds sigma_3, not the initial SFF stress's sigma_xx, which
/// differs from it by the SFF equation's error and the initial anisotropies); otherwise the
/// initial state's own sigma_xx, as the fit holds it.
Curve predict(const Parameters<double>& par, const TestData& test, const FitOptions& options = {},
              std::optional<double> lateral_stress = std::nullopt);

/// RMS errors of a curve against its test: eta and volumetric strain over the rows after the
/// first, the micro variables over the snapshots after the first (Lambda relative).
struct Errors {
  /// p_ratio: RMS of p/p0 - p_DEM/p0_DEM, each mean stress over its own initial one (the model's
  /// stress is the SFF stress of the contacts, below the walls' in small specimens).
  double eta = 0.0, volumetric = 0.0, p_ratio = 0.0;
  double coordination = 0.0, lambda = 0.0, a_c = 0.0, a_n = 0.0, a_t = 0.0;
};
Errors compare(const Curve& curve, const TestData& test);

/// Standard errors of fitted parameters from the second stage's residuals r and Jacobian J at the
/// solution, over the parameters inside their bounds and not held (one at a bound, one the fit
/// holds, FitOptions::held, and e_gamma and lambda_e with d_psi = w_psi = 0, no line: NaN here):
/// `independent`, s^2 (J^T J)^-1 with s^2 = |r|^2 / (n - k), as if the residuals were
/// independent; `robust`, the sandwich of calibration::autocorrelation_robust_standard_errors
/// (fit.h) with one series per test and residual kind (eta; epsilon_v or p; Z; Lambda; a_c; a_n;
/// a_t), which allows for residuals correlated along each curve, as the DEM's are.
struct StandardErrors {
  std::array<double, kNumParameters> independent, robust;
  double mean_bandwidth = 0.0;  ///< of the robust form's series
  bool estimated = false;       ///< false: all NaN, and `missing` says why
  std::string missing;          ///< why there are none (empty when estimated)
};
StandardErrors standard_errors(const std::vector<TestData>& tests, const Parameters<double>& par,
                               const FitOptions& options = {});

struct FitResult {
  Parameters<double> parameters;
  StandardErrors errors;            ///< at the solution
  double initial_cost = 0.0, final_cost = 0.0;  ///< of the second stage, or of the last
  int iterations = 0;
  bool converged = false;
  int start = 0;                    ///< the winning start
  std::vector<double> start_costs;  ///< each start's final cost (NaN: no usable solution)
  /// Whether the last stage (n_ra freed from the winning start's solution) ran and was kept.
  bool fabric_rate_freed = false;
  std::string report;               ///< Ceres' brief reports of the winning start
};

/// The starting values of the fit (its bounds: lower_bounds, upper_bounds in network_model.h).
Parameters<double> default_start();
/// default_start() with the critical void ratio line placed through the tests' ends (Eq. N7b):
/// e_gamma the mean over the tests of e_end + lambda_e ln(Lambda_end / Lambda_ref), e_end the void
/// ratio of the last series row and Lambda_end the last snapshot's, clipped to its bounds (a test
/// sheared to its end is near its critical state). Throws as initial_state for a test without Z,
/// Lambda or a_t.
Parameters<double> default_start(const std::vector<TestData>& tests);

/// The fit's residuals of one test and their Jacobian by the parameters (forward-mode Jets; on
/// the predicted drained path through the implicit function theorem at each increment's solved
/// lateral strain), `predicted` choosing the second stage's objective over the first's.
struct ObjectiveValue {
  Eigen::VectorXd residuals;
  Eigen::MatrixXd jacobian;  ///< residuals x kNumParameters
  /// Each residual's kind: 0 eta, 1 the path's (lateral stress, epsilon_v or p/p0), 2 Z,
  /// 3 Lambda, 4 a_c, 5 a_n, 6 a_t.
  std::vector<int> kinds;
  bool usable = false;       ///< false where the path left the admissible states
};
ObjectiveValue evaluate_objective(const TestData& test, const Parameters<double>& par,
                                  bool predicted, const FitOptions& options = {});

/// The start itself, then starts - 1 points drawn about it from std::mt19937_64(seed) (c_t, c_l,
/// n_kappa, d_psi, e_gamma, lambda_e, w_psi and r_i, added after the first version, from
/// std::mt19937_64(seed + 1) to (seed + 8)): each parameter with a positive range multiplied by a
/// log-uniform factor within 3, each signed one moved uniformly by up to max(|x|, 1), e_gamma (a
/// void ratio placed by the data) by up to 0.1; clipped to the bounds. n_ra keeps the start's
/// value (fit frees it only in its last stage).
std::vector<Parameters<double>> starting_points(const Parameters<double>& start, int starts,
                                                std::uint64_t seed);

/// Fits the parameters by Levenberg-Marquardt within the bounds in two stages: first to the
/// tests' micro histories and stresses along their DEM strain paths (follow_strain_path), then
/// to the micro histories, q/p and the volumetric strain (drained) or p (undrained) on the paths
/// the model predicts (predict); where the second stage cannot start from the first's result (a
/// predicted path leaves the admissible states) it starts from the start's own point. Residuals
/// and their scales: FitOptions. Without an extension test c_t (the Lode factor) is held at its
/// start value, without an undrained test c_l (N5b) and n_kappa (N6), at one pressure lambda_e
/// (N7b), without a test starting from a deposit's fabric (|a_c| >= 0.15) r_i (N2d). Every start
/// holds n_ra (N3b) at its start value; a last stage then frees it on the predicted paths from the
/// winning start's solution (unless FitOptions::held names it), kept where it lowers the cost:
/// freed in every start, the first stage took the starts into other minima of higher cost. Fills
/// the standard errors at the solution.
FitResult fit(const std::vector<TestData>& tests, const Parameters<double>& start,
              const FitOptions& options = {});

/// Writes a fit's outputs into `folder` (created if missing; the caller sees that it holds no
/// earlier outputs) and returns the summary (Markdown):
/// - parameters.json: the parameter file (read_parameters_json) with the fit's record: program,
///   version, date, command line, inputs, starts and their costs, residual scales, standard errors
///   and each test's errors;
/// - <test>_network.csv per test: the prediction on its own loading path at the DEM's rows and
///   snapshots (axial_strain, volumetric_strain, void_ratio, p [Pa], q [Pa], eta, coordination,
///   lambda, a_c, a_n, a_t, dem_row, dem_snapshot: which DEM row or snapshot a node is, -1 none;
///   dem_a_n: the test's a_n at a snapshot's node, NaN elsewhere);
/// - summary.md: the per-test errors (along the DEM strain path and predicted; fitted and held
///   back) and the parameters with their standard errors.
/// Throws std::runtime_error for two tests of one name or a file that cannot be written.
std::string write_fit_outputs(const std::string& folder, const std::vector<TestData>& fitted,
                              const std::vector<TestData>& held_back, const FitResult& result,
                              const FitOptions& options, const std::string& program_version,
                              const std::string& command_line);

}  // namespace calibration::network
