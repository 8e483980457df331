// Template implementation of material_point.h; include material_point.h, not this file.
#pragma once

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace model::acst {

template <typename T>
State<T> isotropic_state(const T& p, const T& void_ratio, const Tensor<T>& fabric) {
  State<T> s;
  s.stress = p * Tensor<T>::Identity();
  s.void_ratio = void_ratio;
  s.alpha.setZero();
  s.alpha_in.setZero();
  s.fabric = fabric;
  return s;
}

template <typename T>
Tensor<T> triaxial_deviator(const T& norm) {
  Tensor<T> t = Tensor<T>::Zero();
  const double k = 1.0 / std::sqrt(6.0);
  t(0, 0) = -k * norm;
  t(1, 1) = -k * norm;
  t(2, 2) = 2.0 * k * norm;
  return t;
}

template <typename T>
PointRecord<T> make_record(const Parameters<T>& par, const State<T>& state, const Tensor<T>& strain,
                           UpdateStatus status) {
  using std::pow;
  using std::sqrt;
  PointRecord<T> r;
  r.axial_strain = strain(2, 2);
  r.volumetric_strain = strain.trace();
  r.p = state.stress.trace() / 3.0;
  r.q = state.stress(2, 2) - 0.5 * (state.stress(0, 0) + state.stress(1, 1));
  r.eta = r.q / r.p;
  r.void_ratio = state.void_ratio;
  r.psi = state.void_ratio - critical_void_ratio(par, r.p);
  r.fabric_triaxial = state.fabric(2, 2) - 0.5 * (state.fabric(0, 0) + state.fabric(1, 1));
  const T ff = state.fabric.cwiseProduct(state.fabric).sum();
  r.fabric_norm = value_of(ff) > 0.0 ? sqrt(ff) : T(0.0);
  r.status = status;
  return r;
}

namespace detail {

/// d sigma_a / d eps_b (Voigt, each shear seed moving eps_kl and eps_lk together) from a
/// strain-seeded update.
inline Eigen::Matrix<double, 6, 6> voigt_tangent(const State<StrainJet>& end) {
  Eigen::Matrix<double, 6, 6> t;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) t(a, b) = end.stress(kVoigtI[a], kVoigtJ[a]).v[b];
  return t;
}

/// x.v += d.v[b] * delta.row(b) summed over the unknown components: the chain rule
/// d x/d par = (d x/d par)|_eps + sum_b (d x/d eps_b)(d eps_b/d par) for one state variable.
template <typename T, typename Delta>
void add_chain_rule(T& x, const StrainJet& d, const int* unknown, int n_unknown,
                    const Delta& delta) {
  for (int b = 0; b < n_unknown; ++b) x.v += d.v[unknown[b]] * delta.row(b).transpose();
}

template <typename T, typename Delta>
void add_chain_rule(Tensor<T>& x, const Tensor<StrainJet>& d, const int* unknown, int n_unknown,
                    const Delta& delta) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) add_chain_rule(x(i, j), d(i, j), unknown, n_unknown, delta);
}

template <typename T>
void set_values(Tensor<T>& x, const Tensor<double>& v) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) x(i, j).a = v(i, j);
}

template <typename T>
void set_values(State<T>& s, const State<double>& v) {
  set_values(s.stress, v.stress);
  s.void_ratio.a = v.void_ratio;
  set_values(s.alpha, v.alpha);
  set_values(s.alpha_in, v.alpha_in);
  set_values(s.fabric, v.fabric);
}

}  // namespace detail

template <typename T>
UpdateStatus mixed_increment(const Parameters<T>& par, const State<T>& start,
                             const std::array<Control, 6>& control,
                             const std::array<T, 6>& value, Tensor<T>& strain_increment,
                             State<T>& end, const DriverOptions& options) {
  NewtonWorkspace workspace;
  return mixed_increment(par, start, control, value, strain_increment, end, options, workspace);
}

