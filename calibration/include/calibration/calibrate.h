// A whole calibration, what `sffcal calibrate` and the Python API's sffcal.calibration.calibrate
// both do (one place): read the fitted and the held-out run files, fit the model with its fit
// (model_fit.h), predict the held-out runs and write the outputs into a folder.
#pragma once

#include <string>
#include <vector>

#include "calibration/model_fit.h"

namespace calibration {

struct CalibrationRequest {
  std::vector<std::string> runs;      ///< run files with /analysis/sff, fitted
  std::vector<std::string> held_out;  ///< run files predicted with the fitted values, not fitted
  /// Tests given as data (test_from_tables), fitted and held out after the run files'.
  std::vector<TestData> tests, held_out_tests;
  std::string model = "acst";         ///< acst | network (contact_network) | any registered model
  FitSettings settings;               ///< progress: also a line per run read
  /// The settings the caller set (kFitSettingNames); one the model's fit does not read is refused
  /// by name, so that nothing asked for is silently ignored.
  std::vector<std::string> given;
  /// The name of a setting (kFitSettingNames, and "model", "output", "hold-out") as the caller
  /// spells it, for the messages: "--name" for the command line; null: as it is.
  std::string (*spell)(const std::string& name) = nullptr;
  std::string output_folder;  ///< parameters.json, the curves, summary.md, ...
  std::string program_version, command_line;  ///< recorded in the outputs
};

struct CalibrationOutcome {
  std::string summary;    ///< summary.md's text
  std::string report;     ///< the solver's own record ("" where the fit keeps none)
  std::string plot_hint;  ///< how to plot the outputs
  bool usable = true;     ///< the solver's verdict
  double seconds = 0.0;   ///< of the fit and the predictions
};

/// Runs the calibration. Throws std::invalid_argument naming a bad model or setting (or one the
/// fit does not read), std::runtime_error for a run that cannot be read or is both fitted and
/// held out.
CalibrationOutcome calibrate(const CalibrationRequest& request);

}  // namespace calibration
