// Outputs of a contact-network fit: parameter file with the fit's record, predicted curves and
// summary (network_fit.h, write_fit_outputs; docs/network-model.md, "Calibration").
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "calibration/network_fit.h"
#include "output_format.h"
#include "sffcal/output_file.h"

namespace calibration::network {
namespace {

using Json = nlohmann::json;
using output::number;

struct TestOutcome {
  const TestData* test;
  bool fitted;
  Curve along, predicted;
  Errors along_errors, predicted_errors;
};

Json errors_json(const TestOutcome& o) {
  const Errors& a = o.along_errors;
  const Errors& b = o.predicted_errors;
  return {{"test", o.test->name},
          {"role", o.fitted ? "fitted" : "held back"},
          {"loading_path", to_string(o.test->path)},
          {"along_dem_strain_path",
           {{"complete", o.along.complete}, {"message", o.along.message}, {"rms_eta", a.eta},
            {"rms_coordination", a.coordination},
            {"rms_lambda_relative", a.lambda}, {"rms_a_c", a.a_c}, {"rms_a_n", a.a_n},
            {"rms_a_t", a.a_t}}},
          {"predicted",
           {{"complete", o.predicted.complete}, {"message", o.predicted.message},
            {"rms_eta", b.eta}, {"rms_volumetric", b.volumetric}, {"rms_p_ratio", b.p_ratio},
            {"rms_coordination", b.coordination}, {"rms_lambda_relative", b.lambda},
            {"rms_a_c", b.a_c}, {"rms_a_n", b.a_n}, {"rms_a_t", b.a_t}}}};
}

Json named(const std::array<double, kNumParameters>& values) {
  Json j = Json::object();
  for (int i = 0; i < kNumParameters; ++i)
    j[parameter_names()[i]] = std::isfinite(values[i]) ? Json(values[i]) : Json();
  return j;
}

std::string summary_markdown(const std::vector<TestOutcome>& outcomes, const FitResult& result) {
  std::ostringstream s;
  s << "Errors (RMS): along the DEM's strain path (the first stage's objective) and on the "
       "test's own loading path as the model predicts it. Lambda relative; p/p0 on undrained "
       "paths.\n\n"
       "| test | role | path | along: q/p | Z | Lambda | a_c | a_n | a_t | predicted: q/p | "
       "eps_v | p/p0 | Z | Lambda | a_c | a_n | a_t |\n"
       "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const TestOutcome& o : outcomes) {
    const Errors& a = o.along_errors;
    const Errors& b = o.predicted_errors;
    s << "| " << o.test->name << " | " << (o.fitted ? "fitted" : "held back") << " | "
      << to_string(o.test->path) << " | " << number(a.eta, 3)
      << (o.along.complete ? "" : " (to the stop)") << " | "
      << number(a.coordination, 3) << " | " << number(a.lambda, 3) << " | " << number(a.a_c, 3)
      << " | " << number(a.a_n, 3) << " | " << number(a.a_t, 3) << " | " << number(b.eta, 3)
      << (o.predicted.complete ? "" : " (to the stop)") << " | " << number(b.volumetric, 3)
      << " | " << number(b.p_ratio, 3) << " | " << number(b.coordination, 3) << " | "
      << number(b.lambda, 3) << " | " << number(b.a_c, 3) << " | " << number(b.a_n, 3) << " | "
      << number(b.a_t, 3) << " |\n";
  }
  for (const TestOutcome& o : outcomes) {
    if (!o.along.complete)
      s << "\n" << o.test->name << ": the path along the DEM's strains stopped: "
        << o.along.message << "\n";
    if (!o.predicted.complete)
      s << "\n" << o.test->name << ": the prediction stopped: " << o.predicted.message << "\n";
  }
  s << "\nParameters (standard errors: robust to residuals correlated along each curve, and as if "
       "independent; - where the parameter was held: at a bound, c_t without an extension test, "
       "c_l and n_kappa without an undrained test, lambda_e at one pressure, r_i without a "
       "deposit's initial fabric, n_ra where the options hold it):\n\n"
       "| parameter | value | standard error | SE if independent | lower | upper |\n"
       "|---|---|---|---|---|---|\n";
  const auto x = to_array(result.parameters), lo = to_array(lower_bounds()),
             hi = to_array(upper_bounds());
  for (int i = 0; i < kNumParameters; ++i) {
    auto error = [](double e) { return std::isfinite(e) ? number(e, 3) : std::string("-"); };
    s << "| " << parameter_names()[i] << " | " << number(x[i], 6) << " | "
      << error(result.errors.robust[i]) << " | " << error(result.errors.independent[i]) << " | "
      << number(lo[i]) << " | " << number(hi[i]) << " |\n";
  }
  if (!result.errors.estimated)
    s << "\nNo standard errors: " << result.errors.missing << ".\n";
  s << "\nStarts (n_ra held at its start value): " << result.start_costs.size() << "; start "
    << result.start + 1 << " won with the cost "
    << number(result.start_costs[static_cast<std::size_t>(result.start)], 6) << " (each start's:";
  for (double c : result.start_costs) s << " " << (std::isfinite(c) ? number(c, 6) : "unusable");
  s << ").";
  if (result.fabric_rate_freed)
    s << " Then n_ra freed on the predicted paths (Eq. N3b): the final cost "
      << number(result.final_cost, 6) << ".";
  s << "\n";
  return s.str();
}

}  // namespace