template <typename T>
UpdateStatus mixed_increment(const Parameters<T>& par, const State<T>& start,
                             const std::array<Control, 6>& control,
                             const std::array<T, 6>& value, Tensor<T>& strain_increment,
                             State<T>& end, const DriverOptions& options,
                             NewtonWorkspace& workspace) {
  int unknown[6];
  int n_unknown = 0;
  for (int k = 0; k < 6; ++k) {
    const int i = kVoigtI[k], j = kVoigtJ[k];
    if (control[k] == Control::kStrain) {
      strain_increment(i, j) = value[k];
      strain_increment(j, i) = value[k];
    } else {
      strain_increment(j, i) = strain_increment(i, j);
      unknown[n_unknown++] = k;
    }
  }
  if (n_unknown == 0)
    return update_state(par, start, strain_increment, end, options.integration);

  // 1. The values: modified Newton in double. The Newton matrix (the consistent tangent from a
  // strain-seeded update) is kept in the workspace from increment to increment and refreshed
  // only where an iteration reduces the residual by less than a factor 4 or fails.
  const Parameters<double> par_value = cast_parameters<double>(par);
  const State<double> start_value = cast_state<double>(start);
  Tensor<double> deps = cast_tensor<double>(strain_increment);
  const double p_scale = std::max(value_of(start.stress.trace()) / 3.0,
                                  options.integration.min_pressure);
  double target[6];
  for (int a = 0; a < n_unknown; ++a) target[a] = value_of(value[unknown[a]]);
  State<double> end_value;
  UpdateStatus status = UpdateStatus::kFailed;
  bool refresh = !workspace.has_tangent;
  bool converged = false;
  double previous_largest = std::numeric_limits<double>::infinity();
  Tensor<double> previous_deps = deps;
  Eigen::VectorXd previous_r;  // residual at previous_deps, for the Broyden update
  bool has_previous_r = false;
  bool polishing = false;  // converged; one more step is being tried
  bool last_step_fresh = false;  // the last correction was computed with a fresh Newton matrix
  double converged_largest = 0.0;
  Tensor<double> converged_deps = Tensor<double>::Zero();
  State<double> converged_end = start_value;
  UpdateStatus converged_status = UpdateStatus::kOk;
  for (int iteration = 0; iteration < options.max_newton_iterations; ++iteration) {
    bool fresh = false;
    if (refresh) {
      State<StrainJet> end_jet;
      status = update_with_strain_derivatives(par_value, start_value, deps, end_jet,
                                              options.integration);
      if (status != UpdateStatus::kFailed) {
        workspace.tangent = detail::voigt_tangent(end_jet);
        workspace.has_tangent = true;
        end_value = cast_state<double>(end_jet);
      }
      fresh = true;
      refresh = false;
    } else {
      status = update_state(par_value, start_value, deps, end_value, options.integration);
    }
    if (status == UpdateStatus::kFailed && polishing) {
      deps = converged_deps;
      end_value = converged_end;
      status = converged_status;
      break;
    }
    if (status == UpdateStatus::kFailed) {
      if (fresh || iteration == 0) return status;
      deps = previous_deps;  // a step from a stale Newton matrix: retry it with a fresh one
      refresh = true;
      has_previous_r = false;
      continue;
    }
    double residual[6];
    double largest = 0.0;
    for (int a = 0; a < n_unknown; ++a) {
      const int k = unknown[a];
      residual[a] = end_value.stress(kVoigtI[k], kVoigtJ[k]) - target[a];
      largest = std::max(largest, std::abs(residual[a]));
    }
    if (polishing) {
      // One Newton step past the criterion (cheap, in double): kept only if it improved.
      if (largest > converged_largest) {
        deps = converged_deps;
        end_value = converged_end;
        status = converged_status;
      }
      break;
    }
    if (largest <= options.stress_tolerance * p_scale) {
      converged = true;
      if (largest == 0.0 || iteration + 1 >= options.max_newton_iterations) break;
      polishing = true;
      converged_largest = largest;
      converged_deps = deps;
      converged_end = end_value;
      converged_status = status;
    }
    if (!polishing && !fresh && largest > 0.25 * previous_largest) {
      // Slow: redo the step with a fresh matrix; if it already came from a fresh one, redoing it
      // would give the same iterate again (a cycle), so go on from here with a fresh matrix
      // (full Newton).
      if (!last_step_fresh) deps = previous_deps;
      refresh = true;
      has_previous_r = false;
      continue;
    }
    previous_largest = largest;
    Eigen::VectorXd r(n_unknown);
    for (int a = 0; a < n_unknown; ++a) r(a) = residual[a];
    if (!fresh && has_previous_r) {
      // Broyden's update of the unknown block (superlinear convergence without a refresh):
      // J += (dr - J dx) dx^T / (dx^T dx).
      Eigen::VectorXd dx(n_unknown);
      for (int b = 0; b < n_unknown; ++b)
        dx(b) = deps(kVoigtI[unknown[b]], kVoigtJ[unknown[b]]) -
                previous_deps(kVoigtI[unknown[b]], kVoigtJ[unknown[b]]);
      const double dx2 = dx.squaredNorm();
      if (dx2 > 0.0) {
        Eigen::VectorXd jdx = Eigen::VectorXd::Zero(n_unknown);
        for (int a = 0; a < n_unknown; ++a)
          for (int b = 0; b < n_unknown; ++b) jdx(a) += workspace.tangent(unknown[a], unknown[b]) * dx(b);
        const Eigen::VectorXd u = (r - previous_r - jdx) / dx2;
        for (int a = 0; a < n_unknown; ++a)
          for (int b = 0; b < n_unknown; ++b) workspace.tangent(unknown[a], unknown[b]) += u(a) * dx(b);
      }
    }
    previous_r = r;
    has_previous_r = true;
    Eigen::MatrixXd jacobian(n_unknown, n_unknown);
    for (int a = 0; a < n_unknown; ++a)
      for (int b = 0; b < n_unknown; ++b) jacobian(a, b) = workspace.tangent(unknown[a], unknown[b]);
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(jacobian);
    if (!lu.isInvertible()) {
      if (fresh) return UpdateStatus::kFailed;
      refresh = true;
      has_previous_r = false;
      continue;
    }
    const Eigen::VectorXd correction = lu.solve(r);
    last_step_fresh = fresh;
    previous_deps = deps;
    for (int b = 0; b < n_unknown; ++b) {
      const int k = kVoigtI[unknown[b]], l = kVoigtJ[unknown[b]];
      deps(k, l) -= correction(b);
      if (k != l) deps(l, k) = deps(k, l);
    }
  }
  if (!converged) return UpdateStatus::kFailed;
  if (polishing && status == UpdateStatus::kFailed) return UpdateStatus::kFailed;

  if constexpr (std::is_same_v<T, double>) {
    end = end_value;
    strain_increment = deps;
    return status;
  } else {
    // 2. The derivative parts (T = ceres::Jet), by the implicit function theorem at the converged
    // values: one update in T with the unknown strain components held (derivative parts zero)
    // gives d r/d par; the exact tangent J at the same values (a strain-seeded update) gives
    // d eps_u/d par = -J^-1 d r/d par, and the chain rule adds d end/d eps_u * d eps_u/d par to
    // every state variable. The values are those of the double Newton above.
    for (int b = 0; b < n_unknown; ++b) {
      const int k = kVoigtI[unknown[b]], l = kVoigtJ[unknown[b]];
      strain_increment(k, l) = T(deps(k, l));
      strain_increment(l, k) = strain_increment(k, l);
    }
    status = update_state(par, start, strain_increment, end, options.integration);
    if (status == UpdateStatus::kFailed) return status;
    State<StrainJet> end_jet;
    if (update_with_strain_derivatives(par_value, start_value, deps, end_jet,
                                       options.integration) == UpdateStatus::kFailed)
      return UpdateStatus::kFailed;
    const Eigen::Matrix<double, 6, 6> tangent = detail::voigt_tangent(end_jet);
    constexpr int kN = decltype(T::v)::RowsAtCompileTime;
    Eigen::MatrixXd jacobian(n_unknown, n_unknown);
    Eigen::Matrix<double, Eigen::Dynamic, kN> dr(n_unknown, kN);
    for (int a = 0; a < n_unknown; ++a) {
      const int k = unknown[a];
      dr.row(a) = (end.stress(kVoigtI[k], kVoigtJ[k]).v - value[k].v).transpose();
      for (int b = 0; b < n_unknown; ++b) jacobian(a, b) = tangent(unknown[a], unknown[b]);
    }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(jacobian);
    if (!lu.isInvertible()) return UpdateStatus::kFailed;
    const Eigen::Matrix<double, Eigen::Dynamic, kN> delta = -lu.solve(dr);  // d eps_u / d par
    for (int b = 0; b < n_unknown; ++b) {
      const int k = kVoigtI[unknown[b]], l = kVoigtJ[unknown[b]];
      strain_increment(k, l).v = delta.row(b).transpose();
      strain_increment(l, k) = strain_increment(k, l);
    }
    detail::add_chain_rule(end.stress, end_jet.stress, unknown, n_unknown, delta);
    detail::add_chain_rule(end.void_ratio, end_jet.void_ratio, unknown, n_unknown, delta);
    detail::add_chain_rule(end.alpha, end_jet.alpha, unknown, n_unknown, delta);
    detail::add_chain_rule(end.alpha_in, end_jet.alpha_in, unknown, n_unknown, delta);
    detail::add_chain_rule(end.fabric, end_jet.fabric, unknown, n_unknown, delta);
    // The values are exactly those of the double Newton (a Jet update can differ in the last
    // bit, and the driver with double must give the same curves).
    detail::set_values(end, end_value);
    return status;
  }
}

