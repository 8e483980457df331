// The contact-network model: a second material whose stress is the SFF equation of its state
// (sff-theory.md §4: sigma = E Z Lambda / (1 + e) [I/3 + (2/15)(A + F) + (2/105) tr(FA) I +
// (8/105) sym(FA) + F^t]) and whose state (e, Z, Lambda, A, F, F^t) is exactly what sff/ measures,
// so its laws are fitted to the DEM's micro histories directly (issue 19, point 2). In the spirit
// of He & Cai (Granular Matter 21, 2019), whose evolution laws were not retrieved: every rate law
// here is ours, derived and justified in docs/network-model.md.
//
// Conventions: compression positive (stress, strain, strain increment), stress in Pa, tensor
// shear components. A, F and F^t are deviatoric. Templated on the scalar type (double or a
// forward-mode dual number such as ceres::Jet) like acst_model.h, and on the tensors' form (a 3x3
// matrix, or a diagonal for paths with fixed principal axes: network_tensor.h); this header needs
// only Eigen.
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "model/network_tensor.h"
#include "model/parameter_field.h"

namespace model::network {

/// The reference normal force of the critical coordination line (Eq. N4): Lambda_ref = 1e-3, the
/// order of Lambda at 100-300 kPa in the DEM (docs/sff-results.md).
inline constexpr double kLambdaReference = 1e-3;

/// The state of a material point: void ratio e, coordination Z = 2 N_c / N_p, mean normalised
/// normal force Lambda, and the deviatoric fabric A, normal-force F and tangential-force F^t
/// anisotropy tensors, all as sff-theory.md §1-3 defines them, and the fabric's inherent part:
/// the memory of the specimen's initial fabric within A, which fades more slowly than the part
/// the loading builds (Eq. N2d; zero: none, the law before it). M is the tensors' form: a 3x3
/// matrix, or DiagonalTensor<T> where the principal axes stay fixed (network_tensor.h).
template <typename T, typename M = Tensor<T>>
struct State {
  T void_ratio, coordination, lambda;
  M fabric, normal, tangential;
  M inherent = M::Zero();
};

/// The fitted parameters (docs/network-model.md, Eqs. N1-N8), all dimensionless. Unset is NaN.
template <typename T>
struct Parameters {
  static T unset() { return T(std::numeric_limits<double>::quiet_NaN()); }
  T kappa = unset();  ///< stiffness of ln Lambda against volumetric strain (N6)
  T z_c = unset(), zeta = unset();  ///< critical coordination z_c (Lambda/Lambda_ref)^zeta (N4)
  T k_z = unset(), c_v = unset();   ///< Z's rate towards Z_c per shear strain; per volume (N5)
  T a_cs = unset(), a_z = unset(), k_a = unset();  ///< fabric A: critical norm, slope, rate (N2)
  T f_cs = unset(), f_z = unset(), k_f = unset();  ///< normal force F (N2)
  T t_cs = unset(), t_z = unset(), k_t = unset();  ///< tangential force F^t (N2)
  T d_z = unset(), d_a = unset();  ///< dilatancy from coordination and fabric (N7)
  T n_r = unset();  ///< the anisotropies' rate exponent in the over-coordination (N3)
  T n_z = unset();  ///< the coordination's rate exponent in the over-coordination (N5)
  /// The tangential anisotropy's target in triaxial extension over that in compression (the Lode
  /// factor g of N2b); 1, no Lode dependence, in files written before it.
  T c_t = unset();
  /// The coordination's gain with the normal force as a share of the critical line's (N5b):
  /// d ln Z = c_l zeta d ln Lambda at a given structure, c_l in [0, 1]; 0, none, in files written
  /// before it.
  T c_l = unset();
  /// The exponent of the normal force's stiffness in Lambda (N6): Lambda-rate = Lambda (Lambda /
  /// Lambda_ref)^(n_kappa - 1) (kappa / 3) (...), n_kappa in [0, 1]; 1 (a stiffness proportional
  /// to the force, ln Lambda linear in the strain) in files written before it, 0 for linear
  /// contacts under affine deformation.
  T n_kappa = unset();
  /// The critical void ratio line in the dilatancy (N7b): D gains d_psi (e_c - e), e_c = e_gamma -
  /// lambda_e ln(Lambda / Lambda_ref); d_psi = 0 (no anchor in the void ratio) in files written
  /// before it.
  T d_psi = unset(), e_gamma = unset(), lambda_e = unset();
  /// The void ratio's weight in the anisotropies' targets (N2c): they follow xi - w_psi (e - e_c)
  /// instead of xi alone; 0 (the coordination's excess alone) in files written before it.
  T w_psi = unset();
  /// The rate at which the fabric's inherent part fades, as a share of k_a (N2d), r_i in [0, 1];
  /// 1 (the inherent part fades with the rest of A: the law before it) in files written before it.
  T r_i = unset();
  /// The fabric's own rate exponent in the over-coordination, over the force anisotropies' n_r
  /// (N3b): A and its inherent part relax at k_a exp((n_r + n_ra) xi); 0 (the fabric at the
  /// forces' exp(n_r xi): the law before it) in files written before it.
  T n_ra = unset();
};

inline constexpr int kNumParameters = 27;
/// The parameters added after the first version come at the end of the order (c_t, c_l, n_kappa,
/// d_psi, e_gamma, lambda_e, w_psi, r_i, n_ra).
inline constexpr int kNumFirstVersionParameters = 18;
inline constexpr int kLodeFactorIndex = 18;
inline constexpr int kLambdaGainIndex = 19;
inline constexpr int kLambdaExponentIndex = 20;
inline constexpr int kStateDilatancyIndex = 21;
inline constexpr int kCriticalVoidRatioIndex = 22;
inline constexpr int kCriticalSlopeIndex = 23;
inline constexpr int kTargetVoidRatioWeightIndex = 24;
inline constexpr int kInherentFadeIndex = 25;
inline constexpr int kFabricRateExponentIndex = 26;

/// One parameter of the model (model/parameter_field.h). Each is dimensionless; its closed range
/// [low, high] is where the model is meant to be used (docs/network-model.md): validate refuses a
/// parameter outside it and the fit searches within it. c_v >= 0: compression adds contacts.
template <typename T>
using ParameterField = model::ParameterField<Parameters<T>, T>;

namespace detail {
template <typename T>
constexpr ParameterField<T> field(const char* name, T Parameters<T>::*member, double low,
                                  double high, double value_if_absent = kRequired) {
  return {name, member, "1", {low, high, true, true}, low, high, value_if_absent};
}
}  // namespace detail

/// The parameters in the order of the fit vector and of UMAT PROPS(22..48): the one list that the
/// parameter file, PROPS, validate, the fit's bounds and tables follow. A parameter added after the
/// first version has the value that gives the model as it was before it, where a parameter file or
/// PROPS does not give it: c_t = 1, no Lode dependence; c_l = 0, no gain of contacts with the
/// normal force; n_kappa = 1, ln Lambda linear in the strain; d_psi = 0, no critical void ratio
/// line, whose e_gamma and lambda_e then do nothing (0.8 and 0, values within their ranges);
/// w_psi = 0, targets in xi alone; r_i = 1, the inherent fabric fading with the rest; n_ra = 0,
/// the fabric at the forces' rate factor.
template <typename T>
inline constexpr std::array<ParameterField<T>, kNumParameters> kParameterFields = {{
    detail::field<T>("kappa", &Parameters<T>::kappa, 10.0, 1e5),
    detail::field<T>("z_c", &Parameters<T>::z_c, 2.0, 10.0),
    detail::field<T>("zeta", &Parameters<T>::zeta, 0.0, 1.0),
    detail::field<T>("k_z", &Parameters<T>::k_z, 0.0, 1000.0),
    detail::field<T>("c_v", &Parameters<T>::c_v, 0.0, 100.0),
    detail::field<T>("a_cs", &Parameters<T>::a_cs, 0.2, 3.0),
    detail::field<T>("a_z", &Parameters<T>::a_z, -5.0, 5.0),
    detail::field<T>("k_a", &Parameters<T>::k_a, 1.0, 1000.0),
    detail::field<T>("f_cs", &Parameters<T>::f_cs, 0.2, 3.0),
    detail::field<T>("f_z", &Parameters<T>::f_z, -5.0, 5.0),
    detail::field<T>("k_f", &Parameters<T>::k_f, 1.0, 3000.0),
    detail::field<T>("t_cs", &Parameters<T>::t_cs, 0.0, 0.5),
    detail::field<T>("t_z", &Parameters<T>::t_z, -1.0, 1.0),
    detail::field<T>("k_t", &Parameters<T>::k_t, 1.0, 5000.0),
    detail::field<T>("d_z", &Parameters<T>::d_z, -30.0, 30.0),
    detail::field<T>("d_a", &Parameters<T>::d_a, -30.0, 30.0),
    detail::field<T>("n_r", &Parameters<T>::n_r, -10.0, 10.0),
    detail::field<T>("n_z", &Parameters<T>::n_z, -10.0, 10.0),
    detail::field<T>("c_t", &Parameters<T>::c_t, 0.2, 2.0, 1.0),
    detail::field<T>("c_l", &Parameters<T>::c_l, 0.0, 1.0, 0.0),
    detail::field<T>("n_kappa", &Parameters<T>::n_kappa, 0.0, 1.0, 1.0),
    detail::field<T>("d_psi", &Parameters<T>::d_psi, 0.0, 30.0, 0.0),
    detail::field<T>("e_gamma", &Parameters<T>::e_gamma, 0.3, 1.5, 0.8),
    detail::field<T>("lambda_e", &Parameters<T>::lambda_e, 0.0, 0.3, 0.0),
    detail::field<T>("w_psi", &Parameters<T>::w_psi, 0.0, 10.0, 0.0),
    detail::field<T>("r_i", &Parameters<T>::r_i, 0.0, 1.0, 1.0),
    detail::field<T>("n_ra", &Parameters<T>::n_ra, -10.0, 10.0, 0.0),
}};

/// The value of the parameter at `index` in a parameter file or UMAT PROPS that does not give it
/// (kParameterFields' value_if_absent; NaN for the first version's, which every file gives).
inline double value_if_absent(int index) { return kParameterFields<double>[index].value_if_absent; }

/// Names in the order of to_array/from_array.
inline const std::array<const char*, kNumParameters>& parameter_names() {
  static const std::array<const char*, kNumParameters> names = [] {
    std::array<const char*, kNumParameters> n{};
    for (int i = 0; i < kNumParameters; ++i) n[i] = kParameterFields<double>[i].name;
    return n;
  }();
  return names;
}

template <typename T>
std::array<T, kNumParameters> to_array(const Parameters<T>& p) {
  std::array<T, kNumParameters> x;
  for (int i = 0; i < kNumParameters; ++i) x[i] = p.*kParameterFields<T>[i].member;
  return x;
}

template <typename T>
Parameters<T> from_array(const T* x) {
  Parameters<T> p;
  for (int i = 0; i < kNumParameters; ++i) p.*kParameterFields<T>[i].member = x[i];
  return p;
}

/// The low (high) ends of the parameters' ranges.
inline Parameters<double> lower_bounds() {
  Parameters<double> p;
  for (const ParameterField<double>& f : kParameterFields<double>) p.*f.member = f.fit_low;
  return p;
}

inline Parameters<double> upper_bounds() {
  Parameters<double> p;
  for (const ParameterField<double>& f : kParameterFields<double>) p.*f.member = f.fit_high;
  return p;
}

/// Throws std::invalid_argument naming the first parameter that is not finite or lies outside
/// its range.
inline void validate(const Parameters<double>& par) {
  for (const ParameterField<double>& f : kParameterFields<double>) {
    const double x = par.*f.member;
    if (!std::isfinite(x) || !f.physical.contains(x))
      throw std::invalid_argument(std::string("contact-network parameter ") + f.name + " = " +
                                  format_number(x) + " is not physical: it must be " +
                                  f.physical.describe());
  }
}

/// The parameter file (docs/network-model.md, "Parameter file"): {"model": "contact_network",
/// "youngs_modulus": {"value": E, "unit": "Pa"}, "parameters": {name: {"value": x, "unit": "1"}}},
/// other top-level keys (the fit's record) ignored. Throws std::runtime_error naming the file and
/// the key, or the parameter out of range; E [Pa] is returned through youngs_modulus if given.
Parameters<double> read_parameters_json(const std::string& path,
                                        double* youngs_modulus = nullptr);
/// Writes that layout, with the members of extra_json_object (a JSON object text) added at the
/// top level. Throws std::invalid_argument for parameters out of range, std::runtime_error if the
/// file cannot be written or the extra text is not a JSON object.
void write_parameters_json(const Parameters<double>& par, double youngs_modulus,
                           const std::string& path, const std::string& extra_json_object = "");

/// The SFF equation (sff-theory.md §4, He & Cai 2019 eq. C0) for the model's state; the grain
/// modulus E [Pa] is the DEM's (the normalisation of Lambda).
template <typename T, typename M>
M stress(const State<T, M>& s, double youngs_modulus) {
  const M& A = s.fabric;
  const M& F = s.normal;
  const M sym_FA = symmetric_product(F, A);
  const M bracket = plus_isotropic<T>(
      T(2.0 / 15.0) * (A + F) + T(8.0 / 105.0) * sym_FA + s.tangential,
      T(1.0 / 3.0) + T(2.0 / 105.0) * trace(sym_FA));
  return (T(youngs_modulus) * s.coordination * s.lambda / (T(1.0) + s.void_ratio)) * bracket;
}

/// Z_c(Lambda) = z_c (Lambda / Lambda_ref)^zeta (Eq. N4).
template <typename T>
T critical_coordination(const Parameters<T>& par, const T& lambda) {
  using std::pow;
  return par.z_c * pow(lambda / T(kLambdaReference), par.zeta);
}

/// ln(Lambda / Lambda_ref), in which the normal force's stiffness (Eq. N6) and the critical void
/// ratio (N7b) are written: a rate evaluation takes this one log for both.
template <typename T>
T log_normal_force(const T& lambda) {
  using std::log;
  return log(lambda / T(kLambdaReference));
}

/// e_c = e_gamma - lambda_e ln(Lambda / Lambda_ref) (log_force = log_normal_force(Lambda)), the
/// critical void ratio line of the dilatancy (Eq. N7b): a line in e - ln p, as the classical
/// critical state line, written in the network's own normal force (p is proportional to
/// Z Lambda / (1 + e), and at the critical state Z = Z_c(Lambda)).
template <typename T>
T critical_void_ratio(const Parameters<T>& par, const T& log_force) {
  return par.e_gamma - par.lambda_e * log_force;
}

/// (Lambda / Lambda_ref)^(n_kappa - 1), the factor of ln Lambda's stiffness kappa (Eq. N6), as
/// exp((n_kappa - 1) log_force), log_force = log_normal_force(Lambda): for dual numbers one exp
/// where pow of two duals takes two pows and a log; with n_kappa = 1 it is exp(0) = 1 exactly, the
/// law before n_kappa bit for bit.
template <typename T>
T stiffness_factor(const Parameters<T>& par, const T& log_force) {
  using std::exp;
  return exp((par.n_kappa - T(1.0)) * log_force);
}

/// Eq. N2b: the Lode factor of a target along the shearing direction n = d_s / |d_s| (d_s the
/// deviatoric strain rate, |d_s|^2 = shear_squared), g = 2c / ((1 + c) - (1 - c) cos 3 theta),
/// cos 3 theta = sqrt(6) tr n^3 clamped to [-1, 1]: 1 in triaxial compression, c in extension
/// (the interpolation ACST uses for M, docs/model.md Eq. 4, after Dafalias & Manzari 2004
/// Eq. 16). 1 without shear (its target term vanishes then).
template <typename T, typename M>
T lode_factor(const T& c, const M& deviator, const T& shear_squared) {
  using std::sqrt;
  if (!(shear_squared > T(0.0))) return T(1.0);
  const T norm = sqrt(shear_squared);
  T cos3 = T(std::sqrt(6.0)) * deviator_cube_trace(deviator) / (norm * norm * norm);
  if (cos3 > T(1.0)) cos3 = T(1.0);
  if (cos3 < T(-1.0)) cos3 = T(-1.0);
  return T(2.0) * c / ((T(1.0) + c) - (T(1.0) - c) * cos3);
}

/// The rate of the state for the strain rate d (compression positive), Eqs. N1-N8: the rates are
/// homogeneous of degree one in d, so a linear strain increment is integrated over a unit
/// pseudo-time with d = the increment.
template <typename T, typename M>
State<T, M> rate(const Parameters<T>& par, const State<T, M>& s, const M& d) {
  using std::exp;
  using std::sqrt;
  const T volumetric = trace(d);
  const M deviator = plus_isotropic<T>(d, -(volumetric / T(3.0)));
  // eps_q rate = sqrt(2/3 d_s:d_s), with no derivative singularity at a pure volume change.
  const T shear_squared = contract(deviator, deviator);
  const T shear = shear_squared > T(0.0) ? sqrt(T(2.0 / 3.0) * shear_squared) : T(0.0);
  const T critical = critical_coordination(par, s.lambda);
  const T excess = (s.coordination - critical) / critical;  // Eq. N3: over-coordination xi
  const T speed = exp(par.n_r * excess);  // Eq. N3: an over-coordinated network evolves faster
  // Eq. N3b: the fabric at its own rate factor exp((n_r + n_ra) xi): a dense fabric reaches its
  // critical norm within a few per cent of strain, a loose one over 20 % (n_ra = 0: exp(0) = 1,
  // the law before it bit for bit).
  const T fabric_speed = speed * exp(par.n_ra * excess);
  // How far the void ratio lies below the critical void ratio line e_c(Lambda) (N7b).
  const T log_force = log_normal_force(s.lambda);
  const T below_line = critical_void_ratio(par, log_force) - s.void_ratio;
  // Eq. N2c: the targets' state, the over-coordination plus w_psi (e_c - e), so that loose
  // specimens whose small xi differ in sign are not set apart (w_psi = 0: xi alone, the model
  // before it bit for bit).
  const T target_state = excess + par.w_psi * below_line;
  // Eq. N2: each anisotropy relaxes towards (x_cs + x_z xi) in the direction of shear, xi the
  // targets' state of N2c, (2/3) d_s = eps_q-rate times the unit triaxial direction (t(.) = 1 in
  // compression).
  auto towards = [&](const T& critical_norm, const T& slope, const T& rate_constant,
                     const T& factor, const M& x) -> M {
    return rate_constant * factor *
           (T(2.0 / 3.0) * (critical_norm + slope * target_state) * deviator - shear * x);
  };
  State<T, M> r;
  r.void_ratio = -(T(1.0) + s.void_ratio) * volumetric;  // Eq. N1
  // Eq. N2d: the fabric's inherent part A_i fades r_i times as fast as the rest, dA_i = -r_i k_a
  // exp((n_r + n_ra) xi) eps_q-rate A_i, and A relaxes towards its target plus what is left of
  // it: under a fixed target A = target (1 - exp(-k eps_q)) + (A_0 - A_i0) exp(-k eps_q) + A_i0
  // exp(-r_i k eps_q). With r_i = 1 or A_i = 0, A follows N2 alone, bit for bit.
  r.fabric = towards(par.a_cs, par.a_z, par.k_a, fabric_speed,
                     s.fabric - (T(1.0) - par.r_i) * s.inherent);
  r.inherent = (-(par.r_i * par.k_a * fabric_speed * shear)) * s.inherent;
  r.normal = towards(par.f_cs, par.f_z, par.k_f, speed, s.normal);
  // Eq. N2b: the tangential anisotropy's target depends on the Lode angle of shearing (in the
  // DEM its critical norm in extension is about two thirds of that in compression).
  const T g = lode_factor(par.c_t, deviator, shear_squared);
  r.tangential = towards(g * par.t_cs, g * par.t_z, par.k_t, speed, s.tangential);
  // Eq. N7: the dilatancy times the shear rate; A:d_s = a_d eps_q-rate, a_d the fabric's norm
  // along the shear direction. N7b: and the distance to the critical void ratio, so that a loose
  // network's contraction stops at its line (d_psi = 0: none, the model before it bit for bit).
  const T dilatancy_rate =
      par.d_z * excess * shear +
      par.d_a * (contract(s.fabric, deviator) - par.a_cs * shear) +
      par.d_psi * below_line * shear;
  // Eq. N6: d ln Lambda = (Lambda / Lambda_ref)^(n_kappa - 1) (kappa / 3) (d_v + D eps_q).
  const T log_lambda_rate =
      stiffness_factor(par, log_force) * par.kappa / T(3.0) * (volumetric + dilatancy_rate);
  r.lambda = s.lambda * log_lambda_rate;
  // Eq. N5 with N5b: towards Z_c under shear, contacts added by compression and by the growth of
  // the normal forces, at most as fast as Z_c grows with them (c_l <= 1), so that a growing Lambda
  // never raises the over-coordination that drives it (N7).
  r.coordination = par.k_z * exp(par.n_z * excess) * shear * (critical - s.coordination) +
                   par.c_v * volumetric + par.c_l * par.zeta * s.coordination * log_lambda_rate;
  return r;
}

template <typename T, typename M>
State<T, M> add_scaled(const State<T, M>& s, const State<T, M>& r, const T& h) {
  return {s.void_ratio + h * r.void_ratio, s.coordination + h * r.coordination,
          s.lambda + h * r.lambda,         s.fabric + h * r.fabric,
          s.normal + h * r.normal,         s.tangential + h * r.tangential,
          s.inherent + h * r.inherent};
}

/// Integrates a linear strain increment (compression positive) with `substeps` classical
/// fourth-order Runge-Kutta steps. The substep count is the caller's, so that a Newton iteration
/// on the increment sees one smooth function (substeps_for gives the usual choice).
template <typename T, typename M>
State<T, M> integrate(const Parameters<T>& par, const State<T, M>& start, const M& increment,
                      int substeps) {
  const T h = T(1.0 / substeps);
  State<T, M> s = start;
  for (int k = 0; k < substeps; ++k) {
    const State<T, M> k1 = rate(par, s, increment);
    const State<T, M> k2 = rate(par, add_scaled(s, k1, T(0.5) * h), increment);
    const State<T, M> k3 = rate(par, add_scaled(s, k2, T(0.5) * h), increment);
    const State<T, M> k4 = rate(par, add_scaled(s, k3, h), increment);
    State<T, M> sum = add_scaled(add_scaled(add_scaled(k1, k2, T(2.0)), k3, T(2.0)), k4, T(1.0));
    s = add_scaled(s, sum, h / T(6.0));
  }
  return s;
}

/// The update's substep size (network_update.h, the FE material and UMAT): RK4's local error is
/// then ~ 0.05^5 / 120 of the change. The fit takes larger substeps (FitOptions::substep_size).
inline constexpr double kUpdateSubstepSize = 0.05;

/// Substeps so that no rate constant times a substep's strain exceeds `step_size`, at the rate
/// factors exp(n_r xi) and the fabric's exp((n_r + n_ra) xi) of the state `at` (the start of the
/// increment). The stiffest coupling may be ln Lambda's through Z_c(Lambda), Z and e_c(Lambda) in
/// the dilatancy, kappa' (|d_z| zeta (1 + c_l Z/Z_c) + |d_a| + d_psi lambda_e) / 3, kappa' = kappa
/// (Lambda / Lambda_ref)^(n_kappa - 1) the stiffness of ln Lambda (N6).
template <typename M>
int substeps_for(const Parameters<double>& par, const State<double, M>& at, double strain_norm,
                 double step_size = kUpdateSubstepSize) {
  const double critical = critical_coordination(par, at.lambda);
  const double excess = (at.coordination - critical) / critical;
  const double speed = std::exp(std::min(par.n_r * excess, 30.0));
  const double fabric_speed = std::exp(std::min((par.n_r + par.n_ra) * excess, 30.0));
  const double kappa = par.kappa * stiffness_factor(par, log_normal_force(at.lambda));
  const double stiffest = std::max(
      {speed * std::max(par.k_f, par.k_t), fabric_speed * par.k_a,
       par.k_z * std::exp(std::min(par.n_z * excess, 30.0)), kappa / 3.0,
       kappa / 3.0 *
           (std::abs(par.d_z) * std::abs(par.zeta) * (1.0 + par.c_l * at.coordination / critical) +
            std::abs(par.d_a) + par.d_psi * par.lambda_e),
       1.0});
  const double n = std::ceil(stiffest * strain_norm / step_size);
  return !(n < 1e6) ? 1000000 : n < 1.0 ? 1 : static_cast<int>(n);
}

}  // namespace model::network
