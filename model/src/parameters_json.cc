// The parameter file of every registered model (parameter_file.h), laid out from its tables, and
// the typed readers and writers of the two fitted models over it: the ACST model's (docs/model.md,
// "Parameter file"):
//   {"model": "acst", "reference_pressure": {"value": 101325, "unit": "Pa"},
//    "parameters": {"G0": {"value": 125, "unit": "1"}, ...}}
// and the contact-network model's (docs/network-model.md, "Parameter file"):
//   {"model": "contact_network", "youngs_modulus": {"value": 1.5e8, "unit": "Pa"},
//    "parameters": {"kappa": {"value": 133.5, "unit": "1"}, ...}, ...}
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "model/acst_model.h"
#include "model/descriptor.h"
#include "model/network_model.h"
#include "model/parameter_file.h"
#include "parameter_vector.h"
#include "sffcal/read_text_file.h"
#include "sffcal/output_file.h"

namespace model {

namespace {

using Json = nlohmann::json;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("parameter file '" + path + "': " + what);
}

// The file's top-level object: one JSON value and nothing after it, no key twice in an object
// (nlohmann keeps the last of a duplicate silently), from a regular file of at most 64 MB.
Json read_json(const std::string& path) {
  std::string text;
  try {
    text = sffcal::read_text_file(path, std::uintmax_t{64} << 20, "parameter file");
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  std::vector<std::set<std::string>> keys;  // of each object being read
  std::string duplicate;
  const Json::parser_callback_t note_keys = [&](int, Json::parse_event_t event, Json& parsed) {
    if (event == Json::parse_event_t::object_start) {
      keys.emplace_back();
    } else if (event == Json::parse_event_t::object_end) {
      keys.pop_back();
    } else if (event == Json::parse_event_t::key && !keys.empty() &&
               !keys.back().insert(parsed.get<std::string>()).second && duplicate.empty()) {
      duplicate = parsed.get<std::string>();
    }
    return true;
  };
  Json root;
  try {
    root = Json::parse(text, note_keys);  // strict: trailing content is an error
  } catch (const Json::exception& e) {  // syntax errors and numbers out of range (1e400)
    fail(path, std::string("is not valid JSON: ") + e.what());
  }
  if (!duplicate.empty()) fail(path, "key '" + duplicate + "' appears twice in one object");
  if (!root.is_object()) fail(path, "the top level must be an object");
  return root;
}

// The edit distance of two names (Levenshtein), for the nearest valid name of a misspelt one.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// Adds the members of extra_json_object (a JSON object text; "" adds nothing) at the top level.
void merge_extra(Json& root, const std::string& extra_json_object, const std::string& path) {
  if (extra_json_object.empty()) return;
  Json extra;
  try {
    extra = Json::parse(extra_json_object);
  } catch (const Json::parse_error& e) {
    fail(path, std::string("extra content is not valid JSON: ") + e.what());
  }
  if (!extra.is_object()) fail(path, "extra content must be a JSON object");
  for (auto it = extra.begin(); it != extra.end(); ++it) {
    if (root.contains(it.key())) fail(path, "extra key '" + it.key() + "' is reserved");
    root[it.key()] = it.value();
  }
}

void write_json(const Json& root, const std::string& path) {
  sffcal::write_text_file(path, root.dump(2) + '\n');
}

// {"value": x, "unit": info.unit} under `key` of `object`; absent: its value_if_absent, or an
// error naming key_path if it has none.
double read_value(const Json& object, const std::string& key, const std::string& key_path,
                  const ParameterInfo& info, const std::string& path) {
  if (!object.contains(key)) {
    if (info.required()) fail(path, "missing key '" + key_path + "'");
    return info.value_if_absent;  // a file older than the parameter
  }
  const Json& entry = object[key];
  if (!entry.is_object() || !entry.contains("value"))
    fail(path, "missing key '" + key_path + ".value'");
  if (!entry["value"].is_number()) fail(path, "key '" + key_path + ".value' must be a number");
  if (!entry.contains("unit")) fail(path, "missing key '" + key_path + ".unit'");
  if (!entry["unit"].is_string() || entry["unit"].get<std::string>() != info.unit)
    fail(path, "key '" + key_path + ".unit' must be \"" + info.unit + "\"");
  const double x = entry["value"].get<double>();
  if (info.fixed() && x != info.physical.low)
    fail(path, "key '" + key_path + "' must be {\"value\": " + format_number(info.physical.low) +
                   ", \"unit\": \"" + info.unit + "\"} (fixed)");
  return x;
}

}  // namespace

std::string parameter_file_model(const std::string& path) {
  const Json root = read_json(path);
  if (!root.contains("model")) return "acst";
  if (!root["model"].is_string()) fail(path, "key 'model' must be a string");
  return root["model"].get<std::string>();
}

ParameterValues read_parameter_file(const std::string& path, const std::string& expected_model) {
  const Json root = read_json(path);
  std::string name = "acst";  // files of the first versions name no model
  if (root.contains("model")) {
    if (!root["model"].is_string()) fail(path, "key 'model' must be a string");
    name = root["model"].get<std::string>();
  }
  if (!expected_model.empty() && name != expected_model)
    fail(path, "key 'model' must be \"" + expected_model + "\"");
  const ModelDescription* description = nullptr;
  try {
    description = &find_model(name);
  } catch (const std::invalid_argument& e) {
    fail(path, e.what());
  }
  ParameterValues values{name, {}, {}};
  for (const ParameterInfo& c : description->constants())
    values.constants.push_back(read_value(root, c.name, c.name, c, path));
  if (!root.contains("parameters") || !root["parameters"].is_object())
    fail(path, "missing key 'parameters' (an object)");
  for (const ParameterInfo& p : description->parameters())
    values.parameters.push_back(
        read_value(root["parameters"], p.name, std::string("parameters.") + p.name, p, path));
  // A member of "parameters" that is not the model's is a misspelling (an optional parameter
  // misspelt would otherwise be read at its value when absent), but for ACST's DEM fabric
  // normalisation a_cs, which fe-check reads from there.
  for (auto it = root["parameters"].begin(); it != root["parameters"].end(); ++it) {
    const std::string& key = it.key();
    const auto& table = description->parameters();
    if (key == "a_cs" || std::any_of(table.begin(), table.end(),
                                     [&](const ParameterInfo& p) { return key == p.name; }))
      continue;
    // Nearest first without case and underscores (nF: n_F), then as written.
    auto folded = [](std::string text) {
      text.erase(std::remove(text.begin(), text.end(), '_'), text.end());
      for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      return text;
    };
    auto distance = [&](const ParameterInfo& p) {
      return std::make_pair(edit_distance(folded(key), folded(p.name)), edit_distance(key, p.name));
    };
    const ParameterInfo* nearest = &table.front();
    for (const ParameterInfo& p : table)
      if (distance(p) < distance(*nearest)) nearest = &p;
    fail(path, "'parameters." + key + "' is no parameter of the " + name +
                   " model (nearest: '" + nearest->name + "')");
  }
  try {
    description->validate(values.constants, values.parameters);
  } catch (const std::invalid_argument& e) {
    fail(path, e.what());
  }
  Json rest = root;
  rest.erase("model");
  for (const ParameterInfo& c : description->constants()) rest.erase(c.name);
  for (const ParameterInfo& p : description->parameters()) rest["parameters"].erase(p.name);
  if (rest["parameters"].empty()) rest.erase("parameters");
  values.rest = rest.dump();
  return values;
}

void write_parameter_file(const std::string& path, const ParameterValues& values,
                          const std::vector<ParameterAnnotation>& annotations,
                          const std::string& extra_json_object) {
  const ModelDescription& description = find_model(values.model);
  description.validate(values.constants, values.parameters);
  Json root;
  root["model"] = values.model;
  for (std::size_t i = 0; i < values.constants.size(); ++i)
    root[description.constants()[i].name] = {{"value", values.constants[i]},
                                             {"unit", description.constants()[i].unit}};
  Json params = Json::object();
  for (std::size_t i = 0; i < values.parameters.size(); ++i)
    params[description.parameters()[i].name] = {{"value", values.parameters[i]},
                                                {"unit", description.parameters()[i].unit}};
  root["parameters"] = params;
  for (const ParameterAnnotation& a : annotations) {
    if (!root["parameters"].contains(a.name))
      fail(path, "annotation for unknown parameter '" + a.name + "'");
    Json& entry = root["parameters"][a.name];
    entry["lower"] = a.lower;
    entry["upper"] = a.upper;
    entry["standard_error"] = a.standard_error >= 0.0 ? Json(a.standard_error) : Json(nullptr);
    entry["fixed"] = a.fixed;
    entry["at_bound"] = a.at_bound;
    entry["stage"] = a.stage;
  }
  merge_extra(root, extra_json_object, path);
  write_json(root, path);
}

namespace acst {

Parameters<double> read_parameters_json(const std::string& path) {
  return parameters_of(read_parameter_file(path, "acst"));
}

Parameters<double> parameters_of(const ParameterValues& values) {
  if (values.model != "acst")
    throw std::runtime_error("the parameters of model '" + values.model + "', not ACST's");
  return set_from_table_order<Parameters<double>>(kParameterFields<double>, values.parameters);
}

void write_parameters_json(const Parameters<double>& par, const std::string& path) {
  write_parameters_json(par, path, {}, "");
}

void write_parameters_json(const Parameters<double>& par, const std::string& path,
                           const std::vector<ParameterAnnotation>& annotations,
                           const std::string& extra_json_object) {
  validate_parameters(par);  // std::runtime_error naming the parameter, as before the file
  write_parameter_file(
      path, {"acst", {kAtmosphericPressure}, values_in_table_order(kParameterFields<double>, par)},
      annotations, extra_json_object);
}

}  // namespace acst

namespace network {

Parameters<double> read_parameters_json(const std::string& path, double* youngs_modulus) {
  const ParameterValues values = read_parameter_file(path, "contact_network");
  if (youngs_modulus) *youngs_modulus = values.constants[0];
  return from_array(values.parameters.data());
}

void write_parameters_json(const Parameters<double>& par, double youngs_modulus,
                           const std::string& path, const std::string& extra_json_object) {
  validate(par);  // std::invalid_argument naming the parameter
  const auto x = to_array(par);
  write_parameter_file(path, {"contact_network", {youngs_modulus}, {x.begin(), x.end()}}, {},
                       extra_json_object);
}

}  // namespace network

}  // namespace model
