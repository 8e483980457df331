// Outputs of the calibration: parameter file, curves, summary (docs/calibration.md).
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "calibration/fit.h"
#include "output_format.h"
#include "sffcal/output_file.h"

namespace calibration {

namespace {

using Json = nlohmann::json;
using output::number;
using output::utc_now;
using output::write_csv;

void errors_table(std::ostringstream& s, const std::vector<TestErrors>& errors) {
  s << "| test | path | rows | snapshots | RMS q/p | max abs q/p | RMS eps_v | RMS e | "
       "RMS p/p0 | RMS a_c | RMS normalised | model status |\n"
       "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const TestErrors& e : errors)
    s << "| " << e.name << " | " << e.path << " | " << e.rows << " | " << e.snapshots << " | "
      << number(e.rms_eta) << " | " << number(e.max_abs_eta) << " | "
      << number(e.rms_volumetric) << " | " << number(e.rms_void_ratio) << " | "
      << number(e.rms_p_ratio) << " | " << number(e.rms_a_c) << " | "
      << number(e.rms_normalised) << " | " << e.status << " |\n";
}

Json errors_json(const std::vector<TestErrors>& errors) {
  Json list = Json::array();
  for (const TestErrors& e : errors)
    list.push_back({{"test", e.name}, {"path", e.path}, {"rms_eta", e.rms_eta},
                    {"max_abs_eta", e.max_abs_eta}, {"rms_volumetric", e.rms_volumetric},
                    {"rms_void_ratio", e.rms_void_ratio}, {"rms_p_ratio", e.rms_p_ratio},
                    {"rms_a_c", e.rms_a_c}, {"status", e.status}});
  return list;
}

}  // namespace

std::string summary_markdown(const CalibrationResult& r) {
  std::ostringstream s;
  errors_table(s, r.errors);
  if (!r.predictions.empty()) {
    s << "\nHeld back from the fit (predicted with the fitted parameters):\n\n";
    errors_table(s, r.predictions);
  }
  s << "\n| parameter | value | standard error | SE if independent | lower | upper | at bound | "
       "stage |\n|---|---|---|---|---|---|---|---|\n";
  const auto& names = fit_parameter_names();
  for (int i = 0; i < kNumFitParameters; ++i) {
    const ParameterEstimate& e = r.estimates[i];
    s << "| " << names[i] << " | " << number(e.value, 5) << " | "
      << (e.standard_error >= 0.0 ? number(e.standard_error, 3) : std::string("-")) << " | "
      << (e.standard_error_independent >= 0.0 ? number(e.standard_error_independent, 3)
                                              : std::string("-"))
      << " | " << number(e.lower) << " | " << number(e.upper) << " | " << (e.at_bound ? "yes" : "")
      << " | " << (e.fixed ? "fixed" : e.stage) << " |\n";
  }
  s << "\nCritical states (last window of each test):\n\n| test | p [Pa] | e | q/p | a_c |\n"
       "|---|---|---|---|---|\n";
  for (const auto& c : r.critical_states)
    s << "| " << c.test << " | " << number(c.p, 6) << " | " << number(c.void_ratio) << " | "
      << number(c.eta) << " | " << number(c.a_c) << " |\n";
  s << "\nStages (time: wall seconds; evaluations of all tests, values only + with Jacobian):\n\n"
       "| stage | free | residuals | starts | initial cost | final cost | iterations | "
       "evaluations | substeps/step | time [s] | processor [s] |\n"
       "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const StageReport& st : r.stages)
    s << "| " << st.stage << " | " << st.free_parameters << " | " << st.residuals << " | "
      << st.starts << " | " << number(st.initial_cost) << " | " << number(st.final_cost)
      << " | " << st.timing.iterations << " | " << st.timing.cost_evaluations << " + "
      << st.timing.jacobian_evaluations << " | " << number(st.timing.substeps_per_step, 3)
      << " | " << number(st.timing.seconds, 3) << " | " << number(st.timing.cpu_seconds, 3)
      << " |\n";
  s << "\nSFF strength relation eta = c1 a_c + c2 a_n + c3 mu m: ";
  if (r.sff.available) {
    s << "c = (" << number(r.sff.coefficients[0]) << " ± " << number(r.sff.standard_errors[0], 2)
      << ", " << number(r.sff.coefficients[1]) << " ± " << number(r.sff.standard_errors[1], 2)
      << ", " << number(r.sff.coefficients[2]) << " ± " << number(r.sff.standard_errors[2], 2)
      << ") over " << r.sff.snapshots << " snapshots, RMS " << number(r.sff.rms)
      << ", distance from (2/5, 2/5, 3/5) " << number(r.sff.distance) << "\n";
  } else {
    s << r.sff.note << "\n";
  }
  if (!r.notes.empty()) {
    s << "\nNotes:\n\n";  // a blank line: Markdown starts a list only after one
    for (const std::string& n : r.notes) s << "- " << n << "\n";
  }
  return s.str();
}

std::string write_calibration_outputs(const std::string& folder,
                                      const std::vector<TestData>& tests,
                                      const CalibrationResult& result, const FitOptions& options,
                                      const std::string& program_version,
                                      const std::string& command_line,
                                      const std::vector<TestData>& held_out) {
  namespace fs = std::filesystem;
  fs::create_directories(folder);
  const auto& names = fit_parameter_names();
  std::vector<ParameterAnnotation> annotations;
  for (int i = 0; i < kAcsIndex; ++i) {
    const ParameterEstimate& e = result.estimates[i];
    annotations.push_back({names[i], e.lower, e.upper, e.standard_error, e.fixed, e.at_bound,
                           e.stage});
  }
  Json extra;
  const ParameterEstimate& acs = result.estimates[kAcsIndex];
  extra["fabric_normalisation"] = {
      {"a_cs", {{"value", acs.value}, {"unit", "1"},
                {"standard_error", acs.standard_error >= 0 ? Json(acs.standard_error) : Json()},
                {"meaning", "critical-state norm of the DEM fabric tensor A; F = A / a_cs"}}}};
  Json inputs = Json::array();
  auto add_inputs = [&](const std::vector<TestData>& list, bool fitted) {
    for (const TestData& t : list)
      inputs.push_back({{"name", t.name}, {"source", t.source}, {"seed", t.seed},
                        {"program_version", t.program_version}, {"p0_Pa", t.p0}, {"e0", t.e0},
                        {"a_c0", t.a_c0}, {"friction", t.friction},
                        {"loading_path", to_string(t.path)}, {"fitted", fitted}});
  };
  add_inputs(tests, true);
  add_inputs(held_out, false);
  Json stages = Json::array();
  for (const StageReport& s : result.stages)
    stages.push_back({{"stage", s.stage}, {"free_parameters", s.free_parameters},
                      {"residuals", s.residuals}, {"starts", s.starts},
                      {"initial_cost", s.initial_cost}, {"final_cost", s.final_cost},
                      {"message", s.message},
                      {"seconds", s.timing.seconds},
                      {"processor_seconds", s.timing.cpu_seconds},
                      {"iterations", s.timing.iterations},
                      {"cost_evaluations", s.timing.cost_evaluations},
                      {"jacobian_evaluations", s.timing.jacobian_evaluations},
                      {"substeps_per_step", s.timing.substeps_per_step}});
  Json independent_errors = Json::object();
  for (int i = 0; i < kNumFitParameters; ++i)
    if (result.estimates[i].standard_error_independent >= 0.0)
      independent_errors[names[i]] = result.estimates[i].standard_error_independent;
  const char* loss = options.loss == Loss::kHuber    ? "huber"
                     : options.loss == Loss::kCauchy ? "cauchy"
                                                     : "none";
  extra["provenance"] = {{"program", "sffcal calibrate"},
                         {"program_version", program_version},
                         {"date", utc_now()},
                         {"command_line", command_line},
                         {"inputs", inputs}};
  extra["fit"] = {{"stages", stages},
                  {"loss", loss},
                  {"loss_scale", options.loss_scale},
                  {"starts", options.starts},
                  {"seed", options.seed},
                  {"max_points", options.max_points},
                  {"fit_max_strain_step", options.fit_max_strain_step},
                  {"report_max_strain_step", options.report_max_strain_step},
                  {"max_iterations", options.max_iterations},
                  {"function_tolerance", options.function_tolerance},
                  {"threads", options.threads},
                  {"fit_tolerance", options.driver.integration.tolerance},
                  {"report_tolerance", options.report_driver.integration.tolerance},
                  {"residual_scales",
                   {{"eta", options.eta_scale},
                    {"volumetric_strain", options.volumetric_scale},
                    {"a_c", options.fabric_scale},
                    {"mean_stress_relative", options.mean_stress_scale}}},
                  {"covariance_scale_s2", result.covariance_scale},
                  {"standard_errors",
                   "robust to residuals correlated along each curve (Newey-West sandwich, "
                   "Bartlett kernel, Andrews AR(1) bandwidth); standard_errors_independent: "
                   "s^2 (J^T J)^-1"},
                  {"mean_bandwidth", result.mean_bandwidth},
                  {"standard_errors_independent", independent_errors},
                  {"notes", result.notes}};
  if (result.sff.available)
    extra["sff_relation"] = {{"coefficients", result.sff.coefficients},
                             {"standard_errors", result.sff.standard_errors},
                             {"snapshots", result.sff.snapshots},
                             {"rms", result.sff.rms},
                             {"distance_from_2_5_2_5_3_5", result.sff.distance}};
  extra["errors"] = errors_json(result.errors);
  if (!result.predictions.empty()) extra["held_out_errors"] = errors_json(result.predictions);
  write_parameters_json(model_parameters(result.values), (fs::path(folder) / "parameters.json").string(),
                        annotations, extra.dump());

  std::vector<const TestData*> curves;
  for (const TestData& t : tests) curves.push_back(&t);
  for (const TestData& t : held_out) curves.push_back(&t);
  for (const TestData* test : curves) {
    const TestData& t = *test;
    const ModelCurves c =
        simulate_test(t, result.values, options.report_driver, options.report_max_strain_step);
    write_csv(fs::path(folder) / (t.name + "_curves.csv"),
              "axial_strain,dem_eta,model_eta,dem_volumetric_strain,model_volumetric_strain,"
              "dem_void_ratio,model_void_ratio,dem_p_Pa,model_p_Pa",
              {c.axial_strain, t.eta, c.eta, t.volumetric_strain, c.volumetric_strain,
               t.void_ratio, c.void_ratio, t.p, c.p});
    write_csv(fs::path(folder) / (t.name + "_fabric.csv"), "axial_strain,dem_a_c,model_a_c",
              {t.snapshot_axial_strain, t.a_c, c.a_c});
  }
  const std::string summary = summary_markdown(result);
  sffcal::write_text_file((fs::path(folder) / "summary.md").string(), "# Calibration summary\n\n" + summary);
  return summary;
}

}  // namespace calibration
