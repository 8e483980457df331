// The ACST model at a quadrature point (acst_material.h): the model interface's adapter with
// ACST's integration options.
#include "fe_model/acst_material.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "tensor_conversion.h"

namespace fe_model {
namespace {

// e_0 and F_0, laid out as ACST's initial inputs (void_ratio, fabric).
std::vector<double> initial_inputs(const AcstInitialState& initial) {
  std::vector<double> inputs(7);
  inputs[0] = initial.void_ratio;
  model::tensor_to_slot(initial.fabric, inputs.data() + 1);
  return inputs;
}

}  // namespace

AcstMaterial::AcstMaterial(const model::acst::Parameters<double>& parameters,
                           const AcstInitialState& initial_state,
                           const model::acst::IntegrationOptions& options)
    : ModelMaterial(model::acst::make_behaviour(parameters, options),
                    initial_inputs(initial_state)) {
  if (!model::acst::is_admissible_void_ratio(initial_state.void_ratio))
    throw std::invalid_argument("AcstMaterial: initial void ratio " +
                                std::to_string(initial_state.void_ratio) +
                                " is not physical: it must be in (0, 2.97)");
  if (!initial_state.fabric.allFinite())
    throw std::invalid_argument("AcstMaterial: the initial fabric is not finite");
}

model::acst::State<double> AcstMaterial::to_model(const PointState& state) const {
  model::acst::State<double> s;
  s.stress = -internal::to_eigen(state.stress);
  s.void_ratio = state.internal_variables.at(0);
  s.alpha = state_tensor(state, "alpha");
  s.alpha_in = state_tensor(state, "alpha_in");
  s.fabric = state_tensor(state, "fabric");
  return s;
}

std::optional<double> AcstMaterial::fabric_invariant(const PointState& state) const {
  if (state.internal_variables.size() != kNumInternalVariables) return std::nullopt;
  const Eigen::Matrix3d F = state_tensor(state, "fabric");
  const double c = std::sqrt(2.0 / 3.0);
  return c * (F(2, 2) - 0.5 * (F(0, 0) + F(1, 1)));
}

}  // namespace fe_model
