// The ACST adapter (built only with the calibration target): sign conversions, the adapter's
// tangent against finite differences of its own update, and a homogeneous triaxial test that
// gives the same answer on one element and on a mesh.
#include "fe_model/acst_material.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>

#include "fe_model/triaxial.h"
#include "material_checks.h"

namespace fe_model {
namespace {

// Toyoura-sand-like values of Dafalias & Manzari (2004), with a fabric part of our choosing.
model::acst::Parameters<double> parameters() {
  model::acst::Parameters<double> p;
  p.G0 = 125.0;
  p.nu = 0.05;
  p.M_c = 1.25;
  p.c = 0.712;
  p.e_gamma = 0.934;
  p.lambda_c = 0.019;
  p.xi = 0.7;
  p.m = 0.01;
  p.h0 = 7.05;
  p.c_h = 0.968;
  p.n_b = 1.1;
  p.A0 = 0.704;
  p.n_d = 3.5;
  p.e_A = 0.1;
  p.k_F = 5.0;
  p.n_b_loose = 0.0;  // DM04's bounding surface and elasticity, LD12's fabric rate
  p.n_G = 0.5;
  p.n_F = 0.0;
  return p;
}

TEST(AcstMaterial, ConvertsSignsAndPacksTheState) {
  AcstInitialState initial;
  initial.void_ratio = 0.8;
  const AcstMaterial material(parameters(), initial);
  SymmetricTensor2 stress = -100e3 * dealii::unit_symmetric_tensor<3>();
  stress[2][2] = -150e3;
  const PointState state = material.initial_state(stress);
  ASSERT_EQ(state.internal_variables.size(), AcstMaterial::kNumInternalVariables);
  const model::acst::State<double> model = material.to_model(state);
  EXPECT_DOUBLE_EQ(model.stress(2, 2), 150e3);  // compression positive in the model
  EXPECT_DOUBLE_EQ(model.void_ratio, 0.8);
  EXPECT_NEAR(model.alpha.trace(), 0.0, 1e-15);
  EXPECT_GT(model.alpha(2, 2), 0.0);
  EXPECT_NEAR(*material.fabric_invariant(state), 0.0, 1e-15);
}

PointState triaxial_start(const AcstMaterial& material) {
  SymmetricTensor2 stress = -100e3 * dealii::unit_symmetric_tensor<3>();
  stress[2][2] = -140e3;
  return material.initial_state(stress);
}

TEST(AcstMaterial, TangentMatchesFiniteDifferencesInTheElasticRange) {
  const AcstMaterial material(parameters(), AcstInitialState{});
  SymmetricTensor2 de;  // axial unloading (tension positive increment): elastic
  de[2][2] = 2e-5;
  de[0][0] = -0.5e-5;
  de[1][1] = -0.5e-5;
  const double error = checks::tangent_error(material, triaxial_start(material), de, 1e-8);
  std::cout << "ACST adapter tangent vs finite differences, elastic: " << error << '\n';
  EXPECT_LT(error, 1e-5);
}

// Plastic loading: the model's tangent is unsymmetric here, so this also checks the index and
// sign mapping of the 9x9 matrix onto deal.II's SymmetricTensor<4,3>. The tolerance allows for
// the substepping error control of the update (finite differences of an adaptive integrator).
TEST(AcstMaterial, TangentMatchesFiniteDifferencesInPlasticLoading) {
  AcstInitialState initial;
  initial.fabric(2, 2) = 0.2;
  initial.fabric(0, 0) = initial.fabric(1, 1) = -0.1;
  const AcstMaterial material(parameters(), initial);
  SymmetricTensor2 de;  // axial compression with a little shear: plastic
  de[2][2] = -2e-4;
  de[0][0] = 0.5e-4;
  de[1][1] = 0.3e-4;
  de[0][2] = 0.2e-4;
  const PointState start = triaxial_start(material);
  PointState end;
  ASSERT_NE(material.update(start, de, end).status, MaterialStatus::kFailed);
  const double alpha_change =
      (material.to_model(end).alpha - material.to_model(start).alpha).norm();
  EXPECT_GT(alpha_change, 1e-6) << "the increment should be plastic (alpha evolves)";
  const double error = checks::tangent_error(material, start, de, 1e-8);
  std::cout << "ACST adapter tangent vs finite differences, plastic (|d alpha| = " << alpha_change
            << "): " << error << '\n';
  EXPECT_LT(error, 1e-4);
}

// The specimen of the homogeneous checks: a 0.5 m x 0.5 m x 1 m eighth at sigma_3 = 100 kPa (the
// answer of a homogeneous test does not depend on the size).
TriaxialOptions specimen_options() {
  TriaxialOptions options;
  options.width = 0.5;
  options.height = 1.0;
  options.confining_pressure = 100e3;
  return options;
}

TEST(AcstMaterial, HomogeneousTriaxialIsTheSameOnOneElementAndOnAMesh) {
  AcstInitialState initial;
  initial.void_ratio = 0.75;
  // The FE default integration (implicit, one step per increment): the update is smooth in the
  // strain increment, so Newton converges to round-off on both meshes.
  const AcstMaterial material(parameters(), initial);
  TriaxialOptions options = specimen_options();
  options.axial_strain_end = 0.01;
  options.n_steps = 10;
  const TriaxialResult one = run_triaxial(material, options);
  ASSERT_TRUE(one.completed) << one.message;
  options.cells_x = 2;  // 32 points
  options.cells_z = 2;
  const auto t0 = std::chrono::steady_clock::now();
  const TriaxialResult mesh = run_triaxial(material, options);
  ASSERT_TRUE(mesh.completed) << mesh.message;
  std::cout << "2x1x2 ACST run: "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()
            << " s\n";
  ASSERT_EQ(one.steps.size(), mesh.steps.size());
  for (std::size_t i = 0; i < one.steps.size(); ++i) {
    EXPECT_TRUE(std::isfinite(one.steps[i].q) && one.steps[i].p > 0.0);
    ASSERT_TRUE(one.steps[i].fabric_invariant.has_value());
    EXPECT_NEAR(mesh.steps[i].q, one.steps[i].q, 1e-8 * (1.0 + std::abs(one.steps[i].q)));
    EXPECT_NEAR(mesh.steps[i].volumetric_strain, one.steps[i].volumetric_strain, 1e-9);
  }
  const TriaxialStep& last = one.steps.back();
  std::cout << "ACST single element at eps_a = " << last.axial_strain
            << ": q/p = " << last.q / last.p << ", eps_v = " << last.volumetric_strain
            << ", F:n_c = " << *last.fabric_invariant << ", Newton iterations of the last step "
            << last.newton_iterations << '\n';
  std::cout << "ACST Newton residuals, last step (one element):";
  for (double r : last.residual_norms) std::cout << ' ' << r;
  std::cout << "\nACST Newton residuals, last step (2x1x2):";
  for (double r : mesh.steps.back().residual_norms) std::cout << ' ' << r;
  std::cout << '\n';
  EXPECT_GT(last.q, 0.0);
  EXPECT_GT(*last.fabric_invariant, 0.0);  // fabric turns towards the compression direction
}

// A step the material cannot take however it is cut (extension to 40 % in one step takes p
// below the model's floor at every quadrature point): the run stops after the bounded number of
// cuts, naming the quadrature point, the strain increment, the start state and the model's reason;
// nothing is NaN.
TEST(AcstMaterial, AStepThatCannotBeCutStopsNamingThePointTheIncrementAndTheState) {
  AcstInitialState initial;
  initial.void_ratio = 0.75;
  const AcstMaterial material(parameters(), initial);
  TriaxialOptions options = specimen_options();
  options.axial_strain_end = -0.4;
  options.n_steps = 1;
  options.solver.max_cuts = 3;
  const TriaxialResult result = run_triaxial(material, options);
  EXPECT_FALSE(result.completed);
  std::cout << "message: " << result.message << '\n';
  for (const char* part : {"after 3 cuts", "ACST update failed", "quadrature point",
                           "strain increment (tension positive", "start state", "void ratio",
                           "mean stress falls below"})
    EXPECT_NE(result.message.find(part), std::string::npos) << part << " in: " << result.message;
  ASSERT_EQ(result.steps.size(), 1u);  // the initial state only
  EXPECT_TRUE(std::isfinite(result.steps[0].p) && std::isfinite(result.steps[0].q));
}

}  // namespace
}  // namespace fe_model
