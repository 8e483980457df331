#include "csv_table.h"

#include <stdexcept>

#include "runfile/run_file.h"
#include "sffcal/output_file.h"

namespace sffcal {

void write_csv(const std::string& path, const std::vector<std::string>& columns,
               const std::vector<std::vector<double>>& rows) {
  OutputFile file(path);
  std::ostream& out = file.stream();
  out.precision(10);
  for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c];
  out << "\n";
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < row.size(); ++c) out << (c ? "," : "") << row[c];
    out << "\n";
  }
  file.commit();
}

void write_series_csv(const runfile::RunFile& file, const std::string& path) {
  const std::vector<std::string>& names = file.series_names();
  std::vector<std::vector<double>> columns;
  for (const std::string& name : names) columns.push_back(file.series(name));
  std::vector<std::vector<double>> rows(file.series_length(), std::vector<double>(names.size()));
  for (std::size_t c = 0; c < columns.size(); ++c)
    for (std::size_t r = 0; r < rows.size() && r < columns[c].size(); ++r) rows[r][c] = columns[c][r];
  write_csv(path, names, rows);
}

}  // namespace sffcal
