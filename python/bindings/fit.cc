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
#include <map>
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
                         (std::is_same_v<T, std::string>                ? "a str"
                          : std::is_same_v<T, std::vector<std::string>> ? "a str or a list of str"
                          : std::is_same_v<T, std::vector<double>>      ? "a sequence of numbers"
                          : std::is_same_v<T, bool>                     ? "a bool"
                          : std::is_integral_v<T>                       ? "an int (>= 0)"
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

// A dict of columns: {name: 1-D sequence of numbers}.
std::map<std::string, std::vector<double>> columns(const py::handle& table, const std::string& what) {
  if (!py::isinstance<py::dict>(table))
    throw py::type_error("calibrate: a test's '" + what + "' must be a dict of columns");
  std::map<std::string, std::vector<double>> out;
  for (const auto& item : py::cast<py::dict>(table)) {
    const std::string name = py::str(item.first);
    out[name] = setting<std::vector<double>>(what + "['" + name + "']", item.second);
  }
  return out;
}

// A test given as data: {"name", "series", "sff", "friction", "path" (drained_compression where
// absent)}, its columns named as a run file's (calibration::test_from_tables).
calibration::TestData test_from_dict(const py::dict& test) {
  for (const auto& item : test) {
    const std::string key = py::str(item.first);
    if (key != "name" && key != "series" && key != "sff" && key != "friction" && key != "path")
      throw std::invalid_argument("calibrate: a test has no key '" + key +
                                  "' (its keys: name, series, sff, friction, path)");
  }
  for (const char* key : {"name", "series", "sff", "friction"})
    if (!test.contains(key))
      throw std::invalid_argument(std::string("calibrate: a test given as data needs '") + key + "'");
  const std::string name = setting<std::string>("name", test["name"]);
  return calibration::test_from_tables(
      name, "test '" + name + "' given from Python", columns(test["series"], "series"),
      columns(test["sff"], "sff"), setting<double>("friction", test["friction"]),
      calibration::parse_test_path(test.contains("path") ? setting<std::string>("path", test["path"])
                                                         : "drained_compression"));
}

// Run files (str) and tests given as data (dict), sorted into the request.
void add_tests(const py::list& given, std::vector<std::string>& paths,
               std::vector<calibration::TestData>& tests) {
  for (const py::handle& item : given) {
    if (py::isinstance<py::str>(item)) paths.push_back(py::cast<std::string>(item));
    else if (py::isinstance<py::dict>(item)) tests.push_back(test_from_dict(py::cast<py::dict>(item)));
    else throw py::type_error("calibrate: a test is a run file's path (str) or a dict of its curves");
  }
}

py::dict calibrate(const py::list& runs, const std::string& output,
                   const std::string& model, const py::list& held_out,
                   const std::function<void(const std::string&)>& progress,
                   const std::string& program_version, const py::kwargs& settings) {
  calibration::CalibrationRequest request;
  add_tests(runs, request.runs, request.tests);
  add_tests(held_out, request.held_out, request.held_out_tests);
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
        py::arg("held_out") = py::list(), py::arg("progress") = nullptr,
        py::arg("program_version") = SFFCAL_VERSION,
        "See sffcal.calibration.calibrate.");
}
