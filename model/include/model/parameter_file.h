// The parameter file of every registered model (descriptor.h), one reader and one writer:
//   {"model": NAME, CONSTANT: {"value": x, "unit": U}, ...,
//    "parameters": {PARAMETER: {"value": x, "unit": U}, ...}, ...}
// laid out from the model's tables; other top-level keys (a fit's record) are kept by the writer's
// extra_json_object and ignored by the reader. docs/model.md and docs/network-model.md, "Parameter
// file", give the two fitted models' files.
#pragma once

#include <string>
#include <vector>

namespace model {

/// A model's values as its parameter file gives them, in the order of its tables.
struct ParameterValues {
  std::string model;               ///< the registered name
  std::vector<double> constants;   ///< ModelDescription::constants()
  std::vector<double> parameters;  ///< ModelDescription::parameters()
  /// What the file holds besides the model's values, as one JSON object text: its other top-level
  /// members (e.g. a fit's record) and, under "parameters", members of "parameters" that are not
  /// the model's; "{}" for none. Filled by the reader; the writer takes its extra members
  /// separately.
  std::string rest = "{}";
};

/// What a calibration knows about one parameter, written next to its value (the reader ignores it).
struct ParameterAnnotation {
  std::string name;             ///< a key of "parameters" (a parameter not in the file is an error)
  double lower = 0.0, upper = 0.0;
  double standard_error = -1.0;  ///< < 0: not estimated (written as null)
  bool fixed = true, at_bound = false;
  std::string stage;            ///< the fit stage that set it
};

/// The model a parameter file is for: its key "model", "acst" where absent (files of the first
/// versions). Throws std::runtime_error naming the file if it cannot be read or is not a JSON
/// object.
std::string parameter_file_model(const std::string& path);

/// Reads a parameter file of any registered model; with `expected_model` non-empty, the file must
/// be that model's. A parameter or constant the file lacks takes its value_if_absent where it has
/// one (a file older than it). Throws std::runtime_error naming the file and the key, or the value
/// that is not physical.
ParameterValues read_parameter_file(const std::string& path,
                                    const std::string& expected_model = "");

/// Writes that layout (validated first: std::invalid_argument naming a value that is not
/// physical), each parameter with its annotation where one is given, and the members of
/// extra_json_object (a JSON object text) at the top level. Throws std::runtime_error if the file
/// cannot be written, the extra text is not a JSON object or names a key of the layout, or an
/// annotation names no parameter.
void write_parameter_file(const std::string& path, const ParameterValues& values,
                          const std::vector<ParameterAnnotation>& annotations = {},
                          const std::string& extra_json_object = "");

}  // namespace model
