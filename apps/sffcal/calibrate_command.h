// The calibrate subcommand: the fit of any registered model to DEM run files through one API
// (calibration/model_fit.h): ACST's staged fit (docs/calibration.md), the contact-network model's
// two-stage fit (--model network, docs/network-model.md), or the fit of any other model over its
// description (--model NAME, docs/model-interface.md).
#pragma once

#include <string>
#include <vector>

#include "calibration/model_fit.h"

namespace CLI {
class App;
}

namespace sffcal {

struct CalibrateCommandOptions {
  std::string model = "acst";     ///< acst | network (or contact_network) | any registered model
  std::string output_folder;      ///< parameters.json, the curves, summary.md, ...
  std::vector<std::string> held_out;  ///< run files predicted with the fitted values, not fitted
  calibration::FitSettings settings;  ///< what the fits read (progress and threads set here)
  /// Threads over tests (results do not depend on it); 0: OpenMP's default (OMP_NUM_THREADS,
  /// else all cores).
  int threads = 0;
  /// The settings given on the command line (kFitSettingNames): refused where the fit does not
  /// read them.
  std::vector<std::string> given;
};

/// Adds every option of the calibrate subcommand but the runs and -o.
void add_calibrate_options(CLI::App& calibrate, CalibrateCommandOptions& options);

/// The settings given on the command line, by their names in calibration::kFitSettingNames.
std::vector<std::string> given_settings(const CLI::App& calibrate);

/// Reads the run files (each needs /analysis/sff), fits the model options.model names (printing a
/// progress line per stage, with the elapsed time), predicts the held-out runs, writes the outputs
/// and prints the summary. Returns the exit status; throws std::exception with the reason for bad
/// input (a setting the model's fit does not read is refused by name).
int calibrate_command(const std::vector<std::string>& run_paths,
                      const CalibrateCommandOptions& options, const std::string& command_line);

}  // namespace sffcal
