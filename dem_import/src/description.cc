#include "dem_import/description.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>

#include "sffcal/read_text_file.h"

namespace dem_import {
namespace {

constexpr std::uintmax_t kMaxDescriptionBytes = 1 << 20;

class Reader {
 public:
  Reader(const toml::table& table, std::string source) : table_(table), source_(std::move(source)) {}

  const toml::node& node(const std::string& key) {
    read_.insert(key);
    const toml::node* n = table_.at_path(key).node();
    if (n == nullptr) fail(key, "is missing; state it (docs/import.md)");
    return *n;
  }
  std::string text(const std::string& key) {
    const toml::node& n = node(key);
    if (!n.is_string()) fail(key, "must be a string");
    return *n.value<std::string>();
  }
  std::string text_or(const std::string& key, const std::string& fallback) {
    return table_.at_path(key).node() == nullptr ? (read_.insert(key), fallback) : text(key);
  }
  double real(const std::string& key, bool zero_allowed = false) {
    const toml::node& n = node(key);
    if (!n.is_number()) fail(key, "must be a number");
    const double v = *n.value<double>();
    if (!std::isfinite(v) || v < 0.0 || (v == 0.0 && !zero_allowed))
      fail(key, zero_allowed ? "must be zero or positive" : "must be positive");
    return v;
  }
  std::map<std::string, std::string> names(const std::string& key) {
    std::map<std::string, std::string> out;
    const toml::node* n = table_.at_path(key).node();
    read_.insert(key);
    if (n == nullptr) return out;
    if (!n->is_table()) fail(key, "must be a table of role = \"column name\"");
    for (const auto& [role, name] : *n->as_table()) {
      if (!name.is_string()) fail(key + "." + std::string(role.str()), "must be a string");
      out[std::string(role.str())] = *name.value<std::string>();
    }
    return out;
  }
  /// Refuses any key the description holds that was not read.
  void refuse_unknown() const {
    std::function<void(const toml::table&, const std::string&)> walk =
        [&](const toml::table& t, const std::string& prefix) {
          for (const auto& [k, v] : t) {
            const std::string key = prefix + std::string(k.str());
            if (read_.count(key)) continue;
            if (v.is_table()) walk(*v.as_table(), key + ".");
            else fail(key, "is not a key of import.toml (docs/import.md)");
          }
        };
    walk(table_, "");
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw std::invalid_argument(source_ + ": [" + key.substr(0, key.rfind('.')) + "] " +
                                key.substr(key.rfind('.') + 1) + " " + what);
  }

 private:
  const toml::table& table_;
  std::string source_;
  std::set<std::string> read_;
};

}  // namespace

const std::string& ImportDescription::column(const std::map<std::string, std::string>& columns,
                                             const std::string& role) {
  const auto it = columns.find(role);
  return it == columns.end() ? role : it->second;
}

ImportDescription read_description(const std::string& path) {
  ImportDescription d;
  d.path = path;
  d.text = sffcal::read_text_file(path, kMaxDescriptionBytes, "import description");
  toml::table table;
  try {
    table = toml::parse(d.text, path);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << path << ": TOML syntax error at line " << e.source().begin.line << ", column "
        << e.source().begin.column << ": " << e.description();
    throw std::invalid_argument(msg.str());
  }
  Reader r(table, path);
  d.program = r.text("source.program");
  if (std::find(std::begin(kSourcePrograms), std::end(kSourcePrograms), d.program) ==
      std::end(kSourcePrograms))
    r.fail("source.program", "'" + d.program + "' is not one of yade, lammps, liggghts");
  d.version = r.text("source.version");
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  const auto file = [&](const std::string& key) { return (folder / r.text(key)).string(); };
  d.atoms_path = file("files.atoms");
  d.contacts_path = file("files.contacts");
  d.series_path = file("files.series");
  d.physics.youngs_modulus = r.real("physics.youngs_modulus");
  d.physics.stiffness_ratio = r.real("physics.stiffness_ratio");
  d.physics.friction = r.real("physics.friction", true);
  d.physics.wall_friction = r.real("physics.wall_friction", true);
  d.physics.grain_density = r.real("physics.grain_density");
  d.physics.density_scaling = r.real("physics.density_scaling");
  if (d.physics.density_scaling < 1.0) r.fail("physics.density_scaling", "must be at least 1");
  d.kind = r.text("test.kind");
  d.loading.path = r.text("test.path");
  d.loading.confining_stress = r.real("test.confining_stress");
  d.loading.strain_rate = r.real("test.strain_rate");
  const std::string boundary = r.text_or("test.boundary", "periodic");
  if (boundary != "periodic" && boundary != "walls")
    r.fail("test.boundary", "must be \"periodic\" or \"walls\"");
  d.walls = boundary == "walls";
  const toml::node& control = r.node("test.axis_control");
  if (!control.is_array() || control.as_array()->size() != 3)
    r.fail("test.axis_control", "must be three strings (what holds x, y and z)");
  for (std::size_t a = 0; a < 3; ++a) {
    const toml::node& n = *control.as_array()->get(a);
    if (!n.is_string()) r.fail("test.axis_control", "must be three strings");
    d.loading.axis_control[a] = *n.value<std::string>();
  }
  const std::string sign = r.text("series.stress_sign");
  if (sign != "tension_positive" && sign != "compression_positive")
    r.fail("series.stress_sign", "must be \"tension_positive\" or \"compression_positive\"");
  d.stress_tension_positive = sign == "tension_positive";
  d.stress_definition = r.text("series.stress_definition");
  const std::string force_on = r.text_or("contacts.force_on", "atom2");
  if (force_on != "atom1" && force_on != "atom2")
    r.fail("contacts.force_on", "must be \"atom1\" or \"atom2\"");
  d.force_on_atom1 = force_on == "atom1";
  d.atoms_columns = r.names("columns.atoms");
  d.contacts_columns = r.names("columns.contacts");
  d.series_columns = r.names("columns.series");
  r.refuse_unknown();
  return d;
}

}  // namespace dem_import