std::string write_fit_outputs(const std::string& folder, const std::vector<TestData>& fitted,
                              const std::vector<TestData>& held_back, const FitResult& result,
                              const FitOptions& options, const std::string& program_version,
                              const std::string& command_line) {
  namespace fs = std::filesystem;
  check_unique_names(fitted, held_back);
  std::vector<TestOutcome> outcomes;
  for (const auto* list : {&fitted, &held_back})
    for (const TestData& t : *list) {
      TestOutcome o{&t, list == &fitted, follow_strain_path(result.parameters, t, options),
                    predict(result.parameters, t, options), {}, {}};
      o.along_errors = compare(o.along, t);
      o.predicted_errors = compare(o.predicted, t);
      outcomes.push_back(std::move(o));
    }
  fs::create_directories(folder);
  for (const TestOutcome& o : outcomes) {
    const Curve& c = o.predicted;
    const std::vector<double> row(c.row.begin(), c.row.end()),
        snapshot(c.snapshot.begin(), c.snapshot.end());
    // The DEM's a_n the fit followed (with_closing_normal_anisotropy), at the snapshots' nodes.
    std::vector<double> dem_a_n(c.snapshot.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t k = 0; k < c.snapshot.size(); ++k)
      if (c.snapshot[k] >= 0) dem_a_n[k] = o.test->a_n[c.snapshot[k]];
    output::write_csv(fs::path(folder) / (o.test->name + "_network.csv"),
                      "axial_strain,volumetric_strain,void_ratio,p,q,eta,coordination,lambda,a_c,"
                      "a_n,a_t,dem_row,dem_snapshot,dem_a_n",
                      {c.axial_strain, c.volumetric_strain, c.void_ratio, c.p, c.q, c.eta,
                       c.coordination, c.lambda, c.a_c, c.a_n, c.a_t, row, snapshot, dem_a_n});
  }
  Json inputs = Json::array(), errors = Json::array();
  for (const TestOutcome& o : outcomes) {
    const TestData& t = *o.test;
    inputs.push_back({{"name", t.name}, {"source", t.source}, {"seed", t.seed},
                      {"program_version", t.program_version}, {"p0_Pa", t.p0}, {"e0", t.e0},
                      {"loading_path", to_string(t.path)}, {"fitted", o.fitted},
                      {"a_n", t.normal_anisotropy}});
    errors.push_back(errors_json(o));
  }
  Json costs = Json::array();
  for (double c : result.start_costs) costs.push_back(std::isfinite(c) ? Json(c) : Json());
  Json record;
  record["provenance"] = {{"program", "sffcal calibrate --model network"},
                          {"program_version", program_version},
                          {"date", output::utc_now()},
                          {"command_line", command_line},
                          {"inputs", inputs}};
  record["fit"] = {
      {"starts", options.starts},
      {"seed", options.seed},
      {"first_stage", options.first_stage},
      {"winning_start", result.start + 1},  // 1-based, as the progress lines count
      {"start_final_costs", costs},
      {"final_cost", result.final_cost},
      {"n_ra_freed_last", result.fabric_rate_freed},
      {"converged", result.converged},
      {"max_iterations", options.max_iterations},
      {"substep_size", options.substep_size},
      {"residual_scales",
       {{"eta", options.eta_scale},
        {"stress_relative", options.stress_scale},
        {"volumetric_strain", options.volumetric_scale},
        {"coordination", options.coordination_scale},
        {"lambda_relative", options.lambda_scale},
        {"a_c_a_n", options.anisotropy_scale},
        {"a_t", options.tangential_scale}}},
      {"standard_errors", named(result.errors.robust)},
      {"standard_errors_independent", named(result.errors.independent)},
      {"standard_errors_note",
       "standard_errors: robust to residuals correlated along each curve (Newey-West sandwich, "
       "one series per test and residual kind); standard_errors_independent: s^2 (J^T J)^-1; "
       "null at a bound"},
      {"standard_errors_missing",
       result.errors.estimated ? Json() : Json(result.errors.missing)},
      {"mean_bandwidth", result.errors.mean_bandwidth},
      {"report", result.report}};
  record["errors"] = errors;
  write_parameters_json(result.parameters, kDemYoungsModulus,
                        (fs::path(folder) / "parameters.json").string(), record.dump());
  const std::string summary = summary_markdown(outcomes, result);
  sffcal::write_text_file((fs::path(folder) / "summary.md").string(), "# Contact-network model: calibration summary\n\n" + summary);
  return summary;
}

}  // namespace calibration::network
