// The ACST fabric-based model of model/ (acst_model.h, docs/model.md, docs/fe.md) at a quadrature
// point, through the model interface's adapter (model_material.h). Signs: the model is
// compression positive, fe_model tension positive; the adapter flips the strain increment and the
// stress. Internal variables: the model's state, laid out as its description (model/descriptor.h).
#ifndef FE_MODEL_ACST_MATERIAL_H_
#define FE_MODEL_ACST_MATERIAL_H_

#include <Eigen/Core>
#include <string>

#include "fe_model/model_material.h"
#include "model/acst_model.h"

namespace fe_model {

/// The initial state of the specimen besides its stress (all compression positive).
struct AcstInitialState {
  double void_ratio = 0.7;
  /// Model fabric F_0 (deviatoric); zero for an isotropic specimen.
  Eigen::Matrix3d fabric = Eigen::Matrix3d::Zero();
};

/// The ACST model at a quadrature point: the model interface's adapter (model_material.h) with
/// ACST's integration options and its fabric invariant.
class AcstMaterial final : public ModelMaterial {
 public:
  /// The model's state: e, alpha, alpha_in, F, status, substeps (model/umat.h's STATEV(2..22)).
  static constexpr std::size_t kNumInternalVariables = 21;
  /// Throws std::invalid_argument naming a parameter that is not physical, or an initial void
  /// ratio outside (0, 2.97) or a fabric that is not finite.
  AcstMaterial(const model::acst::Parameters<double>& parameters,
               const AcstInitialState& initial_state,
               const model::acst::IntegrationOptions& options = {});
  /// F : n_c, with n_c = sqrt(2/3) diag(-1/2, -1/2, 1) the unit deviatoric direction of triaxial
  /// compression along z: 1 when the fabric has reached its critical-state value in compression
  /// (F = n_c), 0 for an isotropic fabric, negative for an extension-type fabric.
  std::optional<double> fabric_invariant(const PointState& state) const override;
  /// The model's state of a point (for tests and output).
  model::acst::State<double> to_model(const PointState& state) const;
};

}  // namespace fe_model

#endif  // FE_MODEL_ACST_MATERIAL_H_
