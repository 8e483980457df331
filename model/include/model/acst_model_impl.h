// Template implementation of acst_model.h; include acst_model.h, not this file.
// Equation numbers refer to docs/model.md, which cites the sources (DM04, Li & Dafalias 2012,
// Sloan, Abbo & Sheng 2001) and marks the choices that are ours.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

namespace model::acst {

/// sqrt(2/3): the radius of the critical and bounding cones per unit m (docs/model.md), and the
/// factor from a triaxial scalar t(X) to X : n_c of an axisymmetric deviator (the fabric's).
constexpr double kSqrtTwoThirds = 0.81649658092772603273;

namespace detail {

constexpr double kSqrtSix = 2.44948974278317809820;
// Floor eps_h of (alpha - alpha_in):n in h = b0 / (alpha - alpha_in):n (ours, docs/model.md §3 Eq. 10).
constexpr double kHardeningFloor = 1e-6;
// |f|/p below which a state counts as on the yield surface (FTOL of Sloan et al.; ours).
constexpr double kYieldTolerance = 1e-9;
// Squared norm of r - alpha below which n is undefined (guards sqrt(0) for Jets).
constexpr double kMinDirectionSquared = 1e-28;

template <typename T>
T contract(const Tensor<T>& a, const Tensor<T>& b) {
  return a.cwiseProduct(b).sum();
}

template <typename T>
Tensor<T> identity() {
  return Tensor<T>::Identity();
}

template <typename T>
bool is_finite(const T& x) {
  if constexpr (std::is_same_v<T, double>) {
    return std::isfinite(x);
  } else {
    if (!is_finite(x.a)) return false;
    for (int i = 0; i < x.v.size(); ++i)
      if (!is_finite(x.v[i])) return false;
    return true;
  }
}

template <typename T>
bool is_finite(const Tensor<T>& t) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!is_finite(t(i, j))) return false;
  return true;
}

template <typename T>
bool is_finite(const State<T>& s) {
  return is_finite(s.stress) && is_finite(s.void_ratio) && is_finite(s.alpha) &&
         is_finite(s.alpha_in) && is_finite(s.fabric);
}

inline double value_norm(const Tensor<double>& t) { return t.norm(); }
template <typename T>
double value_norm(const Tensor<T>& t) {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) sum += value_of(t(i, j)) * value_of(t(i, j));
  return std::sqrt(sum);
}

/// 2^floor(log2 x) for x > 0: substep sizes are dyadic fractions of the increment (ours, docs/model.md §4).
inline double dyadic_floor(double x) {
  int exponent = 0;
  std::frexp(x, &exponent);  // x = m 2^exponent, m in [0.5, 1)
  return std::ldexp(1.0, exponent - 1);
}

/// Increments of the integrated variables over one substep.
template <typename T>
struct Increment {
  Tensor<T> stress, alpha, fabric;
  T void_ratio;
};

/// x^n for x > 0; the square root where n is exactly 1/2 (DM04's exponent: faster, and the
/// value of the first version bit for bit). A Jet takes pow, whose derivative in n it needs.
template <typename T>
T power(const T& x, const T& n) {
  using std::pow;
  using std::sqrt;
  if constexpr (std::is_same_v<T, double>)
    if (n == 0.5) return sqrt(x);
  return pow(x, n);
}

