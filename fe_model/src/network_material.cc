// The contact-network adapter: model/network_model.h behind fe_model::Material.
#include "fe_model/network_material.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "model/network_update.h"
#include "tensor_conversion.h"

namespace fe_model {
namespace {

namespace net = model::network;
using internal::pack;
using internal::to_deal;
using internal::to_eigen;
using internal::unpack;

}  // namespace

NetworkMaterial::NetworkMaterial(const net::Parameters<double>& parameters,
                                 const NetworkInitialState& initial_state, double youngs_modulus)
    : parameters_(parameters), initial_(initial_state), youngs_modulus_(youngs_modulus) {
  net::validate(parameters);  // throws, naming the parameter
  if (!(initial_state.void_ratio > 0.0) || !std::isfinite(initial_state.void_ratio))
    throw std::invalid_argument("NetworkMaterial: initial void ratio " +
                                std::to_string(initial_state.void_ratio) + " must be > 0");
  if (!(initial_state.coordination > 0.0) || !std::isfinite(initial_state.coordination))
    throw std::invalid_argument("NetworkMaterial: initial coordination " +
                                std::to_string(initial_state.coordination) + " must be > 0");
  if (!initial_state.fabric.allFinite() || !initial_state.normal.allFinite() ||
      !initial_state.tangential.allFinite())
    throw std::invalid_argument("NetworkMaterial: an initial anisotropy tensor is not finite");
  if (!(youngs_modulus > 0.0) || !std::isfinite(youngs_modulus))
    throw std::invalid_argument("NetworkMaterial: Young's modulus of the grains " +
                                std::to_string(youngs_modulus) + " Pa must be > 0");
}

net::State<double> NetworkMaterial::to_model(const PointState& state) {
  const auto& v = state.internal_variables;
  if (v.size() != kNumInternalVariables)
    throw std::logic_error("NetworkMaterial: point state has " + std::to_string(v.size()) +
                           " internal variables, expected " +
                           std::to_string(kNumInternalVariables) +
                           " (not a contact-network state?)");
  return {v[0], v[1], v[2], unpack(v, 3), unpack(v, 12), unpack(v, 21), unpack(v, 30)};
}

void NetworkMaterial::from_model(const net::State<double>& model, const SymmetricTensor2& strain,
                                 PointState& state) const {
  state.stress = -to_deal(net::stress(model, youngs_modulus_));  // -> tension positive
  state.strain = strain;
  auto& v = state.internal_variables;
  v.resize(kNumInternalVariables);
  v[0] = model.void_ratio;
  v[1] = model.coordination;
  v[2] = model.lambda;
  pack(model.fabric, v, 3);
  pack(model.normal, v, 12);
  pack(model.tangential, v, 21);
  pack(model.inherent, v, 30);
}

PointState NetworkMaterial::initial_state(const SymmetricTensor2& initial_stress) const {
  const double p = -trace(initial_stress) / 3.0;  // compression positive
  if (!(p > 0.0))
    throw std::invalid_argument("NetworkMaterial: the initial mean stress must be compressive (p = " +
                                std::to_string(p) + " Pa)");
  // The initial fabric is all the specimen's own (its inherent part, Eq. N2d).
  net::State<double> model{initial_.void_ratio, initial_.coordination, 0.0,
                           initial_.fabric,     initial_.normal,       initial_.tangential,
                           initial_.fabric};
  model.lambda = net::lambda_for_mean_stress(model, p, youngs_modulus_);
  PointState state;
  from_model(model, SymmetricTensor2(), state);
  return state;
}

MaterialUpdate NetworkMaterial::update(const PointState& start,
                                       const SymmetricTensor2& strain_increment,
                                       PointState& end) const {
  const Eigen::Matrix3d increment = -to_eigen(strain_increment);  // -> compression positive
  const net::UpdateResult update =
      net::update_with_tangent(parameters_, to_model(start), increment, youngs_modulus_);
  MaterialUpdate result;
  result.status = update.status;
  if (update.status == MaterialStatus::kFailed) {
    result.message = update.message;
    end = start;  // never hand NaN to the caller
    return result;
  }
  from_model(update.end, start.strain + strain_increment, end);
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = i; j < 3; ++j)
      for (unsigned int k = 0; k < 3; ++k)
        for (unsigned int l = k; l < 3; ++l)
          result.tangent[i][j][k][l] = update.tangent(3 * i + j, 3 * k + l);
  return result;
}

std::optional<double> NetworkMaterial::fabric_invariant(const PointState& state) const {
  if (state.internal_variables.size() != kNumInternalVariables) return std::nullopt;
  const Eigen::Matrix3d A = unpack(state.internal_variables, 3);
  return A(2, 2) - 0.5 * (A(0, 0) + A(1, 1));
}

}  // namespace fe_model
