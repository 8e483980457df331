// The contact-network model of model/ (network_model.h, docs/network-model.md) at a quadrature
// point: the stress is the SFF equation of the point's state (e, Z, Lambda, A, F, F^t), integrated
// by RK4 substeps; the consistent tangent comes exactly from forward-mode dual numbers seeded on
// the strain increment (network_update.h). Internal variables: the model's state, laid out as its
// description (model/descriptor.h); A_i, the fabric's inherent part, starts as the initial fabric.
#ifndef FE_MODEL_NETWORK_MATERIAL_H_
#define FE_MODEL_NETWORK_MATERIAL_H_

#include <Eigen/Core>
#include <string>

#include "fe_model/model_material.h"
#include "model/network_model.h"

namespace fe_model {

/// The specimen's network besides its stress (compression positive): void ratio, coordination and
/// the deviatoric anisotropy tensors A, F, F^t (zero: isotropic). Lambda follows from the initial
/// mean stress.
struct NetworkInitialState {
  double void_ratio = 0.7;
  double coordination = 5.0;
  Eigen::Matrix3d fabric = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d tangential = Eigen::Matrix3d::Zero();
};

/// The contact-network model at a quadrature point: the model interface's adapter
/// (model_material.h) with the network's fabric invariant.
class NetworkMaterial final : public ModelMaterial {
 public:
  /// The model's state: e, Z, Lambda, A, F, F^t, substeps, A_i (model/umat_network.h's
  /// STATEV(2..29)).
  static constexpr std::size_t kNumInternalVariables = 28;
  /// Throws std::invalid_argument naming a parameter outside its range or a non-physical initial
  /// state (void ratio or coordination not positive, a tensor not finite). youngs_modulus: the
  /// grains' E [Pa] that normalises Lambda (150 MPa in the DEM). The point's initial state sets
  /// Lambda = 3 p (1 + e) / (E Z (1 + (2/15) tr(FA))), so that the SFF stress of the state has
  /// the initial mean stress p; the point's stress is that SFF stress, whose deviator is the one
  /// the initial anisotropies carry (zero for an isotropic network), not the initial stress's.
  NetworkMaterial(const model::network::Parameters<double>& parameters,
                  const NetworkInitialState& initial_state, double youngs_modulus);
  /// t(A) = A_zz - (A_xx + A_yy)/2, the DEM's triaxial fabric anisotropy a_c.
  std::optional<double> fabric_invariant(const PointState& state) const override;
  /// The model's state of a point (for tests and output).
  model::network::State<double> to_model(const PointState& state) const;
};

}  // namespace fe_model

#endif  // FE_MODEL_NETWORK_MATERIAL_H_
