// The implicit integration of the ACST model (docs/model.md §4): its local Jacobian against
// automatic differentiation, its elastic closed form against the explicit reference, its tangent
// against finite differences and against the Jet replay, its parameter derivatives against finite
// differences after the peak, and its driver paths against the converged explicit reference.
#include "model/acst_model.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "model/material_point.h"
#include "toyoura.h"

namespace model::acst {
namespace {

using implicit_detail::Jacobian;
using implicit_detail::kUnknowns;
using implicit_detail::PlasticStep;
using implicit_detail::Unknowns;
using testing::kP0;
using testing::scientific;
using testing::toyoura;

State<double> loaded_state(double e0, double axial_strain) {
  const PathResult<double> r = drained_triaxial(
      toyoura(), isotropic_state(kP0, e0, triaxial_deviator(0.3)), axial_strain, 50);
  EXPECT_EQ(r.status, UpdateStatus::kOk);
  return r.state;
}

// A general 3D strain increment of size `size` (tensor components, compression positive).
Tensor<double> general_increment(double size) {
  Tensor<double> d;
  d << -0.3, 0.1, -0.05,  //
      0.1, -0.25, 0.08,   //
      -0.05, 0.08, 1.0;
  return size * d;
}

double max_relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

TEST(AcstImplicit, LocalJacobianMatchesAutomaticDifferentiation) {
  using Jet = ceres::Jet<double, kUnknowns>;
  Parameters<double> par = toyoura();
  par.n_b_loose = 4.0;  // the loose side's slope, for the last state
  par.n_G = 0.3;        // not DM04's 1/2, whose power is a square root
  par.n_F = 3.0;        // a fabric rate that follows psi (through p and e)
  // A plastic state, one with alpha_in = alpha (the hardening floor), one from the apex and one
  // looser than the critical state line (psi > 0).
  std::vector<State<double>> starts = {loaded_state(0.80, 0.01), loaded_state(0.70, 0.05)};
  starts[1].alpha_in = 0.5 * starts[1].alpha;
  State<double> at_floor = loaded_state(0.85, 0.02);
  at_floor.alpha_in = at_floor.alpha;
  starts.push_back(at_floor);
  starts.push_back(loaded_state(0.96, 0.01));
  for (std::size_t c = 0; c < starts.size(); ++c) {
    const State<double>& s = starts[c];
    PlasticStep<double> step;
    ASSERT_TRUE(implicit_detail::make_step(par, s, general_increment(1e-3), step));
    if (c == 3) {  // the loose state lies on the loose side of the critical state line
      const double p = s.stress.trace() / 3.0;
      EXPECT_GT(step.void_ratio - (par.e_gamma - par.lambda_c *
                                                     std::pow(p / kAtmosphericPressure, par.xi)),
                0.01);
    }
    // Unknowns near, not at, a solution: every term of the residual is non-zero.
    Unknowns<double> x;
    implicit_detail::pack(Tensor<double>(0.98 * step.stress_trial), x, 0);
    implicit_detail::pack(Tensor<double>(1.02 * s.alpha), x, 6);
    x(3) += 0.01 * kP0;
    x(9) += 0.003;
    x(implicit_detail::kMultiplier) = 2e-4;
    Unknowns<double> r;
    Jacobian analytic;
    ASSERT_TRUE(implicit_detail::plastic_jacobian(par, step, x, r, analytic));

    PlasticStep<Jet> step_jet;
    step_jet.start = cast_state<Jet>(s);
    step_jet.stress_trial = cast_tensor<Jet>(step.stress_trial);
    step_jet.void_ratio = Jet(step.void_ratio);
    step_jet.scale = step.scale;
    Unknowns<Jet> x_jet, r_jet;
    for (int i = 0; i < kUnknowns; ++i) x_jet(i) = Jet(x(i), i);
    ASSERT_TRUE(implicit_detail::plastic_residual(cast_parameters<Jet>(par), step_jet, x_jet, r_jet));
    Jacobian automatic;
    for (int i = 0; i < kUnknowns; ++i) {
      EXPECT_NEAR(r(i), r_jet(i).a, 1e-14 * (1.0 + std::abs(r(i))));
      automatic.row(i) = r_jet(i).v.transpose();
    }
    const double error = max_relative(analytic, automatic);
    RecordProperty("jacobian_error_" + std::to_string(c), scientific(error));
    EXPECT_LT(error, 1e-12) << "case " << c;
  }
}

TEST(AcstImplicit, ElasticClosedFormIsTheIntegratedHypoelasticLaw) {
  // A wide cone (m = 0.5) keeps a combined volumetric-deviatoric increment elastic; the closed
  // form must equal the explicit integration of Eq. (1) at a tight tolerance.
  // Pressure exponents: DM04's 1/2 (its own closed form), 0.3, and 0 (K independent of p).
  Parameters<double> par = toyoura();
  par.m = 0.5;
  const State<double> s0 = isotropic_state(kP0, 0.8, triaxial_deviator(0.2));
  for (const double n_G : {0.5, 0.3, 0.0})
  for (const double size : {1e-5, 1e-3, -1e-3}) {
    par.n_G = n_G;
    const Tensor<double> deps =
        general_increment(0.1 * std::abs(size)) + size * Tensor<double>::Identity();
    State<double> exact, reference;
    ASSERT_EQ(update_state(par, s0, deps, exact), UpdateStatus::kOk);
    ASSERT_LT(relative_yield_function(par, exact), 0.0) << "the increment must stay elastic";
    ASSERT_EQ(update_state(par, s0, deps, reference, IntegrationOptions::explicit_reference(1e-12)),
              UpdateStatus::kOk);
    EXPECT_LT((exact.stress - reference.stress).norm(), 1e-10 * reference.stress.norm())
        << "size " << size << " n_G " << n_G;
    EXPECT_NEAR(exact.void_ratio, reference.void_ratio, 1e-13);
    EXPECT_EQ(exact.alpha, s0.alpha);
    EXPECT_EQ(exact.fabric, s0.fabric);
  }
}

// Centred finite differences of the stress w.r.t. the 6 strain components (each shear component
// moving eps_kl and eps_lk together), in Voigt layout.
Eigen::Matrix<double, 6, 6> fd_tangent(const Parameters<double>& par, const State<double>& s,
                                       const Tensor<double>& deps,
                                       const IntegrationOptions& options) {
  Eigen::Matrix<double, 6, 6> fd;
  const double h = 1e-6 * deps.norm();
  for (int b = 0; b < 6; ++b) {
    Tensor<double> plus = deps, minus = deps;
    plus(kVoigtI[b], kVoigtJ[b]) += h;
    minus(kVoigtI[b], kVoigtJ[b]) -= h;
    if (kVoigtI[b] != kVoigtJ[b]) {
      plus(kVoigtJ[b], kVoigtI[b]) += h;
      minus(kVoigtJ[b], kVoigtI[b]) -= h;
    }
    State<double> sp, sm;
    EXPECT_NE(update_state(par, s, plus, sp, options), UpdateStatus::kFailed);
    EXPECT_NE(update_state(par, s, minus, sm, options), UpdateStatus::kFailed);
    for (int a = 0; a < 6; ++a)
      fd(a, b) = (sp.stress(kVoigtI[a], kVoigtJ[a]) - sm.stress(kVoigtI[a], kVoigtJ[a])) / (2 * h);
  }
  return fd;
}

// The tangent of update_with_tangent in the same Voigt layout.
Eigen::Matrix<double, 6, 6> voigt_of(const Eigen::Matrix<double, 9, 9>& D) {
  Eigen::Matrix<double, 6, 6> t;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      const int row = 3 * kVoigtI[a] + kVoigtJ[a];
      t(a, b) = kVoigtI[b] == kVoigtJ[b]
                    ? D(row, 3 * kVoigtI[b] + kVoigtJ[b])
                    : D(row, 3 * kVoigtI[b] + kVoigtJ[b]) + D(row, 3 * kVoigtJ[b] + kVoigtI[b]);
    }
  return t;
}

struct TangentCase {
  std::string name;
  State<double> start;
  Tensor<double> increment;
  int min_crossings = 0;  // elastic-plastic crossings the increment must contain
};

std::vector<TangentCase> tangent_cases() {
  const State<double> loaded = loaded_state(0.80, 0.01);
  return {
      {"plastic_5e-4", loaded, general_increment(5e-4), 0},
      {"plastic_3e-3", loaded, general_increment(3e-3), 0},
      {"first_loading_crosses_the_cone",
       isotropic_state(kP0, 0.80, triaxial_deviator(0.3)), general_increment(5e-4), 1},
      {"reversal_through_the_cone", loaded, Tensor<double>(-general_increment(5e-4)), 1},
      {"dense_after_the_peak", loaded_state(0.70, 0.08), general_increment(1e-3), 0},
  };
}

TEST(AcstImplicit, TangentMatchesCentredFiniteDifferences) {
  Parameters<double> par = toyoura();
  const IntegrationOptions options;  // the FE default
  // DM04's elastic exponent (closed form) and LD12's constant fabric rate, then others.
  for (const auto& [n_G, n_F] : {std::pair{0.5, 0.0}, std::pair{0.3, 3.0}})
  for (TangentCase c : tangent_cases()) {
    par.n_G = n_G;
    par.n_F = n_F;
    c.name += "_nG" + std::to_string(n_G).substr(0, 3) + "_nF" + std::to_string(n_F).substr(0, 3);
    implicit_detail::Tape tape;
    State<double> end;
    ASSERT_EQ(implicit_detail::integrate_values(par, c.start, c.increment, options, end, &tape,
                                                nullptr),
              UpdateStatus::kOk)
        << c.name;
    int crossings = 0;
    for (const auto& entry : tape.entries)
      crossings += entry.kind == implicit_detail::TapeEntry::Kind::kCrossing;
    EXPECT_GE(crossings, c.min_crossings) << c.name;
    Eigen::Matrix<double, 9, 9> D;
    State<double> end_tangent;
    ASSERT_EQ(update_with_tangent(par, c.start, c.increment, end_tangent, D, options),
              UpdateStatus::kOk);
    EXPECT_EQ(end_tangent.stress, end.stress) << c.name;
    const double error = max_relative(voigt_of(D), fd_tangent(par, c.start, c.increment, options));
    RecordProperty("fd_error_" + c.name, scientific(error));
    EXPECT_LT(error, 1e-6) << c.name;
  }
}

TEST(AcstImplicit, AnalyticTangentEqualsTheJetReplayWithErrorControl) {
  // With error control the update is piecewise smooth (the substeps change with the increment);
  // the tangent is the exact derivative of each piece: the hand-written sensitivities equal the
  // Jet replay of the same tape, with DM04's elastic exponent and LD12's fabric rate, and others.
  Parameters<double> par = toyoura();
  for (const auto& [n_G, n_F] : {std::pair{0.5, 0.0}, std::pair{0.3, 3.0}})
  for (const double tolerance : {0.0, 1e-4, 1e-6}) {
    par.n_G = n_G;
    par.n_F = n_F;
    const IntegrationOptions options = IntegrationOptions::implicit_controlled(tolerance);
    for (const TangentCase& c : tangent_cases()) {
      Eigen::Matrix<double, 9, 9> D;
      State<double> end;
      ASSERT_EQ(update_with_tangent(par, c.start, c.increment, end, D, options), UpdateStatus::kOk);
      State<StrainJet> end_jet;
      ASSERT_EQ(update_with_strain_derivatives(par, c.start, c.increment, end_jet, options),
                UpdateStatus::kOk);
      Eigen::Matrix<double, 6, 6> jet;
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b) jet(a, b) = end_jet.stress(kVoigtI[a], kVoigtJ[a]).v[b];
      EXPECT_LT(max_relative(voigt_of(D), jet), 1e-12)
          << c.name << " tolerance " << tolerance << " n_G " << n_G << " n_F " << n_F;
    }
  }
}

