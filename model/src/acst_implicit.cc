// The implicit integration of the ACST model (acst_implicit.h, docs/model.md §4): the Newton
// solution of the backward-Euler step with its analytic Jacobian, the values run with its tape,
// and the consistent tangent by sensitivities along the tape.
#include "model/acst_model.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace model::acst {
namespace implicit_detail {

namespace {

using Voigt = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Row6 = Eigen::Matrix<double, 1, 6>;

// a:b = w . (a * b) for symmetric tensors in Voigt order with tensor shear components.
const Voigt kWeights = (Voigt() << 1.0, 1.0, 1.0, 2.0, 2.0, 2.0).finished();
const Voigt kDelta = (Voigt() << 1.0, 1.0, 1.0, 0.0, 0.0, 0.0).finished();

Voigt to_voigt(const Tensor<double>& t) {
  Voigt v;
  for (int k = 0; k < 6; ++k) v(k) = t(kRow[k], kCol[k]);
  return v;
}

Tensor<double> to_tensor(const Voigt& v) {
  Tensor<double> t;
  for (int k = 0; k < 6; ++k) {
    t(kRow[k], kCol[k]) = v(k);
    t(kCol[k], kRow[k]) = v(k);
  }
  return t;
}

// The derivatives of docs/model.md §3, Eq. (1)-(10) with e held (it is kinematic), chained by hand
// through the intermediate quantities; checked against Jets of plastic_residual in the tests.
// With inputs, also the derivatives w.r.t. the known data of the step.
//
// Each derivative is kept in the blocks of the unknowns it depends on, suffixes _s (d/d sigma,
// 6 columns), _a (d/d alpha) and _l (d/d dlambda): the stress ratio and the moduli depend on
// sigma only, and only the fabric (Eq. 16, through dlambda) carries a dlambda column, so most
// blocks are 6 x 6 or absent instead of full 6 x 13 rows.
bool plastic_derivatives(const Parameters<double>& par, const PlasticStep<double>& step,
                         const Unknowns<double>& x, Unknowns<double>& r, Jacobian& jacobian,
                         InputDerivatives* inputs) {
  const double k = kSqrtTwoThirds;
  const Voigt sigma = x.segment<6>(0), alpha = x.segment<6>(6);
  const double dlambda = x(kMultiplier);
  const double e = step.void_ratio;
  const Matrix6 I = Matrix6::Identity();

  // Mean stress, stress ratio, loading direction (Eq. 3-4).
  const double p = (sigma(0) + sigma(1) + sigma(2)) / 3.0;
  if (!(p > 0.0) || !(e > 0.0) || !(e < detail::kElasticVoidLimit)) return false;
  if (!(1.0 - par.c_h * e > 0.0)) return false;
  const Row6 d_p = kDelta.transpose() / 3.0;  // d p / d sigma
  const Voigt ratio = (sigma - p * kDelta) / p;
  // d ratio / d sigma = (I - u d_p) / p, u = delta + ratio: identity plus rank one.
  const Voigt u = kDelta + ratio;
  const Voigt xv = ratio - alpha;  // d xv = [d ratio, -I, 0]
  const double rho2 = kWeights.dot(xv.cwiseProduct(xv));
  if (!(rho2 > detail::kMinDirectionSquared)) return false;
  const double rho = std::sqrt(rho2);
  const Voigt n = xv / rho;
  const Voigt wn = kWeights.cwiseProduct(n);  // a : n = wn . a
  const double wn_u = wn.dot(u);
  const Row6 d_rho_s = (wn.transpose() - wn_u * d_p) / p, d_rho_a = -wn.transpose();
  // d n / d sigma = (I - u d_p - n wn^T + (wn . u) n d_p) / (p rho) and d n / d alpha =
  // -(I - n wn^T) / rho, the identity plus rank-one terms: a row times either is formed from
  // dot products (times_d_n_s, times_d_n_a), the matrices only for the Jacobian's blocks.
  const Matrix6 d_n_s = (I - u * d_p - n * (wn.transpose() - wn_u * d_p)) / (p * rho);
  const Matrix6 d_n_a = -(I - n * wn.transpose()) / rho;
  auto times_d_n_s = [&](const Row6& row) -> Row6 {
    const double row_n = row.dot(n.transpose());
    return (row - (row.dot(u.transpose()) - row_n * wn_u) * d_p - row_n * wn.transpose()) /
           (p * rho);
  };
  auto times_d_n_a = [&](const Row6& row) -> Row6 {
    return -(row - row.dot(n.transpose()) * wn.transpose()) / rho;
  };

  // Elastic moduli (Eq. 1) at fixed e.
  const double a = detail::kElasticVoidLimit - e;
  const double G = par.G0 * kAtmosphericPressure * a * a / (1.0 + e) *
                   detail::power(p / kAtmosphericPressure, par.n_G);
  const double kappa = 2.0 * (1.0 + par.nu) / (3.0 * (1.0 - 2.0 * par.nu));
  const double K = kappa * G;
  const Row6 d_G = (par.n_G * G / p) * d_p;  // d / d sigma only, as d_K = kappa d_G
  const Row6 d_K = kappa * d_G;

  // Lode angle and g (Eq. 4).
  const Tensor<double> n_tensor = to_tensor(n);
  const Voigt n2 = to_voigt(n_tensor * n_tensor);
  double cos3 = detail::kSqrtSix * kWeights.dot(n2.cwiseProduct(n));
  const Row6 w_cos3 = 3.0 * detail::kSqrtSix * kWeights.cwiseProduct(n2).transpose();
  Row6 d_cos3_s = times_d_n_s(w_cos3), d_cos3_a = times_d_n_a(w_cos3);
  if (cos3 > 1.0 || cos3 < -1.0) {
    cos3 = std::clamp(cos3, -1.0, 1.0);
    d_cos3_s.setZero();
    d_cos3_a.setZero();
  }
  const double g_denominator = (1.0 + par.c) - (1.0 - par.c) * cos3;
  const double g = 2.0 * par.c / g_denominator;
  const double g_factor = g * (1.0 - par.c) / g_denominator;
  const Row6 d_g_s = g_factor * d_cos3_s, d_g_a = g_factor * d_cos3_a;

  // State parameter (Eq. 5).
  const double p_ratio = std::pow(p / kAtmosphericPressure, par.xi);
  const double psi = e - (par.e_gamma - par.lambda_c * p_ratio);
  const Row6 d_psi = (par.lambda_c * par.xi * p_ratio / p) * d_p;  // d / d sigma only

  // The fabric eliminated by Eq. (16): F = (F_0 + dlambda k n) / (1 + dlambda k), with the rate
  // k = k_F exp(-n_F psi) of the end state.
  const double rate = fabric_rate(par, psi);
  const double fabric_denominator = 1.0 + dlambda * rate;
  const Voigt fabric = (to_voigt(step.start.fabric) + (dlambda * rate) * n) / fabric_denominator;
  const double fabric_factor = dlambda * rate / fabric_denominator;  // dF/dn at fixed dlambda
  const Voigt d_fabric_l = (rate / fabric_denominator) * (n - fabric);
  // Through k, F also depends on psi: dF/dpsi = (dlambda / (1 + dlambda k)) (n - F) dk/dpsi,
  // dk/dpsi = -n_F k (zero for LD12's constant rate, whose terms are then skipped).
  const bool rate_varies = par.n_F != 0.0;
  const Voigt d_fabric_psi =
      (dlambda * (-par.n_F * rate) / fabric_denominator) * (n - fabric);

  // Fabric anisotropy variable (Eq. 6).
  const double A = kWeights.dot(fabric.cwiseProduct(n));
  // d A = wn . dF + (w F) . dn with dF = fabric_factor dn (+ the dlambda and psi columns).
  const Row6 w_A = fabric_factor * wn.transpose() + kWeights.cwiseProduct(fabric).transpose();
  Row6 d_A_s = times_d_n_s(w_A);
  const double d_A_psi = wn.dot(d_fabric_psi);
  if (rate_varies) d_A_s += d_A_psi * d_psi;
  const Row6 d_A_a = times_d_n_a(w_A);
  const double d_A_l = wn.dot(d_fabric_l);
  const double zeta = psi - par.e_A * (A - 1.0);
  const Row6 d_zeta_s = d_psi - par.e_A * d_A_s, d_zeta_a = -par.e_A * d_A_a;
  const double d_zeta_l = -par.e_A * d_A_l;

  // Bounding and dilatancy surfaces (Eq. 7-9).
  // The bounding slope n_b, plus n_b_loose where psi > 0 (the derivative of that branch).
  const double n_bound = psi > 0.0 ? par.n_b + par.n_b_loose : par.n_b;
  const double exp_b = std::exp(-n_bound * psi), exp_d = std::exp(par.n_d * zeta);
  const double M_b = g * par.M_c * exp_b - par.m, M_d = g * par.M_c * exp_d - par.m;
  const Row6 d_M_b_s = par.M_c * exp_b * (d_g_s - (g * n_bound) * d_psi);
  const Row6 d_M_b_a = (par.M_c * exp_b) * d_g_a;
  const Row6 d_M_d_s = par.M_c * exp_d * (d_g_s + (g * par.n_d) * d_zeta_s);
  const Row6 d_M_d_a = par.M_c * exp_d * (d_g_a + (g * par.n_d) * d_zeta_a);
  const double d_M_d_l = par.M_c * exp_d * g * par.n_d * d_zeta_l;
  const Voigt alpha_b = (k * M_b) * n;  // d alpha_b = k (n d M_b + M_b d n), fused below
  const double alpha_n = wn.dot(alpha);
  const Row6 w_alpha = kWeights.cwiseProduct(alpha).transpose();
  const Row6 d_alpha_n_s = times_d_n_s(w_alpha);
  const Row6 d_alpha_n_a = wn.transpose() + times_d_n_a(w_alpha);
  const double D = par.A0 * (k * M_d - alpha_n);
  const Row6 d_D_s = par.A0 * (k * d_M_d_s - d_alpha_n_s);
  const Row6 d_D_a = par.A0 * (k * d_M_d_a - d_alpha_n_a);
  const double d_D_l = par.A0 * k * d_M_d_l;

  // Hardening (Eq. 10) with the floor of (alpha - alpha_in):n.
  const double b0 = par.G0 * par.h0 * (1.0 - par.c_h * e) / std::sqrt(p / kAtmosphericPressure);
  const Row6 d_b0 = (-b0 / (2.0 * p)) * d_p;  // d / d sigma only
  const Voigt alpha_in = to_voigt(step.start.alpha_in);
  const Row6 w_alpha_in = kWeights.cwiseProduct(alpha_in).transpose();
  double distance = alpha_n - wn.dot(alpha_in);
  Row6 d_distance_s = times_d_n_s(w_alpha - w_alpha_in);
  Row6 d_distance_a = wn.transpose() + times_d_n_a(w_alpha - w_alpha_in);
  const bool floored = distance < detail::kHardeningFloor;
  if (floored) {
    distance = detail::kHardeningFloor;
    d_distance_s.setZero();
    d_distance_a.setZero();
  }
  const double h = b0 / distance;
  const Row6 d_h_s = (d_b0 - h * d_distance_s) / distance;
  const Row6 d_h_a = (-h / distance) * d_distance_a;

  // Residual and its blocks.
  const Voigt flow = 2.0 * G * n + K * D * kDelta;
  r.segment<6>(0) = (sigma - to_voigt(step.stress_trial) + dlambda * flow) / step.scale;
  const Voigt back = alpha_b - alpha;
  const double hardening = dlambda * (2.0 / 3.0) * h;
  r.segment<6>(6) = alpha - to_voigt(step.start.alpha) - hardening * back;
  r(kMultiplier) = rho - k * par.m;
  const double inverse_scale = 1.0 / step.scale;
  jacobian.block<6, 6>(0, 0) =
      inverse_scale * (I + dlambda * (2.0 * n * d_G + (2.0 * G) * d_n_s +
                                      kDelta * (D * d_K + K * d_D_s)));
  jacobian.block<6, 6>(0, 6) = (inverse_scale * dlambda) * ((2.0 * G) * d_n_a + kDelta * (K * d_D_a));
  jacobian.block<6, 1>(0, kMultiplier) = inverse_scale * (flow + (dlambda * K * d_D_l) * kDelta);
  const double c_back = -(2.0 / 3.0) * dlambda;  // the alpha rows: I + c_back (...)
  jacobian.block<6, 6>(6, 0) =
      c_back * (back * d_h_s + (h * k) * n * d_M_b_s) + (c_back * h * k * M_b) * d_n_s;
  jacobian.block<6, 6>(6, 6) = c_back * (back * d_h_a + (h * k) * n * d_M_b_a) +
                               (c_back * h * k * M_b) * d_n_a + (1.0 - c_back * h) * I;
  jacobian.block<6, 1>(6, kMultiplier) = -((2.0 / 3.0) * h) * back;
  jacobian.block<1, 6>(kMultiplier, 0) = d_rho_s;
  jacobian.block<1, 6>(kMultiplier, 6) = d_rho_a;
  jacobian(kMultiplier, kMultiplier) = 0.0;
  if (!inputs) return true;

  // Derivatives w.r.t. the known data at fixed x (consistent tangent, docs/model.md §4): the
  // elastic predictor, the end void ratio (through G, K, psi and b0), alpha_0, F_0 (through A)
  // and alpha_in (through h).
  InputDerivatives& d = *inputs;
  const double dlog_g_de = -2.0 / a - 1.0 / (1.0 + e);  // G ~ (2.97 - e)^2 / (1 + e)
  const double dG_de = G * dlog_g_de, dK_de = K * dlog_g_de;
  const double dM_d_dzeta = par.M_c * exp_d * g * par.n_d;
  const double dD_de = par.A0 * k * dM_d_dzeta;            // d zeta / d e = d psi / d e = 1
  const double dD_dA = -par.A0 * k * dM_d_dzeta * par.e_A;  // d zeta / d A = -e_A
  // d zeta / d e = d psi / d e - e_A dA/de, and A depends on e through the fabric's rate.
  const double dD_de_total = dD_de + (rate_varies ? dD_dA * d_A_psi : 0.0);
  d.void_ratio.head<6>() =
      dlambda * (2.0 * dG_de * n + (dK_de * D + K * dD_de_total) * kDelta) / step.scale;
  d.fabric_start = 1.0 / fabric_denominator;  // dF / dF_0 (times the identity)
  d.fabric = (dlambda * K * dD_dA * d.fabric_start / step.scale) * kDelta;
  const double db0_de = -par.c_h * par.G0 * par.h0 / std::sqrt(p / kAtmosphericPressure);
  const double dh_de = db0_de / distance;
  const double dM_b_de = -par.M_c * exp_b * g * n_bound;
  d.void_ratio.tail<6>() = -(2.0 / 3.0) * dlambda * (dh_de * back + (h * k * dM_b_de) * n);
  if (floored)
    d.alpha_in.setZero();
  else
    d.alpha_in = (-(2.0 / 3.0) * dlambda * h / distance) * back;
  d.n_weighted = wn;
  d.fabric_unknowns.block<6, 6>(0, 0) = fabric_factor * d_n_s;
  if (rate_varies) d.fabric_unknowns.block<6, 6>(0, 0) += d_fabric_psi * d_psi;
  d.fabric_unknowns.block<6, 6>(0, 6) = fabric_factor * d_n_a;
  d.fabric_unknowns.col(kMultiplier) = d_fabric_l;
  d.fabric_void_ratio = d_fabric_psi;  // d psi / d e = 1
  return true;
}

}  // namespace

bool plastic_jacobian(const Parameters<double>& par, const PlasticStep<double>& step,
                      const Unknowns<double>& x, Unknowns<double>& r, Jacobian& jacobian) {
  return plastic_derivatives(par, step, x, r, jacobian, nullptr);
}

bool solve_plastic(const Parameters<double>& par, const PlasticStep<double>& step,
                   const Unknowns<double>& guess, PlasticSolution& solution, bool with_inputs) {
  constexpr int kMaxIterations = 30;
  constexpr double kTolerance = 1e-10;  // max |R_i| (all components dimensionless)
  InputDerivatives* inputs = with_inputs ? &solution.inputs : nullptr;
  solution.has_inputs = with_inputs;
  Unknowns<double> x = guess;
  Unknowns<double> r;
  Jacobian jacobian;
  if (!plastic_derivatives(par, step, x, r, jacobian, inputs)) return false;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const double largest = r.cwiseAbs().maxCoeff();
    if (!std::isfinite(largest)) return false;
    if (!solution.lu.compute(jacobian)) return false;
    if (largest <= kTolerance) {
      solution.x = x;
      solution.iterations = iteration;
      return true;
    }
    const Unknowns<double> dx = -solution.lu.solve<1>(r);
    if (!dx.allFinite()) return false;
    // Backtracking on ||R||: the full step unless it increases the residual.
    const double norm = r.norm();
    double lambda = 1.0;
    bool moved = false;
    for (int trial = 0; trial < 12; ++trial, lambda *= 0.5) {
      const Unknowns<double> candidate = x + lambda * dx;
      Unknowns<double> r_candidate;
      if (!plastic_derivatives(par, step, candidate, r_candidate, jacobian, inputs)) continue;
      if (r_candidate.norm() < (1.0 - 1e-4 * lambda) * norm) {
        x = candidate;
        r = r_candidate;
        moved = true;
        break;
      }
    }
    if (!moved) {
      // No decrease: at round-off if already small (the Jacobian and inputs are then those of
      // the last candidate, not of x: recompute them).
      if (largest > 1e3 * kTolerance ||
          !plastic_derivatives(par, step, x, r, jacobian, inputs) || !solution.lu.compute(jacobian))
        return false;
      solution.x = x;
      solution.iterations = iteration;
      return true;
    }
  }
  return false;
}

