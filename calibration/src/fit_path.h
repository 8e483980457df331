// Internal to calibration_fit: the model strain grid of a DEM test and the fit's drained
// axisymmetric path (docs/calibration.md, "Objective"), templated on the scalar (double for
// costs, ceres::Jet seeded on the free parameters for Jacobians).
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <functional>
#include <type_traits>
#include <vector>

#include "calibration/fit.h"
#include "calibration/material_point.h"

namespace calibration {
namespace fit_detail {


/// Model strain grid of one test: 0, then the selected series rows and the snapshots, with
/// intermediate points where two are more than max_strain_step apart (0: no limit). The lateral
/// stress is held only at the grid's points, so the path's error falls with the square of its
/// step (docs/calibration.md, "Objective").
struct Grid {
  std::vector<PathStep> steps;
  std::vector<int> rows;           ///< selected series rows
  std::vector<int> row_at;         ///< grid index of each selected row
  std::vector<int> snapshot_at;    ///< grid index of each snapshot (-1: beyond the series)
};
Grid make_grid(const TestData& t, int max_points, double max_strain_step = 0.0);

struct ResidualSpec {
  bool eta = true, volumetric = true, fabric = true;
  double eta_scale = 0.05, volumetric_scale = 0.005, fabric_scale = 0.05;
};

/// Residuals of one test under spec (series rows, then snapshots).
int count_residuals(const TestData& t, const Grid& g, const ResidualSpec& spec);

template <typename T>
Parameters<T> parameters_of(const std::array<T, kNumFitParameters>& v) {
  Parameters<T> p;
  for (std::size_t k = 0; k < kParameterFields<T>.size(); ++k) p.*kParameterFields<T>[k].member = v[k];
  return p;
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
/// function theorem at the converged values, as in mixed_increment. Attempted substeps of all
/// updates are added to *substeps.
template <typename T>
PathResult<T> axisymmetric_path(const Parameters<T>& par, const State<T>& initial,
                                const std::vector<PathStep>& steps, const DriverOptions& options,
                                long* substeps = nullptr) {
  using J1 = ceres::Jet<double, 1>;
  const Parameters<double> par_value = cast_parameters<double>(par);
  const Parameters<J1> par_j1 = cast_parameters<J1>(par_value);
  PathResult<T> result;
  long used = 0;  // substeps attempted along the path
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
      return update_state(par_j1, start_j1, deps, end, options.integration, &used);
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
      const UpdateStatus jet_status = update_state(par, state, deps, next, options.integration, &used);
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
  if (substeps) *substeps += used;
  return result;
}

template <typename T>
PathResult<T> run_test(const TestData& t, const Grid& g, const std::array<T, kNumFitParameters>& v,
                       const DriverOptions& driver, long* substeps = nullptr) {
  // F0 = A0 / a_cs with an axisymmetric A0 of triaxial value a_c0 (||A0|| = sqrt(2/3) a_c0).
  const T fabric_norm = T(kSqrtTwoThirds * t.a_c0) / v[kAcsIndex];
  const State<T> s0 = isotropic_state(T(t.p0), T(t.e0), triaxial_deviator(fabric_norm));
  return axisymmetric_path(parameters_of(v), s0, g.steps, driver, substeps);
}

/// The normalised residuals (model - DEM)/scale of a path, in the order of count_residuals.
template <typename T>
void path_residuals(const TestData& t, const Grid& g, const ResidualSpec& spec, const T& a_cs,
                    const PathResult<T>& path, T* r) {
  int k = 0;
  const std::size_t rows = g.rows.size();
  if (spec.eta)
    for (std::size_t i = 1; i < rows; ++i)
      r[k++] = (path.rows[g.row_at[i]].eta - t.eta[g.rows[i]]) / spec.eta_scale;
  if (spec.volumetric)
    for (std::size_t i = 1; i < rows; ++i)
      r[k++] = (path.rows[g.row_at[i]].volumetric_strain - t.volumetric_strain[g.rows[i]]) /
               spec.volumetric_scale;
  if (spec.fabric)
    for (std::size_t i = 1; i < t.a_c.size(); ++i)
      if (g.snapshot_at[i] >= 0)
        r[k++] = (a_cs * path.rows[g.snapshot_at[i]].fabric_triaxial - t.a_c[i]) / spec.fabric_scale;
}

}  // namespace fit_detail
}  // namespace calibration
