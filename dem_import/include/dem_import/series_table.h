// The source's scalar series as a table of text: a header line of column names (a leading '#', as
// LAMMPS's `fix print ... title` writes it, is allowed), then one row of numbers per line,
// separated by spaces, tabs or commas (docs/import.md).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace dem_import {

struct SeriesTable {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> values;  ///< one vector per column, all one length

  std::size_t rows() const { return values.empty() ? 0 : values.front().size(); }
  /// The column's values; throws std::runtime_error naming `source` and the column if absent.
  const std::vector<double>& column(const std::string& name, const std::string& source) const;
  bool has(const std::string& name) const;
};

/// Throws std::runtime_error naming the file and line where it cannot be read, has no header or no
/// row, repeats a column name, or a row has too few or too many values or a value not a number.
SeriesTable read_series_table(const std::string& path);

}  // namespace dem_import
