// The deal.II material adapter of every registered model (model_material.h).
#include "fe_model/model_material.h"

#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "tensor_conversion.h"

namespace fe_model {

using internal::to_deal;
using internal::to_eigen;

namespace {

// The strain increment and the start state (its stress, scalars and tensors' norms, by the
// names of the model's state slots), for failure messages.
std::string describe(const SymmetricTensor2& increment, const PointState& start,
                     const std::vector<model::Slot>& layout) {
  std::ostringstream out;
  out << std::setprecision(6) << "strain increment (tension positive; 11 22 33 12 13 23) ["
      << increment[0][0] << ' ' << increment[1][1] << ' ' << increment[2][2] << ' '
      << increment[0][1] << ' ' << increment[0][2] << ' ' << increment[1][2]
      << "]; start state (compression positive): stress [" << -start.stress[0][0] << ' '
      << -start.stress[1][1] << ' ' << -start.stress[2][2] << ' ' << -start.stress[0][1] << ' '
      << -start.stress[0][2] << ' ' << -start.stress[1][2] << "] Pa";
  const double* v = start.internal_variables.data();
  for (const model::Slot& slot : layout) {
    std::string name = slot.name;
    for (char& c : name) c = c == '_' ? ' ' : c;
    if (slot.kind == model::Slot::kTensor)
      out << ", |" << name << "| " << model::tensor_from_slot(v).norm();
    else
      out << ", " << name << ' ' << *v;
    v += slot.size();
  }
  return out.str();
}

}  // namespace

ModelMaterial::ModelMaterial(std::shared_ptr<const model::Behaviour> behaviour,
                             std::vector<double> initial_inputs)
    : behaviour_(std::move(behaviour)),
      initial_inputs_(std::move(initial_inputs)),
      state_size_(static_cast<std::size_t>(
          model::slot_components(behaviour_->description().state()))) {
  const auto needed = static_cast<std::size_t>(
      model::slot_components(behaviour_->description().initial_inputs()));
  if (initial_inputs_.size() != needed)
    throw std::invalid_argument(name() + ": " + std::to_string(initial_inputs_.size()) +
                                " initial inputs given, " + std::to_string(needed) + " expected");
}

PointState ModelMaterial::initial_state(const SymmetricTensor2& initial_stress) const {
  PointState state;
  state.internal_variables.assign(state_size_, 0.0);
  const Eigen::Matrix3d stress = behaviour_->initial_state(
      -to_eigen(initial_stress), initial_inputs_.data(), state.internal_variables.data());
  state.stress = -to_deal(stress);  // -> tension positive
  return state;
}

MaterialUpdate ModelMaterial::update(const PointState& start,
                                     const SymmetricTensor2& strain_increment,
                                     PointState& end) const {
  if (start.internal_variables.size() != state_size_)
    throw std::logic_error(name() + ": point state has " +
                           std::to_string(start.internal_variables.size()) +
                           " internal variables, expected " + std::to_string(state_size_));
  end.internal_variables.resize(state_size_);  // written in place: no allocation per update
  const model::PointUpdate u =
      behaviour_->update(-to_eigen(start.stress), start.internal_variables.data(),
                         -to_eigen(strain_increment),
                         end.internal_variables.data());  // compression positive
  MaterialUpdate result;
  result.status = u.status;
  if (u.status == MaterialStatus::kFailed) {
    result.message = behaviour_->description().umat_name() + " update failed: " + u.message +
                     "; " + describe(strain_increment, start, behaviour_->description().state());
    end = start;  // never hand NaN to the caller
    return result;
  }
  end.stress = -to_deal(u.stress);
  end.strain = start.strain + strain_increment;
  // D(3i+j, 3k+l) = d sigma_ij / d eps_kl; both signs flip, so the tension-positive tangent is the
  // same. The minor-symmetric pairs are averaged (exact where they are equal, as the models give
  // them).
  const Eigen::Matrix<double, 9, 9>& D = u.tangent;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = i; j < 3; ++j)
      for (unsigned int k = 0; k < 3; ++k)
        for (unsigned int l = k; l < 3; ++l) {
          const auto row_ij = static_cast<Eigen::Index>(3 * i + j);
          const auto row_ji = static_cast<Eigen::Index>(3 * j + i);
          const auto col_kl = static_cast<Eigen::Index>(3 * k + l);
          const auto col_lk = static_cast<Eigen::Index>(3 * l + k);
          result.tangent[i][j][k][l] = 0.25 * (D(row_ij, col_kl) + D(row_ij, col_lk) +
                                               D(row_ji, col_kl) + D(row_ji, col_lk));
        }
  if (u.status == MaterialStatus::kUnreliable)
    result.message = behaviour_->description().umat_name() + " update unreliable: " + u.message;
  return result;
}

Eigen::Matrix3d ModelMaterial::state_tensor(const PointState& state,
                                            const std::string& slot) const {
  const auto& layout = behaviour_->description().state();
  const int offset = model::slot_offset(layout, slot);
  if (offset < 0 || state.internal_variables.size() != state_size_)
    throw std::logic_error(name() + ": no state tensor '" + slot + "' in this point state");
  return model::tensor_from_slot(state.internal_variables.data() + offset);
}

}  // namespace fe_model
