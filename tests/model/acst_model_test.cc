// Unit checks of the ACST model and its integrator (acst-model.md, "Unit checks").
#include "model/acst_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "model/material_point.h"
#include "toyoura.h"

namespace model::acst {
namespace {

using testing::toyoura;

using testing::kP0;
using testing::scientific;

double shear_modulus(const Parameters<double>& par, double p, double e) {
  return par.G0 * kAtmosphericPressure * (2.97 - e) * (2.97 - e) / (1.0 + e) *
         std::sqrt(p / kAtmosphericPressure);
}

Tensor<double> deviatoric_unit() { return triaxial_deviator(1.0); }

bool all_finite(const State<double>& s) {
  return s.stress.allFinite() && std::isfinite(s.void_ratio) && s.alpha.allFinite() &&
         s.alpha_in.allFinite() && s.fabric.allFinite();
}

bool same_state(const State<double>& a, const State<double>& b) {
  return a.stress == b.stress && a.void_ratio == b.void_ratio && a.alpha == b.alpha &&
         a.alpha_in == b.alpha_in && a.fabric == b.fabric;
}

// A state on the yield surface after drained loading of a medium-dense specimen to eps_a.
State<double> loaded_state(double axial_strain) {
  const Parameters<double> par = toyoura();
  const State<double> s0 = isotropic_state(kP0, 0.80, triaxial_deviator(0.3));
  const PathResult<double> r = drained_triaxial(par, s0, axial_strain, 100);
  EXPECT_EQ(r.status, UpdateStatus::kOk);
  return r.state;
}

TEST(AcstElastic, DeviatoricIncrementInsideTheConeIsExactlyTwoGDe) {
  const Parameters<double> par = toyoura();
  const State<double> s0 = isotropic_state(kP0, 0.80, triaxial_deviator(0.2));
  // ||r|| after the increment: 2G * 5e-6 / p = 0.0027 < sqrt(2/3) m = 0.0082 (elastic).
  const Tensor<double> deps = 5e-6 * deviatoric_unit();
  State<double> s1;
  ASSERT_EQ(update_state(par, s0, deps, s1), UpdateStatus::kOk);
  const double G = shear_modulus(par, kP0, 0.80);
  const Tensor<double> expected = s0.stress + 2.0 * G * deps;  // p and e unchanged: exact
  EXPECT_LT((s1.stress - expected).norm(), 1e-12 * expected.norm());
  EXPECT_EQ(s1.void_ratio, 0.80);
  EXPECT_EQ(s1.alpha, s0.alpha);
  EXPECT_EQ(s1.fabric, s0.fabric);
  EXPECT_LT(value_of(relative_yield_function(par, s1)), 0.0);
}

TEST(AcstElastic, IsotropicCompressionMatchesTheIntegratedHypoelasticLaw) {
  // dp = K(e, p) d eps_v, de = -(1 + e) d eps_v  =>  2 (sqrt p1 - sqrt p0) = int k(e(eps)) d eps
  // with K = k(e) sqrt(p) and e(eps) = (1 + e0) exp(-eps) - 1; Simpson's rule for the integral.
  const Parameters<double> par = toyoura();
  const double e0 = 0.80;
  for (const double eps : {1e-4, 2e-3, -1e-3}) {
    const State<double> s0 = isotropic_state(kP0, e0, triaxial_deviator(0.2));
    State<double> s1;
    IntegrationOptions options;
    options.tolerance = 1e-10;
    ASSERT_EQ(update_state(par, s0, Tensor<double>((eps / 3.0) * Tensor<double>::Identity()), s1,
                           options),
              UpdateStatus::kOk);
    auto k = [&](double x) {
      const double e = (1.0 + e0) * std::exp(-x) - 1.0;
      const double g = par.G0 * kAtmosphericPressure * (2.97 - e) * (2.97 - e) / (1.0 + e) /
                       std::sqrt(kAtmosphericPressure);
      return g * 2.0 * (1.0 + par.nu) / (3.0 * (1.0 - 2.0 * par.nu));
    };
    const int n = 2000;
    double integral = k(0.0) + k(eps);
    for (int i = 1; i < n; ++i) integral += (i % 2 ? 4.0 : 2.0) * k(eps * i / n);
    integral *= eps / (3.0 * n);
    const double p1 = std::pow(std::sqrt(kP0) + 0.5 * integral, 2);
    EXPECT_NEAR(s1.stress(0, 0), p1, 1e-8 * p1) << "eps_v = " << eps;
    EXPECT_NEAR(s1.stress(0, 1), 0.0, 1e-9);
    EXPECT_NEAR(s1.void_ratio, (1.0 + e0) * std::exp(-eps) - 1.0, 1e-12);
  }
}

TEST(AcstYield, PlasticStatesStayOnTheYieldSurface) {
  const Parameters<double> par = toyoura();
  const State<double> s = loaded_state(0.01);
  EXPECT_LT(std::abs(relative_yield_function(par, s)), 1e-8);
  ModelQuantities<double> q;
  ASSERT_TRUE(evaluate_model(par, s, q));
  EXPECT_TRUE(q.has_direction);
  EXPECT_NEAR(q.cos3theta, 1.0, 1e-9);  // triaxial compression
  EXPECT_NEAR(q.g, 1.0, 1e-9);
  EXPECT_NEAR(q.n.norm(), 1.0, 1e-12);
  EXPECT_NEAR(q.n.trace(), 0.0, 1e-12);
}

TEST(AcstYield, LodeFunctionGivesCInExtension) {
  const Parameters<double> par = toyoura();
  State<double> s = isotropic_state(kP0, 0.8, Tensor<double>(Tensor<double>::Zero()));
  s.stress -= 0.3 * kP0 * deviatoric_unit();  // triaxial extension
  ModelQuantities<double> q;
  ASSERT_TRUE(evaluate_model(par, s, q));
  EXPECT_NEAR(q.cos3theta, -1.0, 1e-12);
  EXPECT_NEAR(q.g, par.c, 1e-12);
}

TEST(AcstYield, IsotropicStateWithJetsHasNoNaN) {
  // r = alpha: the norm ||r - alpha|| is guarded, so Jets see no sqrt(0).
  using Jet = ceres::Jet<double, 6>;
  const Parameters<Jet> par = toyoura<Jet>();
  const State<Jet> s = isotropic_state(Jet(kP0), Jet(0.8), Tensor<Jet>(Tensor<Jet>::Zero()));
  const Jet f = relative_yield_function(par, s);
  EXPECT_TRUE(std::isfinite(f.a));
  EXPECT_TRUE(f.v.allFinite());
  ModelQuantities<Jet> q;
  ASSERT_TRUE(evaluate_model(par, s, q));
  EXPECT_FALSE(q.has_direction);
  Eigen::Matrix<double, 9, 9> tangent;
  State<double> end;
  ASSERT_EQ(update_with_tangent(toyoura(), cast_state<double>(s),
                                Tensor<double>(Tensor<double>::Zero()), end, tangent),
            UpdateStatus::kOk);
  EXPECT_TRUE(tangent.allFinite());
}

// Centred finite differences of the stress after one update w.r.t. the 6 strain components.
Eigen::Matrix<double, 9, 9> finite_difference_tangent(const Parameters<double>& par,
                                                      const State<double>& s,
                                                      const Tensor<double>& deps, double h,
                                                      const IntegrationOptions& options) {
  Eigen::Matrix<double, 9, 9> fd = Eigen::Matrix<double, 9, 9>::Zero();
  for (int k = 0; k < 6; ++k) {
    const int a = kVoigtI[k], b = kVoigtJ[k];
    Tensor<double> plus = deps, minus = deps;
    plus(a, b) += h;
    minus(a, b) -= h;
    if (a != b) {
      plus(b, a) += h;
      minus(b, a) -= h;
    }
    State<double> sp, sm;
    EXPECT_NE(update_state(par, s, plus, sp, options), UpdateStatus::kFailed);
    EXPECT_NE(update_state(par, s, minus, sm, options), UpdateStatus::kFailed);
    const Tensor<double> d = (sp.stress - sm.stress) / (2.0 * h);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double scale = a == b ? 1.0 : 0.5;
        fd(3 * i + j, 3 * a + b) = scale * d(i, j);
        fd(3 * i + j, 3 * b + a) = scale * d(i, j);
      }
  }
  return fd;
}

// The two integrations whose tangents are checked: the implicit one at the FE default (one step
// per increment: the update is smooth in the increment) and the explicit reference.
const IntegrationOptions kTangentIntegrations[] = {IntegrationOptions(),
                                                   IntegrationOptions::explicit_reference(1e-8)};

double tangent_error(const State<double>& s, const Tensor<double>& deps, UpdateStatus expected,
                     const IntegrationOptions& options) {
  const Parameters<double> par = toyoura();
  Eigen::Matrix<double, 9, 9> tangent;
  State<double> end, end_double;
  EXPECT_EQ(update_with_tangent(par, s, deps, end, tangent, options), expected);
  EXPECT_EQ(update_state(par, s, deps, end_double, options), expected);
  EXPECT_LT((end.stress - end_double.stress).norm(), 1e-12 * end.stress.norm());
  const Eigen::Matrix<double, 9, 9> fd =
      finite_difference_tangent(par, s, deps, 1e-6 * deps.norm(), options);
  const double error = (tangent - fd).norm() / tangent.norm();
  // Symmetry in the stress indices and in the strain indices.
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) {
          EXPECT_EQ(tangent(3 * i + j, 3 * k + l), tangent(3 * j + i, 3 * k + l));
          EXPECT_EQ(tangent(3 * i + j, 3 * k + l), tangent(3 * i + j, 3 * l + k));
        }
  return error;
}

