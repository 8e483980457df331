// The sff subcommand: the stress-force-fabric analysis of every snapshot of run files.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace sffcal {

struct SffCommandOptions {
  std::string csv_folder;       ///< where the CSV tables go (empty: beside each run file)
  int resamples = 200;          ///< bootstrap resamples per snapshot (0: no bootstrap)
  std::uint64_t seed = 1;       ///< bootstrap seed
};

int sff_command(const std::vector<std::string>& run_paths, const SffCommandOptions& options);

}  // namespace sffcal
