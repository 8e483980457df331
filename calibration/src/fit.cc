// The staged and joint calibration of the ACST model (docs/calibration.md).
#include "calibration/fit.h"

#include "fit_path.h"
#include "fit_solve.h"
#include "sffcal/final_window.h"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <cstdio>
#include <stdexcept>
#include <string_view>

namespace calibration {

using fit_detail::Grid;
using fit_detail::make_grid;
using fit_detail::parameters_of;
using fit_detail::ResidualSpec;
using fit_detail::run_test;

namespace {

// The model's parameters, then a_cs.
static_assert(kParameterFields<double>.size() + 1 == kNumFitParameters && kAcsIndex == 18);

// The index of a parameter in the fit vector, by its name in kParameterFields (at compile time:
// a misspelt name does not compile).
constexpr int fit_index(std::string_view name) {
  for (std::size_t k = 0; k < kParameterFields<double>.size(); ++k)
    if (std::string_view(kParameterFields<double>[k].name) == name) return static_cast<int>(k);
  return name == "a_cs" ? kAcsIndex : throw std::logic_error("no fit parameter of that name");
}
constexpr int kG0 = fit_index("G0"), kNu = fit_index("nu"), kMc = fit_index("M_c"),
              kC = fit_index("c"), kEGamma = fit_index("e_gamma"),
              kLambdaC = fit_index("lambda_c"), kXi = fit_index("xi"), kH0 = fit_index("h0"),
              kCh = fit_index("c_h"), kNb = fit_index("n_b"), kA0 = fit_index("A0"),
              kNd = fit_index("n_d"), kEA = fit_index("e_A"), kKF = fit_index("k_F"),
              kNbLoose = fit_index("n_b_loose"), kNG = fit_index("n_G"), kNF = fit_index("n_F");
const std::array<const char*, kNumFitParameters> kNames = [] {
  std::array<const char*, kNumFitParameters> names{};
  for (std::size_t k = 0; k < kParameterFields<double>.size(); ++k)
    names[k] = kParameterFields<double>[k].name;
  names[kAcsIndex] = "a_cs";
  return names;
}();

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

double standard_error_of_mean(const std::vector<double>& v) {
  if (v.size() < 2) return -1.0;
  const double m = mean(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1) / static_cast<double>(v.size()));
}

}  // namespace

const std::array<const char*, kNumFitParameters>& fit_parameter_names() { return kNames; }

int fit_parameter_index(const std::string& name) {
  for (int i = 0; i < kNumFitParameters; ++i)
    if (name == kNames[i]) return i;
  throw std::runtime_error("unknown parameter '" + name + "'");
}

void set_search_range(FitOptions& options, const std::string& range) {
  const std::string usage = "--range '" + range + "': ";
  const std::size_t equals = range.find('='), colon = range.find(':', equals);
  if (equals == std::string::npos || colon == std::string::npos)
    throw std::runtime_error(usage + "expected NAME=LOW:HIGH, e.g. n_d=0:60");
  int i = 0;
  try {
    i = fit_parameter_index(range.substr(0, equals));
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(usage + e.what());
  }
  auto number = [&](const std::string& text) {
    std::size_t used = 0;
    double x = std::numeric_limits<double>::quiet_NaN();
    try {
      x = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != text.size() || !std::isfinite(x))
      throw std::runtime_error(usage + "'" + text + "' is not a finite number");
    return x;
  };
  const double low = number(range.substr(equals + 1, colon - equals - 1));
  const double high = number(range.substr(colon + 1));
  if (!(low < high)) throw std::runtime_error(usage + "LOW must be below HIGH");
  for (double x : {low, high}) {
    const bool physical =
        i == kAcsIndex ? x > 0.0 : kParameterFields<double>[i].physical.contains(x);
    if (!physical)
      throw std::runtime_error(usage + model::format_number(x) + " is not physical for '" +
                               kNames[i] + "': it must be " +
                               (i == kAcsIndex ? std::string("> 0")
                                               : kParameterFields<double>[i].physical.describe()));
  }
  options.lower[i] = low;
  options.upper[i] = high;
  options.initial[i] = std::clamp(options.initial[i], low, high);
}

FitVector to_fit_vector(const Parameters<double>& p, double a_cs) {
  FitVector x{};
  for (std::size_t k = 0; k < kParameterFields<double>.size(); ++k)
    x[k] = p.*kParameterFields<double>[k].member;
  x[kAcsIndex] = a_cs;
  return x;
}

Parameters<double> model_parameters(const FitVector& x) {
  std::array<double, kNumFitParameters> v = x;
  return parameters_of(v);
}

const char* to_string(Stage stage) {
  switch (stage) {
    case Stage::kCsl: return "csl";
    case Stage::kElastic: return "elastic";
    case Stage::kFabric: return "fabric";
    case Stage::kPlastic: return "plastic";
    case Stage::kJoint: return "joint";
  }
  return "unknown";
}

std::vector<Stage> parse_stages(const std::string& text) {
  if (text == "all") return FitOptions{}.stages;
  for (Stage s : FitOptions{}.stages)
    if (text == to_string(s)) return {s};
  throw std::runtime_error("unknown stage '" + text +
                           "' (all, csl, elastic, fabric, plastic, joint)");
}

