// One material point of any model along a triaxial path (point_path.h).
#include "fe_model/point_path.h"

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "model/descriptor.h"
#include "model/parameter_file.h"
#include "sffcal/format_number.h"
#include "sffcal/output_file.h"

namespace fe_model {

PointPathResult run_point_path(const PointPathOptions& options) {
  if (options.steps < 1) throw std::invalid_argument("--steps must be >= 1");
  // The driver's own limit (model::kMaxTriaxialStrain), named here by the flag.
  if (!std::isfinite(options.axial_strain_end) || options.axial_strain_end == 0.0 ||
      std::abs(options.axial_strain_end) > model::kMaxTriaxialStrain)
    throw std::invalid_argument("--max-strain " + sffcal::format_number(options.axial_strain_end) +
                                ": give a non-zero axial strain of at most " +
                                sffcal::format_number(model::kMaxTriaxialStrain) +
                                " in size (negative: extension)");
  const model::ParameterValues values = model::read_parameter_file(options.parameters_path);
  const model::ModelDescription& description = model::find_model(values.model);
  PointPathResult result;
  result.model = description.name();
  result.start = specimen_start(values, options.parameters_path, options.start);
  result.void_ratio_offset = model::slot_offset(description.state(), "void_ratio");
  const std::unique_ptr<model::Behaviour> behaviour =
      description.make(values.constants, values.parameters);
  model::TriaxialPath path;
  path.drainage = options.drainage;
  path.lateral_stress = result.start.confining_pressure;
  path.axial_strain_end = options.axial_strain_end;
  path.steps = options.steps;
  result.path = model::drive_triaxial(*behaviour, result.start.inputs, path);
  return result;
}

void write_point_path_csv(const std::string& path, const PointPathOptions& options,
                          const PointPathResult& result) {
  sffcal::OutputFile file(path);
  std::ostream& out = file.stream();
  out << "# sffcal point: model " << result.model << ", parameters " << options.parameters_path
      << ", start "
      << (options.start.dem_run.empty() ? "a plain specimen" : options.start.dem_run)
      << " (sigma_3 " << sffcal::format_number(result.start.confining_pressure) << " Pa, inputs "
      << result.start.source << "), " << model::to_string(options.drainage) << " to axial strain "
      << sffcal::format_number(options.axial_strain_end) << " in " << options.steps
      << " steps; compression positive, stresses in Pa"
      << (result.path.completed ? "" : "; stopped early: " + result.path.message) << '\n';
  out.precision(std::numeric_limits<double>::max_digits10);
  out << "step,axial_strain,volumetric_strain,void_ratio,p,q,eta,sigma_xx,sigma_yy,sigma_zz,"
         "newton_iterations,status\n";
  for (std::size_t k = 0; k < result.path.points.size(); ++k) {
    const model::DriverPoint& x = result.path.points[k];
    const auto [p, q] = model::triaxial_stress(x.stress);
    out << k << ',' << x.strain(2, 2) << ',' << x.strain.trace() << ',';
    if (result.void_ratio_offset >= 0)
      out << x.state[static_cast<std::size_t>(result.void_ratio_offset)];
    out << ',' << p << ',' << q << ',' << q / p << ',' << x.stress(0, 0) << ',' << x.stress(1, 1)
        << ',' << x.stress(2, 2) << ',' << x.newton_iterations << ',' << model::to_string(x.status)
        << '\n';
  }
  file.commit();
}

}  // namespace fe_model
