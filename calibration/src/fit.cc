// The staged and joint calibration of the ACST model (docs/calibration.md).
#include "calibration/fit.h"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>

namespace calibration {

namespace {

constexpr std::array<const char*, kNumFitParameters> kNames = {
    "G0", "nu", "M_c", "c", "e_gamma", "lambda_c", "xi", "m", "h0", "c_h",
    "n_b", "A0", "n_d", "e_A", "k_F", "a_cs"};
const double kSqrtTwoThirds = std::sqrt(2.0 / 3.0);

/// Model strain grid of one test: 0, then the selected series rows and the snapshots.
struct Grid {
  std::vector<PathStep> steps;
  std::vector<int> rows;           ///< selected series rows
  std::vector<int> row_at;         ///< grid index of each selected row
  std::vector<int> snapshot_at;    ///< grid index of each snapshot (-1: beyond the series)
};

Grid make_grid(const TestData& t, int max_points) {
  Grid g;
  const int n = static_cast<int>(t.axial_strain.size());
  const int wanted = std::max(3, std::min(max_points, n));
  for (int k = 0; k < wanted; ++k) {
    const int row = static_cast<int>(std::lround(static_cast<double>(k) * (n - 1) / (wanted - 1)));
    if (g.rows.empty() || row != g.rows.back()) g.rows.push_back(row);
  }
  std::vector<double> strains = {0.0};
  for (int row : g.rows) strains.push_back(t.axial_strain[row]);
  const double last = t.axial_strain.back();
  for (double s : t.snapshot_axial_strain)
    if (s <= last) strains.push_back(s);
  std::sort(strains.begin(), strains.end());
  std::vector<double> grid;
  for (double s : strains)
    if (grid.empty() || s - grid.back() > 1e-7) grid.push_back(s);
  auto index_of = [&](double s) {
    const auto it = std::lower_bound(grid.begin(), grid.end(), s - 1e-7);
    return static_cast<int>(it - grid.begin());
  };
  for (int row : g.rows) g.row_at.push_back(std::min(index_of(t.axial_strain[row]),
                                                     static_cast<int>(grid.size()) - 1));
  for (double s : t.snapshot_axial_strain)
    g.snapshot_at.push_back(s <= last + 1e-7 ? std::min(index_of(s), static_cast<int>(grid.size()) - 1)
                                             : -1);
  for (std::size_t k = 1; k < grid.size(); ++k) {
    PathStep step;
    step.control = {Control::kStress, Control::kStress, Control::kStrain,
                    Control::kStrain, Control::kStrain, Control::kStrain};
    step.value = {t.p0, t.p0, grid[k] - grid[k - 1], 0.0, 0.0, 0.0};
    g.steps.push_back(step);
  }
  return g;
}

template <typename T>
Parameters<T> parameters_of(const std::array<T, kNumFitParameters>& v) {
  return Parameters<T>{v[0], v[1], v[2],  v[3],  v[4],  v[5],  v[6], v[7],
                       v[8], v[9], v[10], v[11], v[12], v[13], v[14]};
}

/// x.v += d.v[0] * delta for every entry (chain rule through the lateral strain).
template <typename T, typename D>
void chain(T& x, const D& d, const Eigen::Matrix<double, Eigen::Dynamic, 1>& delta) {
  x.v += d.v[0] * delta;
}
template <typename T, typename D>
void chain(Tensor<T>& x, const Tensor<D>& d, const Eigen::Matrix<double, Eigen::Dynamic, 1>& delta) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) chain(x(i, j), d(i, j), delta);
}
template <typename T>
void set_value(T& x, double v) {
  x.a = v;
}
template <typename T>
void set_values(Tensor<T>& x, const Tensor<double>& v) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) x(i, j).a = v(i, j);
}