namespace detail {

inline UpdateStatus worse(UpdateStatus a, UpdateStatus b) {
  return static_cast<int>(a) > static_cast<int>(b) ? a : b;
}

/// Runs increments produced by step(k, control, value) from the initial state.
template <typename T, typename StepFunction>
PathResult<T> run_path(const Parameters<T>& par, const State<T>& initial, int increments,
                       StepFunction&& step, const DriverOptions& options) {
  PathResult<T> result;
  result.state = initial;
  result.strain.setZero();
  result.rows.push_back(make_record(par, initial, result.strain, UpdateStatus::kOk));
  Tensor<T> guess = Tensor<T>::Zero();
  NewtonWorkspace workspace;  // the Newton matrix carried along the path
  for (int k = 0; k < increments; ++k) {
    std::array<Control, 6> control;
    std::array<T, 6> value;
    step(k, result.state, control, value);
    Tensor<T> deps = guess;
    State<T> next;
    const UpdateStatus status =
        mixed_increment(par, result.state, control, value, deps, next, options, workspace);
    result.status = worse(result.status, status);
    if (status == UpdateStatus::kFailed) {
      result.rows.push_back(make_record(par, result.state, result.strain, status));
      break;
    }
    result.state = next;
    result.strain += deps;
    guess = deps;
    result.rows.push_back(make_record(par, result.state, result.strain, status));
  }
  return result;
}

}  // namespace detail

