// Internal to calibration_fit: the model strain grid of a DEM test and the fit's axisymmetric
// path (drained, constant p or undrained; docs/calibration.md, "Objective"), templated on the
// scalar (double for costs, ceres::Jet seeded on the free parameters for Jacobians).
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <functional>
#include <type_traits>
#include <vector>

#include "calibration/fit.h"
#include "model/material_point.h"

namespace calibration {
namespace fit_detail {


/// Model strain grid of one test: 0, then the selected series rows and the snapshots, with
/// intermediate points where two are more than max_strain_step apart in |eps_a| (0: no limit).
/// The lateral stress is held only at the grid's points, so the path's error falls with the
/// square of its step (docs/calibration.md, "Objective"). Steps carry the signed axial increment
/// (value[2], negative in extension) and p0 (value[0]).
struct Grid {
  std::vector<PathStep> steps;
  std::vector<int> rows;           ///< selected series rows
  std::vector<int> row_at;         ///< grid index of each selected row
  std::vector<int> snapshot_at;    ///< grid index of each snapshot (-1: beyond the series)
  /// Whether the DEM specimen had liquefied (p < kLiquefiedMeanStress p0) at each selected row
  /// and each snapshot (the series row nearest in strain): no q/p or a_c residual there.
  std::vector<char> row_liquefied, snapshot_liquefied;
};
Grid make_grid(const TestData& t, int max_points, double max_strain_step = 0.0);

/// The residuals of a stage. `volumetric` is the response to the lateral constraint: the
/// volumetric strain on the drained and constant-p paths, the mean stress on the undrained ones.
struct ResidualSpec {
  bool eta = true, volumetric = true, fabric = true;
  double eta_scale = 0.05, volumetric_scale = 0.005, fabric_scale = 0.05;
  double mean_stress_scale = 0.05;  ///< relative to max(p0, p_DEM)
};

/// What holds the lateral axes of the fit's path (TestPath without the direction).
enum class Lateral { kStress, kMeanStress, kVolume };
Lateral lateral_of(TestPath path);

/// The lengths of the residual series of one test under spec, in the order path_residuals
/// writes them: q/p over the rows, eps_v (or p) over the rows, a_c over the snapshots (each only
/// where spec asks for it). Residuals within a series are neighbours in strain.
std::vector<int> residual_series(const TestData& t, const Grid& g, const ResidualSpec& spec);
/// Residuals of one test under spec: the sum of residual_series.
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

/// Axisymmetric triaxial path (docs/calibration.md): eps_zz stepped by value[2] of each step,
/// eps_xx = eps_yy = eps_r. Lateral::kVolume: eps_r = -d eps_zz / 2 (constant volume). Otherwise
/// eps_r is the one unknown, solved so that w_r (sigma_xx + sigma_yy)/2 + w_z sigma_zz = p0
/// (value[0]): (w_r, w_z) = (1, 0) holds the lateral stress (Lateral::kStress), (2/3, 1/3) the
/// mean stress (kMeanStress). The Newton derivative comes from a Jet<1> seeded on both lateral
/// components together, which keeps the symmetry (a strain tangent seeded on eps_xx alone excites
/// the stiff asymmetric lateral mode, docs/model.md §4). Values in double; with T = Jet the
/// derivative parts by the implicit function theorem at the converged values, as in
/// mixed_increment. Attempted substeps of all updates are added to *substeps.
template <typename T>
PathResult<T> axisymmetric_path(const Parameters<T>& par, const State<T>& initial,
                                const std::vector<PathStep>& steps, const DriverOptions& options,
                                Lateral lateral = Lateral::kStress, long* substeps = nullptr) {
  using J1 = ceres::Jet<double, 1>;
  const Parameters<double> par_value = cast_parameters<double>(par);
  const Parameters<J1> par_j1 = cast_parameters<J1>(par_value);
  PathResult<T> result;
  long used = 0;  // substeps attempted along the path
  result.state = initial;
  result.strain.setZero();
  result.rows.push_back(make_record(par, initial, result.strain, UpdateStatus::kOk));
  double guess = 0.0;  // lateral strain per unit axial strain of the last increment
  // The held combination of the stresses (Lateral::kStress or kMeanStress).
  const double w_r = lateral == Lateral::kMeanStress ? 2.0 / 3.0 : 1.0;
  const double w_z = lateral == Lateral::kMeanStress ? 1.0 / 3.0 : 0.0;
  auto held = [&](const auto& stress) {
    return w_r * 0.5 * (stress(0, 0) + stress(1, 1)) + w_z * stress(2, 2);
  };
  // One increment d_axial from (state, strain); false where it cannot be integrated.
  auto advance = [&](State<T>& state, Tensor<T>& strain, double d_axial, double target,
                     UpdateStatus& worst) {
    if (lateral == Lateral::kVolume) {  // the strain is given: no unknown, no chain rule
      Tensor<T> deps = Tensor<T>::Zero();
      deps(0, 0) = deps(1, 1) = T(-0.5 * d_axial);
      deps(2, 2) = T(d_axial);
      State<T> next;
      const UpdateStatus status = update_state(par, state, deps, next, options.integration, &used);
      if (status == UpdateStatus::kFailed) return false;
      if (status == UpdateStatus::kUnreliable) worst = UpdateStatus::kUnreliable;
      state = next;
      strain += deps;
      return true;
    }
    double slope = 0.0;  // d held / d eps_r
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
      const J1 r = held(end.stress) - target;
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
      const auto r_v = held(next.stress).v;
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
  // Static liquefaction: under constant volume the model's p can fall towards 0, where the
  // update cannot go on (its stiffness vanishes with p). From the first such failure below
  // kLiquefiedMeanStress p0 the point stays at its last state (no effective stress, no shear:
  // the DEM's liquefied specimens stay at p' ~ 0, docs/dem.md) and the rows say kUnreliable.
  const double p_initial = value_of(initial.stress.trace()) / 3.0;
  bool liquefied = false;
  auto hold = [&](double d_axial) {
    Tensor<T> deps = Tensor<T>::Zero();
    deps(0, 0) = deps(1, 1) = T(-0.5 * d_axial);
    deps(2, 2) = T(d_axial);
    result.strain += deps;
    result.status = UpdateStatus::kUnreliable;
    result.rows.push_back(make_record(par, result.state, result.strain, UpdateStatus::kUnreliable));
  };
  for (const PathStep& step : steps) {
    if (liquefied) {
      hold(step.value[2]);
      continue;
    }
    UpdateStatus worst = UpdateStatus::kOk;
    State<T> state = result.state;
    Tensor<T> strain = result.strain;
    if (!apply(state, strain, step.value[2], step.value[0], worst, 0)) {
      if (lateral == Lateral::kVolume &&
          value_of(result.state.stress.trace()) / 3.0 < kLiquefiedMeanStress * p_initial) {
        liquefied = true;
        hold(step.value[2]);
        continue;
      }
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
  return axisymmetric_path(parameters_of(v), s0, g.steps, driver, lateral_of(t.path), substeps);
}

/// The normalised residuals (model - DEM)/scale of a path, in the order of count_residuals.
template <typename T>
void path_residuals(const TestData& t, const Grid& g, const ResidualSpec& spec, const T& a_cs,
                    const PathResult<T>& path, T* r) {
  int k = 0;
  const std::size_t rows = g.rows.size();
  if (spec.eta)
    for (std::size_t i = 1; i < rows; ++i)
      if (!g.row_liquefied[i])
        r[k++] = (path.rows[g.row_at[i]].eta - t.eta[g.rows[i]]) / spec.eta_scale;
  if (spec.volumetric && is_undrained(t.path))
    for (std::size_t i = 1; i < rows; ++i) {
      const double p_dem = t.p[g.rows[i]];
      r[k++] = (path.rows[g.row_at[i]].p - p_dem) /
               (spec.mean_stress_scale * std::max(t.p0, p_dem));
    }
  else if (spec.volumetric)
    for (std::size_t i = 1; i < rows; ++i)
      r[k++] = (path.rows[g.row_at[i]].volumetric_strain - t.volumetric_strain[g.rows[i]]) /
               spec.volumetric_scale;
  if (spec.fabric)
    for (std::size_t i = 1; i < t.a_c.size(); ++i)
      if (g.snapshot_at[i] >= 0 && !g.snapshot_liquefied[i])
        r[k++] = (a_cs * path.rows[g.snapshot_at[i]].fabric_triaxial - t.a_c[i]) / spec.fabric_scale;
}

}  // namespace fit_detail
}  // namespace calibration
