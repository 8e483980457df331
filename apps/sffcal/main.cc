// sffcal: the project's command-line front end. Each subcommand is one stage of the pipeline.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "dem_commands.h"
#include "sff_command.h"

int main(int argc, char** argv) {
  CLI::App app{"sffcal " SFFCAL_VERSION
               ": from grain-scale DEM to a calibrated fabric-based soil model"};
  app.require_subcommand(1);

  std::string config_path, out_path, specimen_path, run_path;
  CLI::App* config = app.add_subcommand("config", "Print (or write) the default configuration");
  config->add_option("-o,--output", out_path, "file to write instead of printing");

  CLI::App* prepare = app.add_subcommand("prepare", "Prepare a specimen (insertion, optional "
                                                    "gravity deposition, isotropic compaction)");
  prepare->add_option("-c,--config", config_path, "TOML configuration")->required()->check(CLI::ExistingFile);
  prepare->add_option("-o,--output", out_path, "specimen file to write (HDF5)")->required();

  CLI::App* triaxial = app.add_subcommand("triaxial", "Drained triaxial compression of a specimen");
  triaxial->add_option("-c,--config", config_path, "TOML configuration")->check(CLI::ExistingFile);
  triaxial->add_option("-s,--specimen", specimen_path, "specimen file from 'prepare'")->check(CLI::ExistingFile);
  triaxial->add_option("-o,--output", out_path, "run file to write (HDF5)")->required();
  bool resume = false;
  triaxial->add_flag("--resume", resume, "continue the run file from its last checkpoint "
                                         "(uses the config stored in it)");

  CLI::App* dem = app.add_subcommand("dem", "Prepare a specimen and run the triaxial test");
  dem->add_option("-c,--config", config_path, "TOML configuration")->required()->check(CLI::ExistingFile);
  dem->add_option("-o,--output", out_path, "run file to write (HDF5); the specimen goes to "
                                           "<output>.specimen.h5")->required();

  CLI::App* vtk = app.add_subcommand("vtk", "Export the snapshots of a run file for ParaView");
  vtk->add_option("run", run_path, "run file")->required()->check(CLI::ExistingFile);
  vtk->add_option("-o,--output", out_path, "folder for the VTU/PVD files")->required();

  CLI::App* info = app.add_subcommand("info", "Summarise a run or specimen file");
  info->add_option("run", run_path, "run file")->required()->check(CLI::ExistingFile);

  std::vector<std::string> run_paths;
  CLI::App* sff = app.add_subcommand("sff", "Stress-force-fabric analysis of every snapshot of "
                                            "run files (writes /analysis/sff and a CSV)");
  sff->add_option("runs", run_paths, "run files")->required()->check(CLI::ExistingFile);
  sff->add_option("-o,--output", out_path, "folder for the CSV tables (default: beside each run)");

  CLI11_PARSE(app, argc, argv);
  try {
    if (config->parsed()) return sffcal::print_default_config(out_path);
    if (prepare->parsed()) return sffcal::prepare_command(config_path, out_path);
    if (triaxial->parsed()) {
      if (resume) return sffcal::resume_command(out_path);
      if (config_path.empty() || specimen_path.empty())
        throw std::invalid_argument("triaxial needs --config and --specimen (or --resume)");
      return sffcal::triaxial_command(config_path, specimen_path, out_path);
    }
    if (dem->parsed()) return sffcal::dem_command(config_path, out_path);
    if (vtk->parsed()) return sffcal::vtk_command(run_path, out_path);
    if (info->parsed()) return sffcal::info_command(run_path);
    if (sff->parsed()) return sffcal::sff_command(run_paths, out_path);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sffcal: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
