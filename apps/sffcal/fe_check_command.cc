// sffcal fe-check: see fe_check_command.h and docs/fe.md. deal.II stays out of this translation
// unit: the runs go through fe_model/fe_check.h.
#include "fe_check_command.h"

#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace sffcal {

int fe_check_command(const FeCheckOptions& options) {
  const fe_model::FeCheckResult result = fe_model::run_fe_check(options, [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  });
  std::printf("\n%-22s %-18s %-17s %10s %10s  %s\n", "case", "check", "quantity", "value",
              "tolerance", "result");
  for (const fe_model::FeCheckRow& row : result.checks)
    std::printf("%-22s %-18s %-17s %10.3e %10.3e  %s%s%s\n", row.case_name.c_str(),
                row.check.c_str(), row.quantity.c_str(), row.value, row.tolerance,
                row.pass ? "pass" : "FAIL", row.note.empty() ? "" : "  ", row.note.c_str());
  if (!options.dem_runs.empty())
    std::printf("FE vs DEM uses the parameters of %s; tolerances: --dem-eta-tol, --dem-ev-tol.\n",
                options.parameters_path.c_str());
  const std::string out = options.output_folder;
  std::printf("CSV: %s/<case>/{driver,element,mesh,dem}.csv, table: %s/summary.csv; plot with "
              "scripts/plot_fe_check.py %s\n",
              out.c_str(), out.c_str(), out.c_str());
  return result.exit_code();
}

std::vector<int> parse_element_list(const std::string& text) {
  std::vector<int> elements;
  std::istringstream parts(text);
  std::string part;
  while (std::getline(parts, part, ',')) {
    const std::size_t dash = part.find('-');
    std::size_t used_first = 0, used_last = 0;
    int first = 0, last = 0;
    try {
      first = std::stoi(part.substr(0, dash), &used_first);
      last = dash == std::string::npos ? first : std::stoi(part.substr(dash + 1), &used_last);
    } catch (const std::exception&) {
      used_first = 0;
    }
    const bool whole = used_first == (dash == std::string::npos ? part.size() : dash) &&
                       (dash == std::string::npos || used_last == part.size() - dash - 1);
    if (!whole || first < 1 || last < first)
      throw std::invalid_argument("--elements: '" + part + "' is not N or N-M (1 <= N <= M)");
    if (static_cast<long long>(last) - first >= 10000000)
      throw std::invalid_argument("--elements: '" + part + "' names more than ten million elements");
    for (long long e = first; e <= last; ++e) elements.push_back(static_cast<int>(e));
  }
  return elements;
}

int umat_cards_command(const fe_model::UmatCardOptions& options) {
  std::fputs(fe_model::umat_cards(options).c_str(), stdout);
  return 0;
}

int point_command(const fe_model::PointPathOptions& options, const std::string& output) {
  const fe_model::PointPathResult result = fe_model::run_point_path(options);
  fe_model::write_point_path_csv(output, options, result);
  const model::DriverPoint& end = result.path.points.back();
  const model::TriaxialStress start_stress = model::triaxial_stress(result.path.points.front().stress);
  const model::TriaxialStress end_stress = model::triaxial_stress(end.stress);
  std::printf("%s, %s to axial strain %g in %d steps; start: sigma_3 %g Pa, inputs %s\n",
              result.model.c_str(), model::to_string(options.drainage), options.axial_strain_end,
              options.steps, result.start.confining_pressure, result.start.source.c_str());
  std::printf("start: p %.6g Pa, q %.6g Pa\nend:   axial strain %.6g, volumetric strain %.6g, "
              "p %.6g Pa, q %.6g Pa, q/p %.6g\n",
              start_stress.p, start_stress.q, end.strain(2, 2), end.strain.trace(), end_stress.p,
              end_stress.q, end_stress.q / end_stress.p);
  std::printf("CSV: %s\n", output.c_str());
  if (result.path.completed) return 0;
  std::fprintf(stderr, "sffcal: the path stopped after %zu of %d steps: %s\n",
               result.path.points.size() - 1, options.steps, result.path.message.c_str());
  return 1;
}

}  // namespace sffcal
