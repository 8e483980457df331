// Reading DEM tests for the calibration: run files (runfile::DemTest) or the reduced CSV pair.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "calibration/test_data.h"
#include "model/acst_model.h"
#include "runfile/dem_test.h"

namespace calibration {

namespace {

std::map<std::string, std::vector<double>> read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("calibration data '" + path + "' cannot be opened");
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error("calibration data '" + path + "' is empty");
  std::vector<std::string> names;
  std::istringstream header(line);
  for (std::string name; std::getline(header, name, ',');) {
    while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
    names.push_back(name);
  }
  std::map<std::string, std::vector<double>> columns;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.empty() || line == "\r") continue;
    std::istringstream fields(line);
    std::size_t k = 0;
    for (std::string field; std::getline(fields, field, ','); ++k) {
      if (k >= names.size())
        throw std::runtime_error("calibration data '" + path + "' line " +
                                 std::to_string(number) + ": more fields than columns");
      double v = std::nan("");
      try {
        v = std::stod(field);
      } catch (const std::exception&) {
        // a non-number reads as NaN; validate_test_data names it
      }
      columns[names[k]].push_back(v);
    }
    if (k != names.size())
      throw std::runtime_error("calibration data '" + path + "' line " + std::to_string(number) +
                               ": " + std::to_string(k) + " fields, " +
                               std::to_string(names.size()) + " columns");
  }
  return columns;
}

const std::vector<double>& column(const std::map<std::string, std::vector<double>>& table,
                                  const std::string& name, const std::string& where) {
  const auto it = table.find(name);
  if (it == table.end())
    throw std::runtime_error("calibration data '" + where + "': missing column '" + name + "'");
  return it->second;
}

// The state a test starts from: its first series row and first snapshot.
void set_initial_state(TestData& t) {
  if (!t.p.empty()) t.p0 = t.p.front();
  if (!t.void_ratio.empty()) t.e0 = t.void_ratio.front();
  if (!t.a_c.empty()) t.a_c0 = t.a_c.front();
}

void fill_from_tables(TestData& t, const std::map<std::string, std::vector<double>>& series,
                      const std::string& series_where,
                      const std::map<std::string, std::vector<double>>& sff,
                      const std::string& sff_where) {
  t.axial_strain = column(series, "axial_strain", series_where);
  t.eta = column(series, "eta", series_where);
  t.volumetric_strain = column(series, "volumetric_strain", series_where);
  t.void_ratio = column(series, "void_ratio", series_where);
  t.p = column(series, "p", series_where);
  t.snapshot_axial_strain = column(sff, "axial_strain", sff_where);
  t.a_c = column(sff, "a_c", sff_where);
  t.a_n = column(sff, "a_n", sff_where);
  t.mobilisation = column(sff, "m", sff_where);
  t.snapshot_eta = column(sff, "eta", sff_where);
  if (sff.count("coordination") && sff.count("lambda") && sff.count("a_t")) {
    t.coordination = column(sff, "coordination", sff_where);
    t.lambda = column(sff, "lambda", sff_where);
    t.a_t = column(sff, "a_t", sff_where);
  }
  set_initial_state(t);
}

constexpr std::pair<TestPath, const char*> kPathNames[] = {
    {TestPath::kDrainedCompression, "drained_compression"},
    {TestPath::kDrainedExtension, "drained_extension"},
    {TestPath::kConstantPCompression, "constant_p_compression"},
    {TestPath::kUndrainedCompression, "undrained_compression"},
    {TestPath::kUndrainedExtension, "undrained_extension"},
};

}  // namespace

TestPath parse_test_path(const std::string& name) {
  for (const auto& [path, spelling] : kPathNames)
    if (name == spelling) return path;
  if (name == "true_triaxial")
    throw std::runtime_error("loading path true_triaxial: the calibration follows axisymmetric "
                             "paths only (x and y held alike), and true triaxial holds them apart");
  std::string known;
  for (const auto& entry : kPathNames)
    known += std::string(known.empty() ? "" : ", ") + entry.second;
  throw std::runtime_error("unknown loading path '" + name + "' (the calibration reads " + known +
                           ")");
}

const char* to_string(TestPath path) {
  for (const auto& [p, spelling] : kPathNames)
    if (p == path) return spelling;
  return "unknown";
}

double axial_direction(TestPath path) {
  return path == TestPath::kDrainedExtension || path == TestPath::kUndrainedExtension ? -1.0 : 1.0;
}

bool is_undrained(TestPath path) {
  return path == TestPath::kUndrainedCompression || path == TestPath::kUndrainedExtension;
}

bool holds_lateral_stress(TestPath path) {
  return path == TestPath::kDrainedCompression || path == TestPath::kDrainedExtension;
}

TestData read_run_file(const std::string& path) {
  return test_data(runfile::read_dem_test(path), path);
}

