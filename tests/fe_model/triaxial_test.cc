// The triaxial boundary-value problem: analytic linear-elastic answer on one element and on a
// mesh, Newton convergence (one iteration for linear elasticity, quadratic for a nonlinear law),
// step cutting on an induced material failure, CSV/VTU output.
#include "fe_model/triaxial.h"
#include "material_checks.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "fe_model/material.h"
#include "fe_model/model_material.h"
#include "test_materials.h"

namespace fe_model {
namespace {

constexpr double kE = 50e6, kNu = 0.25, kP0 = 100e3;

void expect_linear_elastic_triaxial(const TriaxialResult& result, unsigned int n_steps) {
  ASSERT_TRUE(result.completed) << result.message;
  ASSERT_EQ(result.steps.size(), n_steps + 1);
  for (const TriaxialStep& row : result.steps) {
    const double eps_a = row.axial_strain;
    const double q = kE * eps_a;  // sigma_3 held: q = E eps_a, eps_v = (1 - 2 nu) eps_a
    const double scale = std::max(kE * 1e-2, kP0);
    EXPECT_NEAR(row.q, q, 1e-10 * scale) << "step " << row.step;
    EXPECT_NEAR(row.p, kP0 + q / 3.0, 1e-10 * scale) << "step " << row.step;
    EXPECT_NEAR(row.radial_stress, kP0, 1e-10 * scale) << "step " << row.step;
    EXPECT_NEAR(row.volumetric_strain, (1.0 - 2.0 * kNu) * eps_a, 1e-10 * 1e-2)
        << "step " << row.step;
    EXPECT_FALSE(row.fabric_invariant.has_value());
    if (row.step > 0) {
      EXPECT_NEAR(eps_a, 0.01 * row.step / n_steps, 1e-14);
      // Linear elasticity: Newton in one iteration; after the first step the extrapolated first
      // iterate (SolverOptions::extrapolate_predictor) is already the answer.
      EXPECT_EQ(row.newton_iterations, row.step == 1 ? 1 : 0) << "step " << row.step;
      EXPECT_EQ(row.cuts, 0);
    }
  }
}

TriaxialOptions elastic_options(unsigned int nx, unsigned int ny, unsigned int nz) {
  TriaxialOptions options;
  options.width = 0.5;
  options.height = 1.0;
  options.cells_x = nx;
  options.cells_y = ny;
  options.cells_z = nz;
  options.confining_pressure = kP0;
  options.axial_strain_end = 0.01;
  options.n_steps = 5;
  return options;
}

double max_relative_error(const TriaxialResult& result) {
  double error = 0.0;
  for (const TriaxialStep& row : result.steps) {
    if (row.step == 0) continue;
    const double q = kE * row.axial_strain;
    error = std::max(error, std::abs(row.q - q) / q);
    error = std::max(error, std::abs(row.volumetric_strain - (1 - 2 * kNu) * row.axial_strain) /
                                row.axial_strain);
  }
  return error;
}

TEST(Triaxial, SingleElementLinearElasticMatchesAnalytic) {
  const LinearElasticMaterial material(kE, kNu);
  const TriaxialResult result = run_triaxial(material, elastic_options(1, 1, 1));
  expect_linear_elastic_triaxial(result, 5);
  std::cout << "single element: max relative error in q and eps_v " << max_relative_error(result)
            << "; Newton residuals of the last step:";
  for (double r : result.steps.back().residual_norms) std::cout << ' ' << r;
  std::cout << '\n';
}

// The third registered model (model/src/linear_elastic.cc) through the one adapter written over
// the model interface: the same analytic answer on a mesh, with no code of its own in fe_model.
TEST(Triaxial, TheThirdRegisteredModelThroughModelMaterialMatchesAnalytic) {
  const ModelMaterial material(model::find_model("linear_elastic").make({}, {kE, kNu}), {});
  EXPECT_EQ(material.name(), "linear_elastic");
  const TriaxialResult result = run_triaxial(material, elastic_options(2, 2, 4));
  expect_linear_elastic_triaxial(result, 5);
}

TEST(Triaxial, SmallMeshGivesTheHomogeneousAnswer) {
  const LinearElasticMaterial material(kE, kNu);
  const TriaxialResult result = run_triaxial(material, elastic_options(2, 2, 4));
  expect_linear_elastic_triaxial(result, 5);
  std::cout << "2x2x4 mesh: max relative error in q and eps_v " << max_relative_error(result)
            << '\n';
}

TEST(Triaxial, InitialStateIsInEquilibriumWithTheConfiningPressure) {
  const LinearElasticMaterial material(kE, kNu);
  TriaxialOptions options = elastic_options(2, 2, 2);
  options.axial_strain_end = 0.0;
  options.n_steps = 1;
  const TriaxialResult result = run_triaxial(material, options);
  ASSERT_TRUE(result.completed) << result.message;
  ASSERT_EQ(result.steps.size(), 2u);
  for (const TriaxialStep& row : result.steps) {
    EXPECT_NEAR(row.p, kP0, 1e-9);
    EXPECT_NEAR(row.q, 0.0, 1e-9);
  }
  EXPECT_EQ(result.steps[1].newton_iterations, 0);  // the first residual already vanishes
}

TEST(Triaxial, NewtonConvergesQuadraticallyForANonlinearMaterial) {
  const testing::HypoelasticTestMaterial material(0.01, 60.0);
  TriaxialOptions options = elastic_options(2, 2, 4);
  options.axial_strain_end = 0.02;
  options.n_steps = 4;
  // Newton from the plain first iterate: the extrapolated one is too close to the answer on this
  // homogeneous path to show the rate.
  options.solver.extrapolate_predictor = false;
  const TriaxialResult result = run_triaxial(material, options);
  ASSERT_TRUE(result.completed) << result.message;
  ASSERT_TRUE(result.steps.back().fabric_invariant.has_value());
  for (const StepReport& report : result.reports) {
    const NewtonLog& log = report.attempts.back();
    ASSERT_TRUE(log.converged);
    std::cout << "load " << log.load_end << ":";
    const std::vector<double> ratios = log.residual_ratios();
    const std::vector<double> quadratic = log.quadratic_ratios();
    for (std::size_t k = 0; k < log.residual_norms.size(); ++k) {
      std::cout << "\n  |R_" << k << "| = " << log.residual_norms[k];
      if (k > 0)
        std::cout << "  ratio " << ratios[k - 1] << "  |R_k|/|R_k-1|^2 (scaled) "
                  << quadratic[k - 1];
    }
    std::cout << '\n';
    EXPECT_GE(log.iterations, 3) << "the test material should be clearly nonlinear";
    // Quadratic convergence: ||R_k+1|| |f_int| / ||R_k||^2 stays bounded all the way ...
    for (double ratio : quadratic) EXPECT_LT(ratio, 10.0);
    // ... and the order log(r_k+1/r_k)/log(r_k/r_k-1) tends to 2 (pre-asymptotic iterates lower;
    // the last pair above round-off is checked).
    const double last_order =
        checks::last_convergence_order(log, 1e-13 * log.force_scale, &std::cout);
    EXPECT_GT(last_order, 1.8);
  }
}

// The iterative linear solver (GMRES + ILU) is an inexact Newton step: on a non-homogeneous
// problem (rough platens: the specimen bulges) it takes the same Newton iterations and reaches
// the answer of the direct solver to the Newton tolerance; where GMRES cannot reach its tolerance
// the correction falls back to the direct solver and the answer is the same again.
TEST(Triaxial, IterativeLinearSolverGivesTheDirectAnswer) {
  using LinearSolver = SolverOptions::LinearSolver;
  const testing::HypoelasticTestMaterial material(0.01, 60.0);
  TriaxialOptions options = elastic_options(3, 3, 4);
  options.rough_platens = true;
  options.axial_strain_end = 0.02;
  options.n_steps = 4;
  options.solver.linear_solver = LinearSolver::kDirect;
  const TriaxialResult direct = run_triaxial(material, options);
  options.solver.linear_solver = LinearSolver::kIterative;
  const TriaxialResult iterative = run_triaxial(material, options);
  options.solver.max_linear_iterations = 2;  // GMRES stops short: the corrections fall back
  const TriaxialResult fallback = run_triaxial(material, options);
  for (const TriaxialResult* result : {&direct, &iterative, &fallback})
    ASSERT_TRUE(result->completed) << result->message;
  ASSERT_EQ(direct.steps.size(), iterative.steps.size());
  for (std::size_t i = 0; i < direct.steps.size(); ++i) {
    const TriaxialStep &a = direct.steps[i], &b = iterative.steps[i], &c = fallback.steps[i];
    EXPECT_EQ(a.newton_iterations, b.newton_iterations) << "step " << i;
    EXPECT_NEAR(b.q, a.q, 1e-8 * (kP0 + std::abs(a.q))) << "step " << i;
    EXPECT_NEAR(b.volumetric_strain, a.volumetric_strain, 1e-12) << "step " << i;
    EXPECT_NEAR(c.q, a.q, 1e-8 * (kP0 + std::abs(a.q))) << "step " << i;
  }
  ASSERT_EQ(direct.bulge.size(), iterative.bulge.size());
  EXPECT_GT(direct.bulge.front().radial_displacement - direct.bulge.back().radial_displacement,
            0.0) << "rough platens: the specimen bulges at mid-height";
  for (std::size_t i = 0; i < direct.bulge.size(); ++i)
    EXPECT_NEAR(iterative.bulge[i].radial_displacement, direct.bulge[i].radial_displacement,
                1e-9 * std::abs(direct.bulge.front().radial_displacement));
  int gmres = 0, fell_back = 0;
  for (const StepReport& report : iterative.reports)
    for (const NewtonLog& log : report.attempts)
      for (int n : log.linear_iterations) (n > 0 ? gmres : fell_back) += 1;
  EXPECT_GT(gmres, 0);
  EXPECT_EQ(fell_back, 0);
  int fallbacks = 0;
  for (const StepReport& report : fallback.reports)
    for (const NewtonLog& log : report.attempts)
      for (int n : log.linear_iterations) fallbacks += n < 0;
  EXPECT_GT(fallbacks, 0);
  for (const StepReport& report : direct.reports)
    for (const NewtonLog& log : report.attempts) EXPECT_TRUE(log.linear_iterations.empty());
}

// The extrapolated first iterate changes the path to the answer, not the answer: on a bulging mesh
// the curves and the bulge are those of the plain first iterate to the Newton tolerance, in fewer
// Newton iterations.
TEST(Triaxial, ExtrapolatedPredictorGivesTheSameAnswerInFewerIterations) {
  const testing::HypoelasticTestMaterial material(0.01, 60.0);
  TriaxialOptions options = elastic_options(3, 3, 4);
  options.rough_platens = true;
  options.axial_strain_end = 0.03;
  options.n_steps = 6;
  const TriaxialResult extrapolated = run_triaxial(material, options);
  options.solver.extrapolate_predictor = false;
  const TriaxialResult plain = run_triaxial(material, options);
  ASSERT_TRUE(extrapolated.completed) << extrapolated.message;
  ASSERT_TRUE(plain.completed) << plain.message;
  ASSERT_EQ(extrapolated.steps.size(), plain.steps.size());
  int iterations_extrapolated = 0, iterations_plain = 0;
  for (std::size_t i = 0; i < plain.steps.size(); ++i) {
    const TriaxialStep &a = plain.steps[i], &b = extrapolated.steps[i];
    EXPECT_NEAR(b.q, a.q, 1e-8 * (kP0 + std::abs(a.q))) << "step " << i;
    EXPECT_NEAR(b.volumetric_strain, a.volumetric_strain, 1e-12) << "step " << i;
    iterations_plain += a.newton_iterations;
    iterations_extrapolated += b.newton_iterations;
  }
  for (std::size_t i = 0; i < plain.bulge.size(); ++i)
    EXPECT_NEAR(extrapolated.bulge[i].radial_displacement, plain.bulge[i].radial_displacement,
                1e-9 * std::abs(plain.bulge.front().radial_displacement));
  std::cout << "Newton iterations: " << iterations_plain << " plain, " << iterations_extrapolated
            << " extrapolated\n";
  EXPECT_LT(iterations_extrapolated, iterations_plain);
}

TEST(Triaxial, StepCuttingRecoversFromAMaterialFailure) {
  const LinearElasticMaterial elastic(kE, kNu);
  const testing::FailingTestMaterial material(elastic, 3e-3);  // one 1e-2 step is too big
  TriaxialOptions options = elastic_options(1, 1, 1);
  options.n_steps = 1;
  const TriaxialResult result = run_triaxial(material, options);
  ASSERT_TRUE(result.completed) << result.message;
  const TriaxialStep& last = result.steps.back();
  EXPECT_GE(last.cuts, 2);
  EXPECT_NEAR(last.axial_strain, 0.01, 1e-14);
  EXPECT_NEAR(last.q, kE * 0.01, 1e-10 * kE * 0.01);
  std::cout << "cut step: " << last.cuts << " cuts, " << result.reports.back().attempts.size()
            << " Newton solves\n";
}

TEST(Triaxial, HopelessStepCuttingEndsWithAClearErrorAndNoNaN) {
  const LinearElasticMaterial elastic(kE, kNu);
  const testing::FailingTestMaterial material(elastic, 1e-9);
  TriaxialOptions options = elastic_options(1, 1, 1);
  options.solver.max_cuts = 4;
  const TriaxialResult result = run_triaxial(material, options);
  EXPECT_FALSE(result.completed);
  EXPECT_NE(result.message.find("failed"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("4 cuts"), std::string::npos) << result.message;
  std::cout << "error message: " << result.message << '\n';
  ASSERT_EQ(result.steps.size(), 1u);  // the initial state only
  for (const TriaxialStep& row : result.steps) {
    EXPECT_TRUE(std::isfinite(row.p) && std::isfinite(row.q) &&
                std::isfinite(row.volumetric_strain));
  }
}

TEST(Triaxial, WritesCsvAndVtu) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("fe_model_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const testing::HypoelasticTestMaterial material(0.01, 60.0);
  TriaxialOptions options = elastic_options(1, 1, 2);
  options.n_steps = 2;
  options.csv_path = (dir / "triaxial.csv").string();
  options.vtu_prefix = (dir / "triaxial").string();
  const TriaxialResult result = run_triaxial(material, options);
  ASSERT_TRUE(result.completed) << result.message;
  std::ifstream in(options.csv_path);
  std::string comment, header, line;
  std::getline(in, comment);
  std::getline(in, header);
  EXPECT_EQ(header,
            "step,axial_strain,volumetric_strain,p,q,axial_stress,radial_stress,fabric_invariant,"
            "newton_iterations,cuts,final_residual,status");
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_EQ(rows, 3);
  EXPECT_TRUE(std::filesystem::exists(dir / "triaxial_0002.vtu"));
  std::filesystem::remove_all(dir);
}

TEST(Triaxial, RejectsBadOptions) {
  const LinearElasticMaterial material(kE, kNu);
  TriaxialOptions options;
  options.cells_z = 0;
  EXPECT_THROW(run_triaxial(material, options), std::invalid_argument);
  options = TriaxialOptions();
  options.confining_pressure = -1.0;
  EXPECT_THROW(run_triaxial(material, options), std::invalid_argument);
  options = TriaxialOptions();
  options.solver.linear_rtol = std::nan("");
  EXPECT_THROW(run_triaxial(material, options), std::invalid_argument);
  options = TriaxialOptions();
  options.solver.max_linear_iterations = 0;
  EXPECT_THROW(run_triaxial(material, options), std::invalid_argument);
}

}  // namespace
}  // namespace fe_model
