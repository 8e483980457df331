#include "runfile/dem_test.h"

#include <map>
#include <stdexcept>
#include <utility>

namespace runfile {
namespace {

std::string stem(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = name.find('.');
  return dot == std::string::npos ? name : name.substr(0, dot);
}

using Columns = std::vector<std::pair<const char*, std::vector<double>*>>;

// All the columns of `group` (e.g. "/series") have the length of the first.
void check_lengths(const RunFile& file, const std::string& group, const Columns& columns) {
  const auto& [first, first_values] = columns.front();
  for (const auto& [name, values] : columns)
    if (values->size() != first_values->size())
      throw std::runtime_error("run file " + file.path() + ": " + group + "/" + name + " has " +
                               std::to_string(values->size()) + " rows, " + group + "/" + first +
                               " " + std::to_string(first_values->size()));
}

void read_series(const RunFile& file, const Columns& columns) {
  for (const auto& [name, values] : columns) *values = file.series(name);
  check_lengths(file, "/series", columns);
}

// The required columns, then the optional ones: those are read only when the table has all of
// them (each then of the table's length).
void read_sff(const RunFile& file, const Columns& required, const Columns& optional) {
  std::map<std::string, std::vector<double>> table;
  for (auto& [name, values] : file.read_table("sff")) table[name] = std::move(values);
  for (const auto& [name, values] : required) {
    const auto it = table.find(name);
    if (it == table.end())
      throw std::runtime_error("run file " + file.path() + ": /analysis/sff has no column '" +
                               name + "'");
    *values = std::move(it->second);
  }
  check_lengths(file, "/analysis/sff", required);
  for (const auto& [name, values] : optional)
    if (table.count(name) == 0) return;
  Columns both = required;
  for (const auto& [name, values] : optional) {
    *values = std::move(table[name]);
    both.emplace_back(name, values);
  }
  check_lengths(file, "/analysis/sff", both);
}

}  // namespace

DemTest read_dem_test(const std::string& path) {
  const RunFile file = RunFile::open(path);
  DemTest test;
  test.path = path;
  test.name = stem(path);
  test.metadata = file.metadata();
  DemTestSeries& s = test.series;
  read_series(file, {{"axial_strain", &s.axial_strain}, {"volumetric_strain", &s.volumetric_strain},
                     {"p", &s.p}, {"q", &s.q}, {"eta", &s.eta}, {"void_ratio", &s.void_ratio},
                     {"sigma_3", &s.sigma_3}});
  test.analysed = file.has_table("sff");
  if (test.analysed) {
    DemTestSff& f = test.sff;
    read_sff(file, {{"axial_strain", &f.axial_strain}, {"p", &f.p}, {"q", &f.q}, {"eta", &f.eta},
                    {"void_ratio", &f.void_ratio}, {"a_c", &f.a_c}, {"a_n", &f.a_n}, {"m", &f.m}},
             {{"coordination", &f.coordination}, {"lambda", &f.lambda}, {"a_t", &f.a_t}});
  }
  return test;
}

}  // namespace runfile
