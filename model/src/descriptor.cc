// The model interface's shared helpers (descriptor.h): slot layouts, their tensors and rotation,
// and the validation every model's values go through.
#include "model/descriptor.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace model {

namespace {

// The UMAT's component order 11, 22, 33, 12, 13, 23.
constexpr int kRow[6] = {0, 1, 2, 0, 0, 1};
constexpr int kCol[6] = {0, 1, 2, 1, 2, 2};

void check_values(const char* what, const std::string& model,
                  const std::vector<ParameterInfo>& table, const std::vector<double>& values) {
  if (values.size() != table.size())
    throw std::invalid_argument(model + ": " + std::to_string(values.size()) + " " + what +
                                " given, " + std::to_string(table.size()) + " expected");
  for (std::size_t i = 0; i < table.size(); ++i)
    if (!std::isfinite(values[i]) || !table[i].physical.contains(values[i]))
      throw std::invalid_argument(model + " " + what + " '" + table[i].name + "' = " +
                                  format_number(values[i]) + " is not physical: it must be " +
                                  table[i].physical.describe());
}

}  // namespace

int slot_components(const std::vector<Slot>& slots) {
  int n = 0;
  for (const Slot& s : slots) n += s.size();
  return n;
}

int slot_offset(const std::vector<Slot>& slots, const std::string& name) {
  int offset = 0;
  for (const Slot& s : slots) {
    if (name == s.name) return offset;
    offset += s.size();
  }
  return -1;
}

Eigen::Matrix3d tensor_from_slot(const double* v) {
  Eigen::Matrix3d t;
  for (int k = 0; k < 6; ++k) t(kRow[k], kCol[k]) = t(kCol[k], kRow[k]) = v[k];
  return t;
}

void tensor_to_slot(const Eigen::Matrix3d& t, double* v) {
  for (int k = 0; k < 6; ++k) v[k] = t(kRow[k], kCol[k]);
}

std::vector<double> umat_props(const ModelDescription& d, const std::vector<double>& inputs,
                               const std::vector<double>& constants,
                               const std::vector<double>& parameters) {
  if (static_cast<int>(inputs.size()) != slot_components(d.initial_inputs()) ||
      constants.size() != d.constants().size() || parameters.size() != d.parameters().size())
    throw std::invalid_argument("UMAT PROPS of model '" + d.name() + "': " +
                                std::to_string(inputs.size()) + " inputs, " +
                                std::to_string(constants.size()) + " constants and " +
                                std::to_string(parameters.size()) + " parameters given, " +
                                std::to_string(slot_components(d.initial_inputs())) + ", " +
                                std::to_string(d.constants().size()) + " and " +
                                std::to_string(d.parameters().size()) + " needed");
  std::vector<double> props = inputs;
  for (std::size_t i = 0; i < constants.size(); ++i)
    if (!d.constants()[i].fixed()) props.push_back(constants[i]);
  props.insert(props.end(), parameters.begin(), parameters.end());
  return props;
}

std::vector<std::string> umat_props_names(const ModelDescription& d) {
  static const char* const kComponents[6] = {"11", "22", "33", "12", "13", "23"};
  std::vector<std::string> names;
  for (const Slot& s : d.initial_inputs()) {
    if (s.kind == Slot::kScalar) {
      names.push_back(s.name);
    } else {
      for (const char* c : kComponents) names.push_back(std::string(s.name) + "_" + c);
    }
  }
  for (const ParameterInfo& c : d.constants())
    if (!c.fixed()) names.push_back(c.name);
  for (const ParameterInfo& p : d.parameters()) names.push_back(p.name);
  return names;
}

void rotate_state(const std::vector<Slot>& slots, const Eigen::Matrix3d& rotation, double* state) {
  for (const Slot& s : slots) {
    if (s.kind == Slot::kTensor) {
      const Eigen::Matrix3d turned = rotation * tensor_from_slot(state) * rotation.transpose();
      tensor_to_slot(0.5 * (turned + turned.transpose()), state);
    }
    state += s.size();
  }
}

void ModelDescription::validate(const std::vector<double>& constants,
                                const std::vector<double>& parameters) const {
  check_values("constant", name(), this->constants(), constants);
  check_values("parameter", name(), this->parameters(), parameters);
}

}  // namespace model
