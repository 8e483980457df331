// sffcal._fit, the compiled half of sffcal.calibration: a whole calibration (calibration/
// calibrate.h, what `sffcal calibrate` runs) from Python. A module of its own: it links Ceres,
// which `import sffcal.models` need not load. The settings are FitSettings' (model_fit.h) by the
// names of the command line's flags with underscores; one the model's fit does not read is
// refused by name, as on the command line.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "calibration/calibrate.h"

namespace py = pybind11;

namespace {

std::string python_name(const std::string& name) {
  if (name == "hold-out") return "held_out";
  std::string spelled = name;
  std::replace(spelled.begin(), spelled.end(), '-', '_');
  return spelled;
}

// A setting's value as T; a TypeError naming the setting otherwise.
template <typename T>
T setting(const std::string& key, const py::handle& value) {
  try {
    return py::cast<T>(value);
  } catch (const py::cast_error&) {
    throw py::type_error("calibrate: setting '" + key + "' must be " +
                         (std::is_same_v<T, std::string> ? "a str"
                          : std::is_same_v<T, bool>      ? "a bool"
                          : std::is_integral_v<T>        ? "an int (>= 0)"
                                                         : "a number") +
                         ", not " + std::string(py::str(value.get_type().attr("__name__"))));
  }
}

// A list setting: one str, or a list of them.
std::vector<std::string> settings_list(const std::string& key, const py::handle& value) {
  if (py::isinstance<py::str>(value)) return {py::cast<std::string>(value)};
  return setting<std::vector<std::string>>(key, value);
}

// FitSettings from keyword arguments named as kFitSettingNames (with underscores); the library
// checks their ranges (calibration::check_settings).
calibration::FitSettings settings_from(const py::kwargs& given, std::vector<std::string>& names) {
  calibration::FitSettings s;
  for (const auto& item : given) {
    const std::string key = py::str(item.first);
    const py::handle value = item.second;
    if (key == "stages") s.stages = setting<std::string>(key, value);
    else if (key == "loss") s.loss = setting<std::string>(key, value);
    else if (key == "starts") s.starts = setting<int>(key, value);
    else if (key == "seed") s.seed = setting<std::uint64_t>(key, value);
    else if (key == "points") s.max_points = setting<int>(key, value);
    else if (key == "max_strain_step") s.max_strain_step = setting<double>(key, value);
    else if (key == "range") s.ranges = settings_list(key, value);
    else if (key == "hold") s.held = settings_list(key, value);
    else if (key == "predicted_only") s.predicted_only = setting<bool>(key, value);
    else if (key == "start") s.start_file = setting<std::string>(key, value);
    else if (key == "threads") s.threads = setting<int>(key, value);
    else if (key == "verbose") s.verbose = setting<bool>(key, value);
    else {
      std::string known;
      for (const char* name : calibration::kFitSettingNames)
        known += (known.empty() ? "" : ", ") + python_name(name);
      throw std::invalid_argument("calibrate: no setting '" + key + "' (the settings: " + known + ")");
    }
    // Its name as kFitSettingNames spells it.
    for (const char* name : calibration::kFitSettingNames)
      if (python_name(name) == key) names.push_back(name);
  }
  return s;
}

py::dict calibrate(const std::vector<std::string>& runs, const std::string& output,
                   const std::string& model, const std::vector<std::string>& held_out,
                   const std::function<void(const std::string&)>& progress,
                   const std::string& program_version, const py::kwargs& settings) {
  calibration::CalibrationRequest request;
  request.runs = runs;
  request.held_out = held_out;
  request.model = model;
  request.settings = settings_from(settings, request.given);
  // An exception of the Python callback is kept, not thrown through the fit (Ceres does not
  // promise to unwind cleanly): it is raised once the calibration has returned.
  auto failure = std::make_shared<std::string>();
  if (progress)
    request.settings.progress = [progress, failure](const std::string& line) {
      py::gil_scoped_acquire acquire;
      if (!failure->empty()) return;
      try {
        progress(line);
      } catch (const py::error_already_set& e) {
        *failure = e.what();
      }
    };
  request.spell = [](const std::string& name) { return python_name(name); };
  request.output_folder = output;
  request.program_version = program_version;
  request.command_line = "sffcal.calibration.calibrate (Python)";
  calibration::CalibrationOutcome outcome;
  {
    py::gil_scoped_release release;
    outcome = calibration::calibrate(request);
  }
  if (!failure->empty()) throw std::runtime_error("calibrate: the progress callback failed: " + *failure);
  py::dict out;
  out["summary"] = outcome.summary;
  out["report"] = outcome.report;
  out["plot_hint"] = outcome.plot_hint;
  out["usable"] = outcome.usable;
  out["seconds"] = outcome.seconds;
  return out;
}

}  // namespace

PYBIND11_MODULE(_fit, m) {
  m.doc() = "sffcal's calibration (Ceres) from Python: sffcal.calibration";
  m.def("calibrate", &calibrate, py::arg("runs"), py::arg("output"), py::arg("model") = "acst",
        py::arg("held_out") = std::vector<std::string>{}, py::arg("progress") = nullptr,
        py::arg("program_version") = SFFCAL_VERSION,
        "See sffcal.calibration.calibrate.");
}
