// The DEM subcommands of sffcal (kept apart from main.cc, which holds the CLI11 parsing).
#pragma once

#include <string>

#include "output_guard.h"

namespace sffcal {

int print_default_config(const std::string& out_path);
int prepare_command(const std::string& config_path, const RunFileTarget& out);
int triaxial_command(const std::string& config_path, const std::string& specimen_path,
                     const RunFileTarget& out);
int resume_command(const std::string& run_path);
/// Prepares the specimen into `specimen` and shears it into `out`.
int dem_command(const std::string& config_path, const RunFileTarget& specimen,
                const RunFileTarget& out);
int vtk_command(const std::string& run_path, const std::string& folder);
int info_command(const std::string& run_path);

}  // namespace sffcal
