// Implicit integration of the ACST model (docs/model.md §4): the elastic response in closed form,
// the crossing of the yield cone and the load reversal located explicitly, and each plastic
// substep a backward-Euler (closest-point) step of the whole local system, solved by Newton with
// its analytic Jacobian; the Richardson extrapolation of two half steps against one whole step
// gives second order (and stays L-stable), their difference the local error estimate.
//
// The values are computed once, in double (integrate_values, acst_implicit.cc), which records
// each operation on a tape. Derivatives of every kind come from the converged local systems by
// the implicit function theorem while the tape is replayed: in a Jet type for the fits
// (derivatives w.r.t. the parameters: one residual evaluation in the Jet type and one solve with
// the factorised Jacobian per plastic step, instead of Jets through every Newton iteration), and
// with hand-written sensitivities for the consistent tangent (update_with_tangent).
// Include model/acst_model.h, not this file.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

namespace model::acst {
namespace implicit_detail {

/// Unknowns of a backward-Euler step: stress [Pa] and alpha (each 6 components, Voigt order xx,
/// yy, zz, xy, yz, xz, tensor components) and the plastic multiplier increment. The fabric is
/// eliminated: its equation is linear in F (end_fabric).
inline constexpr int kUnknowns = 13;
inline constexpr int kMultiplier = 12;
template <typename T>
using Unknowns = Eigen::Matrix<T, kUnknowns, 1>;
using Jacobian = Eigen::Matrix<double, kUnknowns, kUnknowns>;

inline constexpr int kRow[6] = {0, 1, 2, 0, 1, 0};
inline constexpr int kCol[6] = {0, 1, 2, 1, 2, 2};

template <typename T>
void pack(const Tensor<T>& t, Unknowns<T>& x, int offset) {
  for (int k = 0; k < 6; ++k) x(offset + k) = t(kRow[k], kCol[k]);
}

template <typename T>
Tensor<T> unpack(const Unknowns<T>& x, int offset) {
  Tensor<T> t;
  for (int k = 0; k < 6; ++k) {
    t(kRow[k], kCol[k]) = x(offset + k);
    t(kCol[k], kRow[k]) = x(offset + k);
  }
  return t;
}

/// (e^w - 1)/w, accurate at w -> 0.
template <typename T>
T exprel(const T& w) {
  using std::expm1;
  if (std::abs(value_of(w)) < 1e-5) return 1.0 + w * (0.5 + w * (1.0 / 6.0 + w / 24.0));
  return expm1(w) / w;
}

/// The elastic response over the straight strain path deps, exact (ours, docs/model.md §4):
/// with u = 1 + e = u0 exp(-t eps_v), the moduli of Eq. (1) are G = c_g a(u) p^n, c_g =
/// G0 p_a^(1-n), n = n_G, a(u) = (3.97 - u)^2 / u, and K = kappa G; then p^(1-n) grows linearly,
/// d p^(1-n)/dt = (1 - n) kappa c_g a(u) eps_v, and ds/dt = 2 G de integrates in closed form
/// through Psi = int_0^1 a(u(t)) dt (detail::elastic_growth). alpha, alpha_in and F are
/// unchanged. Returns false where p would reach 0 or e leave (0, 2.97).
template <typename T>
bool elastic_path(const Parameters<T>& par, const State<T>& start, const Tensor<T>& deps,
                  State<T>& end) {
  using std::expm1;
  end = start;
  const Tensor<T> I = Tensor<T>::Identity();
  const T w = deps.trace();
  const Tensor<T> de = deps - (w / 3.0) * I;
  const T p0 = start.stress.trace() / 3.0;
  if (!(value_of(p0) > 0.0)) return false;
  const T u0 = 1.0 + start.void_ratio;
  const double c = 1.0 + detail::kElasticVoidLimit;  // a(u) = (c - u)^2 / u
  const T psi = (c * c) * exprel(w) / u0 - 2.0 * c + u0 * exprel(T(-w));
  const T kappa = 2.0 * (1.0 + par.nu) / (3.0 * (1.0 - 2.0 * par.nu));
  const T x = 1.0 - par.n_G;
  const T c_g = par.G0 * detail::power(T(kAtmosphericPressure), x);
  const T p0_n = detail::power(p0, par.n_G);
  const T z = x * kappa * c_g * w * psi * p0_n / p0;  // the relative growth of p^(1-n)
  if (!(value_of(z) > -1.0)) return false;
  T growth, phi;
  detail::elastic_growth(z, x, growth, phi);
  const T shear_integral = c_g * psi * p0_n * phi;  // int G dt
  end.stress = (start.stress - p0 * I) + (2.0 * shear_integral) * de + (p0 * growth) * I;
  end.void_ratio = start.void_ratio + u0 * expm1(-w);  // e exactly unchanged at eps_v = 0
  return value_of(end.void_ratio) > 0.0 && value_of(end.void_ratio) < detail::kElasticVoidLimit;
}

/// The known data of one backward-Euler step.
template <typename T>
struct PlasticStep {
  State<T> start;          ///< at the start of the substep (alpha_in already set by the reversal rule)
  Tensor<T> stress_trial;  ///< the exact elastic stress at the end of the substep [Pa]
  T void_ratio;            ///< the void ratio at the end (kinematic: exact)
  double scale = 1.0;      ///< stress scale of the residual [Pa]
};

/// The step from start over deps (the elastic predictor by elastic_path); false where it fails.
template <typename T>
bool make_step(const Parameters<T>& par, const State<T>& start, const Tensor<T>& deps,
               PlasticStep<T>& step) {
  State<T> trial;
  if (!elastic_path(par, start, deps, trial)) return false;
  step.start = start;
  step.stress_trial = trial.stress;
  step.void_ratio = trial.void_ratio;
  step.scale = std::max(std::abs(value_of(start.stress.trace())) / 3.0, 1.0);
  return true;
}

/// The fabric at the end of a backward-Euler step, F = F_0 + dlambda k (n - F) solved for F, with
/// k = fabric_rate at the end state.
template <typename T>
Tensor<T> end_fabric(const T& rate, const Tensor<T>& start_fabric, const Tensor<T>& n,
                     const T& dlambda) {
  return (start_fabric + (dlambda * rate) * n) / (1.0 + dlambda * rate);
}

/// The end state of a backward-Euler step at the unknowns x (the fabric by end_fabric); false
/// where n is undefined.
template <typename T>
bool end_state(const Parameters<T>& par, const PlasticStep<T>& step, const Unknowns<T>& x,
               State<T>& s) {
  using std::sqrt;
  s.stress = unpack(x, 0);
  s.alpha = unpack(x, 6);
  s.alpha_in = step.start.alpha_in;
  s.void_ratio = step.void_ratio;
  const T p = s.stress.trace() / 3.0;
  const Tensor<T> direction = (s.stress - p * Tensor<T>::Identity()) / p - s.alpha;
  const T squared = detail::contract(direction, direction);
  if (!(value_of(squared) > detail::kMinDirectionSquared)) return false;
  const T rate = fabric_rate(par, T(s.void_ratio - critical_void_ratio(par, p)));
  s.fabric = end_fabric(rate, step.start.fabric, Tensor<T>(direction / sqrt(squared)), x(kMultiplier));
  return true;
}

/// The residual of the backward-Euler step at the unknowns x (Eq. 2, 13, 15 at the end state,
/// with the elastic predictor integrated exactly, and Eq. 3; Eq. 16 by end_fabric):
///   R_sigma = (sigma - sigma_trial + dlambda (2G n + K D I)) / scale,
///   R_alpha = alpha - alpha_0 - dlambda (2/3) h (alpha_b - alpha),
///   R_f     = ||r - alpha|| - sqrt(2/3) m.
/// Returns false where the model cannot be evaluated at x.
template <typename T>
bool plastic_residual(const Parameters<T>& par, const PlasticStep<T>& step, const Unknowns<T>& x,
                      Unknowns<T>& r) {
  State<T> s;
  if (!end_state(par, step, x, s)) return false;
  const T& dlambda = x(kMultiplier);
  ModelQuantities<T> q;
  if (!evaluate_model(par, s, q) || !q.has_direction) return false;
  if (!(value_of(1.0 - par.c_h * s.void_ratio) > 0.0)) return false;  // b0 must stay positive
  const Tensor<T> I = Tensor<T>::Identity();
  const Tensor<T> r_stress =
      (s.stress - step.stress_trial + dlambda * ((2.0 * q.G) * q.n + (q.K * q.D) * I)) /
      step.scale;
  const Tensor<T> r_alpha =
      s.alpha - step.start.alpha - (dlambda * (2.0 / 3.0) * q.h) * (q.alpha_b - s.alpha);
  pack(r_stress, r, 0);
  pack(r_alpha, r, 6);
  r(kMultiplier) = relative_yield_function(par, s);
  return true;
}

/// LU factorisation with partial pivoting of a small fixed-size matrix, written out so that the
/// compiler unrolls it (Eigen's PartialPivLU takes its blocked dynamic-size path at this size and
/// costs several times more).
template <int N>
class SmallLu {
 public:
  /// false where a pivot is zero or not finite.
  bool compute(const Eigen::Matrix<double, N, N>& matrix) {
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) lu_[i][j] = matrix(i, j);
    for (int k = 0; k < N; ++k) {
      int pivot = k;
      double largest = std::abs(lu_[k][k]);
      for (int i = k + 1; i < N; ++i)
        if (std::abs(lu_[i][k]) > largest) {
          largest = std::abs(lu_[i][k]);
          pivot = i;
        }
      if (!(largest > 0.0) || !std::isfinite(largest)) return false;
      permutation_[k] = pivot;
      if (pivot != k)
        for (int j = 0; j < N; ++j) std::swap(lu_[k][j], lu_[pivot][j]);
      const double inverse = 1.0 / lu_[k][k];
      inverse_pivot_[k] = inverse;
      for (int i = k + 1; i < N; ++i) {
        const double factor = lu_[i][k] * inverse;
        lu_[i][k] = factor;
        for (int j = k + 1; j < N; ++j) lu_[i][j] -= factor * lu_[k][j];
      }
    }
    return true;
  }
  /// A^-1 b for every column of b, the columns side by side. Both substitutions in column
  /// (axpy) order and with the pivots' reciprocals: the updates of one step are independent of
  /// one another, instead of one chain of dependent operations per row.
  template <int M>
  Eigen::Matrix<double, N, M> solve(const Eigen::Matrix<double, N, M>& b) const {
    double y[N][M];
    for (int k = 0; k < N; ++k)
      for (int m = 0; m < M; ++m) y[k][m] = b(k, m);
    for (int k = 0; k < N; ++k)  // rows swapped whole
      if (permutation_[k] != k)
        for (int m = 0; m < M; ++m) std::swap(y[k][m], y[permutation_[k]][m]);
    for (int k = 0; k < N; ++k)
      for (int i = k + 1; i < N; ++i)
        for (int m = 0; m < M; ++m) y[i][m] -= lu_[i][k] * y[k][m];
    for (int k = N - 1; k >= 0; --k) {
      for (int m = 0; m < M; ++m) y[k][m] *= inverse_pivot_[k];
      for (int i = 0; i < k; ++i)
        for (int m = 0; m < M; ++m) y[i][m] -= lu_[i][k] * y[k][m];
    }
    Eigen::Matrix<double, N, M> x;
    for (int k = 0; k < N; ++k)
      for (int m = 0; m < M; ++m) x(k, m) = y[k][m];
    return x;
  }

