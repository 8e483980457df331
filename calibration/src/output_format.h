// Formatting shared by the fits' output writers (fit_output.cc, network_fit_output.cc): numbers in
// tables, the UTC time of a run, and CSV columns.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace calibration::output {

/// x with `digits` significant digits; "nan" if not finite.
std::string number(double x, int digits = 4);

/// The current UTC time, ISO 8601 (e.g. 2026-12-03T22:50:00Z).
std::string utc_now();

/// Writes the header line and the columns (equal lengths) with 10 significant digits. Throws
/// std::runtime_error naming the file if it cannot be written.
void write_csv(const std::filesystem::path& path, const std::string& header,
               const std::vector<std::vector<double>>& columns);

}  // namespace calibration::output
