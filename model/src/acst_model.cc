#include "model/acst_model.h"

#include <ceres/jet.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "model/strain_derivatives.h"

namespace model::acst {

namespace {

// Voigt order of the 6 independent strain components seeded as Jet derivatives, and the Voigt
// index of each tensor component.
constexpr int kVoigtRow[6] = {0, 1, 2, 0, 1, 0};
constexpr int kVoigtCol[6] = {0, 1, 2, 1, 2, 2};
constexpr int kVoigtIndex[3][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}};

}  // namespace

UpdateStatus update_with_strain_derivatives(const Parameters<double>& par,
                                            const State<double>& start,
                                            const Tensor<double>& strain_increment,
                                            State<StrainJet>& end, const IntegrationOptions& options) {
  const Parameters<StrainJet> par_jet = cast_parameters<StrainJet>(par);
  const State<StrainJet> start_jet = cast_state<StrainJet>(start);
  Tensor<StrainJet> deps;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      deps(i, j) = StrainJet(0.5 * (strain_increment(i, j) + strain_increment(j, i)));
  for (int k = 0; k < 6; ++k) {
    deps(kVoigtRow[k], kVoigtCol[k]).v[k] = 1.0;
    deps(kVoigtCol[k], kVoigtRow[k]).v[k] = 1.0;  // the same Jet for eps_kl and eps_lk
  }
  IntegrationOptions guarded = options;
  guarded.guard_derivatives = true;
  return update_state(par_jet, start_jet, deps, end, guarded);
}

UpdateStatus update_with_tangent(const Parameters<double>& par, const State<double>& start,
                                 const Tensor<double>& strain_increment, State<double>& end,
                                 Eigen::Matrix<double, 9, 9>& tangent,
                                 const IntegrationOptions& options, UpdateReport* report) {
  tangent.setZero();
  Eigen::Matrix<double, 6, 6> voigt;  // d sigma_a / d eps_b, shear seeds moving eps_kl and eps_lk
  UpdateStatus status = UpdateStatus::kFailed;
  long substeps = 0;
  std::string reason;
  if (options.method == IntegrationMethod::kImplicit) {
    thread_local implicit_detail::Tape tape;  // reused: no allocation per update
    tape.with_inputs = true;
    status = implicit_detail::integrate_values(par, start, strain_increment, options, end, &tape,
                                               &substeps, &reason);
    if (status != UpdateStatus::kFailed &&
        !implicit_detail::replay_tangent(par, start, strain_increment, tape, voigt)) {
      end = start;
      status = UpdateStatus::kFailed;
      reason = "the tangent cannot be evaluated along the update";
    }
  } else {
    State<StrainJet> end_jet;
    status = update_with_strain_derivatives(par, start, strain_increment, end_jet, options);
    end = cast_state<double>(end_jet);
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) voigt(a, b) = end_jet.stress(kVoigtRow[a], kVoigtCol[a]).v[b];
    if (status == UpdateStatus::kFailed) reason = "the explicit integration failed";
    if (status == UpdateStatus::kUnreliable) reason = "a minimum substep above the tolerance";
  }
  if (report) {
    report->substeps = substeps;
    report->message = reason;
  }
  if (status == UpdateStatus::kFailed) return status;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 6; ++k) {
        const int a = kVoigtRow[k], b = kVoigtCol[k];
        const double d = voigt(kVoigtIndex[i][j], k);
        if (a == b) {
          tangent(3 * i + j, 3 * a + b) = d;
        } else {  // d/d(eps_ab) with eps_ab = eps_ba moving together: half to each
          tangent(3 * i + j, 3 * a + b) = 0.5 * d;
          tangent(3 * i + j, 3 * b + a) = 0.5 * d;
        }
      }
    }
  return status;
}

bool is_admissible_void_ratio(double e) { return e > 0.0 && e < detail::kElasticVoidLimit; }

void validate_parameters(const Parameters<double>& par) {
  auto fail = [](const char* name, double value, const std::string& range) {
    throw std::runtime_error(std::string("ACST parameter '") + name + "' = " +
                             format_number(value) + " is not physical: it must be " + range);
  };
  for (const ParameterField<double>& field : kParameterFields<double>) {
    const double value = par.*field.member;
    if (!(std::isfinite(value) && field.physical.contains(value)))
      fail(field.name, value, field.physical.describe());
  }
  // The two conditions that couple parameters (docs/model.md): a cone inside the critical one,
  // and a positive hardening factor 1 - c_h e.
  if (!(par.m < par.c * par.M_c)) fail("m", par.m, "below c M_c");
  if (!(par.c_h * par.e_gamma < 1.0)) fail("c_h", par.c_h, ">= 0 with c_h e_gamma < 1");
}

}  // namespace model::acst
