// sffcal.models (python/sffcal/models.py re-exports it): every registered constitutive model from
// Python through the model interface (model/descriptor.h): its tables and layouts, its initial
// state, updates of one point or of a batch (model/batch_update.h, with the GIL released), and the
// material-point driver on the paths `sffcal point` offers (model/point_driver.h). Conventions as
// the interface's: compression positive, stress in Pa, tensor shear components, a tensor slot's six
// components in the order 11 22 33 12 13 23. C++ exceptions arrive as Python ones with the same
// message (std::invalid_argument as ValueError, std::runtime_error as RuntimeError).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "arrays.h"
#include "model/batch_update.h"
#include "model/descriptor.h"
#include "model/parameter_file.h"
#include "model/point_driver.h"

namespace py = pybind11;

namespace sffcal_python {
namespace {

// The values of a table from a dict: every key must name an entry; an absent entry takes its
// value_if_absent, or the one value a fixed constant admits; a required one absent is an error.
std::vector<double> values_from_dict(const std::vector<model::ParameterInfo>& table,
                                     const std::string& what, const std::string& model_name,
                                     const py::dict& given) {
  std::string names;
  for (const model::ParameterInfo& info : table) names += (names.empty() ? "" : ", ") + std::string(info.name);
  for (const auto& item : given) {
    const std::string key = py::str(item.first);
    if (std::none_of(table.begin(), table.end(),
                     [&](const model::ParameterInfo& info) { return key == info.name; }))
      throw std::invalid_argument("model '" + model_name + "' has no " + what + " '" + key +
                                  "' (its " + what + "s: " + (names.empty() ? "none" : names) + ")");
  }
  std::vector<double> values;
  for (const model::ParameterInfo& info : table) {
    if (given.contains(info.name)) {
      try {
        values.push_back(py::cast<double>(given[info.name]));
      } catch (const py::cast_error&) {
        throw py::type_error("model '" + model_name + "': the " + what + " '" + info.name +
                             "' must be a number [" + info.unit + "]");
      }
    } else if (info.fixed()) {
      values.push_back(info.physical.low);
    } else if (!info.required()) {
      values.push_back(info.value_if_absent);
    } else {
      throw std::invalid_argument("model '" + model_name + "' needs the " + what + " '" +
                                  info.name + "' [" + info.unit + "]");
    }
  }
  return values;
}

py::dict dict_from_values(const std::vector<model::ParameterInfo>& table,
                          const std::vector<double>& values) {
  py::dict out;
  for (std::size_t i = 0; i < table.size(); ++i) out[table[i].name] = values[i];
  return out;
}

// A layout as a list of dicts: name, kind, unit, meaning, offset and size.
py::list layout(const std::vector<model::Slot>& slots) {
  py::list out;
  int offset = 0;
  for (const model::Slot& slot : slots) {
    py::dict entry;
    entry["name"] = slot.name;
    entry["kind"] = slot.kind == model::Slot::kTensor ? "tensor" : "scalar";
    entry["unit"] = slot.unit;
    entry["meaning"] = slot.meaning;
    entry["offset"] = offset;
    entry["size"] = slot.size();
    out.append(entry);
    offset += slot.size();
  }
  return out;
}

// A 3x3 stress from a number (an isotropic stress; numpy scalars too) or a (3, 3) array, finite
// and symmetric.
Eigen::Matrix3d stress_argument(const py::object& value, const char* what) {
  const Array a = py::cast<Array>(value);
  if (a.ndim() == 0) {
    const double x = *a.data();
    if (!std::isfinite(x)) throw std::invalid_argument(std::string(what) + " is not finite");
    return x * Eigen::Matrix3d::Identity();
  }
  if (a.ndim() != 2 || a.shape(0) != 3 || a.shape(1) != 3)
    throw std::invalid_argument(std::string(what) + " must be a number or a (3, 3) array");
  if (!finite_symmetric(a.data()))
    throw std::invalid_argument(std::string(what) + " must be finite and symmetric");
  return Eigen::Map<const RowMajor3>(a.data());
}

class PyModel {
 public:
  PyModel(const model::ModelDescription& description, std::vector<double> constants,
          std::vector<double> parameters)
      : description_(&description),
        constants_(std::move(constants)),
        parameters_(std::move(parameters)),
        behaviour_(description.make(constants_, parameters_)) {}