/// The growth of the mean stress along an elastic path (ours, docs/model.md §4.1): with
/// x = 1 - n_G, p^x grows linearly, p1 = p0 (1 + z)^(1/x); growth = (1 + z)^(1/x) and
/// phi = ((1 + z)^(1/x) - 1) / (z / x), which is 1 at z = 0 (a series near it).
template <typename T>
void elastic_growth(const T& z, const T& x, T& growth, T& phi) {
  using std::expm1;
  using std::log1p;
  if constexpr (std::is_same_v<T, double>) {
    if (x == 0.5) {  // (1 + z)^2 in closed form
      growth = (1.0 + z) * (1.0 + z);
      phi = 1.0 + 0.5 * z;
      return;
    }
  }
  const T r = 1.0 / x;
  if (std::abs(value_of(z)) < 1e-4) {
    const T a1 = r - 1.0, a2 = a1 * (r - 2.0), a3 = a2 * (r - 3.0);
    phi = 1.0 + z * (a1 / 2.0 + z * (a2 / 6.0 + z * (a3 / 24.0)));
    growth = 1.0 + r * z * phi;
    return;
  }
  const T g = expm1(r * log1p(z));
  growth = 1.0 + g;
  phi = g / (r * z);
}

template <typename T>
void elastic_moduli(const Parameters<T>& par, const T& p, const T& e, T& G, T& K) {
  // Eq. (1), DM04 Eq. (5) with the pressure exponent n_G (DM04: 1/2): hypoelastic moduli.
  const T a = kElasticVoidLimit - e;
  G = par.G0 * kAtmosphericPressure * a * a / (1.0 + e) *
      power(T(p / kAtmosphericPressure), par.n_G);
  K = G * 2.0 * (1.0 + par.nu) / (3.0 * (1.0 - 2.0 * par.nu));
}

template <typename T>
void add_scaled(State<T>& s, const Increment<T>& inc, double factor) {
  s.stress += T(factor) * inc.stress;
  s.alpha += T(factor) * inc.alpha;
  s.fabric += T(factor) * inc.fabric;
  s.void_ratio += T(factor) * inc.void_ratio;
}

}  // namespace detail

template <typename U, typename T>
Parameters<U> cast_parameters(const Parameters<T>& par) {
  Parameters<U> cast;
  for (std::size_t k = 0; k < kParameterFields<T>.size(); ++k)
    cast.*kParameterFields<U>[k].member = U(value_of(par.*kParameterFields<T>[k].member));
  return cast;
}

template <typename U, typename T>
Tensor<U> cast_tensor(const Tensor<T>& tensor) {
  Tensor<U> y;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) y(i, j) = U(value_of(tensor(i, j)));
  return y;
}

template <typename U, typename T>
State<U> cast_state(const State<T>& state) {
  return State<U>{cast_tensor<U>(state.stress), U(value_of(state.void_ratio)),
                  cast_tensor<U>(state.alpha), cast_tensor<U>(state.alpha_in),
                  cast_tensor<U>(state.fabric)};
}

template <typename T>
T relative_yield_function(const Parameters<T>& par, const State<T>& state) {
  using std::sqrt;
  const T p = state.stress.trace() / 3.0;
  const Tensor<T> x = (state.stress - p * detail::identity<T>()) / p - state.alpha;
  const T xx = detail::contract(x, x);
  // Eq. (3); the guard keeps sqrt(0) (derivative 1/0) out of Jets.
  const T norm = value_of(xx) > detail::kMinDirectionSquared ? sqrt(xx) : T(0.0);
  return norm - kSqrtTwoThirds * par.m;
}

/// Eq. (5), DM04 Eq. (7): the critical void ratio at mean stress p [Pa].
template <typename T>
T critical_void_ratio(const Parameters<T>& par, const T& p) {
  using std::pow;
  return par.e_gamma - par.lambda_c * pow(p / kAtmosphericPressure, par.xi);
}

/// The rate of Eq. (16), k_F exp(-n_F psi) (docs/model.md, ours): a denser state (psi < 0) turns
/// its fabric faster, a looser one slower; at the critical state (psi = 0) and for n_F = 0 it is
/// LD12's k_F, bit for bit.
template <typename T>
T fabric_rate(const Parameters<T>& par, const T& psi) {
  using std::exp;
  return par.k_F * exp(-par.n_F * psi);
}