 private:
  double lu_[N][N];  // written by compute()
  double inverse_pivot_[N];
  int permutation_[N];
};

/// Derivatives of a backward-Euler residual w.r.t. its known data at fixed unknowns (for the
/// consistent tangent), in the structure they have: dR_sigma/d sigma_trial = -I / scale,
/// dR_alpha/d alpha_0 = -I, a column for the end void ratio, and rank-one terms for F_0 (through
/// A = F:n) and alpha_in (through (alpha - alpha_in):n), both along n:
///   dR = [-d sigma_trial / scale + void_ratio.head(6) de + fabric (n : dF_0);
///         -d alpha_0 + void_ratio.tail(6) de + alpha_in (n : d alpha_in); 0].
struct InputDerivatives {
  Eigen::Matrix<double, 12, 1> void_ratio;
  Eigen::Matrix<double, 6, 1> fabric, alpha_in;
  Eigen::Matrix<double, 6, 1> n_weighted;               ///< n with the Voigt weights (for n : X)
  Eigen::Matrix<double, 6, kUnknowns> fabric_unknowns;  ///< dF_end / dx
  double fabric_start = 1.0;                            ///< dF_end / dF_0 = this * identity
  Eigen::Matrix<double, 6, 1> fabric_void_ratio;        ///< dF_end / de (through the rate, Eq. 16)
};

/// The converged backward-Euler step: the unknowns, the factorised Jacobian at them (for the
/// implicit function theorem), the Newton iterations used and, when asked for, the input
/// derivatives at them.
struct PlasticSolution {
  Unknowns<double> x = Unknowns<double>::Zero();
  SmallLu<kUnknowns> lu;
  int iterations = 0;
  bool has_inputs = false;
  InputDerivatives inputs;
};

/// Newton on the residual (analytic Jacobian, backtracking on ||R||) from guess; false if it does
/// not converge. With with_inputs the input derivatives at the solution are kept too. Defined in
/// acst_implicit.cc.
bool solve_plastic(const Parameters<double>& par, const PlasticStep<double>& step,
                   const Unknowns<double>& guess, PlasticSolution& solution,
                   bool with_inputs = false);

/// The analytic Jacobian dR/dx of plastic_residual at x (exposed for tests); false where the
/// model cannot be evaluated.
bool plastic_jacobian(const Parameters<double>& par, const PlasticStep<double>& step,
                      const Unknowns<double>& x, Unknowns<double>& r, Jacobian& jacobian);

/// One operation of the values run, replayed for the derivatives. The strain of an operation is
/// step * segment, segment = C * (the strain increment) with C = 1 at the start and
/// C <- (1 - done - t step) C after each crossing (the rest of the increment becomes the segment).
struct TapeEntry {
  enum class Kind { kElastic, kCrossing, kPlastic };
  Kind kind = Kind::kElastic;
  double step = 1.0;  ///< dyadic fraction of the segment
  double done = 0.0;  ///< fraction of the segment done before this entry (crossings)
  double t = 0.0;     ///< crossings: the fraction of step * segment at which f = 0
  bool reset_alpha_in = false;  ///< plastic: alpha_in = alpha before the step (load reversal)
  /// plastic: the backward-Euler steps over the whole substep and its two halves; the state is
  /// their Richardson extrapolation 2 B(h/2) B(h/2) - B(h).
  PlasticSolution whole, first_half, second_half;
};

struct Tape {
  std::vector<TapeEntry> entries;
  bool with_inputs = false;  ///< keep the input derivatives of every plastic step (for replay_tangent)
};

/// The values of the implicit integration (docs/model.md §4), in double, with the operations on
/// tape (when given). Defined in acst_implicit.cc.
UpdateStatus integrate_values(const Parameters<double>& par, const State<double>& start,
                              const Tensor<double>& strain_increment,
                              const IntegrationOptions& options, State<double>& end, Tape* tape,
                              long* substeps, std::string* reason = nullptr);

/// A converged plastic step lifted to the scalar T: values from the solution, derivative parts by
/// the implicit function theorem, dx = -J^-1 dR, dR the derivative parts of the residual at the
/// converged x (held constant) through the start state, the strain increment and the parameters.
template <typename T>
bool lift_plastic(const Parameters<T>& par, const State<T>& start, const Tensor<T>& deps,
                  const PlasticSolution& solution, State<T>& end) {
  PlasticStep<T> step;
  if (!make_step(par, start, deps, step)) return false;
  Unknowns<T> x;
  for (int i = 0; i < kUnknowns; ++i) x(i) = T(solution.x(i));
  Unknowns<T> r;
  if (!plastic_residual(par, step, x, r)) return false;
  constexpr int kN = decltype(T::v)::RowsAtCompileTime;
  Eigen::Matrix<double, kUnknowns, kN> dr;
  for (int i = 0; i < kUnknowns; ++i) dr.row(i) = r(i).v.transpose();
  const Eigen::Matrix<double, kUnknowns, kN> dx = -solution.lu.template solve<kN>(dr);
  for (int i = 0; i < kUnknowns; ++i) x(i).v = dx.row(i).transpose();
  return end_state(par, step, x, end);
}

/// The crossing fraction with the derivatives of f(t) = 0 (implicit function theorem:
/// dt = -df / (df/dt), df/dt = [2G n:de - K N eps_v] / p along the elastic path); the value is t.
template <typename T>
T lift_crossing(const Parameters<T>& par, const State<T>& start, const Tensor<T>& deps, double t) {
  State<T> at;
  if (!elastic_path(par, start, Tensor<T>(T(t) * deps), at)) return T(t);
  ModelQuantities<double> q;
  if (!evaluate_model(cast_parameters<double>(par), cast_state<double>(at), q) || !q.has_direction)
    return T(t);
  const Tensor<double> d = cast_tensor<double>(deps);
  const double w = d.trace();
  const double slope =
      (2.0 * q.G * detail::contract(q.n, Tensor<double>(d - (w / 3.0) * Tensor<double>::Identity())) -
       q.K * q.N * w) / q.p;
  if (!(std::abs(slope) > 0.0)) return T(t);
  T lifted = T(t) - relative_yield_function(par, at) / slope;
  lifted.a = t;
  return lifted;
}

/// 2 b - a for the integrated variables (Richardson extrapolation); alpha_in and e from b.
template <typename T>
State<T> richardson(const State<T>& a, const State<T>& b) {
  State<T> s = b;
  s.stress = 2.0 * b.stress - a.stress;
  s.alpha = 2.0 * b.alpha - a.alpha;
  s.fabric = 2.0 * b.fabric - a.fabric;
  return s;
}

/// alpha moved radially onto the cone around r: alpha = r - sqrt(2/3) m (r - alpha)/||r - alpha||.
/// The extrapolated state is off f = 0 by O(|b - a|^2 / (sqrt(2/3) m)) (f is curved on the scale
/// of the narrow cone); this keeps n and restores f = 0 exactly.
template <typename T>
void project_onto_cone(const Parameters<T>& par, State<T>& s) {
  using std::sqrt;
  const T p = s.stress.trace() / 3.0;
  const Tensor<T> ratio = (s.stress - p * Tensor<T>::Identity()) / p;
  const Tensor<T> x = ratio - s.alpha;
  const T squared = detail::contract(x, x);
  if (value_of(squared) > detail::kMinDirectionSquared)
    s.alpha = ratio - (kSqrtTwoThirds * par.m / sqrt(squared)) * x;
}

/// The state of a plastic step: the Richardson extrapolation of the whole step a and the two
/// half steps b, projected onto the cone.
template <typename T>
State<T> extrapolate(const Parameters<T>& par, const State<T>& a, const State<T>& b) {
  State<T> s = richardson(a, b);
  project_onto_cone(par, s);
  return s;
}

/// Replays the tape in the scalar T (a Jet type) from start; false where an operation fails.
template <typename T>
bool replay(const Parameters<T>& par, const State<T>& start, const Tensor<T>& strain_increment,
            const Tape& tape, State<T>& end) {
  State<T> s = start;
  T segment_scale(1.0);  // C of TapeEntry
  for (const TapeEntry& entry : tape.entries) {
    const Tensor<T> deps = (segment_scale * entry.step) * strain_increment;
    switch (entry.kind) {
      case TapeEntry::Kind::kElastic: {
        State<T> next;
        if (!elastic_path(par, s, deps, next)) return false;
        s = next;
        break;
      }
      case TapeEntry::Kind::kCrossing: {
        const T t = lift_crossing(par, s, deps, entry.t);
        State<T> next;
        if (!elastic_path(par, s, Tensor<T>(t * deps), next)) return false;
        s = next;
        segment_scale = (1.0 - entry.done - t * entry.step) * segment_scale;
        break;
      }
      case TapeEntry::Kind::kPlastic: {
        if (entry.reset_alpha_in) s.alpha_in = s.alpha;
        const Tensor<T> half = T(0.5) * deps;
        State<T> whole, first, second;
        if (!lift_plastic(par, s, deps, entry.whole, whole) ||
            !lift_plastic(par, s, half, entry.first_half, first) ||
            !lift_plastic(par, first, half, entry.second_half, second))
          return false;
        s = extrapolate(par, whole, second);
        break;
      }
    }
  }
  end = s;
  return true;
}

/// Copies the values (non-derivative parts) of v into the Jet state s.
template <typename T>
void set_state_values(State<T>& s, const State<double>& v) {
  auto set = [](Tensor<T>& x, const Tensor<double>& y) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) x(i, j).a = y(i, j);
  };
  set(s.stress, v.stress);
  set(s.alpha, v.alpha);
  set(s.alpha_in, v.alpha_in);
  set(s.fabric, v.fabric);
  s.void_ratio.a = v.void_ratio;
}

