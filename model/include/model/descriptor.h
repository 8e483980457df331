// One description per constitutive model, and the interface every consumer of a model is written
// over (the parameter file, the UMAT body, the FE material adapter, the material-point driver), in
// the spirit of MGIS' behaviour description: a model is its name, its parameter table, the inputs
// of its initial state, the layout of its state and a Behaviour that integrates a point. Adding a
// model is one folder of its own and one line in registry.cc (docs/model-interface.md).
//
// Conventions at this interface: compression positive (stress, strain, strain increment), stress
// in Pa, tensor (not engineering) shear components. A symmetric tensor slot of a state or of the
// initial inputs holds six components in the order 11, 22, 33, 12, 13, 23 (the UMAT's).
#pragma once

#include <Eigen/Core>

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "model/parameter_field.h"
#include "model/update_status.h"

namespace model {

/// One parameter or constant of a model: the columns of its table (ParameterField without the
/// member of a typed parameter set, which only the model's own code needs).
struct ParameterInfo {
  const char* name;
  const char* unit;
  ParameterRange physical;
  double fit_low, fit_high;
  double value_if_absent = kRequired;
  bool required() const { return value_if_absent != value_if_absent; }  // NaN: none
  /// A constant with one admissible value (ACST's reference pressure): stated in the parameter
  /// file, never in UMAT PROPS.
  bool fixed() const { return physical.low == physical.high; }
};

/// The columns of a typed table (model::acst::kParameterFields, model::network::kParameterFields).
template <typename Table>
std::vector<ParameterInfo> parameter_infos(const Table& table) {
  std::vector<ParameterInfo> infos;
  for (const auto& f : table)
    infos.push_back({f.name, f.unit, f.physical, f.fit_low, f.fit_high, f.value_if_absent});
  return infos;
}

/// One named slot of a state vector or of the initial inputs: a scalar (one component) or a
/// symmetric tensor (six, 11 22 33 12 13 23), which a rotation of the material turns as R X R^T.
struct Slot {
  enum Kind { kScalar, kTensor };
  const char* name;
  Kind kind;
  const char* unit;
  const char* meaning;
  int size() const { return kind == kTensor ? 6 : 1; }
};

/// Components of a list of slots, and the first component of the slot called `name` (-1: none).
int slot_components(const std::vector<Slot>& slots);
int slot_offset(const std::vector<Slot>& slots, const std::string& name);

/// A 3x3 symmetric tensor from the six components at v (11, 22, 33, 12, 13, 23), and back.
Eigen::Matrix3d tensor_from_slot(const double* v);
void tensor_to_slot(const Eigen::Matrix3d& t, double* v);

/// Turns every tensor slot X of `state` (laid out as `slots`) into R X R^T: the state of a
/// material rotated by R (e.g. the UMAT's DROT), scalars unchanged.
void rotate_state(const std::vector<Slot>& slots, const Eigen::Matrix3d& rotation, double* state);

/// An initial input that is not physical, naming its slot (so that the UMAT can name its PROPS).
class InvalidInput : public std::invalid_argument {
 public:
  InvalidInput(std::string slot, const std::string& what)
      : std::invalid_argument(what), slot_(std::move(slot)) {}
  const std::string& slot() const { return slot_; }