template <typename T>
bool evaluate_model(const Parameters<T>& par, const State<T>& state, ModelQuantities<T>& q) {
  using std::exp;
  using std::sqrt;
  const Tensor<T> I = detail::identity<T>();
  const T& e = state.void_ratio;
  q.p = state.stress.trace() / 3.0;
  if (!(value_of(q.p) > 0.0) || !(value_of(e) > 0.0) ||
      !(value_of(e) < detail::kElasticVoidLimit))
    return false;
  detail::elastic_moduli(par, q.p, e, q.G, q.K);

  // Eq. (4): loading direction n = (r - alpha)/||r - alpha||, Lode angle and g(theta).
  const Tensor<T> x = (state.stress - q.p * I) / q.p - state.alpha;
  const T xx = detail::contract(x, x);
  q.has_direction = value_of(xx) > detail::kMinDirectionSquared;
  if (q.has_direction) {
    q.n = x / sqrt(xx);
  } else {
    q.n.setZero();
  }
  const Tensor<T> n2 = q.n * q.n;
  q.cos3theta = detail::kSqrtSix * detail::contract(n2, Tensor<T>(q.n.transpose()));  // sqrt6 tr(n^3)
  if (value_of(q.cos3theta) > 1.0) q.cos3theta = T(1.0);
  if (value_of(q.cos3theta) < -1.0) q.cos3theta = T(-1.0);
  q.g = 2.0 * par.c / ((1.0 + par.c) - (1.0 - par.c) * q.cos3theta);

  // Eq. (5)-(6): critical state line, state parameter, fabric anisotropy variable, zeta; the
  // fabric's rate of Eq. (16).
  q.e_c = critical_void_ratio(par, q.p);
  q.psi = e - q.e_c;
  q.A = detail::contract(state.fabric, q.n);
  q.zeta = q.psi - par.e_A * (q.A - 1.0);
  q.fabric_rate = fabric_rate(par, q.psi);

  // Eq. (7)-(8): bounding and dilatancy image back-stress ratios; the bounding slope is
  // n_b + n_b_loose where psi > 0 (docs/model.md, ours).
  const T loose_psi = value_of(q.psi) > 0.0 ? q.psi : T(0.0);
  q.alpha_b = (kSqrtTwoThirds *
               (q.g * par.M_c * exp(-par.n_b * q.psi - par.n_b_loose * loose_psi) - par.m)) *
              q.n;
  q.alpha_d = (kSqrtTwoThirds * (q.g * par.M_c * exp(par.n_d * q.zeta) - par.m)) * q.n;

  // Eq. (9)-(12): dilatancy, hardening, plastic modulus, N.
  q.D = par.A0 * detail::contract(Tensor<T>(q.alpha_d - state.alpha), q.n);
  const T b0 = par.G0 * par.h0 * (1.0 - par.c_h * e) / sqrt(q.p / kAtmosphericPressure);
  T distance = detail::contract(Tensor<T>(state.alpha - state.alpha_in), q.n);
  if (value_of(distance) < detail::kHardeningFloor) distance = T(detail::kHardeningFloor);
  q.h = b0 / distance;
  q.K_p = (2.0 / 3.0) * q.p * q.h * detail::contract(Tensor<T>(q.alpha_b - state.alpha), q.n);
  q.N = detail::contract(state.alpha, q.n) + kSqrtTwoThirds * par.m;
  return true;
}

