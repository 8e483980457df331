// The import subcommand: another code's run as a run file (dem_import/, docs/import.md).
#pragma once

#include <string>

#include "output_guard.h"

namespace sffcal {

int import_command(const std::string& description_path, const RunFileTarget& out);

}  // namespace sffcal