namespace {

// Error measure of docs/model.md §4 between two states: the stress difference relative to
// ||stress||, and the absolute differences of alpha, F and e.
double state_difference(const State<double>& a, const State<double>& b) {
  const double stress = (a.stress - b.stress).norm() / std::max(a.stress.norm(), 1e-300);
  return std::max(std::max(stress, (a.alpha - b.alpha).norm()),
                  std::max((a.fabric - b.fabric).norm(), std::abs(a.void_ratio - b.void_ratio)));
}

// Loading index <L> of Eq. (14) for the increment deps (0 where n is undefined).
double loading_index(const ModelQuantities<double>& q, const Tensor<double>& deps) {
  if (!q.has_direction) return 0.0;
  const double w = deps.trace();
  const Tensor<double> de = deps - (w / 3.0) * Tensor<double>::Identity();
  const double denominator = q.K_p + 2.0 * q.G - q.K * q.D * q.N;
  if (!(denominator > 0.0)) return 0.0;
  return std::max(0.0, (2.0 * q.G * detail::contract(q.n, de) - q.K * q.N * w) / denominator);
}

// The Euler (explicit) step of Eq. (13)-(16) from s over deps: the predictor of Newton and the
// reference of the error estimate without extrapolation.
bool euler_step(const Parameters<double>& par, const State<double>& s, const Tensor<double>& deps,
                State<double>& euler, double& multiplier) {
  ModelQuantities<double> q;
  if (!evaluate_model(par, s, q)) return false;
  detail::Increment<double> k1;
  if (!detail::increment(par, s, deps, true, k1)) return false;
  euler = s;
  detail::add_scaled(euler, k1, 1.0);
  multiplier = loading_index(q, deps);
  return true;
}

Unknowns<double> unknowns_of(const State<double>& s, double multiplier) {
  Unknowns<double> x;
  pack(s.stress, x, 0);
  pack(s.alpha, x, 6);
  x(kMultiplier) = multiplier;
  return x;
}

// One backward-Euler step from s over deps (guess: the Euler step when null, then the elastic
// trial); false where Newton does not converge or the step is not a loading one.
bool backward_euler(const Parameters<double>& par, const State<double>& s,
                    const Tensor<double>& deps, const Unknowns<double>* guess, bool with_inputs,
                    PlasticSolution& solution, State<double>& end) {
  PlasticStep<double> step;
  if (!make_step(par, s, deps, step)) return false;
  bool solved = false;
  if (guess) {
    solved = solve_plastic(par, step, *guess, solution, with_inputs);
  } else {
    State<double> euler;
    double multiplier = 0.0;
    solved = euler_step(par, s, deps, euler, multiplier) &&
             solve_plastic(par, step, unknowns_of(euler, multiplier), solution, with_inputs);
  }
  if (!solved) {
    Unknowns<double> trial = unknowns_of(s, 0.0);
    pack(step.stress_trial, trial, 0);
    if (!solve_plastic(par, step, trial, solution, with_inputs)) return false;
  }
  if (!(solution.x(kMultiplier) >= 0.0)) return false;  // <L> = 0: not a plastic step
  return end_state(par, step, solution.x, end);
}

// A plastic step as the values run takes it: the Richardson extrapolation 2 B(h/2)B(h/2) - B(h)
// of backward Euler (second order); error: the local error estimate (docs/model.md §4).
bool plastic_step(const Parameters<double>& par, const State<double>& s,
                  const Tensor<double>& deps, bool with_inputs, TapeEntry& entry,
                  State<double>& end, double& error) {
  const Tensor<double> half = 0.5 * deps;
  State<double> first, second, whole;
  if (!backward_euler(par, s, half, nullptr, with_inputs, entry.first_half, first)) return false;
  // Guesses: the first half continued linearly, then the two halves for the whole step.
  Unknowns<double> guess = 2.0 * entry.first_half.x - unknowns_of(s, 0.0);
  guess(kMultiplier) = entry.first_half.x(kMultiplier);
  if (!backward_euler(par, first, half, &guess, with_inputs, entry.second_half, second))
    return false;
  guess = entry.second_half.x;
  guess(kMultiplier) += entry.first_half.x(kMultiplier);
  if (!backward_euler(par, s, deps, &guess, with_inputs, entry.whole, whole)) return false;
  end = extrapolate(par, whole, second);
  error = state_difference(second, whole);  // the error of the half-step solution
  return detail::is_finite(end);
}

bool loading_from_surface(const Parameters<double>& par, const State<double>& s,
                          const Tensor<double>& deps) {
  ModelQuantities<double> q;
  if (!evaluate_model(par, s, q) || !q.has_direction) return false;
  const double w = deps.trace();
  const Tensor<double> de = deps - (w / 3.0) * Tensor<double>::Identity();
  return 2.0 * q.G * detail::contract(q.n, de) - q.K * q.N * w > 0.0;
}

// The fraction t in [t0, t1] of the elastic path deps at which f crosses zero, f(t0) < 0 < f(t1).
double elastic_crossing(const Parameters<double>& par, const State<double>& start,
                        const Tensor<double>& deps, double t0, double f0, double t1, double f1) {
  auto f = [&](double t, double& ft) {
    State<double> at;
    if (!elastic_path(par, start, Tensor<double>(t * deps), at)) return false;
    ft = relative_yield_function(par, at);
    return true;
  };
  return detail::pegasus_root(f, t0, f0, t1, f1, 1e-3 * detail::kYieldTolerance);
}

// For a path that ends outside the cone: the start of the bracket of the crossing, t_low with
// f(t_low) < 0 (0 from inside; unloading from the surface, where the path enters the cone and
// leaves it on the other side, a fraction inside it), or -1 where the step is a loading one.
double crossing_bracket(const Parameters<double>& par, const State<double>& s,
                        const Tensor<double>& deps, double f0, double& f_low) {
  if (f0 < -detail::kYieldTolerance) {
    f_low = f0;
    return 0.0;
  }
  if (loading_from_surface(par, s, deps)) return -1.0;
  for (double t = 0.5; t > 1e-12; t *= 0.5) {
    State<double> at;
    if (!elastic_path(par, s, Tensor<double>(t * deps), at)) return -1.0;
    const double ft = relative_yield_function(par, at);
    if (ft < -detail::kYieldTolerance) {
      f_low = ft;
      return t;
    }
  }
  return -1.0;
}

}  // namespace