 private:
  std::string slot_;
};

/// What an update returns besides the state at its end.
struct PointUpdate {
  UpdateStatus status = UpdateStatus::kFailed;
  Eigen::Matrix3d stress = Eigen::Matrix3d::Zero();  ///< at the end [Pa]; the start's if failed
  /// d sigma_ij / d eps_kl at row 3 i + j, column 3 k + l, symmetric in (k, l) [Pa]. Where failed,
  /// the stiffness at the start that the model can give (ACST: the elastic one), finite.
  Eigen::Matrix<double, 9, 9> tangent = Eigen::Matrix<double, 9, 9>::Zero();
  /// Where not kOk: the ratio of the increment the model suggests retrying with (< 1).
  double step_ratio = 1.0;
  std::string message;  ///< why the status is not kOk (empty otherwise)
};

class ModelDescription;

/// A model with its parameters and constants: integrates one material point. Stateless apart from
/// them, so one object serves every point and update may be called concurrently.
class Behaviour {
 public:
  virtual ~Behaviour() = default;
  virtual const ModelDescription& description() const = 0;
  /// The state (laid out as description().state) of a point carrying `stress` with the initial
  /// inputs (laid out as description().initial_inputs); returns the point's stress, which a model
  /// whose stress is a function of its state (the contact-network model) sets itself. Throws
  /// InvalidInput naming an input that is not physical, std::invalid_argument for a stress the
  /// model cannot carry.
  virtual Eigen::Matrix3d initial_state(const Eigen::Matrix3d& stress, const double* inputs,
                                        double* state) const = 0;
  /// Integrates the strain increment from (stress, state_start); writes the state at the end
  /// into state_end (state_start's values where failed: never NaN).
  virtual PointUpdate update(const Eigen::Matrix3d& stress, const double* state_start,
                             const Eigen::Matrix3d& strain_increment,
                             double* state_end) const = 0;
};

/// A model: its name, tables and layouts, and the Behaviour for given values.
class ModelDescription {
 public:
  virtual ~ModelDescription() = default;
  /// The key "model" of its parameter files, e.g. "acst", "contact_network".
  virtual std::string name() const = 0;
  /// The prefix that chooses it as a UMAT material name (CMNAME), e.g. "CONTACT_NETWORK".
  virtual std::string umat_name() const = 0;
  /// The environment variable that names its parameter file for a UMAT given only the initial
  /// inputs in PROPS: SFFCAL_<umat_name>_PARAMETERS unless the model keeps an older name.
  virtual std::string parameter_file_variable() const {
    return "SFFCAL_" + umat_name() + "_PARAMETERS";
  }
  /// Constants of the material besides the fitted parameters, top-level keys of the parameter
  /// file ({"value": x, "unit": u}) and, unless fixed, UMAT PROPS before the parameters.
  virtual const std::vector<ParameterInfo>& constants() const = 0;
  /// The fitted parameters, in the order of the parameter vector and of UMAT PROPS.
  virtual const std::vector<ParameterInfo>& parameters() const = 0;
  /// What an initial state needs besides the stress (UMAT PROPS(1..)).
  virtual const std::vector<Slot>& initial_inputs() const = 0;
  /// The state of a material point (UMAT STATEV(2..)).
  virtual const std::vector<Slot>& state() const = 0;
  /// Checks values against the tables and the model's own coupled conditions; throws
  /// std::invalid_argument naming the first value that is not physical.
  virtual void validate(const std::vector<double>& constants,
                        const std::vector<double>& parameters) const;
  /// The behaviour for these values (validated first).
  virtual std::unique_ptr<Behaviour> make(const std::vector<double>& constants,
                                          const std::vector<double>& parameters) const = 0;
};

/// UMAT PROPS for a model (the layout its UMAT body reads, docs/fe.md "Every model's UMAT"): the
/// initial inputs, the constants that are not fixed, then the parameters in the order of the
/// tables; and the name of each entry (a tensor input's components as NAME_11 .. NAME_23). Throws
/// std::invalid_argument where a list has the wrong length.
std::vector<double> umat_props(const ModelDescription& d, const std::vector<double>& inputs,
                               const std::vector<double>& constants,
                               const std::vector<double>& parameters);
std::vector<std::string> umat_props_names(const ModelDescription& d);

/// The registered models (registry.cc), and the one called `name`; throws std::invalid_argument
/// listing the registered names where none is.
const std::vector<const ModelDescription*>& registered_models();
const ModelDescription& find_model(const std::string& name);

}  // namespace model