/// Drained axisymmetric triaxial path (docs/calibration.md): eps_zz stepped, eps_xx = eps_yy =
/// eps_r the one unknown, sigma_xx = sigma_yy held at p0 through sigma_xx + sigma_yy = 2 p0. The
/// Newton derivative comes from a Jet<1> seeded on both lateral components together, which keeps
/// the symmetry (a strain tangent seeded on eps_xx alone excites the stiff asymmetric lateral
/// mode, docs/model.md §4). Values in double; with T = Jet the derivative parts by the implicit
/// function theorem at the converged values, as in mixed_increment.
template <typename T>
PathResult<T> axisymmetric_path(const Parameters<T>& par, const State<T>& initial,
                                const std::vector<PathStep>& steps, const DriverOptions& options) {
  using J1 = ceres::Jet<double, 1>;
  const Parameters<double> par_value = cast_parameters<double>(par);
  const Parameters<J1> par_j1 = cast_parameters<J1>(par_value);
  PathResult<T> result;
  result.state = initial;
  result.strain.setZero();
  result.rows.push_back(make_record(par, initial, result.strain, UpdateStatus::kOk));
  double guess = 0.0;  // lateral strain per unit axial strain of the last increment
  // One increment d_axial from (state, strain); false where it cannot be integrated.
  auto advance = [&](State<T>& state, Tensor<T>& strain, double d_axial, double target,
                     UpdateStatus& worst) {
    double slope = 0.0;  // d ((sxx + syy)/2) / d eps_r
    const State<double> start = cast_state<double>(state);
    const State<J1> start_j1 = cast_state<J1>(start);
    auto evaluate = [&](double eps_r, State<J1>& end) {
      Tensor<J1> deps = Tensor<J1>::Zero();
      deps(0, 0) = J1(eps_r, 0);
      deps(1, 1) = J1(eps_r, 0);
      deps(2, 2) = J1(d_axial);
      return update_state(par_j1, start_j1, deps, end, options.integration);
    };
    const double p_scale = std::max(start.stress.trace() / 3.0, options.integration.min_pressure);
    double eps_r = guess * d_axial;
    State<J1> end;
    UpdateStatus status = UpdateStatus::kFailed;
    bool converged = false;
    for (int iteration = 0; iteration < options.max_newton_iterations; ++iteration) {
      status = evaluate(eps_r, end);
      if (status == UpdateStatus::kFailed) break;
      const J1 r = 0.5 * (end.stress(0, 0) + end.stress(1, 1)) - target;
      slope = r.v[0];
      if (std::abs(r.a) <= options.stress_tolerance * p_scale) {
        converged = true;
        break;
      }
      if (!(slope > 0.0)) break;
      eps_r -= r.a / slope;
    }
    if (!converged || !(slope > 0.0)) return false;
    const State<double> end_value = cast_state<double>(end);
    Tensor<T> deps = Tensor<T>::Zero();
    deps(0, 0) = T(eps_r);
    deps(1, 1) = T(eps_r);
    deps(2, 2) = T(d_axial);
    State<T> next;
    if constexpr (std::is_same_v<T, double>) {
      next = end_value;
    } else {
      const UpdateStatus jet_status = update_state(par, state, deps, next, options.integration);
      if (jet_status == UpdateStatus::kFailed) return false;
      if (jet_status == UpdateStatus::kUnreliable) status = jet_status;
      const auto r_v = (0.5 * (next.stress(0, 0).v + next.stress(1, 1).v)).eval();
      const Eigen::Matrix<double, Eigen::Dynamic, 1> delta = -r_v / slope;  // d eps_r / d par
      chain(next.stress, end.stress, delta);
      chain(next.void_ratio, end.void_ratio, delta);
      chain(next.alpha, end.alpha, delta);
      chain(next.alpha_in, end.alpha_in, delta);
      chain(next.fabric, end.fabric, delta);
      deps(0, 0).v = delta;
      deps(1, 1).v = delta;
      set_values(next.stress, end_value.stress);
      set_value(next.void_ratio, end_value.void_ratio);
      set_values(next.alpha, end_value.alpha);
      set_values(next.alpha_in, end_value.alpha_in);
      set_values(next.fabric, end_value.fabric);
    }
    if (status == UpdateStatus::kUnreliable) worst = UpdateStatus::kUnreliable;
    state = next;
    strain += deps;
    guess = eps_r / d_axial;
    return true;
  };
  // An increment that cannot be integrated is cut in halves, up to 2^kMaxCuts = 8 pieces (a row is
  // recorded only at its end).
  constexpr int kMaxCuts = 3;
  std::function<bool(State<T>&, Tensor<T>&, double, double, UpdateStatus&, int)> apply =
      [&](State<T>& state, Tensor<T>& strain, double d_axial, double target, UpdateStatus& worst,
          int cuts) {
        State<T> s_try = state;
        Tensor<T> e_try = strain;
        if (advance(s_try, e_try, d_axial, target, worst)) {
          state = s_try;
          strain = e_try;
          return true;
        }
        if (cuts >= kMaxCuts) return false;
        return apply(state, strain, 0.5 * d_axial, target, worst, cuts + 1) &&
               apply(state, strain, 0.5 * d_axial, target, worst, cuts + 1);
      };
  for (const PathStep& step : steps) {
    UpdateStatus worst = UpdateStatus::kOk;
    State<T> state = result.state;
    Tensor<T> strain = result.strain;
    if (!apply(state, strain, step.value[2], step.value[0], worst, 0)) {
      result.status = UpdateStatus::kFailed;
      result.rows.push_back(make_record(par, result.state, result.strain, UpdateStatus::kFailed));
      break;
    }
    if (worst == UpdateStatus::kUnreliable) result.status = UpdateStatus::kUnreliable;
    result.state = state;
    result.strain = strain;
    result.rows.push_back(make_record(par, result.state, result.strain, worst));
  }
  return result;
}