// The derivatives of q and eps_v at the end of a drained path w.r.t. every parameter, from the
// converged local systems, against centred differences (relative step 1e-5); returns the worst
// relative error. `skip`: a parameter without effect on the path whose finite difference is
// round-off (c in compression: g = 1).
double worst_parameter_derivative_error(const Parameters<double>& par, const State<double>& s0,
                                        double strain, const std::string& skip,
                                        std::vector<double>* eta = nullptr) {
  constexpr int kCount = static_cast<int>(kParameterFields<double>.size());
  using Jet = ceres::Jet<double, kCount>;
  const int n = 100;
  DriverOptions options;
  options.integration = IntegrationOptions();  // smooth in the parameters: one step per increment
  options.stress_tolerance = 1e-12;
  Parameters<Jet> par_jet = cast_parameters<Jet>(par);
  for (int k = 0; k < kCount; ++k) (par_jet.*kParameterFields<Jet>[k].member).v[k] = 1.0;
  const PathResult<Jet> r_jet = drained_triaxial(par_jet, cast_state<Jet>(s0), strain, n, options);
  EXPECT_EQ(r_jet.status, UpdateStatus::kOk);
  if (r_jet.rows.empty()) return std::numeric_limits<double>::infinity();
  if (eta)
    for (const auto& row : r_jet.rows) eta->push_back(row.eta.a);
  const PointRecord<Jet>& end = r_jet.rows.back();
  double worst = 0.0;
  for (int k = 0; k < kCount; ++k) {
    const char* name = kParameterFields<double>[k].name;
    if (skip == name) continue;
    const double base = par.*kParameterFields<double>[k].member;
    auto run = [&](double factor) {
      Parameters<double> p = par;
      p.*kParameterFields<double>[k].member *= factor;
      return drained_triaxial(p, s0, strain, n, options).rows.back();
    };
    const double h = 1e-5 * base;
    const PointRecord<double> plus = run(1.0 + 1e-5), minus = run(1.0 - 1e-5);
    const double dq = (plus.q - minus.q) / (2 * h);
    const double dv = (plus.volumetric_strain - minus.volumetric_strain) / (2 * h);
    // Relative to the size of the change a 1 % change of the parameter makes (a parameter with
    // almost no effect is not held to a relative error of its tiny derivative).
    const double q_scale = std::max(std::abs(dq), 1e-3 * std::abs(end.q.a) / (0.01 * base));
    const double v_scale =
        std::max(std::abs(dv), 1e-3 * std::abs(end.volumetric_strain.a) / (0.01 * base));
    const double error = std::max(std::abs(end.q.v[k] - dq) / q_scale,
                                  std::abs(end.volumetric_strain.v[k] - dv) / v_scale);
    worst = std::max(worst, error);
    EXPECT_LT(error, 1e-5) << "parameter " << name;
  }
  return worst;
}