TEST(AcstTangent, ElasticTangentIsTheHypoelasticStiffness) {
  const Parameters<double> par = toyoura();
  const State<double> s = isotropic_state(kP0, 0.80, triaxial_deviator(0.2));
  const Tensor<double> deps = Tensor<double>::Zero();  // the tangent at the start state
  Eigen::Matrix<double, 9, 9> tangent;
  State<double> end;
  ASSERT_EQ(update_with_tangent(par, s, deps, end, tangent), UpdateStatus::kOk);
  const double G = shear_modulus(par, kP0, 0.80);
  // d sigma_xy / d eps_xy = 2G (half from eps_xy, half from eps_yx in the symmetric layout).
  const double K = G * 2.0 * (1.0 + par.nu) / (3.0 * (1.0 - 2.0 * par.nu));
  EXPECT_NEAR(tangent(1, 1), G, 1e-10 * G);
  EXPECT_NEAR(tangent(1, 3), G, 1e-10 * G);
  EXPECT_NEAR(tangent(0, 0), K + 4.0 * G / 3.0, 1e-10 * G);
  EXPECT_NEAR(tangent(0, 4), K - 2.0 * G / 3.0, 1e-10 * G);
  EXPECT_NEAR(tangent(0, 1), 0.0, 1e-9 * G);  // no normal-shear coupling
  EXPECT_NEAR(tangent(5, 5), G, 1e-10 * G);  // sigma_yz / eps_yz
  EXPECT_NEAR(tangent(5, 0), 0.0, 1e-9 * G);
}