UpdateStatus integrate_values(const Parameters<double>& par, const State<double>& start,
                              const Tensor<double>& strain_increment,
                              const IntegrationOptions& options, State<double>& end, Tape* tape,
                              long* substeps, std::string* reason) {
  end = start;
  if (tape) tape->entries.clear();
  auto fail = [&](const std::string& why) {
    if (reason) *reason = why;
    return UpdateStatus::kFailed;
  };
  auto where = [](double fraction) { return " (at fraction " + std::to_string(fraction) + ")"; };
  if (!detail::is_finite(start) || !detail::is_finite(strain_increment))
    return fail("non-finite start state or strain increment");
  if (!(start.stress.trace() / 3.0 >= options.min_pressure))
    return fail("mean stress " + std::to_string(start.stress.trace() / 3.0) +
                " Pa at the start is below the minimum " + std::to_string(options.min_pressure) +
                " Pa");

  State<double> s = start;
  Tensor<double> segment = strain_increment;
  double done = 0.0, step = 1.0;
  bool unreliable = false;
  bool on_surface_forced = false;  // just moved onto f = 0 by a crossing
  bool after_plastic = false;      // on f = 0 up to the extrapolation's O(h^3) drift
  bool grading = false;            // in the graded substeps of a fresh loading
  const double first_graded = std::ldexp(1.0, -std::max(options.loading_grading, 0));
  const double min_step = std::max(options.min_substep, 1e-15);
  const bool error_control = options.tolerance > 0.0;
  // Each operation is written in place on the tape (entries hold three Newton solutions: no
  // copies), or in a scratch entry without a tape; a rejected plastic attempt is taken back.
  TapeEntry scratch;
  auto next_entry = [&](TapeEntry::Kind kind) -> TapeEntry& {
    TapeEntry& entry = tape ? tape->entries.emplace_back() : scratch;
    entry.kind = kind;
    entry.step = step;
    entry.reset_alpha_in = false;
    return entry;
  };
  auto take_back = [&]() {
    if (tape) tape->entries.pop_back();
  };

  for (int attempts = 0; done < 1.0; ++attempts) {
    if (attempts >= options.max_substeps)
      return fail("max_substeps (" + std::to_string(options.max_substeps) + ") exhausted" +
                  where(done));
    if (substeps) ++*substeps;
    step = std::min(step, 1.0 - done);
    const bool can_shrink = 0.5 * step >= min_step;
    const Tensor<double> deps = step * segment;
    const double f0 = relative_yield_function(par, s);

    State<double> trial;
    if (!elastic_path(par, s, deps, trial)) {
      if (can_shrink) { step *= 0.5; continue; }
      return fail("the elastic response reaches p <= 0 or a void ratio outside (0, 2.97)" +
                  where(done));
    }
    const double f1 = relative_yield_function(par, trial);
    if (f1 <= detail::kYieldTolerance) {  // ends inside the cone (or on it): elastic
      if (trial.stress.trace() / 3.0 < options.min_pressure)
        return fail("mean stress falls below the minimum " + std::to_string(options.min_pressure) +
                    " Pa" + where(done));
      next_entry(TapeEntry::Kind::kElastic);
      s = trial;
      done += step;
      on_surface_forced = false;
      after_plastic = false;
      continue;
    }

    // Ends outside: elastic up to the crossing, and the rest of the increment a new segment.
    double f_low = 0.0;
    const double t_low = on_surface_forced
                             ? -1.0
                             : crossing_bracket(par, s, deps, after_plastic ? 0.0 : f0, f_low);
    if (t_low >= 0.0) {
      const double t = elastic_crossing(par, s, deps, t_low, f_low, 1.0, f1);
      State<double> at;
      if (!elastic_path(par, s, Tensor<double>(t * deps), at))
        return fail("the elastic path to the yield cone cannot be evaluated");
      TapeEntry& entry = next_entry(TapeEntry::Kind::kCrossing);
      entry.done = done;
      entry.t = t;
      s = at;
      segment = (1.0 - done - t * step) * segment;
      done = 0.0;
      step = 1.0;
      on_surface_forced = true;
      after_plastic = false;
      grading = false;
      continue;
    }

    // Plastic from the surface. Load reversal (DM04): alpha_in = alpha where (alpha - alpha_in):n < 0.
    State<double> from = s;
    bool reset_alpha_in = false;
    double distance = 1.0;  // (alpha - alpha_in):n at the start
    {
      ModelQuantities<double> q;
      if (evaluate_model(par, s, q) && q.has_direction) {
        distance = detail::contract(Tensor<double>(s.alpha - s.alpha_in), q.n);
        if (distance < 0.0) {
          from.alpha_in = from.alpha;
          reset_alpha_in = true;
          distance = 0.0;
        }
      }
    }
    // A fresh loading (alpha = alpha_in: first loading or just after a reversal) starts with the
    // knee of h = b0 / (alpha - alpha_in):n; its first substep is 2^-loading_grading of the
    // segment, the next ones double (docs/model.md §4). A fixed grading keeps the update smooth.
    if (done == 0.0 && !grading && distance <= 1e-12 && step > first_graded) {
      step = first_graded;
      grading = true;
      continue;
    }
    TapeEntry& entry = next_entry(TapeEntry::Kind::kPlastic);
    entry.reset_alpha_in = reset_alpha_in;
    State<double> next;
    double error = 0.0;
    if (!plastic_step(par, from, deps, tape && tape->with_inputs, entry, next, error)) {
      take_back();
      if (can_shrink) { step *= 0.5; continue; }
      return fail("the backward-Euler step does not converge at the minimum substep" + where(done));
    }
    if (error_control && error > options.tolerance) {
      if (can_shrink) {
        take_back();
        const double q = std::clamp(0.9 * std::sqrt(options.tolerance / error), 0.1, 0.5);
        step = std::max(detail::dyadic_floor(q * step), detail::dyadic_floor(min_step) * 2.0);
        continue;
      }
      unreliable = true;
      if (reason)
        *reason = "a substep of the minimum size has an error estimate " + std::to_string(error) +
                  " above the tolerance";
    }
    // Without error control the step is kept whatever its error (the update stays a smooth
    // function of the increment), but one beyond max_step_error is reported.
    if (!error_control && error > options.max_step_error) {
      unreliable = true;
      if (reason)
        *reason = "error estimate " + std::to_string(error) + " above max_step_error " +
                  std::to_string(options.max_step_error) + ": the increment is too large";
    }
    if (!detail::is_finite(next)) return fail("non-finite state after a plastic step");
    if (next.stress.trace() / 3.0 < options.min_pressure)
      return fail("mean stress falls below the minimum " + std::to_string(options.min_pressure) +
                  " Pa" + where(done));
    s = next;
    done += step;
    on_surface_forced = false;
    after_plastic = true;
    if (grading && !error_control) {
      step = std::min(done, 1.0 - done);  // 2^-L, 2^-L, 2^-(L-1), ..., 1/2
      if (done >= 1.0) grading = false;
    } else if (error_control) {  // the controller takes over from the graded first step
      const double q = error > 0.0 ? std::clamp(0.9 * std::sqrt(options.tolerance / error), 0.1, 2.0)
                                   : 2.0;
      step = std::min(1.0, std::max(detail::dyadic_floor(q * step),
                                    detail::dyadic_floor(min_step) * 2.0));
    } else {
      step = std::min(1.0, 2.0 * step);
    }
  }
  if (!detail::is_finite(s)) return fail("non-finite end state");
  end = s;
  if (!unreliable && reason) reason->clear();
  return unreliable ? UpdateStatus::kUnreliable : UpdateStatus::kOk;
}

