// The DEM subcommands of sffcal (kept apart from main.cc, which holds the CLI11 parsing).
#pragma once

#include <string>

namespace sffcal {

int print_default_config(const std::string& out_path);
int prepare_command(const std::string& config_path, const std::string& out_path);
int triaxial_command(const std::string& config_path, const std::string& specimen_path,
                     const std::string& out_path);
int resume_command(const std::string& run_path);
int dem_command(const std::string& config_path, const std::string& out_path);
int vtk_command(const std::string& run_path, const std::string& folder);
int info_command(const std::string& run_path);

}  // namespace sffcal