TEST(AcstTangent, PlasticLoadingMatchesCentredFiniteDifferences) {
  const State<double> s = loaded_state(0.01);
  Tensor<double> deps;
  deps << -2e-5, 1e-5, 3e-5,  //
      1e-5, -2e-5, -2e-5,        //
      3e-5, -2e-5, 1e-4;
  for (const IntegrationOptions& options : kTangentIntegrations) {
    const double error = tangent_error(s, deps, UpdateStatus::kOk, options);
    RecordProperty(options.method == IntegrationMethod::kImplicit ? "relative_fd_error_implicit"
                                                                 : "relative_fd_error_explicit",
                   scientific(error));
    EXPECT_LT(error, 1e-6);
  }
}

TEST(AcstTangent, ElasticToPlasticCrossingMatchesCentredFiniteDifferences) {
  // Unload elastically into the cone, then reload across f = 0 in one increment: the tangent
  // includes the derivative of the intersection point.
  const Parameters<double> par = toyoura();
  const State<double> loaded = loaded_state(0.01);
  State<double> inside;
  ASSERT_EQ(update_state(par, loaded, Tensor<double>(-4e-6 * deviatoric_unit()), inside),
            UpdateStatus::kOk);
  ASSERT_LT(relative_yield_function(par, inside), -1e-4);
  Tensor<double> deps = 2e-5 * deviatoric_unit();
  deps(0, 1) = deps(1, 0) = 2e-6;
  for (const IntegrationOptions& options : kTangentIntegrations) {
    const double error = tangent_error(inside, deps, UpdateStatus::kOk, options);
    RecordProperty(options.method == IntegrationMethod::kImplicit
                       ? "relative_fd_error_crossing_implicit"
                       : "relative_fd_error_crossing_explicit",
                   scientific(error));
    EXPECT_LT(error, 1e-6);
  }
}