namespace {

// d(state)/d(strain increment), each shear seed moving eps_kl and eps_lk together.
struct Sensitivity {
  Matrix6 stress = Matrix6::Zero(), alpha = Matrix6::Zero(), fabric = Matrix6::Zero(),
          alpha_in = Matrix6::Zero();
  Row6 void_ratio = Row6::Zero();
};

// (exprel)'(w) = (e^w (w - 1) + 1) / w^2, by its series near 0.
double exprel_derivative(double w) {
  if (std::abs(w) < 1e-2)
    return 0.5 + w * (1.0 / 3.0 + w * (1.0 / 8.0 + w * (1.0 / 30.0 + w * (1.0 / 144.0 + w / 840.0))));
  return (std::exp(w) * (w - 1.0) + 1.0) / (w * w);
}

// The elastic path of elastic_path and its derivatives w.r.t. the start stress, the start void
// ratio and the strain (Voigt, tensor components), from the same closed form.
struct ElasticJacobian {
  State<double> end;
  Matrix6 stress_stress, stress_strain;
  Voigt stress_void_ratio;
  double void_ratio_void_ratio = 0.0;
  Row6 void_ratio_strain;
};

bool elastic_jacobian(const Parameters<double>& par, const State<double>& start,
                      const Voigt& strain, ElasticJacobian& j) {
  if (!elastic_path(par, start, to_tensor(strain), j.end)) return false;
  const Voigt sigma0 = to_voigt(start.stress);
  const double w = kDelta.dot(strain);
  const Voigt de = strain - (w / 3.0) * kDelta;
  const double p0 = kDelta.dot(sigma0) / 3.0;
  const double u0 = 1.0 + start.void_ratio;
  const double c = 1.0 + detail::kElasticVoidLimit;
  const double ex = exprel(w), exm = exprel(-w);
  const double psi = c * c * ex / u0 - 2.0 * c + u0 * exm;
  const double dpsi_du0 = -c * c * ex / (u0 * u0) + exm;
  const double dpsi_dw = c * c * exprel_derivative(w) / u0 - u0 * exprel_derivative(-w);
  const double kappa = 2.0 * (1.0 + par.nu) / (3.0 * (1.0 - 2.0 * par.nu));
  const double n = par.n_G, x = 1.0 - n;
  const double c_g = par.G0 * detail::power(kAtmosphericPressure, x);
  const double p0_n = detail::power(p0, n);
  const double beta = x * kappa * c_g * p0_n / p0;  // z = beta w psi
  const double z = beta * w * psi;
  double growth, phi;
  detail::elastic_growth(z, x, growth, phi);
  const double shear = c_g * psi * p0_n * phi;
  // phi'(z) and d growth / dz; growth = (1 + z)^r, phi = ((1 + z)^r - 1) / (r z), r = 1/x.
  const double r = 1.0 / x;
  const double dgrowth_dz = r * growth / (1.0 + z);
  const double dphi_dz =
      std::abs(z) < 1e-4  // the series of elastic_growth, differentiated
          ? (r - 1.0) * (0.5 + z * ((r - 2.0) / 3.0 + z * (r - 2.0) * (r - 3.0) / 8.0))
          : (dgrowth_dz * z - (growth - 1.0)) / (r * z * z);
  // Differentials w.r.t. (p0, u0, w) of the scalars; p1 = p0 growth.
  const double dz_dp0 = -x * z / p0, dz_du0 = beta * w * dpsi_du0,
               dz_dw = beta * (psi + w * dpsi_dw);
  const double dp1_dp0 = growth + p0 * dgrowth_dz * dz_dp0, dp1_du0 = p0 * dgrowth_dz * dz_du0,
               dp1_dw = p0 * dgrowth_dz * dz_dw;
  const double dshear_dp0 = c_g * psi * p0_n * (n * phi / p0 + dphi_dz * dz_dp0);
  const double dshear_du0 = c_g * p0_n * (dpsi_du0 * phi + psi * dphi_dz * dz_du0);
  const double dshear_dw = c_g * p0_n * (dpsi_dw * phi + psi * dphi_dz * dz_dw);
  const Row6 dp0_dsigma = kDelta.transpose() / 3.0;
  const Row6 dw_dstrain = kDelta.transpose();
  // sigma1 = sigma0 - p0 delta + 2 shear de + p1 delta.
  j.stress_stress = Matrix6::Identity() +
                    (-kDelta + 2.0 * dshear_dp0 * de + dp1_dp0 * kDelta) * dp0_dsigma;
  j.stress_void_ratio = 2.0 * dshear_du0 * de + dp1_du0 * kDelta;
  j.stress_strain = (2.0 * dshear_dw * de + dp1_dw * kDelta) * dw_dstrain +
                    2.0 * shear * (Matrix6::Identity() - kDelta * kDelta.transpose() / 3.0);
  const double decay = std::exp(-w);  // e1 = e0 + u0 expm1(-w)
  j.void_ratio_void_ratio = decay;
  j.void_ratio_strain = -u0 * decay * dw_dstrain;
  return true;
}

// The elastic path with the sensitivities carried along; strain and its sensitivity.
bool elastic_sensitivity(const Parameters<double>& par, State<double>& s, Sensitivity& y,
                         const Voigt& strain, const Matrix6& d_strain) {
  ElasticJacobian j;
  if (!elastic_jacobian(par, s, strain, j)) return false;
  const Matrix6 stress = j.stress_stress * y.stress + j.stress_void_ratio * y.void_ratio +
                         j.stress_strain * d_strain;
  y.void_ratio = j.void_ratio_void_ratio * y.void_ratio + j.void_ratio_strain * d_strain;
  y.stress = stress;
  s = j.end;
  return true;
}

// The sensitivity of project_onto_cone at the state s before the projection:
// alpha' = r - k m x/|x| with x = r - alpha: d alpha' = dr - (k m/|x|)(dx - n (n : dx)).
void project_sensitivity(const Parameters<double>& par, const State<double>& s, Sensitivity& y) {
  const Voigt sigma = to_voigt(s.stress);
  const double p = kDelta.dot(sigma) / 3.0;
  const Voigt ratio = (sigma - p * kDelta) / p;
  const Voigt x = ratio - to_voigt(s.alpha);
  const double norm = std::sqrt(kWeights.dot(x.cwiseProduct(x)));
  if (!(norm > 0.0)) return;
  const Voigt n = x / norm;
  const Row6 dp = kDelta.transpose() * y.stress / 3.0;
  const Matrix6 d_ratio = (y.stress - kDelta * dp - ratio * dp) / p;
  const Matrix6 dx = d_ratio - y.alpha;
  const Matrix6 dn_part = dx - n * (kWeights.cwiseProduct(n).transpose() * dx);
  y.alpha = d_ratio - (kSqrtTwoThirds * par.m / norm) * dn_part;
}

// A converged backward-Euler step with the sensitivities carried along (implicit function
// theorem: dx = -J^-1 (dR/d inputs) d inputs).
bool plastic_sensitivity(const Parameters<double>& par, const State<double>& s,
                         const Sensitivity& y, const Voigt& strain, const Matrix6& d_strain,
                         const PlasticSolution& solution, State<double>& end, Sensitivity& y_end) {
  ElasticJacobian j;
  if (!elastic_jacobian(par, s, strain, j)) return false;
  PlasticStep<double> step;
  step.start = s;
  step.stress_trial = j.end.stress;
  step.void_ratio = j.end.void_ratio;
  step.scale = std::max(std::abs(s.stress.trace()) / 3.0, 1.0);
  InputDerivatives computed;
  const InputDerivatives* inputs = &solution.inputs;
  if (!solution.has_inputs) {
    Unknowns<double> r;
    Jacobian jacobian;
    if (!plastic_derivatives(par, step, solution.x, r, jacobian, &computed)) return false;
    inputs = &computed;
  }
  const Matrix6 d_trial =
      j.stress_stress * y.stress + j.stress_void_ratio * y.void_ratio + j.stress_strain * d_strain;
  const Row6 d_void_ratio = j.void_ratio_void_ratio * y.void_ratio + j.void_ratio_strain * d_strain;
  Eigen::Matrix<double, kUnknowns, 6> d_residual;  // InputDerivatives applied to d inputs
  d_residual.block<6, 6>(0, 0) = -d_trial / step.scale +
                                 inputs->void_ratio.head<6>() * d_void_ratio +
                                 inputs->fabric * (inputs->n_weighted.transpose() * y.fabric);
  d_residual.block<6, 6>(6, 0) = -y.alpha + inputs->void_ratio.tail<6>() * d_void_ratio +
                                 inputs->alpha_in * (inputs->n_weighted.transpose() * y.alpha_in);
  d_residual.row(kMultiplier).setZero();
  const Eigen::Matrix<double, kUnknowns, 6> dx = -solution.lu.solve<6>(d_residual);
  y_end.stress = dx.block<6, 6>(0, 0);
  y_end.alpha = dx.block<6, 6>(6, 0);
  y_end.fabric = inputs->fabric_unknowns.lazyProduct(dx) + inputs->fabric_start * y.fabric;
  if (par.n_F != 0.0) y_end.fabric += inputs->fabric_void_ratio * d_void_ratio;
  y_end.void_ratio = d_void_ratio;
  y_end.alpha_in = y.alpha_in;
  return end_state(par, step, solution.x, end);
}

}  // namespace

