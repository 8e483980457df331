// sffcal._fit, the compiled half of sffcal.calibration: a whole calibration (calibration/
// calibrate.h, what `sffcal calibrate` runs) from Python. A module of its own: it links Ceres,
// which `import sffcal.models` need not load. The settings are FitSettings' (model_fit.h) by the
// names of the command line's flags with underscores; one the model's fit does not read is
// refused by name, as on the command line.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <string>
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

// FitSettings from keyword arguments named as kFitSettingNames (with underscores).
calibration::FitSettings settings_from(const py::kwargs& given, std::vector<std::string>& names) {
  calibration::FitSettings s;
  for (const auto& item : given) {
    const std::string key = py::str(item.first);
    const py::handle value = item.second;
    if (key == "stages") s.stages = py::cast<std::string>(value);
    else if (key == "loss") s.loss = py::cast<std::string>(value);
    else if (key == "starts") s.starts = py::cast<int>(value);
    else if (key == "seed") s.seed = py::cast<std::uint64_t>(value);
    else if (key == "points") s.max_points = py::cast<int>(value);
    else if (key == "max_strain_step") s.max_strain_step = py::cast<double>(value);
    else if (key == "range") s.ranges = py::cast<std::vector<std::string>>(value);
    else if (key == "hold") s.held = py::cast<std::vector<std::string>>(value);
    else if (key == "predicted_only") s.predicted_only = py::cast<bool>(value);
    else if (key == "start") s.start_file = py::cast<std::string>(value);
    else if (key == "threads") s.threads = py::cast<int>(value);
    else if (key == "verbose") s.verbose = py::cast<bool>(value);
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
  if (s.threads < 1) throw std::invalid_argument("calibrate: threads must be >= 1");
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
  if (progress)
    request.settings.progress = [progress](const std::string& line) {
      py::gil_scoped_acquire acquire;
      progress(line);
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