template <typename T>
PathResult<T> run_test(const TestData& t, const Grid& g, const std::array<T, kNumFitParameters>& v,
                       const DriverOptions& driver) {
  // F0 = A0 / a_cs with an axisymmetric A0 of triaxial value a_c0 (||A0|| = sqrt(2/3) a_c0).
  const T fabric_norm = T(kSqrtTwoThirds * t.a_c0) / v[kAcsIndex];
  const State<T> s0 = isotropic_state(T(t.p0), T(t.e0), triaxial_deviator(fabric_norm));
  return axisymmetric_path(parameters_of(v), s0, g.steps, driver);
}

struct ResidualSpec {
  bool eta = true, volumetric = true, fabric = true;
  double eta_scale = 0.05, volumetric_scale = 0.005, fabric_scale = 0.05;
};

int count_residuals(const TestData& t, const Grid& g, const ResidualSpec& spec) {
  int n = 0;
  const int rows = static_cast<int>(g.rows.size()) - 1;  // the first row is the initial state
  if (spec.eta) n += rows;
  if (spec.volumetric) n += rows;
  if (spec.fabric)
    for (std::size_t k = 1; k < t.a_c.size(); ++k) n += g.snapshot_at[k] >= 0 ? 1 : 0;
  return n;
}

/// Normalised residuals of one test; the free parameters are the first entries of x.
template <int S>
class TestCost {
 public:
  TestCost(const TestData* t, const Grid* g, ResidualSpec spec, FitVector base,
           std::vector<int> free, DriverOptions driver)
      : t_(t), g_(g), spec_(spec), base_(base), free_(std::move(free)), driver_(driver) {}

  template <typename T>
  bool operator()(const T* x, T* r) const {
    std::array<T, kNumFitParameters> v;
    for (int i = 0; i < kNumFitParameters; ++i) v[i] = T(base_[i]);
    for (std::size_t j = 0; j < free_.size(); ++j) v[free_[j]] = x[j];
    const PathResult<T> path = run_test(*t_, *g_, v, driver_);
    if (path.status == UpdateStatus::kFailed) return false;
    int k = 0;
    const std::size_t rows = g_->rows.size();
    if (spec_.eta)
      for (std::size_t i = 1; i < rows; ++i)
        r[k++] = (path.rows[g_->row_at[i]].eta - t_->eta[g_->rows[i]]) / spec_.eta_scale;
    if (spec_.volumetric)
      for (std::size_t i = 1; i < rows; ++i)
        r[k++] = (path.rows[g_->row_at[i]].volumetric_strain -
                  t_->volumetric_strain[g_->rows[i]]) / spec_.volumetric_scale;
    if (spec_.fabric)
      for (std::size_t i = 1; i < t_->a_c.size(); ++i)
        if (g_->snapshot_at[i] >= 0)
          r[k++] = (v[kAcsIndex] * path.rows[g_->snapshot_at[i]].fabric_triaxial - t_->a_c[i]) /
                   spec_.fabric_scale;
    return true;
  }

