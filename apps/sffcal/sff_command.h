// The sff subcommand: the stress-force-fabric analysis of every snapshot of run files.
#pragma once

#include <string>
#include <vector>

namespace sffcal {

int sff_command(const std::vector<std::string>& run_paths, const std::string& csv_folder);

}  // namespace sffcal
