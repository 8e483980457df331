// The contact-network model's stress update with its exact consistent tangent (network_model.h,
// docs/network-model.md): RK4 substeps of the strain increment in forward-mode dual numbers seeded
// on its six independent components. Behind the model interface (make_behaviour), so the FE
// adapter (fe_model::NetworkMaterial) and the UMAT (model/umat_network.h) give the same numbers.
// Needs only Eigen.
//
// Conventions: compression positive, stress in Pa, tensor shear components.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <memory>
#include <string>

#include "model/descriptor.h"
#include "model/network_model.h"
#include "model/update_status.h"

namespace model::network {

/// An increment needing more RK4 substeps than this fails, so that the caller cuts it.
inline constexpr int kMaxUpdateSubsteps = 10000;

struct UpdateResult {
  /// kOk or kFailed (model/update_status.h): RK4 with a fixed substep count has no unreliable case.
  UpdateStatus status = UpdateStatus::kFailed;
  State<double> end;  ///< the start state where failed
  /// d sigma_ij / d eps_kl at row 3 i + j, column 3 k + l, symmetric in (k, l): d sigma_ij =
  /// tangent(ij, kl) d eps_kl summed over all nine kl. The same in the tension-positive
  /// convention (both signs flip).
  Eigen::Matrix<double, 9, 9> tangent = Eigen::Matrix<double, 9, 9>::Zero();
  int substeps = 0;
  std::string message;  ///< why it failed
};

/// Integrates the strain increment (compression positive) from `start` with substeps_for's
/// substep count. Fails (kFailed, the start state kept, message saying why) where the increment
/// needs more than max_substeps substeps or the end state is not admissible (void ratio,
/// coordination or Lambda not positive, or anything not finite).
UpdateResult update_with_tangent(const Parameters<double>& par, const State<double>& start,
                                 const Tensor<double>& increment, double youngs_modulus,
                                 int max_substeps = kMaxUpdateSubsteps);

/// The model behind the model interface (model/descriptor.h) with these parameters and the grains'
/// E [Pa] (validated: std::invalid_argument naming a value that is not physical).
std::unique_ptr<Behaviour> make_behaviour(const Parameters<double>& par, double youngs_modulus);

/// True where the state can carry a stress: e, Z, Lambda positive and everything finite.
template <typename M>
bool admissible(const State<double, M>& s) {
  return std::isfinite(s.void_ratio) && s.void_ratio > 0.0 && std::isfinite(s.coordination) &&
         s.coordination > 0.0 && std::isfinite(s.lambda) && s.lambda > 0.0 &&
         all_finite(s.fabric) && all_finite(s.normal) && all_finite(s.tangential) &&
         all_finite(s.inherent);
}

/// Lambda such that the SFF stress (network_model.h) of the network (e, Z, A, F) has the mean
/// stress p [Pa]: p = E Z Lambda (1 + (2/15) tr(FA)) / (3 (1 + e)), a third of the trace of
/// the SFF equation (sff-theory.md §4): with A, F, F^t deviatoric the bracket's trace is
/// 1 + (3 * 2/105 + 8/105) tr(FA).
double lambda_for_mean_stress(const State<double>& network, double p, double youngs_modulus);

}  // namespace model::network
