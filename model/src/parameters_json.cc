// The parameter files of the two materials: the ACST model's (docs/model.md, "Parameter file"):
//   {"model": "acst", "reference_pressure": {"value": 101325, "unit": "Pa"},
//    "parameters": {"G0": {"value": 125, "unit": "1"}, ...}}
// and the contact-network model's (namespace network below).
#include <array>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <utility>

#include "model/acst_model.h"
#include "model/network_model.h"

namespace model {

namespace {

using Json = nlohmann::json;

constexpr const auto& kFields = acst::kParameterFields<double>;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("parameter file '" + path + "': " + what);
}

// The file's top-level object.
Json read_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot be opened");
  Json root;
  try {
    in >> root;
  } catch (const Json::exception& e) {  // syntax errors and numbers out of range (1e400)
    fail(path, std::string("is not valid JSON: ") + e.what());
  }
  if (!root.is_object()) fail(path, "the top level must be an object");
  return root;
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
  std::ofstream out(path);
  if (!out) fail(path, "cannot be written");
  out << root.dump(2) << '\n';
  if (!out) fail(path, "write failed");
}

}  // namespace

namespace acst {

std::string parameter_file_model(const std::string& path) {
  const Json root = read_json(path);
  if (!root.contains("model")) return "acst";
  if (!root["model"].is_string()) fail(path, "key 'model' must be a string");
  return root["model"].get<std::string>();
}

Parameters<double> read_parameters_json(const std::string& path) {
  const Json root = read_json(path);
  if (root.contains("model") && root["model"] != "acst")
    fail(path, "key 'model' must be \"acst\"");
  if (root.contains("reference_pressure")) {
    const Json& pa = root["reference_pressure"];
    if (!pa.is_object() || !pa.contains("value") || !pa["value"].is_number() ||
        pa.value("unit", "") != "Pa" || pa["value"].get<double>() != kAtmosphericPressure)
      fail(path, "key 'reference_pressure' must be {\"value\": 101325, \"unit\": \"Pa\"} (fixed p_a)");
  }
  if (!root.contains("parameters") || !root["parameters"].is_object())
    fail(path, "missing key 'parameters' (an object)");
  const Json& params = root["parameters"];
  Parameters<double> par{};
  for (const ParameterField<double>& field : kFields) {
    const char* name = field.name;
    const std::string key = std::string("parameters.") + name;
    if (!params.contains(name)) {
      if (field.required()) fail(path, "missing key '" + key + "'");
      par.*field.member = field.value_if_absent;  // a file older than the parameter
      continue;
    }
    const Json& entry = params[name];
    if (!entry.is_object() || !entry.contains("value"))
      fail(path, "missing key '" + key + ".value'");
    if (!entry["value"].is_number()) fail(path, "key '" + key + ".value' must be a number");
    if (!entry.contains("unit")) fail(path, "missing key '" + key + ".unit'");
    if (!entry["unit"].is_string() || entry["unit"].get<std::string>() != field.unit)
      fail(path, "key '" + key + ".unit' must be \"" + field.unit + "\"");
    par.*field.member = entry["value"].get<double>();
  }
  try {
    validate_parameters(par);
  } catch (const std::runtime_error& e) {
    fail(path, e.what());
  }
  return par;
}

namespace {

Json parameters_object(const Parameters<double>& par) {
  validate_parameters(par);
  Json root;
  root["model"] = "acst";
  root["reference_pressure"] = {{"value", kAtmosphericPressure}, {"unit", "Pa"}};
  Json params = Json::object();
  for (const ParameterField<double>& field : kFields)
    params[field.name] = {{"value", par.*field.member}, {"unit", field.unit}};
  root["parameters"] = params;
  return root;
}

}  // namespace

void write_parameters_json(const Parameters<double>& par, const std::string& path) {
  write_json(parameters_object(par), path);
}

void write_parameters_json(const Parameters<double>& par, const std::string& path,
                           const std::vector<ParameterAnnotation>& annotations,
                           const std::string& extra_json_object) {
  Json root = parameters_object(par);
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

}  // namespace acst

namespace network {

// The contact-network model's file (docs/network-model.md, "Parameter file"):
//   {"model": "contact_network", "youngs_modulus": {"value": 1.5e8, "unit": "Pa"},
//    "parameters": {"kappa": {"value": 133.5, "unit": "1"}, ...}, ...}
Parameters<double> read_parameters_json(const std::string& path, double* youngs_modulus) {
  const Json root = read_json(path);
  if (!root.contains("model") || root["model"] != "contact_network")
    fail(path, "key 'model' must be \"contact_network\"");
  if (!root.contains("youngs_modulus") || !root["youngs_modulus"].is_object() ||
      !root["youngs_modulus"].contains("value") || !root["youngs_modulus"]["value"].is_number() ||
      root["youngs_modulus"].value("unit", "") != "Pa" ||
      !(root["youngs_modulus"]["value"].get<double>() > 0.0))
    fail(path, "key 'youngs_modulus' must be {\"value\": E > 0, \"unit\": \"Pa\"}");
  if (youngs_modulus) *youngs_modulus = root["youngs_modulus"]["value"].get<double>();
  if (!root.contains("parameters") || !root["parameters"].is_object())
    fail(path, "missing key 'parameters' (an object)");
  const Json& params = root["parameters"];
  std::array<double, kNumParameters> x;
  for (int i = 0; i < kNumParameters; ++i) {
    const std::string name = parameter_names()[i], key = "parameters." + name;
    if (i >= kNumFirstVersionParameters && !params.contains(name)) {
      x[i] = value_if_absent(i);  // a file written before the parameter was added
      continue;
    }
    if (!params.contains(name) || !params[name].is_object() || !params[name].contains("value"))
      fail(path, "missing key '" + key + ".value'");
    if (!params[name]["value"].is_number()) fail(path, "key '" + key + ".value' must be a number");
    if (params[name].value("unit", "") != "1") fail(path, "key '" + key + ".unit' must be \"1\"");
    x[i] = params[name]["value"].get<double>();
  }
  const Parameters<double> par = from_array(x.data());
  try {
    validate(par);
  } catch (const std::invalid_argument& e) {
    fail(path, e.what());
  }
  return par;
}

void write_parameters_json(const Parameters<double>& par, double youngs_modulus,
                           const std::string& path, const std::string& extra_json_object) {
  validate(par);
  Json root;
  root["model"] = "contact_network";
  root["youngs_modulus"] = {{"value", youngs_modulus}, {"unit", "Pa"}};
  Json params = Json::object();
  const auto x = to_array(par);
  for (int i = 0; i < kNumParameters; ++i)
    params[parameter_names()[i]] = {{"value", x[i]}, {"unit", "1"}};
  root["parameters"] = params;
  merge_extra(root, extra_json_object, path);
  write_json(root, path);
}

}  // namespace network

}  // namespace model
