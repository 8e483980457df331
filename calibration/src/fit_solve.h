// Internal to calibration_fit: one Ceres stage (several starts) over all tests
// (docs/calibration.md, "Objective" and "Speed").
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "fit_path.h"

namespace calibration {
namespace fit_detail {

struct StageResult {
  FitVector x;
  double initial_cost = 0.0, final_cost = std::numeric_limits<double>::infinity();
  int residuals = 0, starts_run = 0;
  /// Standard errors of the free parameters, robust to residuals correlated along each curve
  /// (autocorrelation_robust_standard_errors), and as if independent (scaled_standard_errors);
  /// empty: none.
  std::vector<double> errors, errors_independent;
  double scale = 0.0;           // s^2 of the independent errors
  double mean_bandwidth = 0.0;  // of the robust errors, in residuals
  /// Free parameters (FitVector indices) at a bound, held for the covariance (errors -1).
  std::vector<int> held_for_covariance;
  std::string message;
  /// What the check of solve_stage changed or found (empty: nothing).
  std::string note;
  StageTiming timing;          // summed over the starts
};

/// Empty where a parameter set is acceptable, else why not (e.g. the test it cannot integrate).
using SetCheck = std::function<std::string(const FitVector&)>;

/// Levenberg-Marquardt on the residuals of spec over all tests, free parameters `free` (indices
/// into FitVector), the others held at x0; `starts` starts (the first from x0, the others drawn
/// from seed). Progress lines go to options.progress, prefixed by stage_name. Where `check` is
/// given, a start whose end point would become the best is checked; if the check refuses it,
/// the start's last accepted iterate that the check accepts (tried newest first, going back 1,
/// 2, 4, ... iterations) takes its place, and `note` says so; if none does, the end point stays
/// and `note` says why it was refused.
StageResult solve_stage(const std::vector<TestData>& tests, const std::vector<Grid>& grids,
                        const ResidualSpec& spec, const FitVector& x0, const std::vector<int>& free,
                        const FitOptions& options, const FitVector& lower, const FitVector& upper,
                        int starts, std::uint64_t seed, const std::string& stage_name,
                        const SetCheck& check = {});

}  // namespace fit_detail
}  // namespace calibration