 private:
  const TestData* t_;
  const Grid* g_;
  ResidualSpec spec_;
  FitVector base_;
  std::vector<int> free_;
  DriverOptions driver_;
};

struct StageResult {
  FitVector x;
  double initial_cost = 0.0, final_cost = std::numeric_limits<double>::infinity();
  int residuals = 0, starts_run = 0;
  std::vector<double> errors;  // standard errors of the free parameters (empty: none)
  double scale = 0.0;
  std::string message;
};

std::unique_ptr<ceres::LossFunction> make_loss(Loss loss, double scale) {
  switch (loss) {
    case Loss::kHuber:
      return std::make_unique<ceres::HuberLoss>(scale);
    case Loss::kCauchy:
      return std::make_unique<ceres::CauchyLoss>(scale);
    case Loss::kNone:
      break;
  }
  return nullptr;
}

template <int S>
StageResult solve_stage(const std::vector<TestData>& tests, const std::vector<Grid>& grids,
                        const ResidualSpec& spec, const FitVector& x0,
                        const std::vector<int>& free, const FitOptions& options,
                        const FitVector& lower, const FitVector& upper, int starts,
                        std::uint64_t seed) {
  StageResult best;
  best.x = x0;
  const int k = static_cast<int>(free.size());
  std::mt19937_64 random(seed);
  for (int start = 0; start < starts; ++start) {
    std::array<double, S> block{};
    for (int j = 0; j < k; ++j) {
      const int i = free[j];
      double v = x0[i];
      if (start > 0) {  // seeded start: log-uniform within a factor 3, inside the bounds
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        const double draw = u(random);
        if (v > 0.0) {
          v *= std::exp(draw * std::log(3.0));
        } else {
          v = lower[i] + 0.25 * (0.5 * (draw + 1.0)) * (upper[i] - lower[i]);
        }
      }
      block[j] = std::clamp(v, lower[i], upper[i]);
    }
    ceres::Problem problem;
    int residuals = 0;
    for (std::size_t t = 0; t < tests.size(); ++t) {
      const int n = count_residuals(tests[t], grids[t], spec);
      if (n == 0) continue;
      residuals += n;
      auto* cost = new ceres::AutoDiffCostFunction<TestCost<S>, ceres::DYNAMIC, S>(
          new TestCost<S>(&tests[t], &grids[t], spec, x0, free, options.driver), n);
      problem.AddResidualBlock(cost, make_loss(options.loss, options.loss_scale).release(),
                               block.data());
    }
    if (residuals == 0) {
      best.message = "no residuals";
      return best;
    }
    for (int j = 0; j < k; ++j) {
      problem.SetParameterLowerBound(block.data(), j, lower[free[j]]);
      problem.SetParameterUpperBound(block.data(), j, upper[free[j]]);
    }
    if (k < S) {
      std::vector<int> constant;
      for (int j = k; j < S; ++j) constant.push_back(j);
      problem.SetManifold(block.data(), new ceres::SubsetManifold(S, constant));
    }
    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::DENSE_QR;
    solver.max_num_iterations = options.max_iterations;
    solver.function_tolerance = 1e-7;
    solver.parameter_tolerance = 1e-8;
    solver.num_threads = 1;
    solver.minimizer_progress_to_stdout = options.verbose;
    solver.logging_type = options.verbose ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
    ++best.starts_run;
    const bool usable = summary.IsSolutionUsable() && std::isfinite(summary.final_cost) &&
                        summary.initial_cost > 0.0;
    if (start == 0) best.initial_cost = summary.initial_cost;
    if (!usable || !(summary.final_cost < best.final_cost)) {
      if (best.message.empty() && !usable) best.message = "start " + std::to_string(start) + ": " + summary.message;
      continue;
    }
    best.final_cost = summary.final_cost;
    best.residuals = residuals;
    for (int j = 0; j < k; ++j) best.x[free[j]] = block[j];
    best.message = summary.BriefReport();
    std::vector<double> errors;
    double scale = 0.0;
    if (scaled_standard_errors(problem, block.data(), S, summary.final_cost, residuals, k, errors,
                               &scale)) {
      best.errors.assign(errors.begin(), errors.begin() + k);
      best.scale = scale;
    } else {
      best.errors.clear();
    }
  }
  return best;
}