  static PyModel from_dicts(const std::string& name, const py::dict& parameters,
                            const py::dict& constants) {
    const model::ModelDescription& d = model::find_model(name);
    return PyModel(d, values_from_dict(d.constants(), "constant", name, constants),
                   values_from_dict(d.parameters(), "parameter", name, parameters));
  }
  static PyModel from_file(const std::string& path) {
    const model::ParameterValues values = model::read_parameter_file(path);
    return PyModel(model::find_model(values.model), values.constants, values.parameters);
  }

  std::string name() const { return description_->name(); }
  py::dict parameters() const { return dict_from_values(description_->parameters(), parameters_); }
  py::dict constants() const { return dict_from_values(description_->constants(), constants_); }
  py::list state_layout() const { return layout(description_->state()); }
  py::list input_layout() const { return layout(description_->initial_inputs()); }
  int state_size() const { return model::slot_components(description_->state()); }
  int input_size() const { return model::slot_components(description_->initial_inputs()); }

  // Inputs from an array of input_size() or a dict by slot name (a tensor as a (3, 3) array or
  // six components); an absent slot is zero (an isotropic tensor, or a scalar the model refuses
  // by name where zero is not physical).
  std::vector<double> inputs_argument(const py::object& inputs) const {
    const std::vector<model::Slot>& slots = description_->initial_inputs();
    std::vector<double> values(static_cast<std::size_t>(input_size()), 0.0);
    if (inputs.is_none()) return values;
    if (py::isinstance<py::dict>(inputs)) {
      for (const auto& item : py::cast<py::dict>(inputs)) {
        const std::string key = py::str(item.first);
        const int offset = model::slot_offset(slots, key);
        if (offset < 0) throw std::invalid_argument("model '" + name() + "' has no input '" + key + "'");
        const auto slot = std::find_if(slots.begin(), slots.end(),
                                       [&](const model::Slot& s) { return key == s.name; });
        const Array a = py::cast<Array>(item.second);
        if (slot->kind == model::Slot::kScalar && a.size() == 1) {
          values[static_cast<std::size_t>(offset)] = *a.data();
        } else if (slot->kind == model::Slot::kTensor && a.ndim() == 2 && a.shape(0) == 3 &&
                   a.shape(1) == 3) {
          model::tensor_to_slot(Eigen::Map<const RowMajor3>(a.data()), values.data() + offset);
        } else if (slot->kind == model::Slot::kTensor && a.size() == 6) {
          std::copy(a.data(), a.data() + 6, values.begin() + offset);
        } else {
          throw std::invalid_argument("input '" + key + "' of model '" + name() + "' is a " +
                                      (slot->kind == model::Slot::kTensor
                                           ? "tensor: give a (3, 3) array or six components"
                                           : "number"));
        }
      }
      return values;
    }
    const Array a = py::cast<Array>(inputs);
    if (a.ndim() != 1 || a.shape(0) != input_size())
      throw std::invalid_argument("model '" + name() + "' takes " + std::to_string(input_size()) +
                                  " initial inputs (see input_layout), not " +
                                  std::to_string(a.size()) + " in " + std::to_string(a.ndim()) +
                                  " dimension(s)");
    std::copy(a.data(), a.data() + a.size(), values.begin());
    return values;
  }

  py::tuple initial_state(const py::object& stress, const py::object& inputs) const {
    const Eigen::Matrix3d s = stress_argument(stress, "stress");
    const std::vector<double> in = inputs_argument(inputs);
    py::array_t<double> state(state_size());
    const Eigen::Matrix3d start = behaviour_->initial_state(s, in.data(), state.mutable_data());
    return py::make_tuple(matrix_array(start), state);
  }

