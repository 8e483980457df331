// The outputs of the fit of any registered model (any_model_fit.h): its parameter file with the
// fit's record, the curves at the DEM's rows and a summary.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "calibration/any_model_fit.h"
#include "output_format.h"
#include "sffcal/output_file.h"

namespace calibration {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

std::string summary_markdown(const model::ModelDescription& description,
                             const AnyModelFitResult& result) {
  std::ostringstream md;
  md << "Model `" << description.name() << "`, fitted over its description (any-model fit: "
     << "drained paths from each test's p0 and e0, residuals in q/p and eps_v at the series "
     << "rows).\n\n| parameter | unit | value | search range | at bound |\n|---|---|---|---|---|\n";
  const std::vector<model::ParameterInfo>& table = description.parameters();
  for (std::size_t i = 0; i < table.size(); ++i)
    md << "| " << table[i].name << " | " << table[i].unit << " | "
       << output::number(result.values.parameters[i], 6) << " | "
       << output::number(table[i].fit_low) << " .. " << output::number(table[i].fit_high)
       << " | " << (result.at_bound[i] ? "yes" : "no") << " |\n";
  md << "\n| test | role | rows | RMS q/p | RMS eps_v | note |\n|---|---|---|---|---|---|\n";
  for (const AnyModelTestError& e : result.errors)
    md << "| " << e.name << " | " << (e.fitted ? "fitted" : "held out") << " | " << e.rows
       << " | " << output::number(e.eta_rms) << " | " << output::number(e.volumetric_rms)
       << " | " << e.message << " |\n";
  md << "\nCeres: " << result.termination << " (" << result.iterations << " iterations, cost "
     << output::number(result.initial_cost) << " -> " << output::number(result.final_cost)
     << (result.usable ? "" : "; the solution is NOT usable") << ").\n";
  return md.str();
}

}  // namespace

std::string write_any_model_fit_outputs(const std::string& folder,
                                        const model::ModelDescription& description,
                                        const std::vector<TestData>& fitted,
                                        const std::vector<TestData>& held_out,
                                        const AnyModelFitResult& result,
                                        const AnyModelFitOptions& options,
                                        const std::string& program_version,
                                        const std::string& command_line) {
  check_unique_names(fitted, held_out);
  fs::create_directories(folder);

  Json inputs = Json::array();
  for (const auto* list : {&fitted, &held_out})
    for (const TestData& t : *list) {
      inputs.push_back({{"name", t.name}, {"source", t.source}, {"seed", t.seed},
                        {"program_version", t.program_version}, {"p0_Pa", t.p0}, {"e0", t.e0},
                        {"loading_path", to_string(t.path)}, {"fitted", list == &fitted}});
      const AnyModelCurve curve = any_model_curve(description, result.values, t,
                                                  options.driver_steps);
      output::write_csv(fs::path(folder) / (t.name + "_curves.csv"),
                        "axial_strain,eta_dem,eta_model,volumetric_strain_dem,"
                        "volumetric_strain_model",
                        {t.axial_strain, t.eta, curve.eta, t.volumetric_strain,
                         curve.volumetric_strain});
    }
  Json errors = Json::array();
  for (const AnyModelTestError& e : result.errors)
    errors.push_back({{"name", e.name}, {"fitted", e.fitted}, {"rows", e.rows},
                      {"eta_rms", e.eta_rms}, {"volumetric_strain_rms", e.volumetric_rms},
                      {"message", e.message}});
  Json record;
  record["provenance"] = {{"program", "sffcal calibrate --model " + description.name()},
                          {"program_version", program_version},
                          {"date", output::utc_now()},
                          {"command_line", command_line},
                          {"inputs", inputs}};
  record["fit"] = {{"method", "any-model fit (calibration/any_model_fit.h)"},
                   {"initial_cost", result.initial_cost},
                   {"final_cost", result.final_cost},
                   {"iterations", result.iterations},
                   {"usable", result.usable},
                   {"termination", result.termination},
                   {"max_points", options.max_points},
                   {"driver_steps", options.driver_steps},
                   {"residual_scales",
                    {{"eta", options.eta_scale}, {"volumetric_strain", options.volumetric_scale}}}};
  record["errors"] = errors;
  std::vector<model::ParameterAnnotation> annotations;
  const std::vector<model::ParameterInfo>& table = description.parameters();
  for (std::size_t i = 0; i < table.size(); ++i) {
    model::ParameterAnnotation a;
    a.name = table[i].name;
    a.lower = table[i].fit_low;
    a.upper = table[i].fit_high;
    a.fixed = false;
    a.at_bound = result.at_bound[i];
    a.stage = "any-model fit";
    annotations.push_back(a);
  }
  model::write_parameter_file((fs::path(folder) / "parameters.json").string(), result.values,
                              annotations, record.dump());
  const std::string summary = summary_markdown(description, result);
  sffcal::write_text_file((fs::path(folder) / "summary.md").string(),
                          "# " + description.name() + ": calibration summary\n\n" + summary);
  return summary;
}

}  // namespace calibration