TEST(AcstJet, JetAndDoubleUpdatesAgreeToRoundOff) {
  using Jet = ceres::Jet<double, 15>;
  const Parameters<double> par = toyoura();
  const State<double> s = loaded_state(0.02);
  Tensor<double> deps = 3e-3 * deviatoric_unit();
  deps(0, 0) += 1e-4;
  State<double> end_double;
  State<Jet> end_jet;
  ASSERT_EQ(update_state(par, s, deps, end_double), UpdateStatus::kOk);
  Parameters<Jet> par_jet = cast_parameters<Jet>(par);
  par_jet.h0.v[8] = 1.0;  // seed something, so the derivative parts are exercised
  par_jet.n_d.v[12] = 1.0;
  ASSERT_EQ(update_state(par_jet, cast_state<Jet>(s), cast_tensor<Jet>(deps), end_jet),
            UpdateStatus::kOk);
  const State<double> end_value = cast_state<double>(end_jet);
  EXPECT_LT((end_value.stress - end_double.stress).norm(), 1e-13 * end_double.stress.norm());
  EXPECT_LT((end_value.alpha - end_double.alpha).norm(), 1e-13);
  EXPECT_LT((end_value.fabric - end_double.fabric).norm(), 1e-13);
  EXPECT_NEAR(end_value.void_ratio, end_double.void_ratio, 1e-15);
}

TEST(AcstFabric, RateIsKFTimesExpOfMinusNFPsi) {
  // Eq. (16) with the rate k_F exp(-n_F psi): from one state the increments with and without n_F
  // differ by exactly that factor (the loading index does not depend on n_F), and n_F = 0 gives
  // LD12's rate bit for bit; the ratio is above 1 where psi < 0 (dense) and below where psi > 0.
  Parameters<double> par = toyoura();
  Tensor<double> deps = 1e-4 * deviatoric_unit();
  deps(2, 2) += 2e-5;
  for (const double e0 : {0.70, 0.96}) {
    par.n_F = 0.0;
    const PathResult<double> r =
        drained_triaxial(par, isotropic_state(kP0, e0, triaxial_deviator(0.3)), 0.01, 50);
    ASSERT_EQ(r.status, UpdateStatus::kOk);
    const State<double>& s = r.state;
    ModelQuantities<double> q;
    ASSERT_TRUE(evaluate_model(par, s, q));
    EXPECT_EQ(q.fabric_rate, par.k_F);
    detail::Increment<double> constant_rate, state_rate;
    ASSERT_TRUE(detail::increment(par, s, deps, true, constant_rate));
    par.n_F = 4.0;
    ASSERT_TRUE(detail::increment(par, s, deps, true, state_rate));
    ASSERT_GT(constant_rate.fabric.norm(), 0.0) << "the increment must be plastic";
    const double factor = std::exp(-par.n_F * q.psi);
    EXPECT_LT((state_rate.fabric - factor * constant_rate.fabric).norm(),
              1e-14 * state_rate.fabric.norm())
        << "e0 " << e0;
    EXPECT_EQ(state_rate.stress, constant_rate.stress) << "e0 " << e0;
    if (e0 < 0.8) EXPECT_GT(factor, 1.2) << "dense: psi " << q.psi;
    else EXPECT_LT(factor, 0.9) << "loose: psi " << q.psi;
  }
}