Loss parse_loss(const std::string& text) {
  if (text == "none") return Loss::kNone;
  if (text == "huber") return Loss::kHuber;
  if (text == "cauchy") return Loss::kCauchy;
  throw std::runtime_error("unknown loss '" + text + "' (none, huber, cauchy)");
}

DriverOptions FitOptions::fit_driver_options() {
  DriverOptions d;
  // The implicit integration with error control at 1e-3: its parameter derivatives are exact
  // derivatives of the discrete path (implicit function theorem on each converged local system,
  // docs/model.md §4.1), and the path is within about 4e-4 in q of the converged one (3.7e-4
  // measured on a 500-increment drained path). The reported errors use report_driver_options.
  d.integration = IntegrationOptions::implicit_controlled(1e-3);
  d.stress_tolerance = 1e-6;  // above the integration noise (~tolerance |sigma|)
  // Fail fast: a parameter set the model cannot integrate is rejected by Ceres anyway, and the
  // driver then cuts the increment; 100000 attempted substeps per update made such sets cost
  // minutes.
  d.integration.max_substeps = 4000;
  d.max_newton_iterations = 15;
  return d;
}

DriverOptions FitOptions::report_driver_options() {
  // The fit's path at the driver's default (implicit, 1e-7) with the Newton residual at 1e-8 p,
  // and no fail-fast caps: the reported errors are those of an accurate integration.
  DriverOptions d;
  d.stress_tolerance = 1e-8;
  return d;
}

FitVector FitOptions::default_initial() {
  // Toyoura-like values of docs/model.md (DM04 Table 1), n_b_loose = 0, n_G = 1/2 and n_F = 0
  // (DM04's bounding surface and elasticity, LD12's fabric rate), a_cs = 1.
  return {125.0, 0.05, 1.25, 0.712, 0.934, 0.019, 0.7, 0.01, 7.05,
          0.968, 1.1,  0.704, 3.5, 0.1,  5.0,  0.0, 0.5,  0.0, 1.0};
}

// The model's parameters search kParameterFields' fit ranges; a_cs, the fabric at the critical
// state, [0.05, 3].
FitVector FitOptions::default_lower() {
  FitVector lower{};
  for (std::size_t k = 0; k < kParameterFields<double>.size(); ++k) lower[k] = kParameterFields<double>[k].fit_low;
  lower[kAcsIndex] = 0.05;
  return lower;
}

FitVector FitOptions::default_upper() {
  FitVector upper{};
  for (std::size_t k = 0; k < kParameterFields<double>.size(); ++k) upper[k] = kParameterFields<double>[k].fit_high;
  upper[kAcsIndex] = 3.0;
  return upper;
}

bool scaled_standard_errors(ceres::Problem& problem, double* block, int size, double cost,
                            int n_residuals, int n_free, std::vector<double>& errors,
                            double* scale) {
  if (n_residuals <= n_free) return false;
  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::DENSE_SVD;
  covariance_options.null_space_rank = 0;  // rank deficient: fail rather than guess
  ceres::Covariance covariance(covariance_options);
  std::vector<std::pair<const double*, const double*>> blocks = {{block, block}};
  if (!covariance.Compute(blocks, &problem)) return false;
  std::vector<double> c(static_cast<std::size_t>(size) * size);
  if (!covariance.GetCovarianceBlock(block, block, c.data())) return false;
  const double s2 = 2.0 * cost / static_cast<double>(n_residuals - n_free);
  errors.assign(static_cast<std::size_t>(size), 0.0);
  for (int j = 0; j < size; ++j) {
    const double v = c[static_cast<std::size_t>(j) * size + j];
    if (!(v >= 0.0) || !std::isfinite(v)) return false;
    errors[j] = std::sqrt(s2 * v);
  }
  if (scale) *scale = s2;
  return true;
}

bool autocorrelation_robust_standard_errors(const double* jacobian, int stride, int k,
                                            const double* residuals,
                                            const std::vector<int>& series_lengths,
                                            std::vector<double>& errors, double* mean_bandwidth) {
  int n = 0;
  for (int length : series_lengths) n += length;
  if (k < 1 || n <= k) return false;
  using Matrix = Eigen::MatrixXd;
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
      all(jacobian, n, stride);
  const Matrix J = all.leftCols(k);
  const Eigen::Map<const Eigen::VectorXd> r(residuals, n);
  const Eigen::FullPivLU<Matrix> lu(J.transpose() * J);
  if (!lu.isInvertible()) return false;
  const Matrix bread = lu.inverse();
  Matrix meat = Matrix::Zero(k, k);
  double bandwidth_sum = 0.0;
  int from = 0;
  for (int length : series_lengths) {
    const Eigen::VectorXd r_s = r.segment(from, length);
    // Scores g_i = r_i J_i of this series, and the residuals' lag-1 autocorrelation.
    const Matrix g = (J.middleRows(from, length).array().colwise() * r_s.array()).matrix();
    from += length;
    const double c0 = r_s.squaredNorm();
    const double c1 = length > 1 ? r_s.head(length - 1).dot(r_s.tail(length - 1)) : 0.0;
    const double rho = c0 > 0.0 ? std::clamp(c1 / c0, 0.0, 0.97) : 0.0;
    // Andrews (1991), Bartlett kernel, AR(1): L = 1.1447 (alpha n)^(1/3),
    // alpha = 4 rho^2 / ((1 - rho)^2 (1 + rho)^2).
    const double alpha = 4.0 * rho * rho / std::pow((1.0 - rho) * (1.0 + rho), 2);
    const int bandwidth = std::max(
        0, std::min(length - 1, static_cast<int>(std::ceil(1.1447 * std::cbrt(alpha * length)))));
    bandwidth_sum += bandwidth;
    meat += g.transpose() * g;
    for (int lag = 1; lag <= bandwidth; ++lag) {
      const double w = 1.0 - static_cast<double>(lag) / (bandwidth + 1);
      const Matrix cross = g.topRows(length - lag).transpose() * g.bottomRows(length - lag);
      meat += w * (cross + cross.transpose());
    }
  }
  const Matrix covariance = bread * meat * bread;
  std::vector<double> result(static_cast<std::size_t>(k), 0.0);
  for (int j = 0; j < k; ++j) {
    const double v = covariance(j, j);
    if (!(v >= 0.0) || !std::isfinite(v)) return false;
    result[j] = std::sqrt(v);
  }
  errors = std::move(result);
  if (mean_bandwidth)
    *mean_bandwidth = series_lengths.empty()
                          ? 0.0
                          : bandwidth_sum / static_cast<double>(series_lengths.size());
  return true;
}

