// A specimen's start as a model's initial inputs (model_start.h).
#include "fe_model/model_start.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "calibration/network_test_data.h"
#include "fe_model/acst_check.h"
#include "model/descriptor.h"
#include "runfile/dem_test.h"

namespace fe_model {
namespace {

std::string format_value(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}

// Zero inputs with e_0 in the slot "void_ratio" where the model has one.
std::vector<double> isotropic_inputs(const model::ModelDescription& description, double e0) {
  const std::vector<model::Slot>& slots = description.initial_inputs();
  std::vector<double> inputs(static_cast<std::size_t>(model::slot_components(slots)), 0.0);
  const int void_ratio = model::slot_offset(slots, "void_ratio");
  if (void_ratio >= 0) inputs[static_cast<std::size_t>(void_ratio)] = e0;
  return inputs;
}

void set_tensor(const model::ModelDescription& description, const std::string& slot,
                const Eigen::Matrix3d& value, std::vector<double>& inputs) {
  const int offset = model::slot_offset(description.initial_inputs(), slot);
  if (offset < 0) throw std::logic_error("model '" + description.name() + "' has no input " + slot);
  model::tensor_to_slot(value, inputs.data() + offset);
}

}  // namespace

std::pair<double, std::string> acst_fabric_normalisation(const model::ParameterValues& values,
                                                         const std::string& parameters_path,
                                                         double given) {
  if (given > 0.0) return {given, "--a-cs"};
  if (const std::optional<double> from_file = fabric_normalisation(values, parameters_path))
    return {*from_file, "parameter file"};
  return {kDefaultAcs, "default (dense_100kPa_2000 critical state, docs/fe.md)"};
}

ModelStart dem_start(const model::ParameterValues& values, double a_cs,
                     const runfile::DemTest& run, const std::string& path) {
  const model::ModelDescription& description = model::find_model(values.model);
  if (run.series.axial_strain.empty()) throw std::runtime_error(path + ": /series is empty");
  ModelStart start;
  start.confining_pressure = run.series.sigma_3.front();
  start.void_ratio = run.series.void_ratio.front();
  start.inputs = isotropic_inputs(description, start.void_ratio);
  start.source = "isotropic";
  if (values.model == "acst") {
    start.source = "isotropic (no /analysis/sff: run 'sffcal sff' on the file first)";
    if (run.analysed && !run.sff.axial_strain.empty()) {
      std::size_t first = 0;  // the SFF row at the smallest axial strain
      for (std::size_t i = 0; i < run.sff.axial_strain.size(); ++i)
        if (run.sff.axial_strain[i] < run.sff.axial_strain[first]) first = i;
      const double a_c = run.sff.a_c[first];
      set_tensor(description, "fabric", fabric_from_dem_anisotropy(a_c, a_cs), start.inputs);
      start.source = "/analysis/sff a_c = " + format_value(a_c);
    }
  } else if (values.model == "contact_network") {
    const model::network::State<double> network = calibration::network::initial_state(
        calibration::network::with_closing_normal_anisotropy(calibration::test_data(run, path)));
    start.inputs[static_cast<std::size_t>(
        model::slot_offset(description.initial_inputs(), "void_ratio"))] = network.void_ratio;
    start.inputs[static_cast<std::size_t>(
        model::slot_offset(description.initial_inputs(), "coordination"))] = network.coordination;
    set_tensor(description, "fabric", network.fabric, start.inputs);
    set_tensor(description, "normal", network.normal, start.inputs);
    set_tensor(description, "tangential", network.tangential, start.inputs);
    start.source = "the first snapshot's network (closing a_n)";
  }
  return start;
}

ModelStart plain_start(const model::ParameterValues& values, double confining_pressure,
                       double void_ratio) {
  if (values.model == "contact_network")
    throw std::invalid_argument("the contact-network model starts from a DEM run's network (Z, "
                                "Lambda, anisotropies): give it with --dem RUN.h5");
  ModelStart start;
  start.confining_pressure = confining_pressure;
  start.void_ratio = void_ratio;
  start.inputs = isotropic_inputs(model::find_model(values.model), void_ratio);
  start.source = "isotropic";
  return start;
}

ModelStart specimen_start(const model::ParameterValues& values, const std::string& parameters_path,
                          const StartOptions& options) {
  ModelStart start;
  if (options.dem_run.empty()) {
    if (!(options.confining_pressure > 0.0) || !std::isfinite(options.confining_pressure))
      throw std::invalid_argument("--pressure must be positive [Pa]");
    start = plain_start(values, options.confining_pressure, options.void_ratio);
  } else {
    const double a_cs = values.model == "acst"
                            ? acst_fabric_normalisation(values, parameters_path, options.a_cs).first
                            : 0.0;
    start = dem_start(values, a_cs, runfile::read_dem_test(options.dem_run), options.dem_run);
  }
  if (!(start.confining_pressure > 0.0) || !std::isfinite(start.confining_pressure))
    throw std::invalid_argument("the start's sigma_3 " + format_value(start.confining_pressure) +
                                " Pa is not a positive number");
  const model::ModelDescription& d = model::find_model(values.model);
  const std::unique_ptr<model::Behaviour> behaviour = d.make(values.constants, values.parameters);
  std::vector<double> state(static_cast<std::size_t>(model::slot_components(d.state())));
  behaviour->initial_state(start.confining_pressure * Eigen::Matrix3d::Identity(),
                           start.inputs.data(), state.data());
  return start;
}

}  // namespace fe_model
