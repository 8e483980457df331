// Plain CSV tables (a header of column names, one row per line) that spreadsheets, numpy and
// pandas open directly.
#pragma once

#include <string>
#include <vector>

namespace runfile {
class RunFile;
}

namespace sffcal {

/// Writes the table; throws std::runtime_error when the file cannot be written.
void write_csv(const std::string& path, const std::vector<std::string>& columns,
               const std::vector<std::vector<double>>& rows);

/// Writes a run file's /series (every column) as `path`.
void write_series_csv(const runfile::RunFile& file, const std::string& path);

}  // namespace sffcal
