// Formatting shared by the fits' output writers (output_format.h).
#include "output_format.h"
#include "sffcal/output_file.h"

#include <chrono>
#include <cmath>
#include <ctime>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace calibration::output {

std::string number(double x, int digits) {
  if (!std::isfinite(x)) return "nan";
  std::ostringstream s;
  s << std::setprecision(digits) << x;
  return s.str();
}

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buffer;
}

void write_csv(const std::filesystem::path& path, const std::string& header,
               const std::vector<std::vector<double>>& columns) {
  sffcal::OutputFile file(path.string());
  std::ostream& out = file.stream();
  out << header << '\n' << std::setprecision(10);
  const std::size_t n = columns.empty() ? 0 : columns[0].size();
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c][k];
    out << '\n';
  }
  file.commit();
}

}  // namespace calibration::output
