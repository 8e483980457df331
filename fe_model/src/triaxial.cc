// The triaxial boundary-value problem of triaxial.h on top of Solid.
#include "fe_model/triaxial.h"

#include <deal.II/base/mpi.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <type_traits>

#include "fe_model/solid.h"
#include "sffcal/pvd.h"
#include "sffcal/output_file.h"

namespace fe_model {
namespace {

// Boundary ids of GridGenerator::subdivided_hyper_rectangle with colorize = true.
constexpr dealii::types::boundary_id kXMin = 0, kXMax = 1, kYMin = 2, kYMax = 3, kZMin = 4,
                                     kZMax = 5;

void check(const TriaxialOptions& o) {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("TriaxialOptions: " + what);
  };
  if (!(o.width > 0.0)) fail("width must be positive");
  if (!(o.height > 0.0)) fail("height must be positive");
  if (o.cells_x == 0 || o.cells_y == 0 || o.cells_z == 0) fail("cells_x/y/z must be >= 1");
  if (!(o.confining_pressure >= 0.0))
    fail("confining_pressure must be >= 0 (compression positive)");
  if (!std::isfinite(o.axial_strain_end)) fail("axial_strain_end must be finite");
  if (o.n_steps == 0) fail("n_steps must be >= 1");
  if (!(o.solver.linear_rtol > 0.0 && o.solver.linear_rtol < 1.0))
    fail("solver.linear_rtol must be in (0, 1)");
  if (o.solver.max_linear_iterations == 0) fail("solver.max_linear_iterations must be >= 1");
}

template <typename SolidType>
TriaxialStep measure(const SolidType& solid, unsigned int step) {
  const VolumeAverages averages = solid.volume_averages();
  TriaxialStep row;
  row.step = step;
  // deal.II (tension positive) -> soil mechanics (compression positive).
  row.axial_strain = -averages.strain[2][2];
  row.volumetric_strain = -dealii::trace(averages.strain);
  row.axial_stress = -averages.stress[2][2];
  row.radial_stress = -0.5 * (averages.stress[0][0] + averages.stress[1][1]);
  row.p = -dealii::trace(averages.stress) / 3.0;
  row.q = row.axial_stress - row.radial_stress;
  row.fabric_invariant = averages.fabric_invariant;
  row.internal_variables = averages.internal_variables;
  return row;
}

// u_x at the vertices of the edge x = L, y = 0 (the outer face's radial displacement).
template <typename SolidType>
std::vector<BulgePoint> bulge_profile(const SolidType& solid, double L) {
  std::map<double, double> profile;  // z -> u_x
  for (const VertexDisplacement& vertex :
       solid.vertex_displacements([L](const dealii::Point<3>& x) {
         return std::abs(x[0] - L) < 1e-9 * L && std::abs(x[1]) < 1e-9 * L;
       }))
    profile[vertex.position[2]] = vertex.displacement[0];
  std::vector<BulgePoint> points;
  for (const auto& [z, u] : profile) points.push_back({z, u});
  return points;
}

std::string vtu_name(const std::string& prefix, unsigned int step) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "_%04u.vtu", step);
  return prefix + buffer;
}