StageResult solve_stage_any(const std::vector<TestData>& tests, const std::vector<Grid>& grids,
                            const ResidualSpec& spec, const FitVector& x0,
                            const std::vector<int>& free, const FitOptions& options,
                            const FitVector& lower, const FitVector& upper, int starts,
                            std::uint64_t seed) {
  // One Jet size per block size: the free parameters fill the block, the rest is held constant.
  if (free.size() <= 4)
    return solve_stage<4>(tests, grids, spec, x0, free, options, lower, upper, starts, seed);
  if (free.size() <= 8)
    return solve_stage<8>(tests, grids, spec, x0, free, options, lower, upper, starts, seed);
  return solve_stage<16>(tests, grids, spec, x0, free, options, lower, upper, starts, seed);
}

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

FitVector to_fit_vector(const Parameters<double>& p, double a_cs) {
  return {p.G0, p.nu, p.M_c, p.c, p.e_gamma, p.lambda_c, p.xi, p.m,
          p.h0, p.c_h, p.n_b, p.A0, p.n_d, p.e_A, p.k_F, a_cs};
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
  // 1e-7 (at 1e-6 the first large increment's parameter derivatives were 0.8 % off). The
  // derivative guard would make the post-peak Jacobian accurate too, but with 8-16 parameter
  // directions it drives the substeps to its floor and a Jacobian costs minutes: off
  // (docs/calibration.md, "Open problems").
  d.integration.tolerance = 1e-7;
  d.integration.guard_derivatives = false;
  d.stress_tolerance = 1e-6;  // above the integration noise (~tolerance |sigma|)
  // Fail fast: a parameter set the model cannot integrate is rejected by Ceres anyway, and the
  // driver then cuts the increment; 100000 attempted substeps per update made such sets cost
  // minutes.
  d.integration.max_substeps = 4000;
  d.max_newton_iterations = 15;
  return d;
}

FitVector FitOptions::default_initial() {
  // Toyoura-like values of docs/model.md (DM04 Table 1), a_cs = 1.
  return {125.0, 0.05, 1.25, 0.712, 0.934, 0.019, 0.7, 0.01,
          7.05,  0.968, 1.1, 0.704, 3.5, 0.1, 5.0, 1.0};
}

FitVector FitOptions::default_lower() {
  return {5.0, 0.0, 0.3, 0.5, 0.2, 0.0, 0.1, 0.001, 0.05, 0.0, 0.0, 0.01, 0.0, 0.0, 0.0, 0.05};
}

FitVector FitOptions::default_upper() {
  return {3000.0, 0.45, 2.5, 1.0, 2.0, 0.5, 1.5, 0.1, 200.0, 0.99, 10.0, 10.0, 20.0, 3.0, 200.0,
          3.0};
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

ModelCurves simulate_test(const TestData& t, const FitVector& x, const DriverOptions& driver) {
  const Grid g = make_grid(t, std::numeric_limits<int>::max());
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
    if (ok) ++c.rows_reached;
  }
  for (int at : g.snapshot_at)
    c.a_c.push_back(at >= 0 && at < reached ? x[kAcsIndex] * path.rows[at].fabric_triaxial : nan);
  return c;
}

