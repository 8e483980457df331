// The contact-network adapter: calibration/network_model.h behind fe_model::Material.
#include "fe_model/network_material.h"

#include <ceres/jet.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "tensor_conversion.h"

namespace fe_model {
namespace {

namespace net = calibration::network;
using internal::pack;
using internal::to_deal;
using internal::to_eigen;
using internal::unpack;

// An increment needing more substeps fails, so that the FE code cuts it.
constexpr int kMaxSubsteps = 10000;

// Voigt order of the independent strain components seeded in the tangent's dual numbers.
constexpr int kI[6] = {0, 1, 2, 0, 1, 0};
constexpr int kJ[6] = {0, 1, 2, 1, 2, 2};

bool admissible(const net::State<double>& s) {
  return std::isfinite(s.void_ratio) && s.void_ratio > 0.0 && std::isfinite(s.coordination) &&
         s.coordination > 0.0 && std::isfinite(s.lambda) && s.lambda > 0.0 &&
         s.fabric.allFinite() && s.normal.allFinite() && s.tangential.allFinite();
}

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
                           " internal variables, expected 30 (not a contact-network state?)");
  return {v[0], v[1], v[2], unpack(v, 3), unpack(v, 12), unpack(v, 21)};
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
}

PointState NetworkMaterial::initial_state(const SymmetricTensor2& initial_stress) const {
  const double p = -trace(initial_stress) / 3.0;  // compression positive
  if (!(p > 0.0))
    throw std::invalid_argument("NetworkMaterial: the initial mean stress must be compressive (p = " +
                                std::to_string(p) + " Pa)");
  net::State<double> model{initial_.void_ratio, initial_.coordination, 0.0, initial_.fabric,
                           initial_.normal, initial_.tangential};
  const double product = 1.0 + 2.0 / 15.0 * (initial_.normal * initial_.fabric).trace();
  model.lambda = 3.0 * p * (1.0 + model.void_ratio) /
                 (youngs_modulus_ * model.coordination * product);
  PointState state;
  from_model(model, SymmetricTensor2(), state);
  return state;
}

MaterialUpdate NetworkMaterial::update(const PointState& start,
                                       const SymmetricTensor2& strain_increment,
                                       PointState& end) const {
  using Dual = ceres::Jet<double, 6>;
  const net::State<double> s0 = to_model(start);
  const Eigen::Matrix3d increment = -to_eigen(strain_increment);  // -> compression positive
  // Dual numbers seeded on the six independent components (eps_kl and eps_lk move together).
  net::Tensor<Dual> d;
  for (int a = 0; a < 6; ++a) {
    Dual x(increment(kI[a], kJ[a]), a);
    d(kI[a], kJ[a]) = d(kJ[a], kI[a]) = x;
  }
  auto lift = [](double x) { return Dual(x); };
  const net::State<Dual> s0_dual{lift(s0.void_ratio),           lift(s0.coordination),
                                 lift(s0.lambda),               s0.fabric.unaryExpr(lift),
                                 s0.normal.unaryExpr(lift),     s0.tangential.unaryExpr(lift)};
  const auto par = net::to_array(parameters_);
  std::array<Dual, net::kNumParameters> par_dual;
  for (int i = 0; i < net::kNumParameters; ++i) par_dual[i] = Dual(par[i]);
  const int substeps = net::substeps_for(parameters_, s0, increment.norm());
  if (substeps > kMaxSubsteps) {
    MaterialUpdate failed;
    failed.status = MaterialStatus::kFailed;
    failed.message = "contact-network update: the strain increment of norm " +
                     std::to_string(increment.norm()) + " needs " + std::to_string(substeps) +
                     " RK4 substeps, more than " + std::to_string(kMaxSubsteps) + " (cut it)";
    end = start;
    return failed;
  }
  const net::State<Dual> s1 =
      net::integrate(net::from_array(par_dual.data()), s0_dual, d, substeps);
  auto value = [](const Dual& x) { return x.a; };
  const net::State<double> model_end{s1.void_ratio.a,           s1.coordination.a,
                                     s1.lambda.a,               s1.fabric.unaryExpr(value),
                                     s1.normal.unaryExpr(value), s1.tangential.unaryExpr(value)};
  MaterialUpdate result;
  if (!admissible(model_end)) {
    std::ostringstream why;
    why << "contact-network update failed: the state left its admissible range (e "
        << model_end.void_ratio << ", Z " << model_end.coordination << ", Lambda "
        << model_end.lambda << ") over the strain increment of norm " << increment.norm();
    result.status = MaterialStatus::kFailed;
    result.message = why.str();
    end = start;  // never hand NaN to the caller
    return result;
  }
  from_model(model_end, start.strain + strain_increment, end);
  // d sigma_ij / d eps_kl: a shear seed moved eps_kl and eps_lk together, so it carries twice the
  // tensor component. Both signs flip, so the tension-positive tangent is the same.
  const net::Tensor<Dual> sigma = net::stress(s1, youngs_modulus_);
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = i; j < 3; ++j)
      for (int a = 0; a < 6; ++a) {
        const double dij = 0.5 * (sigma(i, j).v[a] + sigma(j, i).v[a]);
        result.tangent[i][j][kI[a]][kJ[a]] = kI[a] == kJ[a] ? dij : 0.5 * dij;
      }
  return result;
}

std::optional<double> NetworkMaterial::fabric_invariant(const PointState& state) const {
  if (state.internal_variables.size() != kNumInternalVariables) return std::nullopt;
  const Eigen::Matrix3d A = unpack(state.internal_variables, 3);
  return A(2, 2) - 0.5 * (A(0, 0) + A(1, 1));
}

}  // namespace fe_model