namespace detail {

/// Rates of Eq. (13)-(16) over the strain increment deps; plastic = false gives the elastic
/// response. Returns false where the model cannot be evaluated.
template <typename T>
bool increment(const Parameters<T>& par, const State<T>& s, const Tensor<T>& deps, bool plastic,
               Increment<T>& inc) {
  ModelQuantities<T> q;
  if (!evaluate_model(par, s, q)) return false;
  if (!(value_of(1.0 - par.c_h * s.void_ratio) > 0.0)) return false;  // b0 must stay positive
  const Tensor<T> I = identity<T>();
  const T deps_v = deps.trace();
  const Tensor<T> de = deps - (deps_v / 3.0) * I;
  T L(0.0);
  if (plastic && q.has_direction) {
    // Eq. (14): loading index.
    const T denominator = q.K_p + 2.0 * q.G - q.K * q.D * q.N;
    if (!(value_of(denominator) > 0.0)) return false;
    L = (2.0 * q.G * contract(q.n, de) - q.K * q.N * deps_v) / denominator;
    if (!(value_of(L) > 0.0)) L = T(0.0);  // <L>
  }
  // Eq. (2), (13): elastic part of the strain increment and the stress increment.
  inc.stress = (2.0 * q.G) * (de - L * q.n) + (q.K * (deps_v - L * q.D)) * I;
  inc.void_ratio = -(1.0 + s.void_ratio) * deps_v;
  if (plastic && value_of(L) > 0.0) {
    inc.alpha = (L * (2.0 / 3.0) * q.h) * (q.alpha_b - s.alpha);  // Eq. (15)
    inc.fabric = (L * q.fabric_rate) * (q.n - s.fabric);            // Eq. (16)
  } else {
    inc.alpha.setZero();
    inc.fabric.setZero();
  }
  return true;
}

/// Value-part norm of a combination sum_i w_i x_i of tensors.
template <typename T, std::size_t N>
double combination_norm(const std::array<const Tensor<T>*, N>& x, const std::array<double, N>& w) {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double c = 0.0;
      for (std::size_t k = 0; k < N; ++k) c += w[k] * value_of((*x[k])(i, j));
      sum += c * c;
    }
  return std::sqrt(sum);
}

/// Local error measure of Sloan et al. (2001): the largest of the stress error relative to
/// ||stress||, and the absolute errors of alpha, F and e; `w` combines the stage increments into
/// the difference of the two embedded solutions.
template <typename T, std::size_t N>
double local_error(const std::array<const Increment<T>*, N>& k, const std::array<double, N>& w,
                   const State<T>& end) {
  std::array<const Tensor<T>*, N> stress, alpha, fabric;
  double e_void = 0.0;
  for (std::size_t i = 0; i < N; ++i) {
    stress[i] = &k[i]->stress;
    alpha[i] = &k[i]->alpha;
    fabric[i] = &k[i]->fabric;
    e_void += w[i] * value_of(k[i]->void_ratio);
  }
  const double stress_scale = std::max(value_norm(end.stress), 1e-300);
  const double e_stress = combination_norm(stress, w) / stress_scale;
  return std::max(std::max(e_stress, combination_norm(alpha, w)),
                  std::max(combination_norm(fabric, w), std::abs(e_void)));
}

/// For T = ceres::Jet: the largest error of the derivative parts relative to their size, over
/// stress, alpha and F (0 for double). The values alone do not see a stiff mode that only the
/// derivatives excite (e.g. d sigma_xx / d eps_xx on a symmetric triaxial path: the asymmetric
/// lateral mode), and an explicit step beyond its stability limit makes the derivatives grow
/// without bound while the values stay accurate (ours, docs/model.md §4).
template <typename T, std::size_t N>
double derivative_error(const std::array<const Increment<T>*, N>& k,
                        const std::array<double, N>& w, const State<T>& end) {
  if constexpr (std::is_same_v<T, double>) {
    return 0.0;
  } else {
    auto relative = [&](auto member) {
      double err = 0.0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          auto c = (w[0] * (k[0]->*member)(i, j).v).eval();
          for (std::size_t m = 1; m < N; ++m) c += w[m] * (k[m]->*member)(i, j).v;
          err += c.squaredNorm();
        }
      return err;
    };
    auto size_of = [](const Tensor<T>& x) {
      double sum = 0.0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) sum += x(i, j).v.squaredNorm();
      return sum;
    };
    const double e_stress = std::sqrt(relative(&Increment<T>::stress) /
                                      std::max(size_of(end.stress), 1e-300));
    const double e_alpha = std::sqrt(relative(&Increment<T>::alpha) /
                                     std::max(size_of(end.alpha), 1e-300));
    const double e_fabric = std::sqrt(relative(&Increment<T>::fabric) /
                                      std::max(size_of(end.fabric), 1e-300));
    return std::max(e_stress, std::max(e_alpha, e_fabric));
  }
}

