#include "import_command.h"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "dem_import/description.h"
#include "dem_import/import_run.h"

namespace sffcal {

int import_command(const std::string& description_path, const RunFileTarget& out) {
  const dem_import::ImportDescription description = dem_import::read_description(description_path);
  std::printf("importing a %s %s run: %s\n", description.program.c_str(),
              description.version.c_str(), description_path.c_str());
  dem_import::ImportReport report;
  // An import that stops leaves no part of a run file behind (it is quick to make again); one
  // that replaces a file leaves that file as it was (RunFileTarget).
  out.make([&](const std::string& path) {
    try {
      report = dem_import::import_run(description, path, SFFCAL_VERSION, [](const std::string& line) {
        std::printf("  %s\n", line.c_str());
        std::fflush(stdout);
      });
    } catch (const std::exception&) {
      std::error_code error;
      std::filesystem::remove(path, error);
      throw;
    }
  });
  std::printf("wrote %s: %d snapshots, %zu series rows, %zu bodies (%zu spheres), initial void "
              "ratio %.6g\n",
              out.path().c_str(), report.snapshots, report.series_rows, report.bodies,
              report.spheres, report.initial_void_ratio);
  return 0;
}

}  // namespace sffcal
