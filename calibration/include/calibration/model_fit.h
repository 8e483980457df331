// The fit of a model to DEM tests, one API for every model (`sffcal calibrate --model NAME`):
// prepare each test as the model reads it, fit (all the model's stages), predict the held-out
// tests, write the outputs. ACST has its staged fit (fit.h), the contact-network model its
// two-stage fit (network_fit.h), any other registered model the fit over its description
// (any_model_fit.h); make_fit chooses by the model's name.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "calibration/test_data.h"

namespace calibration {

/// The settings of a fit, for every model; each fit reads some of them (ModelFit::reads).
struct FitSettings {
  std::string stages = "all";   ///< ACST: all | csl | elastic | fabric | plastic | joint
  std::string loss = "none";    ///< ACST: none | huber | cauchy
  int starts = 3;               ///< starts of the multi-start stages
  std::uint64_t seed = 1;       ///< seed of the extra starts
  int max_points = 60;          ///< series rows per test in the objective
  double max_strain_step = 5e-4;  ///< ACST: largest axial-strain increment of the fit's path
  std::vector<std::string> ranges;  ///< ACST: NAME=LOW:HIGH search ranges
  std::vector<std::string> held;    ///< network: parameters held at their start values
  bool predicted_only = false;      ///< network: no first stage along the DEM's strain paths
  std::string start_file;           ///< network: a parameter file whose values are the first start
  int threads = 1;                  ///< threads over tests (results do not depend on it)
  bool verbose = false;             ///< the solver's own iteration record as well
  std::function<void(const std::string&)> progress;  ///< a line per stage; may be empty
};

/// Names of the settings as `sffcal calibrate` spells its flags (without "--"), in FitSettings'
/// order.
inline const char* const kFitSettingNames[] = {"stages", "loss",  "starts",         "seed",
                                               "points", "max-strain-step", "range", "hold",
                                               "predicted-only", "start", "threads", "verbose"};

class ModelFit {
 public:
  virtual ~ModelFit() = default;
  /// The registered model it fits (model/descriptor.h).
  virtual std::string model() const = 0;
  /// The settings it reads (kFitSettingNames); a front end refuses the others by name.
  virtual std::vector<std::string> reads() const = 0;
  /// A test as this model reads it; throws std::runtime_error or std::invalid_argument naming a
  /// test it cannot follow. Every test, fitted or held out, goes through it before the fit.
  virtual TestData prepare(TestData test) const { return test; }
  /// Fits the prepared tests: every stage of the model's fit.
  virtual void fit(const std::vector<TestData>& fitted) = 0;
  /// Predicts the prepared held-out tests with the fitted values.
  virtual void predict(const std::vector<TestData>& held_out) = 0;
  /// Writes the parameter file, the curves and summary.md into folder; returns the summary.
  virtual std::string write_outputs(const std::string& folder, const std::string& program_version,
                                    const std::string& command_line) const = 0;
  /// The solver's own record (printed with --verbose), "" where the fit prints none.
  virtual std::string report() const { return ""; }
  /// Whether the solution can be used (Ceres' verdict).
  virtual bool usable() const { return true; }
  /// How to plot the outputs, e.g. "scripts/plot_calibration.py FOLDER".
  virtual std::string plot_hint(const std::string& folder,
                                const std::vector<std::string>& run_paths) const = 0;
};

/// Throws std::invalid_argument naming a setting out of its range (starts 1..100, points
/// 3..100000, max-strain-step [0, 0.1] (NaN refused), threads 1..1024): the one check of every
/// front end.
void check_settings(const FitSettings& settings);

/// The fit of the model called `model` ("acst"; "contact_network", or "network"; any other
/// registered name: the fit over its description) with these settings (checked: std::invalid_argument
/// naming a bad one). Throws std::invalid_argument listing the registered models for an unknown
/// name.
std::unique_ptr<ModelFit> make_fit(const std::string& model, const FitSettings& settings);

}  // namespace calibration
