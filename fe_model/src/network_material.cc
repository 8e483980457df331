// The contact-network model at a quadrature point (network_material.h): the model interface's
// adapter.
#include "fe_model/network_material.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/network_update.h"

namespace fe_model {
namespace {

// e_0, Z_0, A_0, F_0, F^t_0, laid out as the network's initial inputs.
std::vector<double> initial_inputs(const NetworkInitialState& initial) {
  std::vector<double> inputs(20);
  inputs[0] = initial.void_ratio;
  inputs[1] = initial.coordination;
  model::tensor_to_slot(initial.fabric, inputs.data() + 2);
  model::tensor_to_slot(initial.normal, inputs.data() + 8);
  model::tensor_to_slot(initial.tangential, inputs.data() + 14);
  return inputs;
}

}  // namespace

NetworkMaterial::NetworkMaterial(const model::network::Parameters<double>& parameters,
                                 const NetworkInitialState& initial_state, double youngs_modulus)
    : ModelMaterial(model::network::make_behaviour(parameters, youngs_modulus),
                    initial_inputs(initial_state)) {
  if (!(initial_state.void_ratio > 0.0) || !std::isfinite(initial_state.void_ratio))
    throw std::invalid_argument("NetworkMaterial: initial void ratio " +
                                std::to_string(initial_state.void_ratio) + " must be > 0");
  if (!(initial_state.coordination > 0.0) || !std::isfinite(initial_state.coordination))
    throw std::invalid_argument("NetworkMaterial: initial coordination " +
                                std::to_string(initial_state.coordination) + " must be > 0");
  if (!initial_state.fabric.allFinite() || !initial_state.normal.allFinite() ||
      !initial_state.tangential.allFinite())
    throw std::invalid_argument("NetworkMaterial: an initial anisotropy tensor is not finite");
}

model::network::State<double> NetworkMaterial::to_model(const PointState& state) const {
  const auto& v = state.internal_variables;
  return {v.at(0), v.at(1), v.at(2), state_tensor(state, "fabric"), state_tensor(state, "normal"),
          state_tensor(state, "tangential"), state_tensor(state, "inherent")};
}

std::optional<double> NetworkMaterial::fabric_invariant(const PointState& state) const {
  if (state.internal_variables.size() != kNumInternalVariables) return std::nullopt;
  const Eigen::Matrix3d A = state_tensor(state, "fabric");
  return A(2, 2) - 0.5 * (A(0, 0) + A(1, 1));
}

}  // namespace fe_model