bool replay_tangent(const Parameters<double>& par, const State<double>& start,
                    const Tensor<double>& strain_increment, const Tape& tape, Matrix6& tangent) {
  State<double> s = start;
  Sensitivity y;
  double segment_scale = 1.0;  // C of TapeEntry, and its sensitivity
  Row6 d_segment_scale = Row6::Zero();
  const Voigt increment = to_voigt(strain_increment);
  for (const TapeEntry& entry : tape.entries) {
    const double c = segment_scale * entry.step;
    const Voigt strain = c * increment;
    const Matrix6 d_strain = increment * (entry.step * d_segment_scale) + c * Matrix6::Identity();
    switch (entry.kind) {
      case TapeEntry::Kind::kElastic:
        if (!elastic_sensitivity(par, s, y, strain, d_strain)) return false;
        break;
      case TapeEntry::Kind::kCrossing: {
        // f(elastic_path(s, t strain)) = 0: dt = -(df at fixed t) / (df/dt).
        const double t = entry.t;
        ElasticJacobian j;
        if (!elastic_jacobian(par, s, Voigt(t * strain), j)) return false;
        const double p = j.end.stress.trace() / 3.0;
        const Voigt ratio = (to_voigt(j.end.stress) - p * kDelta) / p;
        const Voigt x = ratio - to_voigt(j.end.alpha);
        const double norm = std::sqrt(kWeights.dot(x.cwiseProduct(x)));
        if (!(norm > 0.0)) return false;
        const Voigt wn = kWeights.cwiseProduct(x / norm);
        const Row6 f_stress = (wn - (wn.dot(ratio) / 3.0) * kDelta).transpose() / p;
        const Row6 f_alpha = -wn.transpose();
        const double f_t = f_stress * (j.stress_strain * strain);
        if (!(std::abs(f_t) > 0.0)) return false;
        const Matrix6 d_stress_fixed_t = j.stress_stress * y.stress +
                                         j.stress_void_ratio * y.void_ratio +
                                         j.stress_strain * (t * d_strain);
        const Row6 dt = -(f_stress * d_stress_fixed_t + f_alpha * y.alpha) / f_t;
        if (!elastic_sensitivity(par, s, y, Voigt(t * strain), Matrix6(strain * dt + t * d_strain)))
          return false;
        const double remaining = 1.0 - entry.done - t * entry.step;
        d_segment_scale = -entry.step * segment_scale * dt + remaining * d_segment_scale;
        segment_scale *= remaining;
        break;
      }
      case TapeEntry::Kind::kPlastic: {
        if (entry.reset_alpha_in) {
          s.alpha_in = s.alpha;
          y.alpha_in = y.alpha;
        }
        State<double> whole, first, second;
        Sensitivity y_whole, y_first, y_second;
        if (!plastic_sensitivity(par, s, y, strain, d_strain, entry.whole, whole, y_whole) ||
            !plastic_sensitivity(par, s, y, Voigt(0.5 * strain), Matrix6(0.5 * d_strain),
                                 entry.first_half, first, y_first) ||
            !plastic_sensitivity(par, first, y_first, Voigt(0.5 * strain),
                                 Matrix6(0.5 * d_strain), entry.second_half, second, y_second))
          return false;
        s = richardson(whole, second);
        y.stress = 2.0 * y_second.stress - y_whole.stress;
        y.alpha = 2.0 * y_second.alpha - y_whole.alpha;
        y.fabric = 2.0 * y_second.fabric - y_whole.fabric;
        y.void_ratio = y_second.void_ratio;
        y.alpha_in = y_second.alpha_in;
        project_sensitivity(par, s, y);
        project_onto_cone(par, s);
        break;
      }
    }
  }
  tangent = y.stress;
  return tangent.allFinite();
}

}  // namespace implicit_detail
}  // namespace model::acst
