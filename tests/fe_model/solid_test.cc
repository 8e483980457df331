// deal.II-level tests of Solid: the patch test on a distorted mesh and the assembled tangent
// against finite differences of the assembled residual.
#include "fe_model/solid.h"

#include <deal.II/base/multithread_info.h>
#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/full_matrix.h>
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "fe_model/material.h"
#include "test_materials.h"

namespace fe_model {
namespace {

using dealii::Point;
using dealii::Tensor;

// A 2x2x2 mesh of the unit cube with its inner vertex moved and its face-centre and edge-midpoint
// vertices moved within their faces/edges, so no cell is a parallelepiped (non-constant Jacobian);
// the outer faces stay planar and keep their colorized boundary ids 0..5.
void make_distorted_cube(dealii::Triangulation<3>& triangulation) {
  dealii::GridGenerator::subdivided_hyper_rectangle(triangulation, {2, 2, 2}, Point<3>(0, 0, 0),
                                                    Point<3>(1, 1, 1), true);
  std::vector<bool> moved(triangulation.n_vertices(), false);
  for (const auto& cell : triangulation.active_cell_iterators()) {
    for (const unsigned int v : cell->vertex_indices()) {
      if (moved[cell->vertex_index(v)]) continue;
      moved[cell->vertex_index(v)] = true;
      Point<3>& x = cell->vertex(v);
      // Offsets applied only along coordinates equal to 0.5 (interior directions of that vertex).
      const Point<3> offset(0.12, -0.08, 0.1);
      const Point<3> original = x;
      for (unsigned int d = 0; d < 3; ++d) {
        if (std::abs(original[d] - 0.5) < 1e-12) {
          // vary the offset with the position so that the mesh is not a shifted grid
          x[d] += offset[d] * (1.0 + 0.5 * original[(d + 1) % 3] - 0.3 * original[(d + 2) % 3]);
        }
      }
    }
  }
}

SymmetricTensor2 symmetric_part(const Tensor<2, 3>& g) { return dealii::symmetrize(g); }

// The unit cube's base (face 4) held, its top (face 5) pressed down 1e-3 m at load factor 1; set up.
void clamp_base_and_press_top(Solid& solid) {
  solid.add_displacement_condition(
      {4, {{true, true, true}}, [](const Point<3>&, double) { return Tensor<1, 3>(); }});
  solid.add_displacement_condition({5, {{false, false, true}}, [](const Point<3>&, double load) {
                                      return Tensor<1, 3>({0.0, 0.0, -1e-3 * load});
                                    }});
  solid.setup();
}

TEST(Solid, PatchTestReproducesConstantStrainAndStress) {
  dealii::Triangulation<3> triangulation;
  make_distorted_cube(triangulation);

  Tensor<2, 3> G;  // displacement gradient of the linear field
  const double g[3][3] = {{1.0, 2.0, -0.5}, {0.3, -1.0, 0.7}, {0.4, 0.2, 1.5}};
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j) G[i][j] = 1e-3 * g[i][j];
  const Tensor<1, 3> translation({1e-4, -2e-4, 3e-4});
  auto exact = [G, translation](const Point<3>& x) { return translation + G * x; };

  const LinearElasticMaterial material(50e6, 0.3);
  const SymmetricTensor2 initial_stress = -100e3 * dealii::unit_symmetric_tensor<3>();
  Solid solid(triangulation, material, initial_stress);
  for (dealii::types::boundary_id id = 0; id < 6; ++id) {
    solid.add_displacement_condition(
        {id, {{true, true, true}}, [exact](const Point<3>& x, double load) {
           return load * exact(x);
         }});
  }
  solid.setup();
  const StepReport report = solid.advance_to(1.0);
  ASSERT_TRUE(report.converged) << report.message;
  EXPECT_EQ(report.total_iterations(), 1);

