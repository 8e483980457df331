#include "dem_import/series_table.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "text_fields.h"

namespace dem_import {

bool SeriesTable::has(const std::string& name) const {
  return std::find(columns.begin(), columns.end(), name) != columns.end();
}

const std::vector<double>& SeriesTable::column(const std::string& name,
                                               const std::string& source) const {
  const auto it = std::find(columns.begin(), columns.end(), name);
  if (it == columns.end())
    throw std::runtime_error(source + " has no column '" + name + "'");
  return values[static_cast<std::size_t>(it - columns.begin())];
}

SeriesTable read_series_table(const std::string& path) {
  std::ifstream in(path);
  const std::string source = "the series table " + path;
  if (!in) throw std::runtime_error("cannot read " + source + ": no such file or not readable");
  SeriesTable table;
  std::string line;
  std::size_t number = 0;
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error(source + ", line " + std::to_string(number) + ": " + what);
  };
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::string_view text = line;
    if (table.columns.empty()) {  // the header: the first line that is not blank
      const std::size_t start = text.find_first_not_of(" \t");
      if (start == std::string_view::npos) continue;
      if (text[start] == '#') text.remove_prefix(start + 1);
      for (std::string_view name : internal::fields(text)) {
        if (table.has(std::string(name))) fail("the column '" + std::string(name) + "' is repeated");
        table.columns.emplace_back(name);
      }
      if (table.columns.empty()) fail("the header names no columns");
      table.values.resize(table.columns.size());
      continue;
    }
    const std::size_t start = text.find_first_not_of(" \t");
    if (start == std::string_view::npos || text[start] == '#') continue;  // blank or a comment
    const std::vector<std::string_view> values = internal::fields(text);
    if (values.size() != table.columns.size())
      fail(std::to_string(values.size()) + " values for " + std::to_string(table.columns.size()) +
           " columns");
    for (std::size_t k = 0; k < values.size(); ++k)
      table.values[k].push_back(
          internal::parse_real(values[k], [&](const std::string& w) {
            fail("column '" + table.columns[k] + "': " + w);
          }));
  }
  if (table.columns.empty()) throw std::runtime_error(source + " is empty (no header line)");
  if (table.rows() == 0) throw std::runtime_error(source + " has a header but no row");
  return table;
}

}  // namespace dem_import
