// fe_model::Material adapter for the ACST fabric-based model of calibration/ (see
// out/notes/model_contract.md and docs/fe.md). Built only when the `calibration` CMake target
// exists: link `fe_model_acst`.
//
// Signs: the ACST model is compression positive, fe_model tension positive. The adapter passes
// strain_increment_model = -strain_increment_fe and returns stress_fe = -stress_model; the
// tangent d(stress)/d(strain increment) is the same in both conventions (two sign flips).
// Internal variables (PointState::internal_variables, compression positive, row-major 3x3):
//   [0] void ratio, [1..9] alpha, [10..18] alpha_in, [19..27] fabric F.
#ifndef FE_MODEL_ACST_MATERIAL_H_
#define FE_MODEL_ACST_MATERIAL_H_

#include <Eigen/Core>
#include <string>

#include "model/acst_model.h"
#include "fe_model/material.h"

namespace fe_model {

/// The initial state of the specimen besides its stress (all compression positive).
struct AcstInitialState {
  double void_ratio = 0.7;
  /// Model fabric F_0 (deviatoric); zero for an isotropic specimen.
  Eigen::Matrix3d fabric = Eigen::Matrix3d::Zero();
};

class AcstMaterial final : public Material {
 public:
  static constexpr std::size_t kNumInternalVariables = 28;

  AcstMaterial(const model::acst::Parameters<double>& parameters,
               const AcstInitialState& initial_state,
               const model::acst::IntegrationOptions& options = {});

  std::string name() const override { return "acst"; }
  /// alpha_0 = alpha_in_0 = s/p of the initial stress (zero for an isotropic state).
  PointState initial_state(const SymmetricTensor2& initial_stress) const override;
  MaterialUpdate update(const PointState& start, const SymmetricTensor2& strain_increment,
                        PointState& end) const override;
  /// F : n_c, with n_c = sqrt(2/3) diag(-1/2, -1/2, 1) the unit deviatoric direction of triaxial
  /// compression along z: 1 when the fabric has reached its critical-state value in compression
  /// (F = n_c), 0 for an isotropic fabric, negative for an extension-type fabric.
  std::optional<double> fabric_invariant(const PointState& state) const override;

  /// Conversions between the two conventions (exposed for tests).
  static model::acst::State<double> to_model(const PointState& state);
  static void from_model(const model::acst::State<double>& model, const SymmetricTensor2& strain,
                         PointState& state);

 private:
  model::acst::Parameters<double> parameters_;
  AcstInitialState initial_;
  model::acst::IntegrationOptions options_;
};

}  // namespace fe_model

#endif  // FE_MODEL_ACST_MATERIAL_H_