  const SymmetricTensor2 strain = symmetric_part(G);
  const SymmetricTensor2 stress = initial_stress + material.stiffness() * strain;
  const SymmetricTensor2 stress_increment = material.stiffness() * strain;
  double strain_error = 0.0, stress_error = 0.0;
  solid.for_each_point([&](const Point<3>&, const PointState& state) {
    strain_error = std::max(strain_error, (state.strain - strain).norm() / strain.norm());
    stress_error = std::max(stress_error, (state.stress - stress).norm() / stress_increment.norm());
  });
  // Nodal displacements (the interior node included) equal the linear field.
  std::vector<Point<3>> support(solid.dof_handler().n_dofs());
  dealii::DoFTools::map_dofs_to_support_points(dealii::MappingQ1<3>(), solid.dof_handler(),
                                               support);
  double displacement_error = 0.0;
  for (const auto& cell : solid.dof_handler().active_cell_iterators()) {
    std::vector<dealii::types::global_dof_index> dofs(cell->get_fe().n_dofs_per_cell());
    cell->get_dof_indices(dofs);
    for (unsigned int i = 0; i < dofs.size(); ++i) {
      const unsigned int component = cell->get_fe().system_to_component_index(i).first;
      displacement_error =
          std::max(displacement_error,
                   std::abs(solid.solution()[dofs[i]] - exact(support[dofs[i]])[component]));
    }
  }
  std::cout << "patch test: strain error " << strain_error << ", stress error " << stress_error
            << ", nodal displacement error " << displacement_error
            << " (relative to |G| = " << G.norm() << ")\n";
  RecordProperty("strain_error", std::to_string(strain_error));
  RecordProperty("stress_error", std::to_string(stress_error));
  EXPECT_LT(strain_error, 1e-12);
  EXPECT_LT(stress_error, 1e-12);
  EXPECT_LT(displacement_error, 1e-14);
}

// With and without the mean dilatation (B-bar): both residuals are differentiated exactly.
TEST(Solid, AssembledTangentMatchesFiniteDifferencesOfResidual) {
  for (const bool mean_dilatation : {true, false}) {
  SCOPED_TRACE(mean_dilatation ? "mean dilatation" : "full integration");
  dealii::Triangulation<3> triangulation;
  make_distorted_cube(triangulation);
  const testing::HypoelasticTestMaterial material(0.01, 80.0);
  SymmetricTensor2 initial_stress = -100e3 * dealii::unit_symmetric_tensor<3>();
  initial_stress[2][2] = -150e3;
  initial_stress[0][1] = 10e3;
  SolverOptions options;
  options.mean_dilatation = mean_dilatation;
  Solid solid(triangulation, material, initial_stress, options);
  // Tractions only (no Dirichlet condition): every degree of freedom is free.
  solid.add_traction_condition({1, [](const Point<3>&, const Tensor<1, 3>& n, double load) {
                                  return -(100e3 + 10e3 * load) * n;
                                }});
  solid.setup();

  const unsigned int n = solid.dof_handler().n_dofs();
  dealii::Vector<double> u(n);
  for (unsigned int i = 0; i < n; ++i) u[i] = 1e-4 * std::sin(1.7 * i + 0.3);  // strains ~ 1e-3
  ASSERT_EQ(solid.assemble(u, 0.5, true), MaterialStatus::kOk);
  dealii::FullMatrix<double> analytic(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j) analytic(i, j) = solid.tangent_matrix().el(i, j);

  const double h = 1e-8;
  double max_error = 0.0, max_entry = 0.0, max_asymmetry = 0.0;
  for (unsigned int j = 0; j < n; ++j) {
    dealii::Vector<double> up = u, um = u;
    up[j] += h;
    um[j] -= h;
    ASSERT_EQ(solid.assemble(up, 0.5, false), MaterialStatus::kOk);
    const dealii::Vector<double> rp = solid.residual();
    ASSERT_EQ(solid.assemble(um, 0.5, false), MaterialStatus::kOk);
    const dealii::Vector<double> rm = solid.residual();
    for (unsigned int i = 0; i < n; ++i) {
      const double fd = (rp[i] - rm[i]) / (2.0 * h);
      max_error = std::max(max_error, std::abs(fd - analytic(i, j)));
      max_entry = std::max(max_entry, std::abs(analytic(i, j)));
      max_asymmetry = std::max(max_asymmetry, std::abs(analytic(i, j) - analytic(j, i)));
    }
  }
  const double relative = max_error / max_entry;
  std::cout << (mean_dilatation ? "B-bar: " : "full: ") << "FE tangent vs central differences (" << n << " dofs, h = " << h
            << "): max error / max entry = " << relative
            << "; max |K - K^T| / max entry = " << max_asymmetry / max_entry << '\n';
  RecordProperty("fd_tangent_error", std::to_string(relative));
  EXPECT_LT(relative, 1e-6);
  EXPECT_GT(max_asymmetry / max_entry, 1e-6);  // the test material's tangent is unsymmetric
  }
}

// The mean dilatation gives every quadrature point of a cell the cell's volumetric strain (its
// JxW-weighted mean) and keeps each point's deviatoric strain; full integration does not.
TEST(Solid, MeanDilatationSharesTheCellsVolumetricStrain) {
  std::vector<std::vector<double>> traces(2), deviators(2);
  for (const bool mean_dilatation : {true, false}) {
    dealii::Triangulation<3> triangulation;
    make_distorted_cube(triangulation);
    const LinearElasticMaterial material(1e8, 0.3);
    SolverOptions options;
    options.mean_dilatation = mean_dilatation;
    Solid solid(triangulation, material, SymmetricTensor2(), options);
    solid.setup();
    const unsigned int n = solid.dof_handler().n_dofs();
    dealii::Vector<double> u(n);
    for (unsigned int i = 0; i < n; ++i) u[i] = 1e-4 * std::sin(1.7 * i + 0.3);
    ASSERT_EQ(solid.assemble(u, 0.0, false), MaterialStatus::kOk);
    solid.for_each_point([&](const Point<3>&, const PointState& state) {
      traces[mean_dilatation].push_back(dealii::trace(state.strain));
      deviators[mean_dilatation].push_back(dealii::deviator(state.strain).norm());
    });
  }
  ASSERT_EQ(traces[1].size(), 64u);  // 8 cells (visited in order), 2x2x2 Gauss points each
  double spread_bbar = 0.0, spread_full = 0.0, deviator_difference = 0.0;
  for (std::size_t q = 0; q < 64; ++q) {
    const std::size_t first = q - q % 8;  // the cell's first point
    spread_bbar = std::max(spread_bbar, std::abs(traces[1][q] - traces[1][first]));
    spread_full = std::max(spread_full, std::abs(traces[0][q] - traces[0][first]));
    deviator_difference = std::max(deviator_difference, std::abs(deviators[1][q] - deviators[0][q]));
  }
  double scale = 0.0;
  for (const double t : traces[0]) scale = std::max(scale, std::abs(t));
  std::cout << "volumetric strain spread over the cell: B-bar " << spread_bbar / scale
            << ", full integration " << spread_full / scale << '\n';
  EXPECT_LT(spread_bbar, 1e-13 * scale);
  EXPECT_GT(spread_full, 1e-3 * scale);  // the distorted cell strains non-uniformly
  EXPECT_LT(deviator_difference, 1e-12);
}

// WorkStream assembly: the copier adds the cells in their order, so the residual and the matrix
// are the same for 1 and 2 threads, bit for bit; and so is a whole Newton solve.
TEST(Solid, AssemblyAndSolveAreTheSameForAnyNumberOfThreads) {
  std::vector<dealii::Vector<double>> residuals, solutions;
  std::vector<std::vector<double>> matrices;
  for (const unsigned int threads : {1u, 2u}) {
    dealii::MultithreadInfo::set_thread_limit(threads);
    dealii::Triangulation<3> triangulation;
    dealii::GridGenerator::subdivided_hyper_rectangle(triangulation, {4, 4, 4}, Point<3>(0, 0, 0),
                                                      Point<3>(1, 1, 1), true);
    const testing::HypoelasticTestMaterial material(0.01, 80.0);
    Solid solid(triangulation, material, -100e3 * dealii::unit_symmetric_tensor<3>());
    auto zero = [](const Point<3>&, double) { return Tensor<1, 3>(); };
    solid.add_displacement_condition({0, {{true, false, false}}, zero});
    solid.add_displacement_condition({2, {{false, true, false}}, zero});
    solid.add_displacement_condition({4, {{false, false, true}}, zero});
    solid.add_displacement_condition({5, {{true, true, true}}, [](const Point<3>&, double load) {
                                        Tensor<1, 3> u;
                                        u[2] = -0.01 * load;
                                        return u;
                                      }});
    solid.add_traction_condition({1, [](const Point<3>&, const Tensor<1, 3>& n, double) {
                                    return -100e3 * n;
                                  }});
    solid.setup();
    dealii::Vector<double> u(solid.dof_handler().n_dofs());
    for (unsigned int i = 0; i < u.size(); ++i) u[i] = 1e-4 * std::sin(1.7 * i + 0.3);
    ASSERT_EQ(solid.assemble(u, 0.5, true), MaterialStatus::kOk);
    residuals.push_back(solid.residual());
    std::vector<double> entries;
    for (auto it = solid.tangent_matrix().begin(); it != solid.tangent_matrix().end(); ++it)
      entries.push_back(it->value());
    matrices.push_back(entries);
    const StepReport report = solid.advance_to(1.0);
    ASSERT_TRUE(report.converged) << report.message;
    solutions.push_back(solid.solution());
  }
  dealii::MultithreadInfo::set_thread_limit();
  EXPECT_TRUE(residuals[0] == residuals[1]);
  EXPECT_TRUE(matrices[0] == matrices[1]);
  dealii::Vector<double> difference = solutions[0];
  difference -= solutions[1];
  std::cout << "1 vs 2 threads: |u_1 - u_2|_inf = " << difference.linfty_norm() << '\n';
  EXPECT_TRUE(solutions[0] == solutions[1]);
}

TEST(Solid, RevertRestoresTheCommittedState) {
  dealii::Triangulation<3> triangulation;
  dealii::GridGenerator::hyper_cube(triangulation, 0.0, 1.0, true);
  const LinearElasticMaterial material(10e6, 0.2);
  Solid solid(triangulation, material, SymmetricTensor2());
  clamp_base_and_press_top(solid);
  const NewtonLog log = solid.solve_increment(1.0);
  ASSERT_TRUE(log.converged);
  EXPECT_GT(solid.volume_averages().stress.norm(), 0.0);
  solid.revert();
  EXPECT_EQ(solid.solution().l2_norm(), 0.0);
  EXPECT_EQ(solid.volume_averages().stress.norm(), 0.0);
}

// The wall-time budget ends a run by name at the next Newton iteration, without cutting the step
// (a smaller increment does not give time back); a budget not reached changes nothing.
TEST(Solid, AWallTimeLimitStopsTheRunByNameWithoutCuts) {
  for (const double limit : {1e-9, 1e6}) {
    dealii::Triangulation<3> triangulation;
    dealii::GridGenerator::hyper_cube(triangulation, 0.0, 1.0, true);
    const LinearElasticMaterial material(10e6, 0.2);
    SolverOptions options;
    options.wall_time_limit = limit;
    Solid solid(triangulation, material, SymmetricTensor2(), options);
    clamp_base_and_press_top(solid);
    const StepReport report = solid.advance_to(1.0);
    if (limit > 1.0) {
      EXPECT_TRUE(report.converged) << report.message;
      continue;
    }
    EXPECT_FALSE(report.converged);
    EXPECT_EQ(report.cuts, 0);
    EXPECT_EQ(report.load_reached, 0.0);
    ASSERT_EQ(report.attempts.size(), 1u);
    EXPECT_TRUE(report.attempts.front().out_of_time);
    EXPECT_NE(report.message.find("wall-time limit of 1e-09 s at Newton iteration 0"),
              std::string::npos)
        << report.message;
  }
}

}  // namespace
}  // namespace fe_model
