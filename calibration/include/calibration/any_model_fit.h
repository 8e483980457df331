// The fit of any registered model (model/descriptor.h) to drained triaxial DEM tests, written over
// its description alone: the parameters within their search ranges (the table's fit_low, fit_high),
// each test driven by the driver of any model (model/point_driver.h) from the test's sigma_3 and
// e_0, residuals in q/p and eps_v at the test's series rows, Jacobians by central differences.
// `sffcal calibrate --model NAME` runs it for a model that has no fit of its own (ACST and the
// contact-network model have theirs: fit.h, network_fit.h). docs/model-interface.md.
//
// Conventions: compression positive, stresses in Pa, strains as fractions.
#pragma once

#include <string>
#include <vector>

#include "calibration/test_data.h"
#include "model/descriptor.h"
#include "model/parameter_file.h"

namespace calibration {

struct AnyModelFitOptions {
  int max_points = 60;             ///< series rows per test in the objective (evenly picked)
  int driver_steps = 200;          ///< equal increments of each test's path to its last row
  double eta_scale = 0.05;         ///< residual (q/p model - DEM) / eta_scale
  double volumetric_scale = 0.005; ///< residual (eps_v model - DEM) / volumetric_scale
  int max_iterations = 100;
  /// The first values of the parameters (the table's order); empty: each search range's middle,
  /// geometric where the range is positive and spans more than a decade.
  std::vector<double> start;
  /// The model's constants (the table's order); empty: their values when absent.
  std::vector<double> constants;
};

/// One test's errors with the fitted values: RMS over the rows after the first.
struct AnyModelTestError {
  std::string name;
  bool fitted = true;  ///< false: held out
  double eta_rms = 0.0, volumetric_rms = 0.0;
  int rows = 0;
  std::string message;  ///< where the model's path stopped early (then the RMS cover fewer rows)
};

struct AnyModelFitResult {
  model::ParameterValues values;  ///< the fitted values, as the parameter file holds them
  std::vector<bool> at_bound;     ///< per parameter: on a bound of its search range
  double initial_cost = 0.0, final_cost = 0.0;
  int iterations = 0;
  bool usable = false;            ///< Ceres' verdict on the solution
  std::string termination;        ///< Ceres' brief report
  std::vector<AnyModelTestError> errors;  ///< fitted tests (then held-out ones: any_model_errors)
};

/// Throws std::invalid_argument naming a test that is not a drained triaxial compression with at
/// least two series rows, the tests this fit follows.
void check_any_model_test(const TestData& test);

/// Fits `description`'s parameters to the tests (each a drained triaxial compression from an
/// isotropic stress). Throws std::invalid_argument for a test on another path, no test, a start
/// or constants of the wrong length or outside the ranges.
AnyModelFitResult fit_any_model(const model::ModelDescription& description,
                                const std::vector<TestData>& fitted,
                                const AnyModelFitOptions& options = {});

/// Each test's errors with the given values (`fitted` says which role they had).
std::vector<AnyModelTestError> any_model_errors(const model::ModelDescription& description,
                                                const model::ParameterValues& values,
                                                const std::vector<TestData>& tests, bool fitted,
                                                int driver_steps = AnyModelFitOptions{}.driver_steps);

/// The model curve of a test with the given values, at the test's series rows: q/p and eps_v
/// (NaN past the row where the model's path stopped, which `message` then names).
struct AnyModelCurve {
  std::vector<double> axial_strain, eta, volumetric_strain;
  std::string message;
};
AnyModelCurve any_model_curve(const model::ModelDescription& description,
                              const model::ParameterValues& values, const TestData& test,
                              int driver_steps = AnyModelFitOptions{}.driver_steps);

/// Writes FOLDER/parameters.json (the model's parameter file, each parameter with its search range
/// and whether it ended on a bound), FOLDER/<test>_curves.csv (DEM and model q/p and eps_v at the
/// series rows) and FOLDER/summary.md, and returns the summary's text. Throws std::runtime_error
/// if a file cannot be written.
std::string write_any_model_fit_outputs(const std::string& folder,
                                        const model::ModelDescription& description,
                                        const std::vector<TestData>& fitted,
                                        const std::vector<TestData>& held_out,
                                        const AnyModelFitResult& result,
                                        const AnyModelFitOptions& options,
                                        const std::string& program_version,
                                        const std::string& command_line);

}  // namespace calibration
