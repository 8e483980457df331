// The calibrate subcommand: staged and joint Ceres fits of the ACST model to DEM run files
// (docs/calibration.md), the two-stage fit of the contact-network model (--model network,
// docs/network-model.md), or the fit of any other registered model over its description
// (--model NAME, calibration/any_model_fit.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace sffcal {

struct CalibrateCommandOptions {
  std::string model = "acst";    ///< acst | network (or contact_network) | any registered model
  std::string output_folder;     ///< parameters.json, <test>_curves.csv, summary.md, ...
  std::string stages = "all";    ///< all | csl | elastic | fabric | plastic | joint
  int starts = 3;                ///< starts of the plastic and joint stages
  std::uint64_t seed = 1;        ///< seed of the extra starts
  std::string loss = "none";     ///< none | huber | cauchy
  int max_points = 60;           ///< series rows per test in the fit
  /// Largest axial-strain increment of the fit's path (0: rows only); as FitOptions.
  double max_strain_step = 5e-4;
  bool verbose = false;          ///< Ceres' own iteration table as well
  /// Threads over tests (results do not depend on it); 0: OpenMP's default (OMP_NUM_THREADS,
  /// else all cores).
  int threads = 0;
  std::vector<std::string> held_out;  ///< run files predicted with the fitted values, not fitted
  /// --model network: parameters held at their start values (network::FitOptions::held).
  std::vector<std::string> held_parameters;
  /// --model network: no first stage (network::FitOptions::first_stage = false).
  bool predicted_only = false;
  /// --model network: a parameter file whose values are the first start (an earlier fit); empty:
  /// network::default_start(tests).
  std::string start_file;
  /// NAME=LOW:HIGH search ranges replacing the defaults (calibration::set_search_range).
  std::vector<std::string> ranges;
};

/// Which fit --model chooses: ACST's, the contact-network model's, or the fit of any other
/// registered model. Throws std::invalid_argument listing the registered names for an unknown one.
enum class FitKind { kAcst, kNetwork, kAnyModel };
FitKind fit_kind(const std::string& model);

/// The options that only the ACST fit reads: refused with --model network.
inline const char* const kAcstOnlyOptions[] = {"--stages", "--loss", "--points",
                                               "--max-strain-step", "--range"};
/// The options that the fit of any other model does not read (it reads -o, --hold-out, --points
/// and -v): refused with such a model.
inline const char* const kNotReadByAnyModelFit[] = {
    "--stages", "--loss",  "--max-strain-step", "--range",          "--starts",
    "--seed",   "--hold",  "--predicted-only",  "--start",          "--threads"};

/// Adds --model, --threads, --hold-out, --hold, --predicted-only, --start and --range to the
/// calibrate subcommand.
void add_calibrate_options(CLI::App& calibrate, CalibrateCommandOptions& options);

/// Reads the run files (each needs /analysis/sff), calibrates the model options.model names
/// (printing a progress line per stage, with the elapsed time), writes the outputs and prints the
/// summary. Returns the exit status; throws std::exception with the reason for bad input.
int calibrate_command(const std::vector<std::string>& run_paths,
                      const CalibrateCommandOptions& options, const std::string& command_line);

}  // namespace sffcal