ModelCurves simulate_test(const TestData& t, const FitVector& x, const DriverOptions& driver,
                          double max_strain_step) {
  const Grid g = make_grid(t, std::numeric_limits<int>::max(), max_strain_step);
  const PathResult<double> path = run_test(t, g, x, driver);
  ModelCurves c;
  c.status = path.status;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const int reached = static_cast<int>(path.rows.size()) - (path.status == UpdateStatus::kFailed ? 1 : 0);
  for (std::size_t i = 0; i < g.rows.size(); ++i) {
    const int at = g.row_at[i];
    const bool ok = at < reached;
    c.axial_strain.push_back(t.axial_strain[g.rows[i]]);
    c.eta.push_back(ok ? path.rows[at].eta : nan);
    c.volumetric_strain.push_back(ok ? path.rows[at].volumetric_strain : nan);
    c.void_ratio.push_back(ok ? path.rows[at].void_ratio : nan);
    c.p.push_back(ok ? path.rows[at].p : nan);
    if (ok) ++c.rows_reached;
  }
  for (int at : g.snapshot_at)
    c.a_c.push_back(at >= 0 && at < reached ? x[kAcsIndex] * path.rows[at].fabric_triaxial : nan);
  // A held row (fit_path.h): unreliable, with the stress of the row before.
  for (std::size_t k = 1; k < path.rows.size() && is_undrained(t.path); ++k)
    if (path.rows[k].status == UpdateStatus::kUnreliable && path.rows[k].p == path.rows[k - 1].p) {
      c.liquefied_at = path.rows[k - 1].axial_strain;
      break;
    }
  return c;
}

TestErrors test_errors(const TestData& t, const FitVector& x, const FitOptions& options) {
  const ModelCurves c = simulate_test(t, x, options.report_driver, options.report_max_strain_step);
  TestErrors e;
  e.name = t.name;
  e.path = to_string(t.path);
  e.status = to_string(c.status);
  const bool undrained = is_undrained(t.path);
  double se = 0, sv = 0, sr = 0, sp = 0, sa = 0, sn = 0;
  int nn = 0, eta_rows = 0, snapshots_used = 0;
  for (std::size_t i = 1; i < c.eta.size(); ++i) {
    if (!std::isfinite(c.eta[i])) continue;
    const double dv = c.volumetric_strain[i] - t.volumetric_strain[i];
    const double dr = c.void_ratio[i] - t.void_ratio[i];
    const double dp = c.p[i] - t.p[i];
    sv += dv * dv;
    sr += dr * dr;
    sp += dp * dp / (t.p0 * t.p0);
    // The objective's second residual (fit_path.h): the mean stress undrained, else eps_v.
    const double second = undrained ? dp / (options.mean_stress_scale * std::max(t.p0, t.p[i]))
                                    : dv / options.volumetric_scale;
    sn += second * second;
    ++nn;
    ++e.rows;
    if (liquefied_at_row(t, i)) continue;  // q/p of a liquefied specimen: noise
    const double de = c.eta[i] - t.eta[i];
    se += de * de;
    e.max_abs_eta = std::max(e.max_abs_eta, std::abs(de));
    sn += std::pow(de / options.eta_scale, 2);
    ++nn;
    ++eta_rows;
  }
  const Grid g = make_grid(t, 3);  // for the snapshots' liquefaction flags only
  for (std::size_t i = 1; i < c.a_c.size(); ++i) {
    if (!std::isfinite(c.a_c[i]) || g.snapshot_liquefied[i]) continue;
    const double da = c.a_c[i] - t.a_c[i];
    sa += da * da;
    sn += std::pow(da / options.fabric_scale, 2);
    ++nn;
    ++snapshots_used;
  }
  e.snapshots = snapshots_used;
  if (eta_rows > 0) e.rms_eta = std::sqrt(se / eta_rows);
  if (e.rows > 0) {
    e.rms_volumetric = std::sqrt(sv / e.rows);
    e.rms_void_ratio = std::sqrt(sr / e.rows);
    e.rms_p_ratio = std::sqrt(sp / e.rows);
  }
  if (snapshots_used > 0) e.rms_a_c = std::sqrt(sa / snapshots_used);
  if (nn > 0) e.rms_normalised = std::sqrt(sn / nn);
  if (e.rows + 1 < static_cast<int>(c.eta.size()))
    e.status += " (model failed after " + std::to_string(e.rows) + " rows)";
  if (std::isfinite(c.liquefied_at)) {
    char text[96];
    std::snprintf(text, sizeof text, " (model liquefied at axial strain %.4f, held there)",
                  c.liquefied_at);
    e.status += text;
  }
  return e;
}