// The test on `triangulation` (empty) with a SolidType (Solid or DistributedSolid).
template <typename SolidType>
TriaxialResult run_on(dealii::Triangulation<3>& triangulation, const Material& material,
                      const TriaxialOptions& options) {
  const double L = options.width, H = options.height, p0 = options.confining_pressure;
  dealii::GridGenerator::subdivided_hyper_rectangle(
      triangulation, {options.cells_x, options.cells_y, options.cells_z}, dealii::Point<3>(0, 0, 0),
      dealii::Point<3>(L, L, H), /*colorize=*/true);
  const bool writes_serial_files =
      !std::is_same_v<SolidType, DistributedSolid> ||
      dealii::Utilities::MPI::this_mpi_process(triangulation.get_communicator()) == 0;

  const SymmetricTensor2 initial_stress = -p0 * dealii::unit_symmetric_tensor<3>();
  SolidType solid(triangulation, material, initial_stress, options.solver);

  auto zero = [](const dealii::Point<3>&, double) { return dealii::Tensor<1, 3>(); };
  solid.add_displacement_condition({kXMin, {{true, false, false}}, zero});
  solid.add_displacement_condition({kYMin, {{false, true, false}}, zero});
  solid.add_displacement_condition({kZMin, {{false, false, true}}, zero});
  const double strain_end = options.axial_strain_end;
  solid.add_displacement_condition(
      {kZMax,
       {{options.rough_platens, options.rough_platens, true}},
       [strain_end, H](const dealii::Point<3>&, double load) {
         dealii::Tensor<1, 3> u;  // u_x = u_y = 0 where the platen is rough
         u[2] = -load * strain_end * H;  // compression positive eps_a -> downward displacement
         return u;
       }});
  auto confining = [p0](const dealii::Point<3>&, const dealii::Tensor<1, 3>& normal, double) {
    return -p0 * normal;
  };
  solid.add_traction_condition({kXMax, confining});
  solid.add_traction_condition({kYMax, confining});
  solid.setup();

  TriaxialResult result;
  result.steps.push_back(measure(solid, 0));
  std::vector<std::string> vtu_files;
  auto write_vtu = [&](unsigned int step) {
    if (options.vtu_prefix.empty()) return;
    const std::string name = vtu_name(options.vtu_prefix, step);
    solid.write_vtu(name);
    vtu_files.push_back(std::filesystem::path(name).filename().string());
  };
  write_vtu(0);

  for (unsigned int step = 1; step <= options.n_steps; ++step) {
    const double load = static_cast<double>(step) / options.n_steps;
    if (options.solver.verbose && writes_serial_files) {
      std::cout << "step " << step << ": axial strain " << load * strain_end << '\n';
    }
    StepReport report = solid.advance_to(load);
    if (!report.converged) {
      result.message = "step " + std::to_string(step) + ": " + report.message;
      result.reports.push_back(std::move(report));
      break;
    }
    TriaxialStep row = measure(solid, step);
    row.newton_iterations = report.total_iterations();
    row.cuts = report.cuts;
    for (const NewtonLog& attempt : report.attempts) {
      if (attempt.converged) {
        row.worst_status = worst(row.worst_status, attempt.worst_status);
        row.residual_norms = attempt.residual_norms;
      }
    }
    result.steps.push_back(row);
    result.reports.push_back(std::move(report));
    write_vtu(step);
  }
  result.completed = result.message.empty();
  result.bulge = bulge_profile(solid, L);
  if (!writes_serial_files) return result;
  if (!options.csv_path.empty()) write_triaxial_csv(options.csv_path, result.steps);
  if (!options.vtu_prefix.empty()) {
    std::vector<double> times;
    for (const TriaxialStep& row : result.steps) times.push_back(row.axial_strain);
    sffcal::write_pvd(options.vtu_prefix + ".pvd", vtu_files, times, "axial strain (compression positive)");
  }
  return result;
}

}  // namespace

TriaxialResult run_triaxial(const Material& material, const TriaxialOptions& options) {
  check(options);
  if (options.distributed) {
    if (!dealii::Utilities::MPI::job_supports_mpi())
      throw std::invalid_argument("TriaxialOptions: distributed needs MPI initialised (e.g. by "
                                  "dealii::Utilities::MPI::MPI_InitFinalize in main)");
    dealii::parallel::distributed::Triangulation<3> triangulation(MPI_COMM_WORLD);
    return run_on<DistributedSolid>(triangulation, material, options);
  }
  dealii::Triangulation<3> triangulation;
  return run_on<Solid>(triangulation, material, options);
}

void write_triaxial_csv(const std::string& path, const std::vector<TriaxialStep>& steps) {
  sffcal::OutputFile file(path);
  std::ostream& out = file.stream();
  const bool has_fabric = !steps.empty() && steps.front().fabric_invariant.has_value();
  out << "# fe_model triaxial test; compression positive; stresses in Pa\n";
  out << "step,axial_strain,volumetric_strain,p,q,axial_stress,radial_stress";
  if (has_fabric) out << ",fabric_invariant";
  out << ",newton_iterations,cuts,final_residual,status\n";
  out << std::setprecision(12);
  for (const TriaxialStep& row : steps) {
    out << row.step << ',' << row.axial_strain << ',' << row.volumetric_strain << ',' << row.p
        << ',' << row.q << ',' << row.axial_stress << ',' << row.radial_stress;
    if (has_fabric) out << ',' << row.fabric_invariant.value_or(0.0);
    out << ',' << row.newton_iterations << ',' << row.cuts << ','
        << (row.residual_norms.empty() ? 0.0 : row.residual_norms.back()) << ','
        << to_string(row.worst_status) << '\n';
  }
  file.commit();
}

}  // namespace fe_model
