// The fit of any registered model over its description (any_model_fit.h).
#include "calibration/any_model_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/point_driver.h"

namespace calibration {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

void check_any_model_test(const TestData& test) {
  if (test.path != TestPath::kDrainedCompression)
    throw std::invalid_argument("test '" + test.name + "': the fit of any model follows drained "
                                "compression, not " + std::string(to_string(test.path)));
  if (test.axial_strain.size() < 2)
    throw std::invalid_argument("test '" + test.name + "': fewer than two series rows");
}

namespace {

// The initial inputs of a test's specimen: its void ratio where the model takes one, zero for
// every other slot (an isotropic specimen), as fe-check gives them (docs/fe.md).
std::vector<double> initial_inputs(const model::ModelDescription& description,
                                   const TestData& test) {
  const std::vector<model::Slot>& slots = description.initial_inputs();
  std::vector<double> inputs(static_cast<std::size_t>(model::slot_components(slots)), 0.0);
  const int void_ratio = model::slot_offset(slots, "void_ratio");
  if (void_ratio >= 0) inputs[static_cast<std::size_t>(void_ratio)] = test.e0;
  return inputs;
}

// The middle of a search range: geometric where it is positive and spans more than a decade.
double middle(const model::ParameterInfo& info) {
  if (info.fit_low > 0.0 && info.fit_high > 10.0 * info.fit_low)
    return std::sqrt(info.fit_low * info.fit_high);
  return 0.5 * (info.fit_low + info.fit_high);
}

// The rows after the first that enter the objective: at most max_points, evenly picked.
std::vector<std::size_t> objective_rows(const TestData& test, int max_points) {
  const std::size_t n = test.axial_strain.size() - 1;  // rows after the first
  const std::size_t m = std::min<std::size_t>(n, static_cast<std::size_t>(std::max(1, max_points)));
  std::vector<std::size_t> rows;
  for (std::size_t k = 1; k <= m; ++k) rows.push_back(k * n / m);
  return rows;
}

// The residuals of one test for Ceres, the parameters in one block.
struct TestResidual {
  const model::ModelDescription* description;
  const TestData* test;
  std::vector<double> constants;
  std::vector<std::size_t> rows;
  const AnyModelFitOptions* options;

