// One Ceres stage over all tests (fit_solve.h). Every test is integrated once per evaluation
// point, all tests in parallel (OpenMP over tests, options.threads); each residual is its own
// Ceres block of size 1 (so the robust loss acts on every residual), reading a cache that holds
// the residuals, and with Jacobians their derivatives, of all tests at the last point asked for.
// Ceres itself runs single-threaded, so the results do not depend on the thread count.
#include "fit_solve.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <cstring>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace calibration {
namespace fit_detail {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The residuals of all tests at one point, with or without their Jacobian (S columns: the
/// free parameters, then unused columns held at zero).
template <int S>
class TestsEvaluator {
 public:
  TestsEvaluator(const std::vector<TestData>& tests, const std::vector<Grid>& grids,
                 const ResidualSpec& spec, const FitVector& base, const std::vector<int>& free,
                 const FitOptions& options)
      : tests_(tests), grids_(grids), spec_(spec), base_(base), free_(free), options_(options) {
    for (std::size_t t = 0; t < tests.size(); ++t) {
      offsets_.push_back(total_);
      total_ += count_residuals(tests[t], grids[t], spec);
    }
    residuals_.assign(static_cast<std::size_t>(total_), 0.0);
    jacobian_.assign(static_cast<std::size_t>(total_) * S, 0.0);
  }

  int num_residuals() const { return total_; }
  int residuals_of(std::size_t t) const {
    return (t + 1 < offsets_.size() ? offsets_[t + 1] : total_) - offsets_[t];
  }
  int offset_of(std::size_t t) const { return offsets_[t]; }

  /// Brings the cache to x (S values); false if the model fails on some test there.
  bool ensure(const double* x, bool jacobian) {
    if (valid_ && std::memcmp(x, point_.data(), sizeof(double) * S) == 0 &&
        (has_jacobian_ || !jacobian))
      return ok_;
    std::copy(x, x + S, point_.begin());
    const auto start = Clock::now();
    const int n = static_cast<int>(tests_.size());
    std::vector<char> ok(static_cast<std::size_t>(n), 1);
    std::vector<long> substeps(static_cast<std::size_t>(n), 0);
    // Each test is independent and written to its own slots: the same result for any number of
    // threads and any schedule.
#pragma omp parallel for schedule(dynamic, 1) num_threads(std::max(1, options_.threads))
    for (int t = 0; t < n; ++t) {
      const std::size_t u = static_cast<std::size_t>(t);
      ok[u] = jacobian ? evaluate_with_jacobian(u, &substeps[u]) : evaluate_values(u, &substeps[u]);
    }
    ok_ = std::all_of(ok.begin(), ok.end(), [](char c) { return c != 0; });
    valid_ = true;
    has_jacobian_ = jacobian;
    long steps = 0, sub = 0;
    for (int t = 0; t < n; ++t) {
      steps += static_cast<long>(grids_[static_cast<std::size_t>(t)].steps.size());
      sub += substeps[static_cast<std::size_t>(t)];
    }
    const double per_step = static_cast<double>(sub) / static_cast<double>(std::max(1L, steps));
    timing_.substeps_per_step += per_step;
    timing_.max_substeps_per_step = std::max(timing_.max_substeps_per_step, per_step);
    (jacobian ? timing_.jacobian_evaluations : timing_.cost_evaluations) += 1;
    (jacobian ? timing_.jacobian_seconds : timing_.cost_seconds) += seconds_since(start);
    return ok_;
  }

  double residual(int i) const { return residuals_[static_cast<std::size_t>(i)]; }
  const double* residuals() const { return residuals_.data(); }
  /// num_residuals() rows of S values (valid after ensure(x, true)).
  const double* jacobian() const { return jacobian_.data(); }
  const double* jacobian_row(int i) const { return &jacobian_[static_cast<std::size_t>(i) * S]; }
  const StageTiming& timing() const { return timing_; }

 private:
  bool evaluate_values(std::size_t t, long* substeps) {
    std::array<double, kNumFitParameters> v = base_;
    for (std::size_t j = 0; j < free_.size(); ++j) v[free_[j]] = point_[j];
    const PathResult<double> path = run_test(tests_[t], grids_[t], v, options_.driver, substeps);
    if (path.status == UpdateStatus::kFailed) return false;
    path_residuals(tests_[t], grids_[t], spec_, v[kAcsIndex], path, &residuals_[offsets_[t]]);
    return true;
  }

  bool evaluate_with_jacobian(std::size_t t, long* substeps) {
    using Jet = ceres::Jet<double, S>;
    std::array<Jet, kNumFitParameters> v;
    for (int i = 0; i < kNumFitParameters; ++i) v[i] = Jet(base_[i]);
    for (std::size_t j = 0; j < free_.size(); ++j)
      v[free_[j]] = Jet(point_[j], static_cast<int>(j));
    const PathResult<Jet> path = run_test(tests_[t], grids_[t], v, options_.driver, substeps);
    if (path.status == UpdateStatus::kFailed) return false;
    std::vector<Jet> r(static_cast<std::size_t>(residuals_of(t)));
    path_residuals(tests_[t], grids_[t], spec_, v[kAcsIndex], path, r.data());
    for (std::size_t k = 0; k < r.size(); ++k) {
      const std::size_t row = static_cast<std::size_t>(offsets_[t]) + k;
      residuals_[row] = r[k].a;
      for (int j = 0; j < S; ++j) jacobian_[row * S + static_cast<std::size_t>(j)] = r[k].v[j];
    }
    return true;
  }

  const std::vector<TestData>& tests_;
  const std::vector<Grid>& grids_;
  ResidualSpec spec_;
  FitVector base_;
  std::vector<int> free_;
  const FitOptions& options_;
  std::vector<int> offsets_;
  int total_ = 0;
  std::array<double, S> point_{};
  bool valid_ = false, has_jacobian_ = false, ok_ = false;
  std::vector<double> residuals_, jacobian_;
  StageTiming timing_;
};

/// One residual of the cache as a Ceres cost (block of size 1).
template <int S>
class CachedResidual final : public ceres::SizedCostFunction<1, S> {
 public:
  CachedResidual(TestsEvaluator<S>* evaluator, int index) : evaluator_(evaluator), index_(index) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const bool jacobian = jacobians != nullptr && jacobians[0] != nullptr;
    if (!evaluator_->ensure(parameters[0], jacobian)) return false;
    residuals[0] = evaluator_->residual(index_);
    if (jacobian) std::copy_n(evaluator_->jacobian_row(index_), S, jacobians[0]);
    return true;
  }

 private:
  TestsEvaluator<S>* evaluator_;
  int index_;
};

/// Prints one line per Levenberg-Marquardt iteration to options.progress.
class ProgressCallback final : public ceres::IterationCallback {
 public:
  ProgressCallback(const FitOptions& options, std::string prefix, Clock::time_point stage_start)
      : options_(options), prefix_(std::move(prefix)), stage_start_(stage_start) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (options_.progress) {
      char line[256];
      std::snprintf(line, sizeof line, "%s iteration %d: cost %.6e%s, %.1f s in stage",
                    prefix_.c_str(), s.iteration, s.cost,
                    s.iteration == 0 ? "" : (s.step_is_successful ? "" : " (step rejected)"),
                    seconds_since(stage_start_));
      options_.progress(line);
    }
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const FitOptions& options_;
  std::string prefix_;
  Clock::time_point stage_start_;
};

/// Keeps the parameter block at the start and after every accepted step, with its cost (needs
/// Solver::Options::update_state_every_iteration, so that the block holds the iterate).
template <int S>
class IterateRecorder final : public ceres::IterationCallback {
 public:
  struct Iterate {
    std::array<double, S> x;
    double cost;
    int iteration;
  };
  explicit IterateRecorder(const std::array<double, S>& block) : block_(block) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
    if (s.iteration == 0 || s.step_is_successful) iterates.push_back({block_, s.cost, s.iteration});
    return ceres::SOLVER_CONTINUE;
  }
  std::vector<Iterate> iterates;