TEST(AcstImplicit, ParameterDerivativesMatchFiniteDifferencesAfterThePeak) {
  // A dense specimen past its peak. n_b_loose (non-zero here) acts only where psi > 0: its
  // derivatives must come out 0 on this path, as the differences do. n_F (non-zero: the
  // differences step it relatively) speeds the fabric of this dense state.
  Parameters<double> par = toyoura();
  par.n_b_loose = 3.0;
  par.n_F = 4.0;
  std::vector<double> eta;
  const double worst = worst_parameter_derivative_error(
      par, isotropic_state(kP0, 0.70, triaxial_deviator(0.3)), 0.10, "c", &eta);
  ASSERT_FALSE(eta.empty());
  EXPECT_LT(eta.back(), 0.97 * *std::max_element(eta.begin(), eta.end()))
      << "the path must end past the peak";
  RecordProperty("worst_relative_error", scientific(worst));
}

TEST(AcstImplicit, ParameterDerivativesMatchFiniteDifferencesOnTheLooseSide) {
  // A loose specimen (psi_0 = +0.035), where the bounding slope is n_b + n_b_loose and n_F
  // slows the fabric.
  Parameters<double> par = toyoura();
  par.n_b_loose = 4.0;
  par.n_F = 4.0;
  const double worst = worst_parameter_derivative_error(
      par, isotropic_state(kP0, 0.95, triaxial_deviator(0.3)), 0.10, "c");
  RecordProperty("worst_relative_error", scientific(worst));
}

