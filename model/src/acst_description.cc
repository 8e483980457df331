// The ACST model behind the model interface (descriptor.h): its tables, its state laid out as the
// UMAT's STATEV(2..22) (model/umat.h) and its Behaviour, the implicit integration with its
// consistent tangent (acst_model.h).
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/acst_model.h"
#include "model/descriptor.h"
#include "parameter_vector.h"

namespace model {

namespace {

using acst::Parameters;
using acst::State;
using acst::Tensor;

const std::vector<Slot> kInitialInputs = {
    {"void_ratio", Slot::kScalar, "1", "initial void ratio e_0"},
    {"fabric", Slot::kTensor, "1", "initial model fabric F_0 (deviatoric)"},
};

const std::vector<Slot> kState = {
    {"void_ratio", Slot::kScalar, "1", "void ratio e"},
    {"alpha", Slot::kTensor, "1", "back-stress ratio alpha"},
    {"alpha_in", Slot::kTensor, "1", "alpha at the last load reversal"},
    {"fabric", Slot::kTensor, "1", "model fabric F"},
    {"status", Slot::kScalar, "1", "the last update: 0 ok, 1 unreliable"},
    {"substeps", Slot::kScalar, "1", "substeps of the last update"},
};
// Offsets into kState.
constexpr int kVoidRatio = 0, kAlpha = 1, kAlphaIn = 7, kFabric = 13, kStatus = 19, kSubsteps = 20;

Parameters<double> typed(const std::vector<double>& values) {
  return set_from_table_order<Parameters<double>>(acst::kParameterFields<double>, values);
}

class AcstBehaviour final : public Behaviour {
 public:
  AcstBehaviour(const ModelDescription& description, const Parameters<double>& parameters,
                const acst::IntegrationOptions& options)
      : description_(description), parameters_(parameters), options_(options) {}

  const ModelDescription& description() const override { return description_; }

  // The hypoelastic stiffness of Eq. (1) at the state (docs/model.md), the tangent a failed
  // update returns; zero outside the elastic law's domain.
  Eigen::Matrix<double, 9, 9> elastic_tangent(const State<double>& s) const {
    Eigen::Matrix<double, 9, 9> d = Eigen::Matrix<double, 9, 9>::Zero();
    const double p = s.stress.trace() / 3.0;
    if (!(p > 0.0) || !acst::is_admissible_void_ratio(s.void_ratio)) return d;
    double G = 0.0, K = 0.0;
    acst::detail::elastic_moduli(parameters_, p, s.void_ratio, G, K);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        d(3 * i + i, 3 * j + j) = K - 2.0 * G / 3.0 + (i == j ? 2.0 * G : 0.0);
        if (i != j) d(3 * i + j, 3 * i + j) = d(3 * i + j, 3 * j + i) = G;
      }
    return d;
  }

  Eigen::Matrix3d initial_state(const Eigen::Matrix3d& stress, const double* inputs,
                                double* state) const override {
    const double e = inputs[0];
    if (!acst::is_admissible_void_ratio(e))
      throw InvalidInput("void_ratio", "the initial void ratio " + format_number(e) +
                                           " is not physical: it must be in (0, 2.97)");
    const Tensor<double> fabric = tensor_from_slot(inputs + 1);
    if (!fabric.allFinite()) throw InvalidInput("fabric", "the initial fabric is not finite");
    const double p = stress.trace() / 3.0;
    const Tensor<double> alpha =
        p > 0.0 ? Tensor<double>((stress - p * Tensor<double>::Identity()) / p)
                : Tensor<double>(Tensor<double>::Zero());
    state[kVoidRatio] = e;
    tensor_to_slot(alpha, state + kAlpha);
    tensor_to_slot(alpha, state + kAlphaIn);
    tensor_to_slot(fabric, state + kFabric);
    state[kStatus] = 0.0;
    state[kSubsteps] = 0.0;
    return stress;
  }

  PointUpdate update(const Eigen::Matrix3d& stress, const double* state_start,
                     const Eigen::Matrix3d& strain_increment, double* state_end) const override {
    State<double> start;
    start.stress = stress;
    start.void_ratio = state_start[kVoidRatio];
    start.alpha = tensor_from_slot(state_start + kAlpha);
    start.alpha_in = tensor_from_slot(state_start + kAlphaIn);
    start.fabric = tensor_from_slot(state_start + kFabric);
    State<double> end;
    PointUpdate result;
    acst::UpdateReport report;
    result.status = acst::update_with_tangent(parameters_, start, strain_increment, end,
                                              result.tangent, options_, &report);
    const int n = slot_components(kState);
    if (result.status == UpdateStatus::kFailed) {
      std::copy(state_start, state_start + n, state_end);
      result.stress = stress;
      result.tangent = elastic_tangent(start);
      result.step_ratio = 0.5;
      result.message = report.message;
      return result;
    }
    result.stress = end.stress;
    state_end[kVoidRatio] = end.void_ratio;
    tensor_to_slot(end.alpha, state_end + kAlpha);
    tensor_to_slot(end.alpha_in, state_end + kAlphaIn);
    tensor_to_slot(end.fabric, state_end + kFabric);
    state_end[kStatus] = result.status == UpdateStatus::kOk ? 0.0 : 1.0;
    state_end[kSubsteps] = static_cast<double>(report.substeps);
    if (result.status == UpdateStatus::kUnreliable) {
      result.step_ratio = 0.5;
      result.message = report.message;
    }
    return result;
  }

 private:
  const ModelDescription& description_;
  Parameters<double> parameters_;
  acst::IntegrationOptions options_;
};

class AcstDescription final : public ModelDescription {
 public:
  std::string name() const override { return "acst"; }
  std::string umat_name() const override { return "ACST"; }
  const std::vector<ParameterInfo>& constants() const override {
    // p_a, fixed (acst_model.h): stated in the parameter file, not in PROPS.
    static const std::vector<ParameterInfo> constants = {
        {"reference_pressure", "Pa",
         {acst::kAtmosphericPressure, acst::kAtmosphericPressure, true, true},
         acst::kAtmosphericPressure, acst::kAtmosphericPressure, acst::kAtmosphericPressure}};
    return constants;
  }
  const std::vector<ParameterInfo>& parameters() const override {
    static const std::vector<ParameterInfo> infos = parameter_infos(acst::kParameterFields<double>);
    return infos;
  }
  const std::vector<Slot>& initial_inputs() const override { return kInitialInputs; }
  const std::vector<Slot>& state() const override { return kState; }
  void validate(const std::vector<double>& constants,
                const std::vector<double>& parameters) const override {
    ModelDescription::validate(constants, parameters);
    try {
      acst::validate_parameters(typed(parameters));  // the coupled conditions
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(e.what());
    }
  }
  std::unique_ptr<Behaviour> make(const std::vector<double>& constants,
                                  const std::vector<double>& parameters) const override {
    validate(constants, parameters);
    return std::make_unique<AcstBehaviour>(*this, typed(parameters), acst::IntegrationOptions());
  }
};

}  // namespace

const ModelDescription& acst_description() {
  static const AcstDescription description;
  return description;
}

std::unique_ptr<Behaviour> acst::make_behaviour(const acst::Parameters<double>& par,
                                                const acst::IntegrationOptions& options) {
  acst_description().validate({acst::kAtmosphericPressure},
                              values_in_table_order(acst::kParameterFields<double>, par));
  return std::make_unique<AcstBehaviour>(acst_description(), par, options);
}

}  // namespace model
