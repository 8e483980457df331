// Uniqueness of the one-element triaxial check (docs/fe.md, "The element leaves the homogeneous
// path"): one Q1 cell (B-bar) of the ACST model in drained compression, as fe-check's element,
// and after every converged step the eigenvalues of its tangent stiffness restricted to the free
// degrees of freedom (the lateral displacements of the two loaded faces; the lateral stress is a
// dead load). A negative eigenvalue means the incremental problem has more than one solution
// (Hill 1958; a sufficient condition for uniqueness fails): the homogeneous path the driver
// follows is one of them, and the element may take another. The table says whether the weakest
// mode is the homogeneous one (the same lateral displacement at every node of a face) or not.
//
//   fe_element_stability PARAMS.json [--void-ratio E] [--pressure P] [--strain E] [--steps N]
//   (defaults: e0 = 0.8, 100 kPa, to 0.25 in 100 steps; isotropic fabric)
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/component_mask.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>

#include "model/acst_model.h"
#include "fe_model/acst_material.h"
#include "fe_model/solid.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: fe_element_stability PARAMS.json [--void-ratio E] [--pressure P] "
                         "[--strain E] [--steps N]\n");
    return 2;
  }
  double void_ratio = 0.8, pressure = 100e3, strain_end = 0.25;
  int steps = 100;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const double value = std::stod(argv[i + 1]);
    if (key == "--void-ratio") void_ratio = value;
    else if (key == "--pressure") pressure = value;
    else if (key == "--strain") strain_end = value;
    else if (key == "--steps") steps = static_cast<int>(value);
    else {
      std::fprintf(stderr, "fe_element_stability: unknown option %s\n", key.c_str());
      return 2;
    }
  }
  try {
    fe_model::AcstInitialState initial;
    initial.void_ratio = void_ratio;
    const fe_model::AcstMaterial material(model::acst::read_parameters_json(argv[1]), initial);

    // The unit cube, symmetry planes x = 0, y = 0, z = 0 (boundary ids 0, 2, 4), the top face
    // (5) moved down, the confining pressure on x = 1 and y = 1 (1, 3): fe_model/triaxial.cc.
    dealii::Triangulation<3> triangulation;
    dealii::GridGenerator::hyper_cube(triangulation, 0.0, 1.0, /*colorize=*/true);
    fe_model::Solid solid(triangulation, material, -pressure * dealii::unit_symmetric_tensor<3>());
    auto zero = [](const dealii::Point<3>&, double) { return dealii::Tensor<1, 3>(); };
    solid.add_displacement_condition({0, {{true, false, false}}, zero});
    solid.add_displacement_condition({2, {{false, true, false}}, zero});
    solid.add_displacement_condition({4, {{false, false, true}}, zero});
    solid.add_displacement_condition(
        {5, {{false, false, true}}, [strain_end](const dealii::Point<3>&, double load) {
           dealii::Tensor<1, 3> u;
           u[2] = -load * strain_end;
           return u;
         }});
    auto confining = [pressure](const dealii::Point<3>&, const dealii::Tensor<1, 3>& normal,
                                double) { return -pressure * normal; };
    solid.add_traction_condition({1, confining});
    solid.add_traction_condition({3, confining});
    solid.setup();

    // The free degrees of freedom: u_x on x = 1 and u_y on y = 1, with their support points.
    std::set<dealii::types::global_dof_index> fixed;
    for (const auto& [boundary, component] : {std::pair{0, 0}, {2, 1}, {4, 2}, {5, 2}}) {
      std::vector<bool> mask(3, false);
      mask[component] = true;
      for (const auto dof : dealii::DoFTools::extract_boundary_dofs(
               solid.dof_handler(), dealii::ComponentMask(mask),
               {static_cast<dealii::types::boundary_id>(boundary)}))
        fixed.insert(dof);
    }
    std::vector<dealii::types::global_dof_index> free;
    for (dealii::types::global_dof_index d = 0; d < solid.dof_handler().n_dofs(); ++d)
      if (!fixed.count(d)) free.push_back(d);
    const int n = static_cast<int>(free.size());

    std::printf("| step | axial strain | q/p | smallest eigenvalue [N/m] | weakest mode |\n");
    std::printf("|---|---|---|---|---|\n");
    for (int step = 1; step <= steps; ++step) {
      const fe_model::StepReport report = solid.advance_to(static_cast<double>(step) / steps);
      if (!report.converged) {
        std::printf("step %d did not converge: %s\n", step, report.message.c_str());
        return 1;
      }
      Eigen::MatrixXd k(n, n);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) k(i, j) = solid.tangent_matrix().el(free[i], free[j]);
      const Eigen::EigenSolver<Eigen::MatrixXd> eigen(k);
      int weakest = 0;
      for (int i = 1; i < n; ++i)
        if (eigen.eigenvalues()(i).real() < eigen.eigenvalues()(weakest).real()) weakest = i;
      // Homogeneous: all entries of the mode of one sign and equal (up to 1 % of its norm).
      const Eigen::VectorXd mode = eigen.eigenvectors().col(weakest).real();
      const bool homogeneous = (mode.array() - mode.mean()).abs().maxCoeff() < 1e-2 * mode.norm();
      const fe_model::VolumeAverages averages = solid.volume_averages();
      const double q = -(averages.stress[2][2] -
                         0.5 * (averages.stress[0][0] + averages.stress[1][1]));
      const double p = -dealii::trace(averages.stress) / 3.0;
      std::printf("| %d | %.4f | %.4f | %.4e | %s |\n", step,
                  static_cast<double>(step) / steps * strain_end, q / p,
                  eigen.eigenvalues()(weakest).real(),
                  homogeneous ? "homogeneous" : "non-homogeneous");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fe_element_stability: %s\n", e.what());
    return 1;
  }
  return 0;
}