/// The consistent tangent of the implicit integration from the tape, by hand-written
/// sensitivities (acst_implicit.cc); Voigt layout d sigma_a / d eps_b, each shear seed moving
/// eps_kl and eps_lk together. false where an operation fails.
bool replay_tangent(const Parameters<double>& par, const State<double>& start,
                    const Tensor<double>& strain_increment, const Tape& tape,
                    Eigen::Matrix<double, 6, 6>& tangent);

}  // namespace implicit_detail

/// Implicit integration (docs/model.md §4). Values by integrate_values; for a Jet type the
/// derivative parts by replaying its tape, the values kept exactly those of the double run.
template <typename T>
UpdateStatus update_state_implicit(const Parameters<T>& par, const State<T>& start,
                                   const Tensor<T>& strain_increment, State<T>& end,
                                   const IntegrationOptions& options, long* substeps) {
  namespace id = implicit_detail;
  end = start;
  if constexpr (std::is_same_v<T, double>) {
    return id::integrate_values(par, start, strain_increment, options, end, nullptr, substeps);
  } else {
    if (!detail::is_finite(start) || !detail::is_finite(strain_increment))
      return UpdateStatus::kFailed;
    id::Tape tape;
    State<double> end_value;
    const UpdateStatus status =
        id::integrate_values(cast_parameters<double>(par), cast_state<double>(start),
                             cast_tensor<double>(strain_increment), options, end_value, &tape,
                             substeps);
    if (status == UpdateStatus::kFailed) return status;
    State<T> replayed;
    if (!id::replay(par, start, strain_increment, tape, replayed) || !detail::is_finite(replayed))
      return UpdateStatus::kFailed;
    id::set_state_values(replayed, end_value);
    end = replayed;
    return status;
  }
}

}  // namespace model::acst
