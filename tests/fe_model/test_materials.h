// Materials used only by fe_model's tests: a nonlinear (hypoelastic, pressure-dependent) law with
// an exact consistent tangent, and a wrapper that fails above a strain-increment size.
#ifndef SFFCAL_TESTS_FE_MODEL_TEST_MATERIALS_H_
#define SFFCAL_TESTS_FE_MODEL_TEST_MATERIALS_H_

#include <cmath>
#include <string>

#include "fe_model/material.h"

namespace fe_model::testing {

// Hypoelastic, pressure-dependent (tension-positive increments, compression-positive p):
//   p_end = p_start exp(-tr(de) / kappa),  G_end = shear_ratio * p_end,
//   s_end = s_start + 2 G_end dev(de),     stress_end = s_end - p_end I.
// Exact tangent:
//   d stress/d de = 2 G dev_4 + (p/kappa) I (x) I - (2 shear_ratio p/kappa) dev(de) (x) I,
// not major-symmetric. fabric_invariant returns q/p of the point, a stand-in that exercises the
// fabric column of the output.
class HypoelasticTestMaterial final : public Material {
 public:
  HypoelasticTestMaterial(double kappa, double shear_ratio)
      : kappa_(kappa), shear_ratio_(shear_ratio) {}
  std::string name() const override { return "hypoelastic_test"; }
  PointState initial_state(const SymmetricTensor2& stress) const override {
    PointState state;
    state.stress = stress;
    return state;
  }
  MaterialUpdate update(const PointState& start, const SymmetricTensor2& de,
                        PointState& end) const override {
    MaterialUpdate result;
    const SymmetricTensor2 identity = dealii::unit_symmetric_tensor<3>();
    const double p_start = -dealii::trace(start.stress) / 3.0;
    if (!(p_start > 0.0)) {
      result.status = MaterialStatus::kFailed;
      result.message = "non-positive mean stress";
      return result;
    }
    const double p = p_start * std::exp(-dealii::trace(de) / kappa_);
    const double G = shear_ratio_ * p;
    const SymmetricTensor2 de_dev = dealii::deviator(de);
    end.stress = dealii::deviator(start.stress) + 2.0 * G * de_dev - p * identity;
    end.strain = start.strain + de;
    end.internal_variables = start.internal_variables;
    result.tangent = 2.0 * G * dealii::deviator_tensor<3>() +
                     (p / kappa_) * dealii::outer_product(identity, identity) -
                     (2.0 * shear_ratio_ * p / kappa_) * dealii::outer_product(de_dev, identity);
    return result;
  }
  std::optional<double> fabric_invariant(const PointState& state) const override {
    const double p = -dealii::trace(state.stress) / 3.0;
    const double q = -state.stress[2][2] + 0.5 * (state.stress[0][0] + state.stress[1][1]);
    return q / p;
  }

 private:
  double kappa_;
  double shear_ratio_;
};

// Delegates to `inner` but fails (kFailed, end left untouched) when |strain increment| exceeds
// `max_increment`: an induced material failure for the step-cutting tests.
class FailingTestMaterial final : public Material {
 public:
  FailingTestMaterial(const Material& inner, double max_increment)
      : inner_(inner), max_increment_(max_increment) {}
  std::string name() const override { return "failing_test"; }
  PointState initial_state(const SymmetricTensor2& stress) const override {
    return inner_.initial_state(stress);
  }
  MaterialUpdate update(const PointState& start, const SymmetricTensor2& de,
                        PointState& end) const override {
    if (de.norm() > max_increment_) {
      MaterialUpdate result;
      result.status = MaterialStatus::kFailed;
      result.message = "strain increment above the test threshold";
      return result;
    }
    return inner_.update(start, de, end);
  }

 private:
  const Material& inner_;
  double max_increment_;
};

}  // namespace fe_model::testing

#endif  // SFFCAL_TESTS_FE_MODEL_TEST_MATERIALS_H_
