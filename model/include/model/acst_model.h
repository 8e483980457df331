// The fabric-based sand model of the anisotropic critical state theory (ACST) family: Dafalias &
// Manzari (2004, "DM04") with the fabric tensor and dilatancy state parameter of Li & Dafalias
// (2012), integrated by explicit substepping with error control (Sloan, Abbo & Sheng 2001; a
// third-order Bogacki-Shampine step by default).
// Equations, parameters, status codes and every choice of ours: docs/model.md.
//
// Conventions: compression positive (stress, strain and their increments); stress in Pa; the
// shear components of strain tensors are tensor components (eps_xy), not engineering (gamma_xy).
// Everything that depends on the scalar type is a template on T (double, or a forward-mode dual
// number with the value in .a and the derivatives in .v, such as ceres::Jet): the same code gives
// the stress (double) and derivatives w.r.t. parameters (Jets seeded on parameters). This header
// does not include Ceres: it is the public interface of the installed sffcal::model.
#pragma once

#include <Eigen/Core>

#include <array>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "model/descriptor.h"
#include "model/parameter_field.h"
#include "model/parameter_file.h"
#include "model/update_status.h"

namespace model::acst {

/// p_a, the reference pressure of the model [Pa].
inline constexpr double kAtmosphericPressure = 101325.0;

template <typename T>
using Tensor = Eigen::Matrix<T, 3, 3>;  // symmetric, compression positive

/// The 15 parameters of acst-model.md, then three of ours (docs/model.md): n_b_loose, the
/// bounding surface's added slope on the loose side (Eq. 7; 0 is the model of acst-model.md), n_G,
/// the pressure exponent of the elastic moduli (Eq. 1; 1/2 is acst-model.md's), and n_F, the
/// state exponent of the fabric rate (Eq. 16; 0 is acst-model.md's). All are dimensionless (G0
/// multiplies p_a). Each starts unset (NaN), which validate_parameters refuses by name: a set
/// filled in member by member that misses one is an error, not an indeterminate value.
template <typename T>
struct Parameters {
  static T unset() { return T(std::numeric_limits<double>::quiet_NaN()); }
  T G0 = unset(), nu = unset(), M_c = unset(), c = unset(), e_gamma = unset(),
    lambda_c = unset(), xi = unset(), m = unset(), h0 = unset(), c_h = unset(), n_b = unset(),
    A0 = unset(), n_d = unset(), e_A = unset(), k_F = unset(), n_b_loose = unset(),
    n_G = unset(), n_F = unset();
};

namespace detail {
/// The void ratio where the elastic law's (2.97 - e)^2 vanishes (DM04 Eq. 5).
inline constexpr double kElasticVoidLimit = 2.97;
inline constexpr double kUnbounded = model::kUnbounded;
}  // namespace detail

using model::ParameterRange;

/// One parameter of acst-model.md (model/parameter_field.h): besides its range,
/// validate_parameters checks the coupled conditions m < c M_c and c_h e_gamma < 1; every
/// parameter is dimensionless (unit "1": G0 multiplies p_a).
template <typename T>
using ParameterField = model::ParameterField<Parameters<T>, T>;

/// The parameters in the order of acst-model.md, then n_b_loose, n_G and n_F (ours): the one
/// list that the parameter file, its validation, the fit vector, the fit's bounds and tables and
/// docs/model.md's table follow.
template <typename T>
inline constexpr std::array<ParameterField<T>, 18> kParameterFields = {{
    {"G0", &Parameters<T>::G0, "1", {0.0, detail::kUnbounded, false, false}, 5.0, 3000.0},
    {"nu", &Parameters<T>::nu, "1", {-1.0, 0.5, false, false}, 0.0, 0.45},
    {"M_c", &Parameters<T>::M_c, "1", {0.0, detail::kUnbounded, false, false}, 0.3, 2.5},
    {"c", &Parameters<T>::c, "1", {0.0, 1.0, false, true}, 0.5, 1.0},
    {"e_gamma", &Parameters<T>::e_gamma, "1", {0.0, detail::kElasticVoidLimit, false, false}, 0.2, 2.0},
    {"lambda_c", &Parameters<T>::lambda_c, "1", {0.0, detail::kUnbounded, true, false}, 0.0, 0.5},
    {"xi", &Parameters<T>::xi, "1", {0.0, detail::kUnbounded, false, false}, 0.1, 1.5},
    // m >= 1e-4: the backward-Euler step converges only on substeps that shrink as sqrt(m)
    // (measured on a 0.3 % triaxial increment: 29 plastic substeps at m = 1e-4, 256 at 1e-6,
    // 2365 at 1e-8), and at 1e-8 the cone's radius sqrt(2/3) m is within ten times the yield
    // tolerance kYieldTolerance; DM04 and LD12 use 0.01.
    {"m", &Parameters<T>::m, "1", {1e-4, detail::kUnbounded, true, false}, 0.001, 0.1},
    {"h0", &Parameters<T>::h0, "1", {0.0, detail::kUnbounded, false, false}, 0.05, 200.0},
    {"c_h", &Parameters<T>::c_h, "1", {0.0, detail::kUnbounded, true, false}, 0.0, 2.0},
    {"n_b", &Parameters<T>::n_b, "1", {0.0, detail::kUnbounded, true, false}, 0.0, 10.0},
    {"A0", &Parameters<T>::A0, "1", {0.0, detail::kUnbounded, true, false}, 0.01, 10.0},
    {"n_d", &Parameters<T>::n_d, "1", {0.0, detail::kUnbounded, true, false}, 0.0, 20.0},
    {"e_A", &Parameters<T>::e_A, "1", {0.0, detail::kUnbounded, true, false}, 0.0, 3.0},
    {"k_F", &Parameters<T>::k_F, "1", {0.0, detail::kUnbounded, true, false}, 0.0, 200.0},
    {"n_b_loose", &Parameters<T>::n_b_loose, "1", {0.0, detail::kUnbounded, true, false}, 0.0,
     60.0, 0.0},
    {"n_G", &Parameters<T>::n_G, "1", {0.0, 1.0, true, false}, 0.0, 0.9, 0.5},
    // n_F <= 100 keeps exp(-n_F psi) finite and meaningful (below 1e22) for |psi| <= 0.5.
    {"n_F", &Parameters<T>::n_F, "1", {0.0, 100.0, true, true}, 0.0, 40.0, 0.0},
}};

template <typename T>
struct State {
  Tensor<T> stress;    // effective stress [Pa], compression positive
  T void_ratio;
  Tensor<T> alpha;     // back-stress ratio (deviatoric)
  Tensor<T> alpha_in;  // alpha at last load reversal
  Tensor<T> fabric;    // model fabric F (deviatoric)
};

/// The update's outcome (model/update_status.h). For ACST, kOk: integrated to tolerance.
/// kUnreliable: integrated over the whole increment, but at least one substep of the minimum size
/// was accepted with a local error above the tolerance, or (implicit without error control) a step
/// whose error estimate exceeds max_step_error. kFailed: not integrated (non-finite input or
/// result, p below options.min_pressure, e outside the range of the elastic law, no admissible
/// plastic modulus, max_substeps exhausted); the returned state is then the start state, unchanged.
using model::UpdateStatus;
using model::to_string;

/// The explicit substep scheme: kBogackiShampine, the embedded Runge-Kutta pair of order 3(2)
/// (Bogacki & Shampine 1989; the default, ours), or kModifiedEuler, the order 2(1) pair of Sloan,
/// Abbo & Sheng (2001). Both share the error measure, dyadic substeps and drift correction.
enum class IntegrationScheme { kBogackiShampine, kModifiedEuler };

/// kImplicit (the default): the elastic part in closed form, the crossing of the yield cone and
/// the load reversal located explicitly, plastic substeps by backward Euler with Richardson
/// extrapolation, derivatives by the implicit function theorem (acst_implicit.h). kExplicit: the
/// explicit substepping of the first version, kept as the reference (`scheme` chooses the pair).
enum class IntegrationMethod { kImplicit, kExplicit };

struct IntegrationOptions {
  IntegrationMethod method = IntegrationMethod::kImplicit;
  IntegrationScheme scheme = IntegrationScheme::kBogackiShampine;  ///< explicit only
  /// Local error tolerance of the substeps (docs/model.md §4). Implicit: <= 0 (the default, the
  /// FE setting) takes each increment in one second-order step, split only where the cone is
  /// crossed or Newton fails, so that the update is a smooth function of the strain increment;
  /// > 0 chooses the substeps so that the estimated error of the half-step solution stays below
  /// it (the extrapolated result is more accurate still). Explicit: the relative error per
  /// substep of Sloan et al. (2001, STOL), must be > 0.
  double tolerance = 0.0;
  /// Implicit without error control: an update with a step whose error estimate exceeds this is
  /// reported kUnreliable (an absurd increment, e.g. a 30 % shear in one step; the FE cuts such
  /// steps with SolverOptions::cut_on_unreliable).
  double max_step_error = 1e-2;
  /// Implicit: the first plastic substep of a fresh loading (alpha = alpha_in: first loading, or
  /// after a load reversal) is 2^-loading_grading of the plastic segment, the next ones double;
  /// they resolve the knee of the hardening law there (0: no grading).
  int loading_grading = 4;
  double min_substep = 1e-6;  // smallest substep, as a fraction of the strain increment
  int max_substeps = 100000;  // attempted substeps per update, accepted or rejected
  double min_pressure = 100.0 /*Pa*/;
  /// Explicit with T = ceres::Jet: also reject substeps whose derivative parts are unstable
  /// (relative error estimate above 1 %, Bogacki-Shampine only, down to 1/4096 of the segment).
  /// update_with_strain_derivatives and update_with_tangent switch it on (strain seeds excite
  /// the stiff asymmetric lateral mode of a triaxial path). Off, the substeps of a Jet update are
  /// those of the double update. The implicit integration needs no guard (its derivatives come
  /// from the converged local systems).
  bool guard_derivatives = false;

