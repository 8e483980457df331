// fe_model::Material adapter for the contact-network model of calibration/ (network_model.h,
// docs/network-model.md): the stress is the SFF equation of the point's state (e, Z, Lambda, A, F,
// F^t), integrated by RK4 substeps; the consistent tangent comes exactly from forward-mode dual
// numbers seeded on the strain increment.
//
// Signs: the model is compression positive, fe_model tension positive; the adapter flips the
// strain increment and the stress (the tangent is the same in both conventions).
// Internal variables (PointState::internal_variables, compression positive, row-major 3x3):
//   [0] void ratio, [1] coordination Z, [2] Lambda, [3..11] A, [12..20] F, [21..29] F^t,
//   [30..38] A_i, the fabric's inherent part (Eq. N2d; the initial fabric at the start).
#ifndef FE_MODEL_NETWORK_MATERIAL_H_
#define FE_MODEL_NETWORK_MATERIAL_H_

#include <Eigen/Core>
#include <string>

#include "model/network_model.h"
#include "fe_model/material.h"

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

class NetworkMaterial final : public Material {
 public:
  static constexpr std::size_t kNumInternalVariables = 39;

  /// Throws std::invalid_argument naming a parameter outside its range or a non-physical initial
  /// state (void ratio or coordination not positive, a tensor not finite). youngs_modulus: the
  /// grains' E [Pa] that normalises Lambda (150 MPa in the DEM).
  NetworkMaterial(const model::network::Parameters<double>& parameters,
                  const NetworkInitialState& initial_state, double youngs_modulus);

  std::string name() const override { return "contact_network"; }
  /// Lambda = 3 p (1 + e) / (E Z (1 + (2/15) tr(FA))), so that the SFF stress of the state has the
  /// initial mean stress p; the point's stress is that SFF stress, whose deviator is the one the
  /// initial anisotropies carry (zero for an isotropic network), not the initial stress's.
  PointState initial_state(const SymmetricTensor2& initial_stress) const override;
  MaterialUpdate update(const PointState& start, const SymmetricTensor2& strain_increment,
                        PointState& end) const override;
  /// t(A) = A_zz - (A_xx + A_yy)/2, the DEM's triaxial fabric anisotropy a_c.
  std::optional<double> fabric_invariant(const PointState& state) const override;

  static model::network::State<double> to_model(const PointState& state);
  void from_model(const model::network::State<double>& model,
                  const SymmetricTensor2& strain, PointState& state) const;

 private:
  model::network::Parameters<double> parameters_;
  NetworkInitialState initial_;
  double youngs_modulus_;
};

}  // namespace fe_model

#endif  // FE_MODEL_NETWORK_MATERIAL_H_