TestErrors test_errors(const TestData& t, const FitVector& x, const FitOptions& options) {
  const ModelCurves c = simulate_test(t, x, options.driver);
  TestErrors e;
  e.name = t.name;
  e.status = to_string(c.status);
  double se = 0, sv = 0, sr = 0, sa = 0, sn = 0;
  int nn = 0;
  for (std::size_t i = 1; i < c.eta.size(); ++i) {
    if (!std::isfinite(c.eta[i])) continue;
    const double de = c.eta[i] - t.eta[i], dv = c.volumetric_strain[i] - t.volumetric_strain[i];
    const double dr = c.void_ratio[i] - t.void_ratio[i];
    se += de * de;
    sv += dv * dv;
    sr += dr * dr;
    e.max_abs_eta = std::max(e.max_abs_eta, std::abs(de));
    sn += std::pow(de / options.eta_scale, 2) + std::pow(dv / options.volumetric_scale, 2);
    nn += 2;
    ++e.rows;
  }
  for (std::size_t i = 1; i < c.a_c.size(); ++i) {
    if (!std::isfinite(c.a_c[i])) continue;
    const double da = c.a_c[i] - t.a_c[i];
    sa += da * da;
    sn += std::pow(da / options.fabric_scale, 2);
    ++nn;
    ++e.snapshots;
  }
  if (e.rows > 0) {
    e.rms_eta = std::sqrt(se / e.rows);
    e.rms_volumetric = std::sqrt(sv / e.rows);
    e.rms_void_ratio = std::sqrt(sr / e.rows);
  }
  if (e.snapshots > 0) e.rms_a_c = std::sqrt(sa / e.snapshots);
  if (nn > 0) e.rms_normalised = std::sqrt(sn / nn);
  if (e.rows + 1 < static_cast<int>(c.eta.size()))
    e.status += " (model failed after " + std::to_string(e.rows) + " rows)";
  return e;
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

CalibrationResult calibrate(const std::vector<TestData>& tests, const FitOptions& options) {
  if (tests.empty()) throw std::runtime_error("calibrate: no tests");
  for (const TestData& t : tests) validate_test_data(t);
  if (options.starts < 1) throw std::runtime_error("calibrate: starts must be >= 1");
  if (!(options.eta_scale > 0.0 && options.volumetric_scale > 0.0 && options.fabric_scale > 0.0))
    throw std::runtime_error("calibrate: residual scales must be > 0");
  CalibrationResult result;
  FitVector x = options.initial;
  FitVector lower = options.lower, upper = options.upper;
  for (int i = 0; i < kNumFitParameters; ++i)
    if (!(lower[i] <= x[i] && x[i] <= upper[i]))
      throw std::runtime_error(std::string("calibrate: initial value of '") + kNames[i] +
                               "' = " + std::to_string(x[i]) + " is outside its bounds [" +
                               std::to_string(lower[i]) + ", " + std::to_string(upper[i]) + "]");
  std::array<bool, kNumFitParameters> user_fixed{};
  for (const std::string& name : options.fixed) user_fixed[fit_parameter_index(name)] = true;
  for (int i = 0; i < kNumFitParameters; ++i) {
    result.estimates[i].lower = lower[i];
    result.estimates[i].upper = upper[i];
  }
  auto has = [&](Stage s) {
    return std::find(options.stages.begin(), options.stages.end(), s) != options.stages.end();
  };
  auto set = [&](int i, double value, double error, const char* stage) {
    x[i] = std::clamp(value, lower[i], upper[i]);
    result.estimates[i].standard_error = error;
    result.estimates[i].fixed = false;
    result.estimates[i].stage = stage;
  };

  // Critical states: means over the last critical_window of axial strain.
  for (const TestData& t : tests) {
    CriticalStatePoint c;
    c.test = t.name;
    const double from = t.axial_strain.back() - options.critical_window;
    std::vector<double> p, e, eta, a;
    for (std::size_t k = 0; k < t.axial_strain.size(); ++k)
      if (t.axial_strain[k] >= from) {
        p.push_back(t.p[k]);
        e.push_back(t.void_ratio[k]);
        eta.push_back(t.eta[k]);
      }
    for (std::size_t k = 0; k < t.a_c.size(); ++k)
      if (t.snapshot_axial_strain[k] >= from) a.push_back(t.a_c[k]);
    if (a.empty()) a.push_back(t.a_c.back());
    c.p = mean(p);
    c.void_ratio = mean(e);
    c.eta = mean(eta);
    c.a_c = mean(a);
    result.critical_states.push_back(c);
  }

  // Stage csl: M_c and the critical state line.
  if (has(Stage::kCsl)) {
    std::vector<double> eta_cs;
    for (const auto& c : result.critical_states) eta_cs.push_back(c.eta);
    if (!user_fixed[2]) set(2, mean(eta_cs), standard_error_of_mean(eta_cs), "csl");
    // Distinct pressures (more than 10 % apart).
    std::vector<double> pressures;
    for (const auto& c : result.critical_states) {
      bool distinct = true;
      for (double q : pressures) distinct = distinct && std::abs(c.p - q) > 0.1 * q;
      if (distinct) pressures.push_back(c.p);
    }
    const int n = static_cast<int>(result.critical_states.size());
    const int distinct = static_cast<int>(pressures.size());
    auto line_fit = [&](double xi, double& e_gamma, double& lambda, double& rss,
                        double* se_e, double* se_l) {
      Eigen::MatrixXd X(n, 2);
      Eigen::VectorXd y(n);
      for (int k = 0; k < n; ++k) {
        X(k, 0) = 1.0;
        X(k, 1) = -std::pow(result.critical_states[k].p / kAtmosphericPressure, xi);
        y(k) = result.critical_states[k].void_ratio;
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
    const int ig = 4, il = 5, ix = 6;
    if (distinct == 1 || user_fixed[il]) {
      // One pressure: only e_Gamma is identifiable; lambda_c and xi keep their values.
      std::vector<double> eg;
      for (const auto& c : result.critical_states)
        eg.push_back(c.void_ratio + x[il] * std::pow(c.p / kAtmosphericPressure, x[ix]));
      if (!user_fixed[ig]) set(ig, mean(eg), standard_error_of_mean(eg), "csl");
      result.notes.push_back(
          "critical state line: " + std::to_string(distinct) +
          " distinct pressure(s): only e_gamma fitted; lambda_c = " + std::to_string(x[il]) +
          " and xi = " + std::to_string(x[ix]) + " held at their initial values");
    } else {
      double best_xi = x[ix], best_rss = std::numeric_limits<double>::infinity();
      if (distinct >= 3 && !user_fixed[ix]) {
        for (double xi = lower[ix]; xi <= upper[ix] + 1e-12; xi += 0.005) {
          double eg, l, rss;
          line_fit(xi, eg, l, rss, nullptr, nullptr);
          if (rss < best_rss && l >= 0.0) {
            best_rss = rss;
            best_xi = xi;
          }
        }
      } else {
        result.notes.push_back("critical state line: " + std::to_string(distinct) +
                               " distinct pressures: xi = " + std::to_string(x[ix]) +
                               " held at its initial value");
      }
      double eg, l, rss, se_e = -1.0, se_l = -1.0;
      line_fit(best_xi, eg, l, rss, &se_e, &se_l);
      if (!user_fixed[ig]) set(ig, eg, se_e, "csl");
      set(il, l, se_l, "csl");
      if (distinct >= 3 && !user_fixed[ix]) set(ix, best_xi, -1.0, "csl");
    }
  }
  // c_h e_gamma < 1 (b0 > 0 over the void ratios the model can reach).
  upper[9] = std::min(upper[9], 0.99 / x[4]);
  x[9] = std::min(x[9], upper[9]);
  result.estimates[9].upper = upper[9];

  // Stage elastic: secant over the first output interval of each test.
  if (has(Stage::kElastic)) {
    std::vector<double> g0, nu;
    for (const TestData& t : tests) {
      const std::size_t k = 1;
      const double dea = t.axial_strain[k] - t.axial_strain[0];
      const double dev = t.volumetric_strain[k] - t.volumetric_strain[0];
      const double deq = dea - dev / 3.0;
      const double dq = t.eta[k] * t.p[k] - t.eta[0] * t.p[0];
      if (!(dea > 0.0 && deq > 0.0 && dq > 0.0)) continue;
      const double G = dq / (3.0 * deq);
      const double f = kAtmosphericPressure * std::pow(2.97 - t.e0, 2) / (1.0 + t.e0) *
                       std::sqrt(t.p0 / kAtmosphericPressure);
      g0.push_back(G / f);
      nu.push_back(0.5 * (1.0 - dev / dea));  // drained elastic: de_v/de_a = 1 - 2 nu
    }
    if (!g0.empty()) {
      if (!user_fixed[0]) set(0, mean(g0), standard_error_of_mean(g0), "elastic");
      if (!user_fixed[1]) set(1, mean(nu), standard_error_of_mean(nu), "elastic");
      result.notes.push_back(
          "elasticity: secant over the first output interval (a lower bound of G0, the cone is "
          "crossed almost at once); refined by the joint stage");
    }
  }

  std::vector<Grid> grids;
  for (const TestData& t : tests) grids.push_back(make_grid(t, options.max_points));
  double e_min = 1e300, e_max = -1e300;
  for (const TestData& t : tests) {
    e_min = std::min(e_min, t.e0);
    e_max = std::max(e_max, t.e0);
  }
  const bool c_h_identifiable = e_max - e_min >= 0.05;
  if (!c_h_identifiable && !user_fixed[9])
    result.notes.push_back("c_h held (initial void ratios span less than 0.05: it trades off "
                           "with h0)");

  auto free_of = [&](std::initializer_list<int> wanted) {
    std::vector<int> free;
    for (int i : wanted)
      if (!user_fixed[i] && (i != 9 || c_h_identifiable)) free.push_back(i);
    return free;
  };
  std::uint64_t stage_seed = options.seed;
  auto run = [&](Stage stage, const ResidualSpec& spec, const std::vector<int>& free, int starts) {
    StageReport report;
    report.stage = to_string(stage);
    report.free_parameters = static_cast<int>(free.size());
    if (free.empty()) {
      report.message = "no free parameters";
      result.stages.push_back(report);
      return;
    }
    const StageResult r = solve_stage_any(tests, grids, spec, x, free, options, lower, upper,
                                          starts, stage_seed++ * 7919);
    report.residuals = r.residuals;
    report.starts = r.starts_run;
    report.initial_cost = r.initial_cost;
    report.final_cost = r.final_cost;
    report.message = r.message;
    result.stages.push_back(report);
    if (!std::isfinite(r.final_cost))
      throw std::runtime_error(std::string("calibrate: stage '") + to_string(stage) +
                               "' found no usable solution from any start: " + r.message);
    for (std::size_t j = 0; j < free.size(); ++j)
      set(free[j], r.x[free[j]], r.errors.empty() ? -1.0 : r.errors[j], to_string(stage));
    if (!r.errors.empty()) result.covariance_scale = r.scale;
    else
      result.notes.push_back(std::string("stage ") + to_string(stage) +
                             ": covariance not available (rank deficient or too few residuals)");
  };
  ResidualSpec base_spec;
  base_spec.eta_scale = options.eta_scale;
  base_spec.volumetric_scale = options.volumetric_scale;
  base_spec.fabric_scale = options.fabric_scale;

  // Stage fabric: a_cs measured at the critical state, then k_F from the a_c histories.
  if (has(Stage::kFabric)) {
    std::vector<double> a_cs;
    for (const auto& c : result.critical_states) a_cs.push_back(kSqrtTwoThirds * c.a_c);
    if (!user_fixed[kAcsIndex] && mean(a_cs) > lower[kAcsIndex]) {
      const double se = standard_error_of_mean(a_cs);
      set(kAcsIndex, mean(a_cs), se, "fabric");
    }
    ResidualSpec spec = base_spec;
    spec.eta = spec.volumetric = false;
    run(Stage::kFabric, spec, free_of({14}), 1);
  }
  if (has(Stage::kPlastic)) {
    ResidualSpec spec = base_spec;
    spec.fabric = false;
    run(Stage::kPlastic, spec, free_of({8, 9, 10, 11, 12, 13}), options.starts);
  }
  if (has(Stage::kJoint))
    run(Stage::kJoint, base_spec, free_of({0, 1, 2, 8, 9, 10, 11, 12, 13, 14}), options.starts);

  result.values = x;
  for (int i = 0; i < kNumFitParameters; ++i) {
    ParameterEstimate& e = result.estimates[i];
    e.value = x[i];
    e.lower = lower[i];
    e.upper = upper[i];
    const double tol = 1e-4 * (upper[i] - lower[i]);
    e.at_bound = !e.fixed && (x[i] - lower[i] <= tol || upper[i] - x[i] <= tol);
  }
  for (const TestData& t : tests) result.errors.push_back(test_errors(t, x, options));
  result.sff = fit_sff_relation(tests);
  return result;
}

}  // namespace calibration
