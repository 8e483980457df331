// The contact-network model behind the model interface (descriptor.h): its tables, its state laid
// out as the UMAT's STATEV(2..29) (model/umat_network.h) and its Behaviour, the RK4 update with
// its exact tangent (network_update.h). Its stress is the SFF equation of its state.
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/descriptor.h"
#include "model/network_model.h"
#include "model/network_update.h"

namespace model {

namespace {

using network::Parameters;
using network::State;

const std::vector<Slot> kInitialInputs = {
    {"void_ratio", Slot::kScalar, "1", "initial void ratio e_0"},
    {"coordination", Slot::kScalar, "1", "initial coordination number Z_0"},
    {"fabric", Slot::kTensor, "1", "initial fabric anisotropy A_0 (deviatoric)"},
    {"normal", Slot::kTensor, "1", "initial normal-force anisotropy F_0 (deviatoric)"},
    {"tangential", Slot::kTensor, "1", "initial tangential-force anisotropy F^t_0 (deviatoric)"},
};

const std::vector<Slot> kState = {
    {"void_ratio", Slot::kScalar, "1", "void ratio e"},
    {"coordination", Slot::kScalar, "1", "coordination number Z"},
    {"lambda", Slot::kScalar, "1", "mean normal contact force over E d^2, Lambda"},
    {"fabric", Slot::kTensor, "1", "fabric anisotropy A"},
    {"normal", Slot::kTensor, "1", "normal-force anisotropy F"},
    {"tangential", Slot::kTensor, "1", "tangential-force anisotropy F^t"},
    {"substeps", Slot::kScalar, "1", "RK4 substeps of the last update"},
    {"inherent", Slot::kTensor, "1", "the fabric's inherent part A_i (Eq. N2d)"},
};
// Offsets into kState.
constexpr int kVoidRatio = 0, kCoordination = 1, kLambda = 2, kFabric = 3, kNormal = 9,
              kTangential = 15, kSubsteps = 21, kInherent = 22;

State<double> from_state(const double* s) {
  return {s[kVoidRatio],
          s[kCoordination],
          s[kLambda],
          tensor_from_slot(s + kFabric),
          tensor_from_slot(s + kNormal),
          tensor_from_slot(s + kTangential),
          tensor_from_slot(s + kInherent)};
}

void to_state(const State<double>& m, int substeps, double* s) {
  s[kVoidRatio] = m.void_ratio;
  s[kCoordination] = m.coordination;
  s[kLambda] = m.lambda;
  tensor_to_slot(m.fabric, s + kFabric);
  tensor_to_slot(m.normal, s + kNormal);
  tensor_to_slot(m.tangential, s + kTangential);
  s[kSubsteps] = static_cast<double>(substeps);
  tensor_to_slot(m.inherent, s + kInherent);
}

// A deviatoric tensor of the initial inputs; throws naming it otherwise.
Eigen::Matrix3d deviatoric_input(const double* v, const char* slot, const std::string& name) {
  const Eigen::Matrix3d t = tensor_from_slot(v);
  if (!t.allFinite()) throw InvalidInput(slot, "the initial " + name + " is not finite");
  if (std::abs(t.trace()) > 1e-9 * std::max(1.0, t.norm()))
    throw InvalidInput(slot, "the initial " + name + " has the trace " +
                                 std::to_string(t.trace()) + ": it must be deviatoric");
  return t;
}

class NetworkBehaviour final : public Behaviour {
 public:
  NetworkBehaviour(const ModelDescription& description, const Parameters<double>& parameters,
                   double youngs_modulus)
      : description_(description), parameters_(parameters), youngs_modulus_(youngs_modulus) {}

  const ModelDescription& description() const override { return description_; }

