// The one fit API over the three fits (model_fit.h): ACST's staged fit, the contact-network
// model's two-stage fit and the fit of any other registered model over its description.
#include "calibration/model_fit.h"

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "calibration/any_model_fit.h"
#include "calibration/fit.h"
#include "calibration/network_fit.h"
#include "model/descriptor.h"

namespace calibration {
namespace {

std::string joined(const std::vector<std::string>& paths) {
  std::string text;
  for (const std::string& path : paths) text += " " + path;
  return text;
}

// ACST (docs/calibration.md): critical state line, elasticity, fabric, plastic, joint.
class AcstFit final : public ModelFit {
 public:
  explicit AcstFit(const FitSettings& settings) {
    options_.stages = parse_stages(settings.stages);
    options_.loss = parse_loss(settings.loss);
    options_.starts = settings.starts;
    options_.seed = settings.seed;
    options_.max_points = settings.max_points;
    options_.fit_max_strain_step = settings.max_strain_step;
    options_.verbose = settings.verbose;
    options_.threads = settings.threads;
    for (const std::string& range : settings.ranges) set_search_range(options_, range);
    options_.progress = settings.progress;
  }
  std::string model() const override { return "acst"; }
  std::vector<std::string> reads() const override {
    return {"stages", "loss", "starts", "seed", "points", "max-strain-step", "range", "threads",
            "verbose"};
  }
  void fit(const std::vector<TestData>& fitted) override {
    fitted_ = fitted;
    result_ = calibrate(fitted_, options_);
  }
  void predict(const std::vector<TestData>& held_out) override {
    held_out_ = held_out;
    calibration::predict(held_out_, options_, result_);
  }
  std::string write_outputs(const std::string& folder, const std::string& program_version,
                            const std::string& command_line) const override {
    return write_calibration_outputs(folder, fitted_, result_, options_, program_version,
                                     command_line, held_out_);
  }
  std::string plot_hint(const std::string& folder,
                        const std::vector<std::string>&) const override {
    return "scripts/plot_calibration.py " + folder;
  }

 private:
  FitOptions options_;
  std::vector<TestData> fitted_, held_out_;
  CalibrationResult result_;
};

// The contact-network model (docs/network-model.md, "Calibration").
class NetworkFit final : public ModelFit {
 public:
  explicit NetworkFit(const FitSettings& settings) : start_file_(settings.start_file) {
    options_.starts = settings.starts;
    options_.seed = settings.seed;
    options_.threads = settings.threads;
    options_.held = settings.held;
    options_.first_stage = !settings.predicted_only;
    options_.progress = settings.progress;
  }
  std::string model() const override { return "contact_network"; }
  std::vector<std::string> reads() const override {
    return {"starts", "seed", "threads", "hold", "predicted-only", "start", "verbose"};
  }
  // The run's network checked (a test without Z is named) and the closing a_n.
  TestData prepare(TestData test) const override {
    network::initial_state(test);
    return network::with_closing_normal_anisotropy(std::move(test));
  }
  void fit(const std::vector<TestData>& fitted) override {
    fitted_ = fitted;
    result_ = network::fit(fitted_, first_start(), options_);
  }
  void predict(const std::vector<TestData>& held_out) override { held_out_ = held_out; }
  std::string write_outputs(const std::string& folder, const std::string& program_version,
                            const std::string& command_line) const override {
    return network::write_fit_outputs(folder, fitted_, held_out_, result_, options_,
                                      program_version, command_line);
  }
  std::string report() const override { return result_.report; }
  std::string plot_hint(const std::string& folder,
                        const std::vector<std::string>& run_paths) const override {
    return "scripts/plot_network.py " + folder + joined(run_paths) + " -o network.png";
  }

 private:
  // The first start: the parameter file's values (those it lacks at their value_if_absent), or
  // the default start placed by the tests.
  network::Parameters<double> first_start() const {
    if (start_file_.empty()) return network::default_start(fitted_);
    double youngs_modulus = network::kDemYoungsModulus;
    const network::Parameters<double> start =
        model::network::read_parameters_json(start_file_, &youngs_modulus);
    if (youngs_modulus != network::kDemYoungsModulus)
      throw std::runtime_error("--start " + start_file_ + ": its youngs_modulus " +
                               std::to_string(youngs_modulus) + " Pa is not the DEM's " +
                               std::to_string(network::kDemYoungsModulus) +
                               " Pa, which normalises Lambda in the fit");
    if (options_.progress) options_.progress("first start from " + start_file_);
    return start;
  }

  std::string start_file_;
  network::FitOptions options_;
  std::vector<TestData> fitted_, held_out_;
  network::FitResult result_;
};

// Any other registered model, over its description (any_model_fit.h).
class AnyModelFit final : public ModelFit {
 public:
  AnyModelFit(const model::ModelDescription& description, const FitSettings& settings)
      : description_(description) {
    options_.max_points = settings.max_points;
  }
  std::string model() const override { return description_.name(); }
  std::vector<std::string> reads() const override { return {"points", "verbose"}; }
  TestData prepare(TestData test) const override {
    check_any_model_test(test);
    return test;
  }
  void fit(const std::vector<TestData>& fitted) override {
    fitted_ = fitted;
    result_ = fit_any_model(description_, fitted_, options_);
  }
  void predict(const std::vector<TestData>& held_out) override {
    held_out_ = held_out;
    const std::vector<AnyModelTestError> errors =
        any_model_errors(description_, result_.values, held_out_, false, options_.driver_steps);
    result_.errors.insert(result_.errors.end(), errors.begin(), errors.end());
  }
  std::string write_outputs(const std::string& folder, const std::string& program_version,
                            const std::string& command_line) const override {
    return write_any_model_fit_outputs(folder, description_, fitted_, held_out_, result_,
                                       options_, program_version, command_line);
  }
  std::string report() const override { return result_.termination; }
  bool usable() const override { return result_.usable; }
  std::string plot_hint(const std::string& folder,
                        const std::vector<std::string>&) const override {
    return "the columns of " + folder + "/<run>_curves.csv";
  }

 private:
  const model::ModelDescription& description_;
  AnyModelFitOptions options_;
  std::vector<TestData> fitted_, held_out_;
  AnyModelFitResult result_;
};

}  // namespace

void check_settings(const FitSettings& s) {
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
  };
  require(s.starts >= 1 && s.starts <= 100, "starts must be in 1..100");
  require(s.max_points >= 3 && s.max_points <= 100000, "points must be in 3..100000");
  require(s.max_strain_step >= 0.0 && s.max_strain_step <= 0.1,
          "max-strain-step must be in [0, 0.1] (0: the rows only)");
  require(s.threads >= 1 && s.threads <= 1024, "threads must be in 1..1024");
}

std::unique_ptr<ModelFit> make_fit(const std::string& model, const FitSettings& settings) {
  check_settings(settings);
  if (model == "acst") return std::make_unique<AcstFit>(settings);
  if (model == "contact_network" || model == "network")
    return std::make_unique<NetworkFit>(settings);
  return std::make_unique<AnyModelFit>(model::find_model(model), settings);
}

}  // namespace calibration
