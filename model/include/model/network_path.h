// The contact-network model along a triaxial path about z (docs/network-model.md, "Calibration"):
// the material-point driver of the model, which the fit differentiates (T = ceres::Jet) and which
// fe-check runs beside its element. From an axisymmetric start every tensor of the state stays
// diagonal (network_tensor.h), so the path integrates the laws on the diagonals alone: a third of
// the work of the full tensors, the same numbers to rounding.
//
// Conventions: compression positive, stress in Pa, strains as fractions.
#pragma once

#include <ceres/jet.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "model/network_model.h"
#include "model/network_update.h"

namespace model::network {

/// x diag(-1, -1, 2) / 3: the axisymmetric deviatoric tensor whose triaxial part t(.) is x.
template <typename T>
Tensor<T> axisymmetric(const T& x) {
  Tensor<T> t = Tensor<T>::Zero();
  t(0, 0) = t(1, 1) = -x / T(3.0);
  t(2, 2) = T(2.0) * x / T(3.0);
  return t;
}

/// The state along a triaxial path: the diagonals of the tensors.
template <typename T>
using PathState = State<T, DiagonalTensor<T>>;

/// The diagonal of a state whose tensors are diagonal (an axisymmetric start).
PathState<double> diagonal_state(const State<double>& s);

inline double value_of(double x) { return x; }
template <int N>
double value_of(const ceres::Jet<double, N>& x) {
  return x.a;
}

/// The parameters' values (the Jets' value parts), and parameters of another scalar type.
template <typename T>
Parameters<double> parameter_values(const Parameters<T>& par) {
  const auto in = to_array(par);
  std::array<double, kNumParameters> out;
  for (int i = 0; i < kNumParameters; ++i) out[i] = value_of(in[i]);
  return from_array(out.data());
}
template <typename Dual>
Parameters<Dual> lift_parameters(const Parameters<double>& par) {
  const auto x = to_array(par);
  std::array<Dual, kNumParameters> y;
  for (int i = 0; i < kNumParameters; ++i) y[i] = Dual(x[i]);
  return from_array(y.data());
}

/// Applies f to every scalar of a state (e, Z, Lambda and the tensors' components).
template <typename R, typename S, typename F>
PathState<R> map_state(const PathState<S>& s, F f) {
  return {f(s.void_ratio), f(s.coordination), f(s.lambda), map_components<R>(s.fabric, f),
          map_components<R>(s.normal, f), map_components<R>(s.tangential, f),
          map_components<R>(s.inherent, f)};
}
template <typename T>
PathState<T> cast_state(const PathState<double>& s) {
  return map_state<T>(s, [](double x) { return T(x); });
}
template <typename T>
PathState<double> state_values(const PathState<T>& s) {
  return map_state<double>(s, [](const T& x) { return value_of(x); });
}

/// admissible (network_update.h) of a state's values, for any scalar type.
template <typename T>
bool admissible_values(const PathState<T>& s) {
  return admissible(state_values(s));
}

/// The strain increment with this axial (zz) and lateral (xx = yy) part.
template <typename T>
DiagonalTensor<T> strain_increment(const T& axial, const T& lateral) {
  return {{lateral, lateral, axial}};
}

/// How the path integrates each increment.
struct PathOptions {
  /// Rate constant times substep strain (substeps_for). 0.2, four times the update's: on the
  /// paper-size runs the paths' q/p then lies within 2.1e-6 of converged ones along the DEM's
  /// strain path (1.3e-8 at 0.05, 1.7e-5 at 0.4), far below the 6e-4 to 8.6e-4 the predicted
  /// path's increments leave (test TheFitsPathsAreWithin1e3OfConvergedPaths;
  /// docs/network-model.md).
  double substep_size = 0.2;
  /// An increment that needs more RK4 substeps fails (the fit's step is refused, a path stops):
  /// about 400 times what the paper-size runs' fitted rates need per row.
  int max_substeps = 2000;
};

/// The substeps of an increment, or 0 where it would need more than options.max_substeps: rates
/// that fast (a start far off in the fit, exp(n_r xi) large) make the path unusable, not slow.
int checked_substeps(const Parameters<double>& par, const PathState<double>& start,
                     double strain_norm, const PathOptions& options);

/// Substeps of a drained increment, fixed for it (from the axial strain and a lateral one of half
/// its size), so that the Newton iterates on one smooth function; 0 as checked_substeps.
int drained_substeps(const Parameters<double>& par, const PathState<double>& start, double da,
                     const PathOptions& options);

/// Why a path stopped at `axial` for want of substeps.
std::string too_stiff_message(double axial, const PathOptions& options);

/// Solves one drained increment: the lateral strain increment that brings sigma_xx to `target`
/// [Pa] (stresses with the grains' E = youngs_modulus), by Newton with the derivative from a
/// one-component Jet; `lateral` holds the first guess on entry. Returns false if it does not
/// converge.
bool drained_increment(const Parameters<double>& par, const PathState<double>& start, double da,
                       double target, double youngs_modulus, double& lateral,
                       PathState<double>& end, const PathOptions& options);

/// The same with parameter derivatives (T a Jet of N): the lateral strain increment solved in
/// doubles, its derivatives from the implicit function theorem, dx/dtheta = -g_theta / g_x, with g
/// and the end state evaluated once in Jets of N + 1 (the last component seeded on x).
template <int N>
bool drained_increment(const Parameters<ceres::Jet<double, N>>& par,
                       const PathState<ceres::Jet<double, N>>& start, double da, double target,
                       double youngs_modulus, ceres::Jet<double, N>& lateral,
                       PathState<ceres::Jet<double, N>>& end, const PathOptions& options) {
  using J = ceres::Jet<double, N>;
  using Ext = ceres::Jet<double, N + 1>;
  const Parameters<double> par_values = parameter_values(par);
  double x = value_of(lateral);
  PathState<double> end_values;
  const PathState<double> start_values = state_values(start);
  if (!drained_increment(par_values, start_values, da, target, youngs_modulus, x, end_values,
                         options))
    return false;
  auto extend = [](const J& y) {
    Ext r(y.a);
    for (int i = 0; i < N; ++i) r.v[i] = y.v[i];
    return r;
  };
  std::array<Ext, kNumParameters> par_ext;
  const auto par_jets = to_array(par);
  for (int i = 0; i < kNumParameters; ++i) par_ext[i] = extend(par_jets[i]);
  const PathState<Ext> s = integrate(from_array(par_ext.data()), map_state<Ext>(start, extend),
                                     strain_increment(Ext(da), Ext(x, N)),
                                     drained_substeps(par_values, start_values, da, options));
  const Ext g = lateral_component(stress(s, youngs_modulus)) / target;
  if (!(std::abs(g.v[N]) > 0.0)) return false;
  std::array<double, N> dx;
  for (int i = 0; i < N; ++i) dx[i] = -g.v[i] / g.v[N];
  auto total = [&](const Ext& y) {
    J r(y.a);
    for (int i = 0; i < N; ++i) r.v[i] = y.v[i] + y.v[N] * dx[i];
    return r;
  };
  end = map_state<J>(s, total);
  lateral = J(x);
  for (int i = 0; i < N; ++i) lateral.v[i] = dx[i];
  return true;
}

/// One node of a path: its axial strain, the volumetric strain there where the path follows a
/// measured strain path, and which DEM series row and snapshot it is (-1: none; carried into the
/// curve for comparisons).
struct PathNode {
  double axial, volumetric;
  int row, snapshot;
};

/// The model along a path, one entry per node reached.
struct Curve {
  std::vector<double> axial_strain, volumetric_strain, void_ratio, p, q, eta, lateral_stress;
  std::vector<double> coordination, lambda, a_c, a_n, a_t;
  std::vector<int> row, snapshot;
  bool complete = true;   ///< false if the path stopped early (message says why)
  std::string message;
};

/// Drives the model along a measured strain path (the nodes' axial and volumetric strains, x and y
/// alike) from `start`: the stress is the model's, the strains the nodes'.
Curve follow_strain_path(const Parameters<double>& par, const PathState<double>& start,
                         const std::vector<PathNode>& nodes, double youngs_modulus,
                         const PathOptions& options = {});

/// How the lateral directions are held on a predicted path.
enum class Lateral {
  kStressHeld,      ///< drained: sigma_xx = sigma_yy = lateral_stress, eps_xx found by Newton
  kConstantVolume,  ///< undrained: eps_xx = eps_yy = -eps_zz / 2
};

/// Predicts the path from `start` at the nodes' axial strains (their volumetric strains unused).
/// Stops with complete = false where an increment cannot be solved.
Curve predict(const Parameters<double>& par, const PathState<double>& start,
              const std::vector<PathNode>& nodes, Lateral lateral, double lateral_stress,
              double youngs_modulus, const PathOptions& options = {});

}  // namespace model::network