TestData test_data(const runfile::DemTest& dem, const std::string& path) {
  TestPath test_path;
  try {
    test_path = parse_test_path(dem.loading_path());
  } catch (const std::exception& e) {
    throw std::runtime_error("run file '" + path + "': " + e.what());
  }
  if (!dem.analysed)
    throw std::runtime_error("run file '" + path +
                             "' has no SFF table /analysis/sff (run `sffcal sff " + path +
                             "` first)");
  TestData t;
  t.name = dem.name;
  t.source = path;
  t.seed = dem.metadata.seed;
  t.program_version = dem.metadata.program_version;
  t.friction = dem.metadata.physics.friction;  // the friction of shearing, as the DEM used it
  t.path = test_path;
  t.axial_strain = dem.series.axial_strain;
  t.eta = dem.series.eta;
  t.volumetric_strain = dem.series.volumetric_strain;
  t.void_ratio = dem.series.void_ratio;
  t.p = dem.series.p;
  t.snapshot_axial_strain = dem.sff.axial_strain;
  t.a_c = dem.sff.a_c;
  t.a_n = dem.sff.a_n;
  t.mobilisation = dem.sff.m;
  t.snapshot_eta = dem.sff.eta;
  t.coordination = dem.sff.coordination;
  t.lambda = dem.sff.lambda;
  t.a_t = dem.sff.a_t;
  set_initial_state(t);
  validate_test_data(t);
  return t;
}

TestData test_from_tables(const std::string& name, const std::string& source,
                          const std::map<std::string, std::vector<double>>& series,
                          const std::map<std::string, std::vector<double>>& sff, double friction,
                          TestPath path) {
  if (!(friction >= 0.0) || !std::isfinite(friction))
    throw std::runtime_error(source + ": the friction must be a number >= 0 (0: unknown)");
  TestData t;
  t.name = name;
  t.source = source;
  t.friction = friction;
  t.path = path;
  fill_from_tables(t, series, source + " series", sff, source + " sff");
  validate_test_data(t);
  return t;
}

TestData read_csv_pair(const std::string& series_csv, const std::string& sff_csv,
                       const std::string& name, double friction, TestPath path) {
  TestData t;
  t.name = name;
  t.source = series_csv + " + " + sff_csv;
  t.friction = friction;
  t.path = path;
  fill_from_tables(t, read_csv(series_csv), series_csv, read_csv(sff_csv), sff_csv);
  validate_test_data(t);
  return t;
}

void validate_test_data(const TestData& t) {
  auto fail = [&](const std::string& what) {
    throw std::runtime_error("test '" + t.name + "' (" + t.source + "): " + what);
  };
  const std::size_t n = t.axial_strain.size();
  if (n < 3) fail("fewer than 3 series rows (" + std::to_string(n) + ")");
  const std::pair<const char*, const std::vector<double>*> series[] = {
      {"eta", &t.eta}, {"volumetric_strain", &t.volumetric_strain},
      {"void_ratio", &t.void_ratio}, {"p", &t.p}, {"axial_strain", &t.axial_strain}};
  for (const auto& [name, values] : series) {
    if (values->size() != n)
      fail(std::string("series '") + name + "' has " + std::to_string(values->size()) +
           " rows, axial_strain " + std::to_string(n));
    for (std::size_t k = 0; k < n; ++k)
      if (!std::isfinite((*values)[k]))
        fail(std::string("series '") + name + "' row " + std::to_string(k) + " is not finite");
  }
  const double direction = axial_direction(t.path);
  for (std::size_t k = 1; k < n; ++k)
    if (!(direction * (t.axial_strain[k] - t.axial_strain[k - 1]) > 0.0))
      fail(std::string("axial_strain does not ") + (direction > 0 ? "increase" : "decrease") +
           " at row " + std::to_string(k) + " (path " + to_string(t.path) + ")");
  const std::size_t m = t.snapshot_axial_strain.size();
  if (m < 1) fail("no snapshot in the SFF table (the initial fabric comes from the first)");
  auto check_snapshots = [&](const char* name, const std::vector<double>& values) {
    if (values.size() != m)
      fail(std::string("SFF column '") + name + "' has " + std::to_string(values.size()) +
           " rows, axial_strain " + std::to_string(m));
    for (std::size_t k = 0; k < m; ++k)
      if (!std::isfinite(values[k]))
        fail(std::string("SFF column '") + name + "' snapshot " + std::to_string(k) +
             " is not finite");
  };
  const std::pair<const char*, const std::vector<double>*> snaps[] = {
      {"a_c", &t.a_c}, {"a_n", &t.a_n}, {"m", &t.mobilisation}, {"eta", &t.snapshot_eta},
      {"axial_strain", &t.snapshot_axial_strain}};
  for (const auto& [name, values] : snaps) check_snapshots(name, *values);
  // Optional: only the contact-network model reads them.
  const std::pair<const char*, const std::vector<double>*> network[] = {
      {"coordination", &t.coordination}, {"lambda", &t.lambda}, {"a_t", &t.a_t}};
  for (const auto& [name, values] : network)
    if (!values->empty()) check_snapshots(name, *values);
  if (!(t.p0 > 0.0)) fail("initial p must be > 0 Pa");
  if (!model::acst::is_admissible_void_ratio(t.e0)) fail("initial void ratio must lie in (0, 2.97)");
  if (!(t.friction >= 0.0)) fail("friction must be >= 0");
}

void check_unique_names(const std::vector<TestData>& fitted,
                        const std::vector<TestData>& held_back) {
  std::set<std::string> names;
  for (const auto* list : {&fitted, &held_back})
    for (const TestData& t : *list)
      if (!names.insert(t.name).second)
        throw std::runtime_error("two tests are named '" + t.name +
                                 "': their outputs would overwrite each other");
}

}  // namespace calibration