/// Relative derivative error above which a substep counts as unstable for the derivatives
/// (stable steps give about the value tolerance; unstable ones order 1 and more).
constexpr double kDerivativeStabilityLimit = 1e-2;
/// The guard stops shrinking at this fraction of the segment (a kink of the hardening floor gives
/// an O(1) derivative error at any substep; it must not exhaust max_substeps).
constexpr double kDerivativeGuardMinStep = 1.0 / 4096.0;

/// One modified-Euler step (Sloan et al. 2001, Eq. 16-18): end = start + (k1 + k2)/2 with the
/// local error estimate ||k2 - k1||/2, relative to ||stress|| for the stress.
template <typename T>
bool modified_euler(const Parameters<T>& par, const State<T>& start, const Tensor<T>& deps,
                    bool plastic, State<T>& end, double& error, double& derivative) {
  Increment<T> k1, k2;
  if (!increment(par, start, deps, plastic, k1)) return false;
  State<T> euler = start;
  add_scaled(euler, k1, 1.0);
  if (!increment(par, euler, deps, plastic, k2)) return false;
  end = start;
  add_scaled(end, k1, 0.5);
  add_scaled(end, k2, 0.5);
  error = local_error<T, 2>({{&k1, &k2}}, {{-0.5, 0.5}}, end);
  derivative = derivative_error<T, 2>({{&k1, &k2}}, {{-0.5, 0.5}}, end);
  return is_finite(end) && std::isfinite(error);
}

/// One step of the embedded Runge-Kutta pair of order 3(2) of Bogacki & Shampine (1989, Appl.
/// Math. Lett. 2(4)): k1 = f(y), k2 = f(y + k1/2), k3 = f(y + 3k2/4),
/// end = y + (2k1 + 3k2 + 4k3)/9 (third order), k4 = f(end); the second-order solution
/// y + 7k1/24 + k2/4 + k3/3 + k4/8 differs from end by -5k1/72 + k2/12 + k3/9 - k4/8, which is the
/// local error estimate (measured as in modified_euler). Ours (docs/model.md §4): the same error
/// control as Sloan et al. (2001) with a third-order step, so the substeps scale as tol^(-1/3)
/// instead of tol^(-1/2).
template <typename T>
bool bogacki_shampine(const Parameters<T>& par, const State<T>& start, const Tensor<T>& deps,
                      bool plastic, State<T>& end, double& error, double& derivative) {
  Increment<T> k1, k2, k3, k4;
  if (!increment(par, start, deps, plastic, k1)) return false;
  State<T> stage = start;
  add_scaled(stage, k1, 0.5);
  if (!increment(par, stage, deps, plastic, k2)) return false;
  stage = start;
  add_scaled(stage, k2, 0.75);
  if (!increment(par, stage, deps, plastic, k3)) return false;
  end = start;
  add_scaled(end, k1, 2.0 / 9.0);
  add_scaled(end, k2, 1.0 / 3.0);
  add_scaled(end, k3, 4.0 / 9.0);
  if (!increment(par, end, deps, plastic, k4)) return false;
  error = local_error<T, 4>({{&k1, &k2, &k3, &k4}},
                            {{-5.0 / 72.0, 1.0 / 12.0, 1.0 / 9.0, -1.0 / 8.0}}, end);
  derivative = derivative_error<T, 4>({{&k1, &k2, &k3, &k4}},
                                      {{-5.0 / 72.0, 1.0 / 12.0, 1.0 / 9.0, -1.0 / 8.0}}, end);
  return is_finite(end) && std::isfinite(error);
}