// Max relative difference of q and of eps_v (or p where eps_v is 0) between two paths.
void path_difference(const PathResult<double>& a, const PathResult<double>& b, double& dq,
                     double& dv) {
  double q_scale = 0.0, v_scale = 0.0;
  dq = dv = 0.0;
  const bool volume_held = std::abs(b.rows.back().volumetric_strain) < 1e-12;
  for (std::size_t k = 0; k < std::min(a.rows.size(), b.rows.size()); ++k) {
    q_scale = std::max(q_scale, std::abs(b.rows[k].q));
    dq = std::max(dq, std::abs(a.rows[k].q - b.rows[k].q));
    const double va = volume_held ? a.rows[k].p : a.rows[k].volumetric_strain;
    const double vb = volume_held ? b.rows[k].p : b.rows[k].volumetric_strain;
    v_scale = std::max(v_scale, std::abs(vb));
    dv = std::max(dv, std::abs(va - vb));
  }
  dq /= q_scale;
  dv /= v_scale;
}

TEST(AcstImplicit, DriverPathsAgreeWithTheConvergedExplicitReference) {
  // Reference: the explicit integration at 1e-10 on the same increments (converged to about
  // 1e-10). The implicit at the driver's default (error control 1e-7) must agree to 1e-6 in q
  // and eps_v (p for undrained paths); the FE default (one step per increment) is recorded.
  // n_b_loose acts on the loose specimen (e0 0.95, psi_0 = +0.035); n_F on every one.
  Parameters<double> par = toyoura();
  par.n_b_loose = 4.0;
  par.n_F = 3.0;
  DriverOptions reference;
  reference.integration = IntegrationOptions::explicit_reference(1e-10);
  DriverOptions fe_default;
  fe_default.integration = IntegrationOptions();
  for (const double e0 : {0.70, 0.80, 0.90, 0.95}) {
    const State<double> s0 = isotropic_state(kP0, e0, triaxial_deviator(0.3));
    for (const bool drained : {true, false}) {
      if (!drained && e0 > 0.9) continue;  // liquefies: p' reaches the 100 Pa cutoff at 1.5 %
      auto path = [&](const DriverOptions& o) {
        return drained ? drained_triaxial(par, s0, 0.25, 500, o)
                       : undrained_triaxial(par, s0, 0.10, 500, o);
      };
      const PathResult<double> ref = path(reference), implicit = path(DriverOptions{}),
                               fe = path(fe_default);
      ASSERT_EQ(ref.status, UpdateStatus::kOk);
      ASSERT_EQ(implicit.status, UpdateStatus::kOk);
      ASSERT_EQ(fe.status, UpdateStatus::kOk);
      double dq = 0.0, dv = 0.0, dq_fe = 0.0, dv_fe = 0.0;
      path_difference(implicit, ref, dq, dv);
      path_difference(fe, ref, dq_fe, dv_fe);
      const std::string name =
          std::string(drained ? "drained" : "undrained") + "_e" + std::to_string(e0).substr(0, 4);
      RecordProperty(name + "_q", scientific(dq));
      RecordProperty(name + "_second", scientific(dv));
      RecordProperty(name + "_q_fe_default", scientific(dq_fe));
      RecordProperty(name + "_second_fe_default", scientific(dv_fe));
      EXPECT_LT(dq, 1e-6) << name;
      EXPECT_LT(dv, 1e-6) << name;
      EXPECT_LT(dq_fe, 2e-2) << name;  // second order at 5e-4 per increment (recorded)
    }
  }
}

}  // namespace
}  // namespace model::acst