void predict(const std::vector<TestData>& held_out, const FitOptions& options,
             CalibrationResult& result) {
  for (const TestData& t : held_out) {
    validate_test_data(t);
    result.predictions.push_back(test_errors(t, result.values, options));
  }
}

SffRelationFit fit_sff_relation(const std::vector<TestData>& tests) {
  SffRelationFit f;
  std::vector<std::array<double, 4>> rows;  // a_c, a_n, mu m, eta
  for (const TestData& t : tests) {
    if (!(t.friction > 0.0)) continue;
    for (std::size_t k = 0; k < t.a_c.size(); ++k)
      rows.push_back({t.a_c[k], t.a_n[k], t.friction * t.mobilisation[k], t.snapshot_eta[k]});
  }
  f.snapshots = static_cast<int>(rows.size());
  if (rows.size() < 4) {
    f.note = "fewer than 4 snapshots with a known friction: not fitted";
    return f;
  }
  Eigen::MatrixXd X(rows.size(), 3);
  Eigen::VectorXd y(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    X.row(static_cast<Eigen::Index>(k)) << rows[k][0], rows[k][1], rows[k][2];
    y(static_cast<Eigen::Index>(k)) = rows[k][3];
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(X);
  if (qr.rank() < 3) {
    f.note = "a_c, a_n and mu m are linearly dependent over the snapshots: not fitted";
    return f;
  }
  const Eigen::Vector3d c = qr.solve(y);
  const Eigen::VectorXd residual = y - X * c;
  const double s2 = residual.squaredNorm() / static_cast<double>(rows.size() - 3);
  const Eigen::Matrix3d covariance = s2 * (X.transpose() * X).inverse();
  f.available = true;
  for (int j = 0; j < 3; ++j) {
    f.coefficients[j] = c(j);
    f.standard_errors[j] = std::sqrt(covariance(j, j));
  }
  f.rms = std::sqrt(residual.squaredNorm() / static_cast<double>(rows.size()));
  f.distance = (c - Eigen::Vector3d(0.4, 0.4, 0.6)).norm();
  return f;
}

namespace {

// |strain| (the rule of sffcal::final_window_start: the strain grows along the test; extension
// runs to negative axial strain).
std::vector<double> magnitudes(const std::vector<double>& strain) {
  std::vector<double> m(strain.size());
  std::transform(strain.begin(), strain.end(), m.begin(), [](double x) { return std::abs(x); });
  return m;
}

// The critical state of each test: means of p, e and q/p over the final critical_window of axial
// strain (sffcal::final_window_start on |strain|), and of a_c over the snapshots in the same window.
std::vector<CriticalStatePoint> measure_critical_states(const std::vector<TestData>& tests,
                                                        double window) {
  std::vector<CriticalStatePoint> points;
  for (const TestData& t : tests) {
    CriticalStatePoint c;
    c.test = t.name;
    const std::vector<double> strain = magnitudes(t.axial_strain);
    const std::size_t from = sffcal::final_window_start(strain, window);
    std::vector<double> p, e, eta, a;
    for (std::size_t k = from; k < t.axial_strain.size(); ++k) {
      p.push_back(t.p[k]);
      e.push_back(t.void_ratio[k]);
      eta.push_back(t.eta[k]);
    }
    // The snapshots within the same window (of the series' last strain).
    for (std::size_t k = sffcal::final_window_start(magnitudes(t.snapshot_axial_strain),
                                                    strain.back(), window);
         k < t.a_c.size(); ++k)
      a.push_back(t.a_c[k]);
    if (a.empty()) a.push_back(t.a_c.back());
    c.p = mean(p);
    c.void_ratio = mean(e);
    c.eta = mean(eta);
    c.a_c = mean(a);
    points.push_back(c);
  }
  return points;
}

// One calibration, stage by stage (docs/calibration.md): the fit vector, its bounds and the
// result shared by the stages, each stage a member. calibrate() runs them in order.
class Calibration {
 public:
  Calibration(const std::vector<TestData>& tests, const FitOptions& options);

  void fit_critical_state_line();  // stage csl: M_c, c, e_Gamma, lambda_c, xi
  void bound_c_h();                // c_h e_Gamma < 1
  void estimate_elasticity();      // stage elastic: G0, nu from the first output interval
  void prepare_paths();            // the strain grids; whether c_h, n_b_loose, n_G are identifiable
  void fit_fabric();               // stage fabric: a_cs measured, k_F and n_F fitted
  void fit_plastic();              // stage plastic: h0, c_h, n_b, A0, n_d, e_A, n_b_loose
  void fit_jointly();              // stage joint: all but the critical state line and m
  CalibrationResult finish();      // values, bounds, errors per test, the SFF relation

  bool has(Stage s) const {
    return std::find(options_.stages.begin(), options_.stages.end(), s) != options_.stages.end();
  }

 private:
  void set(int i, double value, double error, const char* stage,
           double error_independent = -1.0);
  // The free ones of `wanted`: not fixed by the user, and c, c_h, n_b_loose, n_G only where
  // identifiable.
  std::vector<int> free_of(std::initializer_list<int> wanted) const;
  // One least-squares stage over every test's path, recorded in the result.
  void run_stage(Stage stage, const ResidualSpec& spec, const std::vector<int>& free, int starts);
  /// Empty where every test of the fit integrates to its last row at the report's integration
  /// (FitOptions::report_driver), else the first that does not: the fit's own, looser
  /// integration can pass a set the report then fails on (docs/calibration.md, "Objective").
  std::string report_integration_refusal(const FitVector& x) const;
  ResidualSpec base_spec() const;

  const std::vector<TestData>& tests_;
  const FitOptions& options_;
  CalibrationResult result_;
  FitVector x_, lower_, upper_;
  std::array<bool, kNumFitParameters> user_fixed_{};
  std::vector<Grid> grids_;
  bool c_h_identifiable_ = true;
  bool c_identifiable_ = false;  // an extension test: c = M_e / M_c
  bool n_b_loose_identifiable_ = true;  // a test starts looser than the critical state line
  bool n_G_identifiable_ = true;        // mean stresses over more than a factor 1.5
  // The tests whose end stands for the critical state (csl_tests()).
  std::vector<std::size_t> csl_tests_;
  std::uint64_t stage_seed_ = 0;
};

Calibration::Calibration(const std::vector<TestData>& tests, const FitOptions& options)
    : tests_(tests), options_(options), x_(options.initial), lower_(options.lower),
      upper_(options.upper), stage_seed_(options.seed) {
  if (tests.empty()) throw std::runtime_error("calibrate: no tests");
  for (const TestData& t : tests) validate_test_data(t);
  if (options.starts < 1) throw std::runtime_error("calibrate: starts must be >= 1");
  if (!(options.eta_scale > 0.0 && options.volumetric_scale > 0.0 && options.fabric_scale > 0.0 &&
        options.mean_stress_scale > 0.0))
    throw std::runtime_error("calibrate: residual scales must be > 0");
  for (int i = 0; i < kNumFitParameters; ++i)
    if (!(lower_[i] <= x_[i] && x_[i] <= upper_[i]))
      throw std::runtime_error(std::string("calibrate: initial value of '") + kNames[i] +
                               "' = " + std::to_string(x_[i]) + " is outside its bounds [" +
                               std::to_string(lower_[i]) + ", " + std::to_string(upper_[i]) + "]");
  for (const std::string& name : options.fixed) user_fixed_[fit_parameter_index(name)] = true;
  for (int i = 0; i < kNumFitParameters; ++i) {
    result_.estimates[i].lower = lower_[i];
    result_.estimates[i].upper = upper_[i];
  }
  result_.critical_states = measure_critical_states(tests, options.critical_window);
  // The critical state is read from the drained and constant-p tests that have not liquefied:
  // the undrained runs stop at a few percent of strain with p' still moving (docs/calibration.md).
  for (std::size_t k = 0; k < tests.size(); ++k) {
    if (is_undrained(tests[k].path)) continue;
    if (result_.critical_states[k].p < kLiquefiedMeanStress * tests[k].p0) continue;
    csl_tests_.push_back(k);
    if (axial_direction(tests[k].path) < 0.0) c_identifiable_ = true;
  }
  if (csl_tests_.size() < tests.size())
    result_.notes.push_back("critical state: " + std::to_string(tests.size() - csl_tests_.size()) +
                            " undrained or liquefied test(s) not used (their ends are not "
                            "critical states)");
  if (!c_identifiable_ && !user_fixed_[kC])
    result_.notes.push_back("c held (no drained extension test: M_e is not measured)");
}

void Calibration::set(int i, double value, double error, const char* stage,
                      double error_independent) {
  x_[i] = std::clamp(value, lower_[i], upper_[i]);
  result_.estimates[i].standard_error = error;
  result_.estimates[i].standard_error_independent = error_independent;
  result_.estimates[i].fixed = false;
  result_.estimates[i].stage = stage;
}

void Calibration::fit_critical_state_line() {
  if (csl_tests_.empty()) {
    result_.notes.push_back("critical state line: no drained test reached its end without "
                            "liquefying: M_c, c, e_gamma, lambda_c and xi keep their values");
    return;
  }
  std::vector<CriticalStatePoint> points;
  for (std::size_t k : csl_tests_) points.push_back(result_.critical_states[k]);
  // M_c from compression, M_e = c M_c from extension (q/p < 0 there).
  std::vector<double> eta_c, eta_e;
  for (std::size_t k : csl_tests_)
    (axial_direction(tests_[k].path) > 0.0 ? eta_c : eta_e).push_back(
        std::abs(result_.critical_states[k].eta));
  if (!user_fixed_[kMc] && !eta_c.empty())
    set(kMc, mean(eta_c), standard_error_of_mean(eta_c), "csl");
  if (!user_fixed_[kC] && !eta_e.empty()) {
    const double m_c = eta_c.empty() ? x_[kMc] : mean(eta_c);
    const double se_e = standard_error_of_mean(eta_e);
    set(kC, mean(eta_e) / m_c, se_e >= 0.0 ? se_e / m_c : -1.0, "csl");
  }
  // Distinct pressures (more than 10 % apart).
  std::vector<double> pressures;
  for (const auto& c : points) {
    bool distinct = true;
    for (double q : pressures) distinct = distinct && std::abs(c.p - q) > 0.1 * q;
    if (distinct) pressures.push_back(c.p);
  }
  const int n = static_cast<int>(points.size());
  const int distinct = static_cast<int>(pressures.size());
  auto line_fit = [&](double xi, double& e_gamma, double& lambda, double& rss, double* se_e,
                      double* se_l) {
    Eigen::MatrixXd X(n, 2);
    Eigen::VectorXd y(n);
    for (int k = 0; k < n; ++k) {
      X(k, 0) = 1.0;
      X(k, 1) = -std::pow(points[k].p / kAtmosphericPressure, xi);
      y(k) = points[k].void_ratio;
    }
    const Eigen::Vector2d b = X.colPivHouseholderQr().solve(y);
    e_gamma = b(0);
    lambda = b(1);
    rss = (y - X * b).squaredNorm();
    if (se_e && n > 2) {
      const Eigen::Matrix2d cov = rss / (n - 2) * (X.transpose() * X).inverse();
      *se_e = std::sqrt(cov(0, 0));
      *se_l = std::sqrt(cov(1, 1));
    }
  };
  const int ig = kEGamma, il = kLambdaC, ix = kXi;
  if (distinct == 1 || user_fixed_[il]) {
    // One pressure: only e_Gamma is identifiable; lambda_c and xi keep their values.
    std::vector<double> eg;
    for (const auto& c : points)
      eg.push_back(c.void_ratio + x_[il] * std::pow(c.p / kAtmosphericPressure, x_[ix]));
    if (!user_fixed_[ig]) set(ig, mean(eg), standard_error_of_mean(eg), "csl");
    result_.notes.push_back(
        "critical state line: " + std::to_string(distinct) +
        " distinct pressure(s): only e_gamma fitted; lambda_c = " + std::to_string(x_[il]) +
        " and xi = " + std::to_string(x_[ix]) + " held at their initial values");
    return;
  }
  double best_xi = x_[ix], best_rss = std::numeric_limits<double>::infinity();
  if (distinct >= 3 && !user_fixed_[ix]) {
    for (double xi = lower_[ix]; xi <= upper_[ix] + 1e-12; xi += 0.005) {
      double eg, l, rss;
      line_fit(xi, eg, l, rss, nullptr, nullptr);
      if (rss < best_rss && l >= 0.0) {
        best_rss = rss;
        best_xi = xi;
      }
    }
  } else {
    result_.notes.push_back("critical state line: " + std::to_string(distinct) +
                            " distinct pressures: xi = " + std::to_string(x_[ix]) +
                            " held at its initial value");
  }
  double eg, l, rss, se_e = -1.0, se_l = -1.0;
  line_fit(best_xi, eg, l, rss, &se_e, &se_l);
  if (l < 0.0) {
    // lambda_c >= 0 is active: the least-squares line with lambda_c = 0 is the mean void ratio.
    // (Clamping lambda_c alone would keep the rising line's intercept, below every point.)
    std::vector<double> e_cs;
    for (const auto& c : points) e_cs.push_back(c.void_ratio);
    result_.notes.push_back("critical state line: the critical void ratios rise with pressure "
                            "(least-squares lambda_c = " + std::to_string(l) +
                            "): lambda_c = 0 at its bound and e_gamma their mean");
    eg = mean(e_cs);
    se_e = standard_error_of_mean(e_cs);
    l = 0.0;
    se_l = -1.0;
  }
  if (!user_fixed_[ig]) set(ig, eg, se_e, "csl");
  set(il, l, se_l, "csl");
  if (distinct >= 3 && !user_fixed_[ix]) set(ix, best_xi, -1.0, "csl");
}

void Calibration::bound_c_h() {
  // b0 > 0 over the void ratios the model can reach: c_h e < 1 for e up to e_gamma and up to
  // the largest void ratio of the tests (a loose specimen starts above e_gamma).
  double e_max = x_[kEGamma];
  for (const TestData& t : tests_)
    for (double e : t.void_ratio) e_max = std::max(e_max, e);
  upper_[kCh] = std::min(upper_[kCh], 0.99 / e_max);
  x_[kCh] = std::min(x_[kCh], upper_[kCh]);
  result_.estimates[kCh].upper = upper_[kCh];
}

void Calibration::estimate_elasticity() {
  // Secant over the first output interval of each test (signed: q and eps_q fall together in
  // extension). nu only where sigma_3 is held: elastic de_v/de_a = 1 - 2 nu holds there alone.
  std::vector<double> g0, nu;
  for (const TestData& t : tests_) {
    const std::size_t k = 1;
    const double dea = t.axial_strain[k] - t.axial_strain[0];
    const double dev = t.volumetric_strain[k] - t.volumetric_strain[0];
    const double deq = dea - dev / 3.0;
    const double dq = t.eta[k] * t.p[k] - t.eta[0] * t.p[0];
    if (!(dq / deq > 0.0)) continue;
    const double G = dq / (3.0 * deq);
    const double f = kAtmosphericPressure * std::pow(2.97 - t.e0, 2) / (1.0 + t.e0) *
                     std::pow(t.p0 / kAtmosphericPressure, x_[kNG]);
    g0.push_back(G / f);
    if (holds_lateral_stress(t.path)) nu.push_back(0.5 * (1.0 - dev / dea));
  }
  if (g0.empty()) return;
  if (!user_fixed_[kG0]) set(kG0, mean(g0), standard_error_of_mean(g0), "elastic");
  if (!user_fixed_[kNu] && !nu.empty()) set(kNu, mean(nu), standard_error_of_mean(nu), "elastic");
  result_.notes.push_back(
      "elasticity: secant over the first output interval (a lower bound of G0, the cone is "
      "crossed almost at once); refined by the joint stage");
}

void Calibration::prepare_paths() {
  for (const TestData& t : tests_)
    grids_.push_back(make_grid(t, options_.max_points, options_.fit_max_strain_step));
  double e_min = 1e300, e_max = -1e300;
  for (const TestData& t : tests_) {
    e_min = std::min(e_min, t.e0);
    e_max = std::max(e_max, t.e0);
  }
  c_h_identifiable_ = e_max - e_min >= 0.05;
  if (!c_h_identifiable_ && !user_fixed_[kCh])
    result_.notes.push_back("c_h held (initial void ratios span less than 0.05: it trades off "
                            "with h0)");
  // n_b_loose acts only where psi > 0: it needs a test that starts looser than the critical state
  // line (of the csl stage). A dense test's path crosses psi = 0 only at its end.
  n_b_loose_identifiable_ = false;
  for (const TestData& t : tests_) {
    const double e_c =
        x_[kEGamma] - x_[kLambdaC] * std::pow(t.p0 / kAtmosphericPressure, x_[kXi]);
    n_b_loose_identifiable_ = n_b_loose_identifiable_ || t.e0 > e_c;
  }
  if (!n_b_loose_identifiable_ && !user_fixed_[kNbLoose])
    result_.notes.push_back("n_b_loose held at " + std::to_string(x_[kNbLoose]) +
                            " (no test starts looser than the critical state line: psi_0 <= 0)");
  // n_G sets how the stiffness follows p: it needs mean stresses apart (tests at several
  // pressures, or one whose p moves, as an undrained test's does); at one p it trades off with G0.
  double p_min = 1e300, p_max = 0.0;
  for (const TestData& t : tests_)
    for (double p : t.p) p_min = std::min(p_min, p), p_max = std::max(p_max, p);
  n_G_identifiable_ = p_max > 1.5 * p_min;
  if (!n_G_identifiable_ && !user_fixed_[kNG])
    result_.notes.push_back("n_G held at " + std::to_string(x_[kNG]) +
                            " (the tests' mean stresses span less than a factor 1.5)");
}

std::vector<int> Calibration::free_of(std::initializer_list<int> wanted) const {
  std::vector<int> free;
  for (int i : wanted)
    if (!user_fixed_[i] && (i != kCh || c_h_identifiable_) && (i != kC || c_identifiable_) &&
        (i != kNbLoose || n_b_loose_identifiable_) && (i != kNG || n_G_identifiable_))
      free.push_back(i);
  return free;
}

ResidualSpec Calibration::base_spec() const {
  ResidualSpec spec;
  spec.eta_scale = options_.eta_scale;
  spec.volumetric_scale = options_.volumetric_scale;
  spec.fabric_scale = options_.fabric_scale;
  spec.mean_stress_scale = options_.mean_stress_scale;
  return spec;
}

void Calibration::run_stage(Stage stage, const ResidualSpec& spec, const std::vector<int>& free,
                            int starts) {
  StageReport report;
  report.stage = to_string(stage);
  report.free_parameters = static_cast<int>(free.size());
  if (free.empty()) {
    report.message = "no free parameters";
    result_.stages.push_back(report);
    return;
  }
  int residuals = 0;
  for (std::size_t t = 0; t < tests_.size(); ++t)
    residuals += fit_detail::count_residuals(tests_[t], grids_[t], spec);
  if (residuals == 0) {  // e.g. the fabric stage on liquefied undrained tests alone
    report.message = "no residuals";
    result_.stages.push_back(report);
    result_.notes.push_back(std::string("stage ") + to_string(stage) + ": no residuals, skipped");
    return;
  }
  if (options_.progress)
    options_.progress(std::string("stage ") + to_string(stage) + ": " +
                      std::to_string(free.size()) + " free parameters, " +
                      std::to_string(residuals) + " residuals, " + std::to_string(starts) +
                      " start(s), " + std::to_string(options_.threads) + " thread(s)");
  // The stages that move the stress paths keep a set the report can integrate.
  fit_detail::SetCheck check;
  if (stage != Stage::kFabric)
    check = [this](const FitVector& x) { return report_integration_refusal(x); };
  const fit_detail::StageResult r =
      fit_detail::solve_stage(tests_, grids_, spec, x_, free, options_, lower_, upper_, starts,
                              stage_seed_++ * 7919, to_string(stage), check);
  report.timing = r.timing;
  if (options_.progress) {
    char line[320];
    std::snprintf(line, sizeof line,
                  "stage %s done: cost %.6e -> %.6e, %d iterations, %d cost + %d Jacobian "
                  "evaluations (%.1f s + %.1f s), %.0f substeps per step (at most %.0f), "
                  "%.1f s (processor %.1f s)",
                  to_string(stage), r.initial_cost, r.final_cost, r.timing.iterations,
                  r.timing.cost_evaluations, r.timing.jacobian_evaluations,
                  r.timing.cost_seconds, r.timing.jacobian_seconds, r.timing.substeps_per_step,
                  r.timing.max_substeps_per_step, r.timing.seconds, r.timing.cpu_seconds);
    options_.progress(line);
  }
  report.residuals = r.residuals;
  report.starts = r.starts_run;
  report.initial_cost = r.initial_cost;
  report.final_cost = r.final_cost;
  report.message = r.message;
  result_.stages.push_back(report);
  if (!r.note.empty()) {
    result_.notes.push_back(std::string("stage ") + to_string(stage) + ": " + r.note);
    if (options_.progress) options_.progress(result_.notes.back());
  }
  if (!std::isfinite(r.final_cost))
    throw std::runtime_error(std::string("calibrate: stage '") + to_string(stage) +
                             "' found no usable solution from any start: " + r.message);
  for (std::size_t j = 0; j < free.size(); ++j)
    set(free[j], r.x[free[j]], r.errors.empty() ? -1.0 : r.errors[j], to_string(stage),
        r.errors.empty() ? -1.0 : r.errors_independent[j]);
  std::string held;  // the free parameters at a bound, held for the covariance
  for (int i : r.held_for_covariance) held += std::string(held.empty() ? "" : ", ") + kNames[i];
  const std::string prefix = std::string("stage ") + to_string(stage) + ": ";
  if (!r.errors.empty()) {
    result_.covariance_scale = r.scale;
    result_.mean_bandwidth = r.mean_bandwidth;
    if (!held.empty())
      result_.notes.push_back(prefix + "standard errors with " + held + " held (at a bound)");
  } else if (r.held_for_covariance.size() == free.size()) {
    result_.notes.push_back(prefix + "no standard errors (every free parameter at a bound: " +
                            held + ")");
  } else {
    result_.notes.push_back(prefix +
                            "covariance not available (rank deficient or too few residuals)");
  }
}

std::string Calibration::report_integration_refusal(const FitVector& x) const {
  const int n = static_cast<int>(tests_.size());
  std::vector<std::string> refusal(tests_.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(std::max(1, options_.threads))
  for (int t = 0; t < n; ++t) {
    const TestData& test = tests_[static_cast<std::size_t>(t)];
    const ModelCurves c =
        simulate_test(test, x, options_.report_driver, options_.report_max_strain_step);
    if (c.rows_reached < static_cast<int>(c.axial_strain.size()))
      refusal[static_cast<std::size_t>(t)] =
          test.name + " fails at the report's integration after " +
          std::to_string(c.rows_reached) + " of " + std::to_string(c.axial_strain.size()) + " rows";
  }
  for (const std::string& r : refusal)
    if (!r.empty()) return r;
  return {};
}

void Calibration::fit_fabric() {
  // a_cs measured at the critical state (|a_c|: negative in extension, acst-model.md), then k_F
  // from the a_c histories.
  std::vector<double> a_cs;
  for (std::size_t k : csl_tests_)
    a_cs.push_back(kSqrtTwoThirds * std::abs(result_.critical_states[k].a_c));
  if (!user_fixed_[kAcsIndex] && mean(a_cs) > lower_[kAcsIndex])
    set(kAcsIndex, mean(a_cs), standard_error_of_mean(a_cs), "fabric");
  ResidualSpec spec = base_spec();
  spec.eta = spec.volumetric = false;
  run_stage(Stage::kFabric, spec, free_of({kKF, kNF}), 1);
}

void Calibration::fit_plastic() {
  ResidualSpec spec = base_spec();
  spec.fabric = false;
  run_stage(Stage::kPlastic, spec, free_of({kH0, kCh, kNb, kA0, kNd, kEA, kNbLoose}),
            options_.starts);
}

void Calibration::fit_jointly() {
  run_stage(Stage::kJoint, base_spec(),
            free_of({kG0, kNu, kMc, kC, kH0, kCh, kNb, kA0, kNd, kEA, kKF, kNbLoose, kNG, kNF}),
            options_.starts);
}

CalibrationResult Calibration::finish() {
  result_.values = x_;
  for (int i = 0; i < kNumFitParameters; ++i) {
    ParameterEstimate& e = result_.estimates[i];
    e.value = x_[i];
    e.lower = lower_[i];
    e.upper = upper_[i];
    const double tol = 1e-4 * (upper_[i] - lower_[i]);
    e.at_bound = !e.fixed && (x_[i] - lower_[i] <= tol || upper_[i] - x_[i] <= tol);
  }
  if (options_.progress) options_.progress("errors per test (report integration)");
  for (const TestData& t : tests_) result_.errors.push_back(test_errors(t, x_, options_));
  result_.sff = fit_sff_relation(tests_);
  return std::move(result_);
}

}  // namespace

CalibrationResult calibrate(const std::vector<TestData>& tests, const FitOptions& options) {
  Calibration c(tests, options);
  if (c.has(Stage::kCsl)) c.fit_critical_state_line();
  c.bound_c_h();
  if (c.has(Stage::kElastic)) c.estimate_elasticity();
  c.prepare_paths();
  if (c.has(Stage::kFabric)) c.fit_fabric();
  if (c.has(Stage::kPlastic)) c.fit_plastic();
  if (c.has(Stage::kJoint)) c.fit_jointly();
  return c.finish();
}

}  // namespace calibration