  /// The explicit reference integration at the given tolerance.
  static IntegrationOptions explicit_reference(double tolerance) {
    IntegrationOptions o;
    o.method = IntegrationMethod::kExplicit;
    o.tolerance = tolerance;
    return o;
  }
  /// The implicit integration with error control at the given tolerance.
  static IntegrationOptions implicit_controlled(double tolerance) {
    IntegrationOptions o;
    o.tolerance = tolerance;
    return o;
  }
};

/// The value (non-derivative part) of a scalar: the number itself, or the .a of a dual number.
inline double value_of(double x) { return x; }
template <typename J, typename = decltype(std::declval<const J&>().a)>
double value_of(const J& x) {
  return value_of(x.a);
}

/// Why an update is not kOk, and what it cost (filled by the double updates when given).
struct UpdateReport {
  long substeps = 0;    ///< substeps attempted, accepted or rejected
  std::string message;  ///< empty for kOk
};

/// Strain-driven update: strain_increment is compression positive (de_v = tr > 0 compacts).
/// If substeps is given, the substeps attempted (accepted or rejected) are added to it.
template <typename T>
UpdateStatus update_state(const Parameters<T>& par, const State<T>& start,
                          const Tensor<T>& strain_increment, State<T>& end,
                          const IntegrationOptions& options = {}, long* substeps = nullptr);

/// Consistent (algorithmic) tangent d(stress_end)/d(strain_increment): for the implicit
/// integration by sensitivities carried along its operations, for the explicit one by Jets seeded
/// on the 6 independent strain components. D(3*i+j, 3*k+l) = d sigma_ij / d eps_kl (symmetrised:
/// the derivatives w.r.t. eps_kl and eps_lk are equal, each half of the engineering-shear
/// derivative), so that d sigma_ij = sum_kl D(3i+j,3k+l) d eps_kl for symmetric d eps. [Pa]
/// With a report: why the status is not kOk, and the substeps.
UpdateStatus update_with_tangent(const Parameters<double>& par, const State<double>& start,
                                 const Tensor<double>& strain_increment, State<double>& end,
                                 Eigen::Matrix<double, 9, 9>& tangent,
                                 const IntegrationOptions& options = {},
                                 UpdateReport* report = nullptr);

/// Throws std::runtime_error naming the first non-physical parameter.
void validate_parameters(const Parameters<double>& par);

/// Whether e is a void ratio the model can carry: in (0, 2.97), the limit of its elastic law
/// (docs/model.md §3, Eq. 1).
bool is_admissible_void_ratio(double e);

/// The ACST parameter file (model/parameter_file.h, docs/model.md); throws std::runtime_error
/// naming the missing/invalid key.
Parameters<double> read_parameters_json(const std::string& path);
/// The parameters of an ACST file already read (read_parameter_file); throws std::runtime_error
/// if it is another model's.
Parameters<double> parameters_of(const ParameterValues& values);
using model::parameter_file_model;
using model::ParameterAnnotation;
/// Writes the layout read_parameters_json reads (each parameter with value and unit).
void write_parameters_json(const Parameters<double>& par, const std::string& path);
/// The same layout, each parameter with its annotation ("lower", "upper", "standard_error",
/// "fixed", "at_bound", "stage"), and the members of extra_json_object (a JSON object text, e.g.
/// "provenance") added at the top level. Throws std::runtime_error if extra_json_object is not
/// an object or names a key of the layout.
void write_parameters_json(const Parameters<double>& par, const std::string& path,
                           const std::vector<ParameterAnnotation>& annotations,
                           const std::string& extra_json_object);

/// The model behind the model interface (model/descriptor.h) with these parameters (validated:
/// std::invalid_argument naming one that is not physical) and integration options, e.g. the FE
/// material's tolerance; find_model("acst").make(...) gives it with the default options.
std::unique_ptr<Behaviour> make_behaviour(const Parameters<double>& par,
                                          const IntegrationOptions& options = {});

/// The parameters with another scalar type (derivative parts zero).
template <typename U, typename T>
Parameters<U> cast_parameters(const Parameters<T>& par);
/// The state with another scalar type (derivative parts zero).
template <typename U, typename T>
State<U> cast_state(const State<T>& state);
/// A tensor with another scalar type (derivative parts zero).
template <typename U, typename T>
Tensor<U> cast_tensor(const Tensor<T>& tensor);

/// f/p = ||r - alpha|| - sqrt(2/3) m: < 0 inside the yield cone, 0 on it.
template <typename T>
T relative_yield_function(const Parameters<T>& par, const State<T>& state);

/// Quantities of the model at a state (for drivers, tests and output).
template <typename T>
struct ModelQuantities {
  T p, G, K;              // mean stress [Pa], elastic moduli [Pa]
  Tensor<T> n;            // loading direction (valid only if has_direction)
  bool has_direction;     // false where r = alpha (n undefined)
  T cos3theta, g;         // Lode angle measure, g(theta)
  T e_c, psi, A, zeta;    // critical void ratio, state parameter, F:n, dilatancy state parameter
  T fabric_rate;          // k_F exp(-n_F psi), the rate of Eq. (16)
  Tensor<T> alpha_b, alpha_d;  // bounding and dilatancy image back-stress ratios
  T D, h, K_p, N;         // dilatancy, hardening coefficient, plastic modulus [Pa], n:r on f = 0
};
/// Evaluates the model at a state; returns false where p <= 0 or e is outside (0, 2.97).
template <typename T>
bool evaluate_model(const Parameters<T>& par, const State<T>& state, ModelQuantities<T>& q);

}  // namespace model::acst

#include "model/acst_model_impl.h"
#include "model/acst_implicit.h"

namespace model::acst {

template <typename T>
UpdateStatus update_state(const Parameters<T>& par, const State<T>& start,
                          const Tensor<T>& strain_increment, State<T>& end,
                          const IntegrationOptions& options, long* substeps) {
  return options.method == IntegrationMethod::kImplicit
             ? update_state_implicit(par, start, strain_increment, end, options, substeps)
             : update_state_explicit(par, start, strain_increment, end, options, substeps);
}

}  // namespace model::acst