template <typename T>
PathResult<T> drained_triaxial(const Parameters<T>& par, const State<T>& initial,
                               double axial_strain_end, int increments,
                               const DriverOptions& options) {
  const T lateral_x = initial.stress(0, 0), lateral_y = initial.stress(1, 1);
  const double d_axial = axial_strain_end / std::max(increments, 1);
  auto step = [&](int, const State<T>&, std::array<Control, 6>& control, std::array<T, 6>& value) {
    control = {Control::kStress, Control::kStress, Control::kStrain,
               Control::kStrain, Control::kStrain, Control::kStrain};
    value = {lateral_x, lateral_y, T(d_axial), T(0.0), T(0.0), T(0.0)};
  };
  return detail::run_path(par, initial, increments, step, options);
}

template <typename T>
PathResult<T> undrained_triaxial(const Parameters<T>& par, const State<T>& initial,
                                 double axial_strain_end, int increments,
                                 const DriverOptions& options) {
  const double d_axial = axial_strain_end / std::max(increments, 1);
  auto step = [&](int, const State<T>&, std::array<Control, 6>& control, std::array<T, 6>& value) {
    control.fill(Control::kStrain);
    value = {T(-0.5 * d_axial), T(-0.5 * d_axial), T(d_axial), T(0.0), T(0.0), T(0.0)};
  };
  return detail::run_path(par, initial, increments, step, options);
}

template <typename T>
PathResult<T> isotropic_compression(const Parameters<T>& par, const State<T>& initial,
                                    double p_end, int increments, const DriverOptions& options) {
  const T p0 = initial.stress.trace() / 3.0;
  const int n = std::max(increments, 1);
  auto step = [&](int k, const State<T>&, std::array<Control, 6>& control,
                  std::array<T, 6>& value) {
    control = {Control::kStress, Control::kStress, Control::kStress,
               Control::kStrain, Control::kStrain, Control::kStrain};
    const double w = static_cast<double>(k + 1) / n;
    const T p = (1.0 - w) * p0 + T(w * p_end);
    value = {p, p, p, T(0.0), T(0.0), T(0.0)};
  };
  return detail::run_path(par, initial, n, step, options);
}

template <typename T>
PathResult<T> general_path(const Parameters<T>& par, const State<T>& initial,
                           const std::vector<PathStep>& steps, const DriverOptions& options) {
  auto step = [&](int k, const State<T>&, std::array<Control, 6>& control,
                  std::array<T, 6>& value) {
    control = steps[static_cast<std::size_t>(k)].control;
    for (int c = 0; c < 6; ++c) value[c] = T(steps[static_cast<std::size_t>(k)].value[c]);
  };
  return detail::run_path(par, initial, static_cast<int>(steps.size()), step, options);
}

}  // namespace model::acst