 private:
  const std::array<double, S>& block_;
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

/// The full fit vector of x0 with the free parameters set from a block.
template <int S>
FitVector with_block(const FitVector& x0, const std::vector<int>& free,
                     const std::array<double, S>& block) {
  FitVector x = x0;
  for (std::size_t j = 0; j < free.size(); ++j) x[free[j]] = block[j];
  return x;
}

/// solve_stage's check of a start's end point: where the check refuses it, the newest recorded
/// iterate it accepts (going back 1, 2, 4, ... accepted steps, then the start) replaces block and
/// cost. False where neither the end point nor any of those is accepted.
template <int S>
bool check_end_point(const SetCheck& check, const FitVector& x0, const std::vector<int>& free,
                     const std::vector<typename IterateRecorder<S>::Iterate>& iterates,
                     std::array<double, S>& block, double& cost, const std::string& where,
                     std::string& note) {
  const std::string refused = check(with_block<S>(x0, free, block));
  if (refused.empty()) return true;
  std::ostringstream text;
  text << where << ": its end point (cost " << cost << ") was refused (" << refused << "); ";
  const int last = static_cast<int>(iterates.size()) - 1;
  for (int back = 1; last - back >= 0; back = last - 2 * back > 0 ? 2 * back : last) {
    const auto& earlier = iterates[static_cast<std::size_t>(last - back)];
    if (check(with_block<S>(x0, free, earlier.x)).empty()) {
      text << "kept iteration " << earlier.iteration << " instead (cost " << earlier.cost << ")";
      block = earlier.x;
      cost = earlier.cost;
      note = text.str();
      return true;
    }
    if (back == last) break;  // the start point was the last candidate
  }
  text << "no earlier iterate was accepted either";
  note = text.str();
  return false;
}

template <int S>
StageResult solve_stage_sized(const std::vector<TestData>& tests, const std::vector<Grid>& grids,
                              const ResidualSpec& spec, const FitVector& x0,
                              const std::vector<int>& free, const FitOptions& options,
                              const FitVector& lower, const FitVector& upper, int starts,
                              std::uint64_t seed, const std::string& stage_name,
                              const SetCheck& check) {
  const auto stage_start = Clock::now();
  const std::clock_t cpu_start = std::clock();
  StageResult best;
  best.x = x0;
  const int k = static_cast<int>(free.size());
  std::mt19937_64 random(seed);
  bool best_accepted = false;  // by check; no best yet counts as refused
  double substep_sum = 0.0;
  int evaluations = 0;
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
    TestsEvaluator<S> evaluator(tests, grids, spec, x0, free, options);
    const int residuals = evaluator.num_residuals();
    if (residuals == 0) {
      best.message = "no residuals";
      return best;
    }
    ceres::Problem problem;
    for (int i = 0; i < residuals; ++i)
      problem.AddResidualBlock(new CachedResidual<S>(&evaluator, i),
                               make_loss(options.loss, options.loss_scale).release(),
                               block.data());
    for (int j = 0; j < k; ++j) {
      problem.SetParameterLowerBound(block.data(), j, lower[free[j]]);
      problem.SetParameterUpperBound(block.data(), j, upper[free[j]]);
    }
    if (k < S) {
      std::vector<int> constant;
      for (int j = k; j < S; ++j) constant.push_back(j);
      problem.SetManifold(block.data(), new ceres::SubsetManifold(S, constant));
    }
    ProgressCallback progress(options,
                              stage_name + " start " + std::to_string(start + 1) + "/" +
                                  std::to_string(starts),
                              stage_start);
    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::DENSE_QR;
    solver.max_num_iterations = options.max_iterations;
    solver.function_tolerance = options.function_tolerance;
    solver.parameter_tolerance = 1e-8;
    solver.num_threads = 1;  // the tests are threaded inside the evaluator
    // With bounds, Ceres runs a projected Armijo line search along every trust-region step; its
    // default cubic interpolation asks for the gradient (a Jacobian evaluation of all tests) at
    // every trial point, and on a rejected step it contracted up to 20 times (~10 s per step on
    // the 9-test matrix). One trial at the full (projected) step, values only: that point is the
    // candidate the trust region evaluates anyway (same bits, read from the cache), so the step
    // is plain projected Levenberg-Marquardt at no extra cost.
    solver.line_search_interpolation_type = ceres::BISECTION;
    solver.max_num_line_search_step_size_iterations = 1;
    solver.minimizer_progress_to_stdout = options.verbose;
    solver.logging_type = options.verbose ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
    solver.callbacks.push_back(&progress);
    IterateRecorder<S> recorder(block);
    if (check) {
      solver.update_state_every_iteration = true;  // copies only: the iterates are unchanged
      solver.callbacks.push_back(&recorder);
    }
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
    ++best.starts_run;
    best.timing.iterations += static_cast<int>(summary.iterations.size()) - 1;
    const bool usable = summary.IsSolutionUsable() && std::isfinite(summary.final_cost) &&
                        summary.initial_cost > 0.0;
    if (start == 0) best.initial_cost = summary.initial_cost;
    double final_cost = summary.final_cost;
    std::string start_note;
    // A start the check accepts beats one it refuses, whatever their costs.
    bool accepted = true;
    if (usable && check && (final_cost < best.final_cost || !best_accepted))
      accepted = check_end_point<S>(check, x0, free, recorder.iterates, block, final_cost,
                                    stage_name + " start " + std::to_string(start + 1), start_note);
    const bool better = accepted != best_accepted ? accepted : final_cost < best.final_cost;
    if (usable && better) {
      best_accepted = accepted;
      best.final_cost = final_cost;
      best.note = start_note;
      best.residuals = residuals;
      for (int j = 0; j < k; ++j) best.x[free[j]] = block[j];
      best.message = summary.BriefReport();
      // The covariance at the solution, with the parameters that sit at a bound held (the
      // active constraints: a parameter there has no symmetric uncertainty, and one at a bound
      // can make the rest rank deficient, e.g. e_A when n_d = 0).
      std::vector<int> interior, at_bound;
      for (int j = 0; j < k; ++j) {
        const double tol = 1e-4 * (upper[free[j]] - lower[free[j]]);
        const bool bound = block[j] - lower[free[j]] <= tol || upper[free[j]] - block[j] <= tol;
        (bound ? at_bound : interior).push_back(j);
      }
      best.errors.clear();
      best.errors_independent.clear();
      best.held_for_covariance.clear();
      for (int j : at_bound) best.held_for_covariance.push_back(free[j]);
      const int m = static_cast<int>(interior.size());
      if (m > 0 && !at_bound.empty()) {
        std::vector<int> constant;
        for (int j = 0; j < S; ++j)
          if (std::find(interior.begin(), interior.end(), j) == interior.end())
            constant.push_back(j);
        problem.SetManifold(block.data(), new ceres::SubsetManifold(S, constant));
      }
      std::vector<double> errors, robust;
      double scale = 0.0;
      if (m > 0 &&
          scaled_standard_errors(problem, block.data(), S, summary.final_cost, residuals, m,
                                 errors, &scale) &&
          evaluator.ensure(block.data(), true)) {
        std::vector<int> series;
        for (std::size_t t = 0; t < tests.size(); ++t)
          for (int length : residual_series(tests[t], grids[t], spec)) series.push_back(length);
        // The Jacobian's columns of the interior parameters.
        std::vector<double> jacobian(static_cast<std::size_t>(residuals) * m);
        for (int i = 0; i < residuals; ++i)
          for (int c = 0; c < m; ++c)
            jacobian[static_cast<std::size_t>(i) * m + c] =
                evaluator.jacobian()[static_cast<std::size_t>(i) * S + interior[c]];
        if (autocorrelation_robust_standard_errors(jacobian.data(), m, m, evaluator.residuals(),
                                                   series, robust, &best.mean_bandwidth)) {
          best.errors.assign(static_cast<std::size_t>(k), -1.0);
          best.errors_independent.assign(static_cast<std::size_t>(k), -1.0);
          for (int c = 0; c < m; ++c) {
            best.errors[interior[c]] = robust[c];
            best.errors_independent[interior[c]] = errors[interior[c]];
          }
          best.scale = scale;
        }
      }
    } else if (best.message.empty() && !usable) {
      best.message = "start " + std::to_string(start) + ": " + summary.message;
    }
    const StageTiming& t = evaluator.timing();
    best.timing.cost_evaluations += t.cost_evaluations;
    best.timing.jacobian_evaluations += t.jacobian_evaluations;
    best.timing.cost_seconds += t.cost_seconds;
    best.timing.jacobian_seconds += t.jacobian_seconds;
    substep_sum += t.substeps_per_step;
    best.timing.max_substeps_per_step =
        std::max(best.timing.max_substeps_per_step, t.max_substeps_per_step);
    evaluations += t.cost_evaluations + t.jacobian_evaluations;
  }
  best.timing.substeps_per_step = evaluations > 0 ? substep_sum / evaluations : 0.0;
  best.timing.seconds = seconds_since(stage_start);
  best.timing.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  return best;
}

}  // namespace