  // One point ((3, 3), (m,), (3, 3)) or a batch ((n, 3, 3), (n, m), (n, 3, 3)).
  py::dict update(const Array& stress, const Array& state, const Array& increment,
                  bool tangent) const {
    const bool single = stress.ndim() == 2;
    const py::ssize_t n = single ? 1 : (stress.ndim() == 3 ? stress.shape(0) : -1);
    const py::ssize_t m = state_size();
    const auto shaped = [&](const Array& a, py::ssize_t last, py::ssize_t middle) {
      if (single) return a.ndim() == (middle ? 2 : 1) && a.shape(a.ndim() - 1) == last &&
                         (!middle || a.shape(0) == middle);
      return a.ndim() == (middle ? 3 : 2) && a.shape(0) == n && a.shape(a.ndim() - 1) == last &&
             (!middle || a.shape(1) == middle);
    };
    if (n < 0 || !shaped(stress, 3, 3) || !shaped(state, m, 0) || !shaped(increment, 3, 3))
      throw std::invalid_argument(
          "update takes stress (3, 3), state (" + std::to_string(m) + ",) and strain_increment "
          "(3, 3) for one point, or (n, 3, 3), (n, " + std::to_string(m) + ") and (n, 3, 3) for n");
    // Every point's stress and increment finite and symmetric, every state finite: a model reads
    // only one triangle of a tensor, and would integrate NaN as numbers.
    // The message is built only for the point that fails: the loop runs over the whole batch.
    const auto refuse = [single](const char* what, py::ssize_t k, const char* problem) {
      throw std::invalid_argument(std::string("the ") + what +
                                  (single ? std::string() : " of point " + std::to_string(k)) +
                                  " is not " + problem);
    };
    for (py::ssize_t k = 0; k < n; ++k) {
      if (!finite_symmetric(stress.data() + 9 * k)) refuse("stress", k, "finite and symmetric");
      if (!finite_symmetric(increment.data() + 9 * k))
        refuse("strain increment", k, "finite and symmetric");
      for (py::ssize_t j = 0; j < m; ++j)
        if (!std::isfinite(state.data()[m * k + j])) refuse("state", k, "finite");
    }
    std::vector<py::ssize_t> lead = single ? std::vector<py::ssize_t>{} : std::vector<py::ssize_t>{n};
    const auto with = [&](std::vector<py::ssize_t> tail) {
      std::vector<py::ssize_t> shape = lead;
      shape.insert(shape.end(), tail.begin(), tail.end());
      return shape;
    };
    py::array_t<double> stress_end(with({3, 3})), state_end(with({m})), step_ratio(lead);
    py::array_t<int> status(lead);
    py::array_t<double> tangents = tangent ? py::array_t<double>(with({9, 9})) : py::array_t<double>();
    model::PointBatch batch;
    batch.points = static_cast<std::size_t>(n);
    batch.stress = stress.data();
    batch.state = state.data();
    batch.increment = increment.data();
    batch.stress_end = stress_end.mutable_data();
    batch.state_end = state_end.mutable_data();
    batch.tangent = tangent ? tangents.mutable_data() : nullptr;
    batch.status = status.mutable_data();
    batch.step_ratio = step_ratio.mutable_data();
    std::vector<std::pair<std::size_t, std::string>> messages;
    {
      py::gil_scoped_release release;
      messages = model::update_points(*behaviour_, batch);
    }
    py::dict out;
    out["stress"] = stress_end;
    out["state"] = state_end;
    if (tangent) out["tangent"] = tangents;
    if (single) {
      out["step_ratio"] = *step_ratio.data();
      out["status"] = model::to_string(static_cast<model::UpdateStatus>(*status.data()));
      out["message"] = messages.empty() ? std::string() : messages.front().second;
    } else {
      out["step_ratio"] = step_ratio;
      out["status"] = status;
      py::dict by_point;
      for (const auto& [k, message] : messages) by_point[py::int_(k)] = message;
      out["messages"] = by_point;
    }
    return out;
  }

  py::dict triaxial(double sigma_3, double axial_strain_end, int steps, const std::string& drainage,
                    const py::object& inputs) const {
    model::TriaxialPath path;
    path.drainage = model::parse_drainage(drainage);
    path.lateral_stress = sigma_3;
    path.axial_strain_end = axial_strain_end;
    path.steps = steps;
    const std::vector<double> in = inputs_argument(inputs);
    model::DriverPath driven;
    {
      py::gil_scoped_release release;
      driven = model::drive_triaxial(*behaviour_, in, path);
    }
    const py::ssize_t n = static_cast<py::ssize_t>(driven.points.size());
    const py::ssize_t m = state_size();
    py::array_t<double> strain({n, py::ssize_t{3}, py::ssize_t{3}});
    py::array_t<double> stress({n, py::ssize_t{3}, py::ssize_t{3}});
    py::array_t<double> state({n, m});
    py::array_t<int> iterations(n);
    py::list status;
    for (py::ssize_t k = 0; k < n; ++k) {
      const model::DriverPoint& x = driven.points[static_cast<std::size_t>(k)];
      Eigen::Map<RowMajor3>(strain.mutable_data(k)) = x.strain;
      Eigen::Map<RowMajor3>(stress.mutable_data(k)) = x.stress;
      std::copy(x.state.begin(), x.state.end(), state.mutable_data(k));
      iterations.mutable_data()[k] = x.newton_iterations;
      status.append(model::to_string(x.status));
    }
    py::dict out;
    out["strain"] = strain;
    out["stress"] = stress;
    out["state"] = state;
    out["newton_iterations"] = iterations;
    out["status"] = status;
    out["completed"] = driven.completed;
    out["message"] = driven.message;
    return out;
  }