  bool operator()(double const* const* x, double* residual) const {
    model::ParameterValues values;
    values.model = description->name();
    values.constants = constants;
    values.parameters.assign(x[0], x[0] + description->parameters().size());
    AnyModelCurve curve;
    try {
      curve = any_model_curve(*description, values, *test, options->driver_steps);
    } catch (const std::invalid_argument&) {
      return false;  // a value the model refuses (a central difference past a physical bound)
    }
    std::size_t n = 0;
    for (std::size_t r : rows) {
      residual[n++] = (curve.eta[r] - test->eta[r]) / options->eta_scale;
      residual[n++] =
          (curve.volumetric_strain[r] - test->volumetric_strain[r]) / options->volumetric_scale;
    }
    return std::all_of(residual, residual + n, [](double v) { return std::isfinite(v); });
  }
};

AnyModelTestError test_error(const model::ModelDescription& description,
                             const model::ParameterValues& values, const TestData& test,
                             bool fitted, int driver_steps) {
  AnyModelTestError error;
  error.name = test.name;
  error.fitted = fitted;
  const AnyModelCurve curve = any_model_curve(description, values, test, driver_steps);
  error.message = curve.message;
  for (std::size_t r = 1; r < test.axial_strain.size(); ++r) {
    if (!std::isfinite(curve.eta[r])) break;
    error.eta_rms += std::pow(curve.eta[r] - test.eta[r], 2);
    error.volumetric_rms += std::pow(curve.volumetric_strain[r] - test.volumetric_strain[r], 2);
    ++error.rows;
  }
  if (error.rows > 0) {
    error.eta_rms = std::sqrt(error.eta_rms / error.rows);
    error.volumetric_rms = std::sqrt(error.volumetric_rms / error.rows);
  }
  return error;
}

}  // namespace

AnyModelCurve any_model_curve(const model::ModelDescription& description,
                              const model::ParameterValues& values, const TestData& test,
                              int driver_steps) {
  check_any_model_test(test);
  const std::unique_ptr<model::Behaviour> behaviour =
      description.make(values.constants, values.parameters);
  model::TriaxialPath path;
  path.lateral_stress = test.p0;
  path.axial_strain_end = test.axial_strain.back();
  path.steps = driver_steps;
  const model::DriverPath driven =
      model::drive_triaxial(*behaviour, initial_inputs(description, test), path);
  AnyModelCurve curve;
  curve.message = driven.message;
  curve.axial_strain = test.axial_strain;
  // The model's points at each row's axial strain, linear between the driver's equal increments.
  const std::vector<model::DriverPoint>& points = driven.points;
  const double step = path.axial_strain_end / driver_steps;
  for (double axial : test.axial_strain) {
    const double at = std::clamp(axial / step, 0.0, static_cast<double>(driver_steps));
    const std::size_t k = std::min(static_cast<std::size_t>(at), points.size() - 1);
    if (k + 1 >= points.size() && at > static_cast<double>(k)) {  // past the last point reached
      curve.eta.push_back(kNaN);
      curve.volumetric_strain.push_back(kNaN);
      continue;
    }
    const std::size_t k1 = std::min(k + 1, points.size() - 1);
    const double w = at - static_cast<double>(k);
    auto eta = [](const model::DriverPoint& x) {
      const Eigen::Matrix3d& s = x.stress;
      return (s(2, 2) - 0.5 * (s(0, 0) + s(1, 1))) / (s.trace() / 3.0);
    };
    curve.eta.push_back((1.0 - w) * eta(points[k]) + w * eta(points[k1]));
    curve.volumetric_strain.push_back((1.0 - w) * points[k].strain.trace() +
                                      w * points[k1].strain.trace());
  }
  return curve;
}

AnyModelFitResult fit_any_model(const model::ModelDescription& description,
                                const std::vector<TestData>& fitted,
                                const AnyModelFitOptions& options) {
  if (fitted.empty()) throw std::invalid_argument("the fit needs at least one test");
  if (options.max_points < 1 || options.driver_steps < 1 || options.max_iterations < 1 ||
      !(options.eta_scale > 0.0) || !(options.volumetric_scale > 0.0))
    throw std::invalid_argument("the fit's points, steps, iterations and scales must be positive");
  for (const TestData& t : fitted) check_any_model_test(t);
  const std::vector<model::ParameterInfo>& table = description.parameters();
  const std::size_t n = table.size();
  if (n == 0)
    throw std::invalid_argument("model '" + description.name() + "' has no parameter to fit");

  std::vector<double> constants = options.constants;
  if (constants.empty())
    for (const model::ParameterInfo& c : description.constants()) {
      if (c.required())
        throw std::invalid_argument("model '" + description.name() + "': its constant '" +
                                    c.name + "' has no value when absent; give it");
      constants.push_back(c.value_if_absent);
    }
  for (const model::ParameterInfo& info : table)
    if (!std::isfinite(info.fit_low) || !std::isfinite(info.fit_high) ||
        !(info.fit_low < info.fit_high))
      throw std::invalid_argument("model '" + description.name() + "': the search range of '" +
                                  info.name + "' is not a finite interval: the fit of any model "
                                  "needs one for every parameter");
  std::vector<double> x = options.start;
  if (x.empty())
    for (const model::ParameterInfo& info : table) x.push_back(middle(info));
  if (x.size() != n || constants.size() != description.constants().size())
    throw std::invalid_argument("model '" + description.name() + "': the start needs " +
                                std::to_string(n) + " values and the constants " +
                                std::to_string(description.constants().size()));
  for (std::size_t i = 0; i < n; ++i)
    if (!(x[i] >= table[i].fit_low && x[i] <= table[i].fit_high))
      throw std::invalid_argument("the start of '" + std::string(table[i].name) +
                                  "' lies outside its search range");
  description.validate(constants, x);

  ceres::Problem problem;
  problem.AddParameterBlock(x.data(), static_cast<int>(n));
  for (std::size_t i = 0; i < n; ++i) {
    if (std::isfinite(table[i].fit_low))
      problem.SetParameterLowerBound(x.data(), static_cast<int>(i), table[i].fit_low);
    if (std::isfinite(table[i].fit_high))
      problem.SetParameterUpperBound(x.data(), static_cast<int>(i), table[i].fit_high);
  }
  for (const TestData& test : fitted) {
    auto* residual = new TestResidual{&description, &test, constants,
                                      objective_rows(test, options.max_points), &options};
    auto* cost = new ceres::DynamicNumericDiffCostFunction<TestResidual, ceres::CENTRAL>(residual);
    cost->AddParameterBlock(static_cast<int>(n));
    cost->SetNumResiduals(static_cast<int>(2 * residual->rows.size()));
    problem.AddResidualBlock(cost, nullptr, x.data());
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = 1e-12;
  solver.parameter_tolerance = 1e-12;
  solver.gradient_tolerance = 1e-14;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);

  AnyModelFitResult result;
  result.values.model = description.name();
  result.values.constants = constants;
  result.values.parameters = x;
  for (std::size_t i = 0; i < n; ++i) {
    const double tolerance = 1e-9 * std::max(std::abs(table[i].fit_high - table[i].fit_low), 1e-300);
    result.at_bound.push_back(std::abs(x[i] - table[i].fit_low) <= tolerance ||
                              std::abs(x[i] - table[i].fit_high) <= tolerance);
  }
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.usable = summary.IsSolutionUsable();
  result.termination = summary.BriefReport();
  result.errors = any_model_errors(description, result.values, fitted, true, options.driver_steps);
  return result;
}

std::vector<AnyModelTestError> any_model_errors(const model::ModelDescription& description,
                                                const model::ParameterValues& values,
                                                const std::vector<TestData>& tests, bool fitted,
                                                int driver_steps) {
  std::vector<AnyModelTestError> errors;
  for (const TestData& t : tests)
    errors.push_back(test_error(description, values, t, fitted, driver_steps));
  return errors;
}

}  // namespace calibration