TEST(AcstIntegration, LoadReversalResetsAlphaIn) {
  const Parameters<double> par = toyoura();
  const State<double> loaded = loaded_state(0.01);
  EXPECT_LT(loaded.alpha_in.norm(), 1e-12);  // first loading from alpha = 0
  State<double> reversed;
  ASSERT_EQ(update_state(par, loaded, Tensor<double>(-2e-3 * deviatoric_unit()), reversed),
            UpdateStatus::kOk);
  EXPECT_GT(loaded.alpha.norm(), 0.1);
  // Reverse loading went plastic on the other side of the cone: alpha_in is the alpha there.
  EXPECT_GT(reversed.alpha_in.norm(), 0.1);
  EXPECT_LT(reversed.alpha(2, 2), reversed.alpha_in(2, 2));
}

TEST(AcstIntegration, HugeIncrementFailsCleanlyOrIsRight) {
  const Parameters<double> par = toyoura();
  const State<double> s0 = isotropic_state(kP0, 0.80, triaxial_deviator(0.3));
  // 1) 30% shear at constant volume in one increment: fine increments give the reference. With
  // error control (the explicit reference at 1e-6, the implicit at 1e-5) the answer must be
  // within 1e-3; the FE default (one step per increment, whatever its error) must report the
  // update unreliable (its error estimate exceeds max_step_error), or be within 1e-3.
  Tensor<double> deps = 0.3 * deviatoric_unit();
  const IntegrationOptions modes[] = {IntegrationOptions::explicit_reference(1e-6),
                                      IntegrationOptions::implicit_controlled(1e-5),
                                      IntegrationOptions()};
  State<double> many = s0;
  for (int k = 0; k < 300; ++k) {
    State<double> next;
    ASSERT_NE(update_state(par, many, Tensor<double>(deps / 300.0), next,
                           IntegrationOptions::implicit_controlled(1e-7)),
              UpdateStatus::kFailed);
    many = next;
  }
  for (const IntegrationOptions& options : modes) {
    State<double> one;
    const UpdateStatus status = update_state(par, s0, deps, one, options);
    EXPECT_TRUE(all_finite(one));
    if (status == UpdateStatus::kFailed) {
      EXPECT_TRUE(same_state(one, s0));
    } else if (!(options.method == IntegrationMethod::kImplicit && options.tolerance <= 0.0 &&
                 status == UpdateStatus::kUnreliable)) {
      EXPECT_LT((one.stress - many.stress).norm(), 1e-3 * many.stress.norm());
    }
  }
  // 2) 50% extension in every direction: p -> 0, must fail and return the start state.
  State<double> torn;
  EXPECT_EQ(update_state(par, s0, Tensor<double>(-0.5 * Tensor<double>::Identity()), torn),
            UpdateStatus::kFailed);
  EXPECT_TRUE(same_state(torn, s0));
  // 3) Non-finite input.
  Tensor<double> bad = deps;
  bad(0, 0) = std::nan("");
  EXPECT_EQ(update_state(par, s0, bad, torn), UpdateStatus::kFailed);
  EXPECT_TRUE(all_finite(torn));
}

}  // namespace
}  // namespace model::acst