 private:
  const model::ModelDescription* description_;
  std::vector<double> constants_, parameters_;
  std::shared_ptr<const model::Behaviour> behaviour_;
};

}  // namespace

void bind_models(py::module_& m) {
  m.def("model_names", [] {
    std::vector<std::string> names;
    for (const model::ModelDescription* d : model::registered_models()) names.push_back(d->name());
    return names;
  }, "The names of the registered models (the key \"model\" of their parameter files).");

  py::class_<PyModel>(m, "Model", R"doc(
A constitutive model with its parameters: the model interface of sffcal (docs/model-interface.md).
Compression positive, stress in Pa, tensor shear components; a tensor slot of a state or of the
inputs holds six components, 11 22 33 12 13 23.

    Model(name, parameters={...}, constants={...})   # values by name (SI units)
    Model.from_file("parameters.json")               # a parameter file of sffcal
)doc")
      .def(py::init(&PyModel::from_dicts), py::arg("name"), py::arg("parameters") = py::dict(),
           py::arg("constants") = py::dict(),
           "A registered model from its values by name; an absent value takes its default where "
           "the model has one. ValueError names an unknown or missing name, or a value that is not "
           "physical.")
      .def_static("from_file", &PyModel::from_file, py::arg("path"),
                  "The model and values of a parameter file (what `sffcal calibrate` writes).")
      .def_property_readonly("name", &PyModel::name)
      .def_property_readonly("parameters", &PyModel::parameters, "{name: value} in SI units")
      .def_property_readonly("constants", &PyModel::constants, "{name: value} in SI units")
      .def_property_readonly("state_layout", &PyModel::state_layout,
                             "the state's slots: name, kind, unit, meaning, offset, size")
      .def_property_readonly("input_layout", &PyModel::input_layout,
                             "the initial inputs' slots, laid out as state_layout")
      .def_property_readonly("state_size", &PyModel::state_size)
      .def_property_readonly("input_size", &PyModel::input_size)
      .def("initial_state", &PyModel::initial_state, py::arg("stress"),
           py::arg("inputs") = py::none(),
           "(stress (3, 3), state) of a point carrying `stress` (a number: isotropic) with the "
           "initial inputs (an array of input_size, or a dict by slot name; absent slots zero).")
      .def("update", &PyModel::update, py::arg("stress"), py::arg("state"),
           py::arg("strain_increment"), py::arg("tangent") = false,
           "Integrates strain increments. One point: stress (3, 3), state (state_size,), "
           "strain_increment (3, 3); a batch: (n, 3, 3), (n, state_size), (n, 3, 3). Returns a "
           "dict: stress, state, step_ratio, tangent (9, 9) per point if asked (d sigma_ij / d "
           "eps_kl at row 3 i + j, column 3 k + l), and status: 'ok', 'unreliable' or 'failed' "
           "with its message for one point; for a batch an int array (STATUS_NAMES) and messages "
           "{index: text} of the points not ok.")
      .def("triaxial", &PyModel::triaxial, py::arg("sigma_3"), py::arg("axial_strain_end"),
           py::arg("steps") = 50, py::arg("drainage") = "drained", py::arg("inputs") = py::none(),
           "The material-point driver (`sffcal point`): from the isotropic stress sigma_3 [Pa], "
           "eps_zz to axial_strain_end (negative: extension) in equal steps, 'drained' (sigma_xx = "
           "sigma_yy = sigma_3) or 'undrained' (constant volume). Returns a dict: strain, stress "
           "(n, 3, 3), state (n, state_size), newton_iterations, status (per point, the start "
           "first), completed and message.");
  // The names of the statuses, indexed by their values in a batch's status array.
  m.attr("STATUS_NAMES") = py::make_tuple(model::to_string(model::UpdateStatus::kOk),
                                          model::to_string(model::UpdateStatus::kUnreliable),
                                          model::to_string(model::UpdateStatus::kFailed));
}

}  // namespace sffcal_python