/// One substep of the scheme chosen in the options.
template <typename T>
bool integration_step(const Parameters<T>& par, const State<T>& start, const Tensor<T>& deps,
                      bool plastic, State<T>& end, double& error,
                      const IntegrationOptions& options, double substep_fraction = 1.0) {
  double derivative = 0.0;
  const bool ok = options.scheme == IntegrationScheme::kModifiedEuler
                      ? modified_euler(par, start, deps, plastic, end, error, derivative)
                      : bogacki_shampine(par, start, deps, plastic, end, error, derivative);
  // An unstable derivative counts as an error above the tolerance, scaled so that the step
  // shrinks in proportion.
  // Only for the 3(2) pair: its larger substeps are the ones that reach the stability limit;
  // modified Euler's error control keeps its substeps far below it, while its first-order
  // derivative estimate is O(1) at the kink of the hardening floor and would only flag
  // those substeps as unreliable.
  if (ok && options.guard_derivatives && options.scheme == IntegrationScheme::kBogackiShampine &&
      !(derivative <= kDerivativeStabilityLimit) && substep_fraction > kDerivativeGuardMinStep)
    error = std::max(error, options.tolerance * derivative / kDerivativeStabilityLimit);
  return ok && std::isfinite(error);
}

/// Returns the state to f = 0 after a plastic substep: consistent correction at fixed total strain
/// (Sloan et al. 2001, Eq. 30-33), falling back to a correction normal to f.
template <typename T>
bool correct_drift(const Parameters<T>& par, State<T>& s) {
  const Tensor<T> I = identity<T>();
  for (int iteration = 0; iteration < 10; ++iteration) {
    const T f = relative_yield_function(par, s);
    if (std::abs(value_of(f)) <= kYieldTolerance) return true;
    ModelQuantities<T> q;
    if (!evaluate_model(par, s, q) || !q.has_direction) return false;
    const T f_abs = f * q.p;  // f in Pa
    const T denominator = 2.0 * q.G - q.N * q.K * q.D + q.K_p;  // a : D_e : m + K_p
    State<T> corrected = s;
    if (value_of(denominator) > 0.0) {
      const T dlambda = f_abs / denominator;
      corrected.stress -= dlambda * ((2.0 * q.G) * q.n + (q.K * q.D) * I);
      corrected.alpha += (dlambda * (2.0 / 3.0) * q.h) * (q.alpha_b - s.alpha);
      corrected.fabric += (dlambda * q.fabric_rate) * (q.n - s.fabric);
    }
    const T f_new = relative_yield_function(par, corrected);
    if (!(value_of(denominator) > 0.0) || !is_finite(corrected) ||
        std::abs(value_of(f_new)) > std::abs(value_of(f))) {
      // Normal correction: sigma -= f a / (a:a), a = df/dsigma = n - (N/3) I.
      const Tensor<T> a = q.n - (q.N / 3.0) * I;
      corrected = s;
      corrected.stress -= (f_abs / (1.0 + q.N * q.N / 3.0)) * a;
    }
    s = corrected;
    if (!is_finite(s)) return false;
  }
  return std::abs(value_of(relative_yield_function(par, s))) <= 10.0 * kYieldTolerance;
}

/// The root t in [t0, t1] of f, f(t0) < 0 < f(t1), by the Pegasus method (Sloan et al. 2001,
/// Algorithm 2), to |f| <= tolerance; f(t) returns false where it cannot be evaluated (t is then
/// returned as it is).
template <typename F>
double pegasus_root(F&& f, double t0, double f0, double t1, double f1, double tolerance) {
  double t = t1;
  for (int iteration = 0; iteration < 60; ++iteration) {
    t = t1 - f1 * (t1 - t0) / (f1 - f0);
    double ft = 0.0;
    if (!f(t, ft)) return t;
    if (std::abs(ft) <= tolerance) return t;
    if (ft * f0 < 0.0) {
      t1 = t0;
      f1 = f0;
    } else {
      f1 = f1 * f0 / (f0 + ft);
    }
    t0 = t;
    f0 = ft;
  }
  return t;
}