StageResult solve_stage(const std::vector<TestData>& tests, const std::vector<Grid>& grids,
                        const ResidualSpec& spec, const FitVector& x0, const std::vector<int>& free,
                        const FitOptions& options, const FitVector& lower, const FitVector& upper,
                        int starts, std::uint64_t seed, const std::string& stage_name,
                        const SetCheck& check) {
  // The Jet size is the number of free parameters (Jet arithmetic costs about its size, and a
  // Jacobian evaluation is mostly Jet arithmetic): 1 or 2 (fabric stage: k_F, n_F), 6 or 7
  // (plastic, 7 with n_b_loose), 10 to 14 (joint: with c, n_b_loose and n_G where each is
  // identifiable).
  // Larger stages are not built (each size compiles the whole path integration once more).
  auto sized = [&](auto size) {
    return solve_stage_sized<decltype(size)::value>(tests, grids, spec, x0, free, options, lower,
                                                    upper, starts, seed, stage_name, check);
  };
  switch (free.size()) {
    case 1: return sized(std::integral_constant<int, 1>());
    case 2: return sized(std::integral_constant<int, 2>());
    case 3: case 4: case 5:
    case 6: return sized(std::integral_constant<int, 6>());
    case 7: return sized(std::integral_constant<int, 7>());
    case 8: case 9:
    case 10: return sized(std::integral_constant<int, 10>());
    case 11: return sized(std::integral_constant<int, 11>());
    case 12: return sized(std::integral_constant<int, 12>());
    case 13: return sized(std::integral_constant<int, 13>());
    case 14: return sized(std::integral_constant<int, 14>());
    default:
      throw std::logic_error("solve_stage: " + std::to_string(free.size()) +
                             " free parameters in stage " + stage_name + " (1 to 14 are built)");
  }
}

}  // namespace fit_detail
}  // namespace calibration