  Eigen::Matrix3d initial_state(const Eigen::Matrix3d& stress, const double* inputs,
                                double* state) const override {
    State<double> s;
    s.void_ratio = inputs[0];
    s.coordination = inputs[1];
    if (!(s.void_ratio > 0.0) || !std::isfinite(s.void_ratio))
      throw InvalidInput("void_ratio", "the initial void ratio " + std::to_string(s.void_ratio) +
                                           " must be > 0");
    if (!(s.coordination > 0.0) || !std::isfinite(s.coordination))
      throw InvalidInput("coordination", "the initial coordination number " +
                                             std::to_string(s.coordination) + " must be > 0");
    s.fabric = deviatoric_input(inputs + 2, "fabric", "fabric anisotropy A");
    s.normal = deviatoric_input(inputs + 8, "normal", "normal-force anisotropy F");
    s.tangential = deviatoric_input(inputs + 14, "tangential", "tangential-force anisotropy F^t");
    s.inherent = s.fabric;  // the specimen's initial fabric is all its own (Eq. N2d)
    const double p = stress.trace() / 3.0;
    if (!(p > 0.0))
      throw std::invalid_argument("contact_network: the initial stress must be compressive (mean "
                                  "stress " + std::to_string(p) + " Pa, compression positive)");
    s.lambda = network::lambda_for_mean_stress(s, p, youngs_modulus_);
    to_state(s, 0, state);
    return network::stress(s, youngs_modulus_);
  }

  PointUpdate update(const Eigen::Matrix3d& stress, const double* state_start,
                     const Eigen::Matrix3d& strain_increment, double* state_end) const override {
    const network::UpdateResult u = network::update_with_tangent(
        parameters_, from_state(state_start), strain_increment, youngs_modulus_);
    PointUpdate result;
    result.status = u.status;
    if (u.status == UpdateStatus::kFailed) {
      std::copy(state_start, state_start + slot_components(kState), state_end);
      result.stress = stress;
      // The start's stiffness: the tangent of a zero increment (zero where even that fails).
      result.tangent = network::update_with_tangent(parameters_, from_state(state_start),
                                                    Eigen::Matrix3d::Zero(), youngs_modulus_)
                           .tangent;
      result.step_ratio = 0.5;
      result.message = u.message;
      return result;
    }
    result.stress = network::stress(u.end, youngs_modulus_);
    result.tangent = u.tangent;
    to_state(u.end, u.substeps, state_end);
    return result;
  }

 private:
  const ModelDescription& description_;
  Parameters<double> parameters_;
  double youngs_modulus_;
};

class NetworkDescription final : public ModelDescription {
 public:
  std::string name() const override { return "contact_network"; }
  std::string umat_name() const override { return "CONTACT_NETWORK"; }
  std::string parameter_file_variable() const override { return "SFFCAL_NETWORK_PARAMETERS"; }
  const std::vector<ParameterInfo>& constants() const override {
    // The grains' Young's modulus, the normalisation of Lambda (150 MPa in the DEM).
    static const std::vector<ParameterInfo> constants = {
        {"youngs_modulus", "Pa", {0.0, kUnbounded, false, false}, 0.0, kUnbounded}};
    return constants;
  }
  const std::vector<ParameterInfo>& parameters() const override {
    static const std::vector<ParameterInfo> infos =
        parameter_infos(network::kParameterFields<double>);
    return infos;
  }
  const std::vector<Slot>& initial_inputs() const override { return kInitialInputs; }
  const std::vector<Slot>& state() const override { return kState; }
  std::unique_ptr<Behaviour> make(const std::vector<double>& constants,
                                  const std::vector<double>& parameters) const override {
    validate(constants, parameters);
    return std::make_unique<NetworkBehaviour>(*this, network::from_array(parameters.data()),
                                              constants[0]);
  }
};

}  // namespace

const ModelDescription& network_description() {
  static const NetworkDescription description;
  return description;
}

std::unique_ptr<Behaviour> network::make_behaviour(const network::Parameters<double>& par,
                                                   double youngs_modulus) {
  const auto x = network::to_array(par);
  network_description().validate({youngs_modulus}, {x.begin(), x.end()});
  return std::make_unique<NetworkBehaviour>(network_description(), par, youngs_modulus);
}

}  // namespace model