/// Fraction t in (0, 1] of an elastic step deps at which f crosses zero, f0 < 0 < f1 the values at
/// t = 0 and t = 1.
template <typename T>
double elastic_intersection(const Parameters<T>& par, const State<T>& start, const Tensor<T>& deps,
                            double f0, double f1, const IntegrationOptions& options) {
  auto f = [&](double t, double& ft) {
    State<T> at;
    double error = 0.0;
    if (!integration_step(par, start, Tensor<T>(T(t) * deps), false, at, error, options))
      return false;
    ft = value_of(relative_yield_function(par, at));
    return true;
  };
  return pegasus_root(f, 0.0, f0, 1.0, f1, 0.01 * kYieldTolerance);
}

}  // namespace detail

/// Explicit substepping (Bogacki-Shampine 3(2) or modified Euler) with error control and drift correction (Sloan, Abbo &
/// Sheng 2001), over dyadic substeps (ours): docs/model.md §4.
template <typename T>
UpdateStatus update_state_explicit(const Parameters<T>& par, const State<T>& start,
                                   const Tensor<T>& strain_increment, State<T>& end,
                                   const IntegrationOptions& options, long* substeps) {
  end = start;
  if (!(options.tolerance > 0.0)) return UpdateStatus::kFailed;  // explicit needs a tolerance
  if (!detail::is_finite(start) || !detail::is_finite(strain_increment)) return UpdateStatus::kFailed;
  if (!(value_of(start.stress.trace()) / 3.0 >= options.min_pressure)) return UpdateStatus::kFailed;

  State<T> s = start;
  Tensor<T> segment = strain_increment;  // strain still to apply is (1 - done) * segment
  double done = 0.0;                     // dyadic fraction of segment applied so far
  double step = 1.0;                     // dyadic substep, as a fraction of segment
  bool unreliable = false;
  bool on_surface_forced = false;        // just moved onto f = 0 by the intersection search
  const double min_step = std::max(options.min_substep, 1e-15);

  for (int attempts = 0; done < 1.0; ++attempts) {
    if (attempts >= options.max_substeps) return UpdateStatus::kFailed;
    if (substeps) ++*substeps;
    step = std::min(step, 1.0 - done);
    const bool can_shrink = 0.5 * step >= min_step;
    const Tensor<T> deps = T(step) * segment;
    const double f0 = value_of(relative_yield_function(par, s));
    State<T> trial;
    double error = 0.0;

    // Step factor 0.9 (tol/err)^(1/(order+1)) of the lower-order solution's error.
    const double exponent = options.scheme == IntegrationScheme::kModifiedEuler ? 0.5 : 1.0 / 3.0;
    auto shrink = [&](double err) {
      const double q = std::isfinite(err) && err > 0.0
                           ? std::clamp(0.9 * std::pow(options.tolerance / err, exponent), 0.1, 0.5)
                           : 0.1;
      step = std::max(detail::dyadic_floor(q * step), detail::dyadic_floor(min_step) * 2.0);
    };
    auto accept = [&](const State<T>& next, double err) {
      s = next;
      done += step;
      const double q = err > 0.0
                           ? std::clamp(0.9 * std::pow(options.tolerance / err, exponent), 0.1, 2.0)
                           : 2.0;
      step = std::min(1.0, detail::dyadic_floor(q * step));
      if (step < min_step) step = detail::dyadic_floor(min_step) * 2.0;
      on_surface_forced = false;
    };

    const bool inside = f0 < -detail::kYieldTolerance && !on_surface_forced;
    bool plastic = !inside;
    if (plastic) {
      // On the surface: elastic unloading if the loading index is not positive.
      ModelQuantities<T> q;
      if (!evaluate_model(par, s, q)) return UpdateStatus::kFailed;
      if (q.has_direction) {
        const T deps_v = deps.trace();
        const T numerator =
            2.0 * q.G * detail::contract(q.n, Tensor<T>(deps - (deps_v / 3.0) * detail::identity<T>())) -
            q.K * q.N * deps_v;
        plastic = value_of(numerator) > 0.0;
      } else {
        plastic = false;
      }
    }

    if (!plastic) {
      if (!detail::integration_step(par, s, deps, false, trial, error, options, step)) {
        if (can_shrink) { shrink(0.0); continue; }
        return UpdateStatus::kFailed;
      }
      if (error > options.tolerance) {
        if (can_shrink) { shrink(error); continue; }
        unreliable = true;
      }
      const double f1 = value_of(relative_yield_function(par, trial));
      if (f1 <= detail::kYieldTolerance) {
        if (value_of(trial.stress.trace()) / 3.0 < options.min_pressure) return UpdateStatus::kFailed;
        accept(trial, error);
        continue;
      }
      if (!inside) {
        // Unloading that reloads within the substep: subdivide, or at the minimum substep treat
        // it as plastic (drift correction returns it to f = 0).
        if (can_shrink) { step *= 0.5; continue; }
        plastic = true;
      } else {
        // Crosses f = 0: move elastically to the intersection, then restart the segment there.
        double t = detail::elastic_intersection(par, s, deps, f0, f1, options);
        State<T> at;
        double e_at = 0.0;
        if (!detail::integration_step(par, s, Tensor<T>(T(t) * deps), false, at, e_at, options))
          return UpdateStatus::kFailed;
        // Implicit-function correction so that t carries the derivatives of f(t) = 0 (Jets):
        // t <- t - f(t) / f'(t), f'(t) = df/dsigma : dsigma/dt.
        ModelQuantities<T> q;
        T t_corrected = T(t);
        if (evaluate_model(par, at, q) && q.has_direction) {
          detail::Increment<T> rate;
          if (detail::increment(par, at, deps, false, rate)) {
            const Tensor<T> a = q.n - (q.N / 3.0) * detail::identity<T>();
            const double dfdt = value_of(detail::contract(a, rate.stress)) / value_of(q.p);
            if (dfdt > 0.0) {
              t_corrected = T(t) - relative_yield_function(par, at) / dfdt;
              if (!detail::integration_step(par, s, Tensor<T>(t_corrected * deps), false, at, e_at,
                                           options))
                return UpdateStatus::kFailed;
            }
          }
        }
        s = at;
        segment = (T(1.0 - done) - t_corrected * step) * segment;
        done = 0.0;
        step = 1.0;
        on_surface_forced = true;
        continue;
      }
    }

    // Plastic substep. Load reversal (DM04): alpha_in = alpha where (alpha - alpha_in):n < 0.
    {
      ModelQuantities<T> q;
      if (evaluate_model(par, s, q) && q.has_direction &&
          value_of(detail::contract(Tensor<T>(s.alpha - s.alpha_in), q.n)) < 0.0)
        s.alpha_in = s.alpha;
    }
    if (!detail::integration_step(par, s, deps, true, trial, error, options, step)) {
      if (can_shrink) { shrink(0.0); continue; }
      return UpdateStatus::kFailed;
    }
    if (error > options.tolerance) {
      if (can_shrink) { shrink(error); continue; }
      unreliable = true;
    }
    if (!detail::correct_drift(par, trial)) {
      if (can_shrink) { shrink(0.0); continue; }
      return UpdateStatus::kFailed;
    }
    if (value_of(trial.stress.trace()) / 3.0 < options.min_pressure) return UpdateStatus::kFailed;
    accept(trial, error);
  }
  if (!detail::is_finite(s)) return UpdateStatus::kFailed;
  end = s;
  return unreliable ? UpdateStatus::kUnreliable : UpdateStatus::kOk;
}

}  // namespace model::acst
