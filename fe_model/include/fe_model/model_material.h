// fe_model::Material for any registered constitutive model (model/descriptor.h): the one deal.II
// adapter, written over the model interface. The point's internal variables are the model's
// state, laid out as its description's state() (docs/model-interface.md).
//
// Signs: the models are compression positive, fe_model tension positive; the adapter flips the
// stress, the strain increment and nothing else (the tangent is the same in both conventions).
#ifndef FE_MODEL_MODEL_MATERIAL_H_
#define FE_MODEL_MODEL_MATERIAL_H_

#include <memory>
#include <string>
#include <vector>

#include "fe_model/material.h"
#include "model/descriptor.h"

namespace fe_model {

class ModelMaterial : public Material {
 public:
  /// The behaviour (a model with its values) and the initial inputs of every point, laid out as
  /// behaviour->description().initial_inputs() (compression positive).
  ModelMaterial(std::shared_ptr<const model::Behaviour> behaviour,
                std::vector<double> initial_inputs);
  std::string name() const override { return behaviour_->description().name(); }
  /// The model's initial state for the initial stress; the point's stress is the one the model
  /// gives back (the contact-network model's SFF stress of its initial state).
  PointState initial_state(const SymmetricTensor2& initial_stress) const override;
  MaterialUpdate update(const PointState& start, const SymmetricTensor2& strain_increment,
                        PointState& end) const override;
  const model::Behaviour& behaviour() const { return *behaviour_; }
  /// The tensor of the point's state slot `name` (compression positive); throws std::logic_error
  /// where the state has no such tensor or is not this model's.
  Eigen::Matrix3d state_tensor(const PointState& state, const std::string& name) const;
  std::size_t num_internal_variables() const { return state_size_; }

 private:
  std::shared_ptr<const model::Behaviour> behaviour_;
  std::vector<double> initial_inputs_;
  std::size_t state_size_;
};

}  // namespace fe_model

#endif  // FE_MODEL_MODEL_MATERIAL_H_
