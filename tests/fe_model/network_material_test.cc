// The contact-network adapter (fe_model/network_material.h): its exact tangent against finite
// differences of its own update, and a single-element drained triaxial test against the
// material-point prediction of calibration/network_fit.h.
#include "fe_model/network_material.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>

#include "calibration/network_fit.h"
#include "fe_model/fe_check.h"
#include "fe_model/triaxial.h"
#include "material_checks.h"

namespace fe_model {
namespace {

namespace net = calibration::network;

// Values of the order of the paper-size fit (docs/network-model.md).
model::network::Parameters<double> parameters() {
  model::network::Parameters<double> p = net::default_start();
  p.kappa = 80.0, p.c_v = 4.0, p.a_z = 0.9, p.k_a = 15.0, p.f_z = 2.0, p.t_z = 0.2;
  p.d_z = 2.3, p.d_a = 0.5, p.n_r = 1.3, p.n_z = 4.0, p.k_z = 4.0;
  p.d_psi = 1.0, p.e_gamma = 0.62;  // a critical void ratio line a little above the dense one (N7b)
  return p;
}

NetworkInitialState dense() {
  NetworkInitialState s;
  s.void_ratio = 0.58;
  s.coordination = 6.7;
  return s;
}

TEST(NetworkMaterial, PacksTheStateAndStartsAtTheInitialMeanStress) {
  const NetworkMaterial material(parameters(), dense(), net::kDemYoungsModulus);
  const PointState state = material.initial_state(-100e3 * dealii::unit_symmetric_tensor<3>());
  ASSERT_EQ(state.internal_variables.size(), NetworkMaterial::kNumInternalVariables);
  for (unsigned int i = 0; i < 3; ++i) EXPECT_NEAR(state.stress[i][i], -100e3, 1e-9);
  const model::network::State<double> model = material.to_model(state);
  // Lambda = 3 p (1 + e) / (E Z) for an isotropic network (sff-theory.md §4).
  EXPECT_NEAR(model.lambda, 3.0 * 100e3 * 1.58 / (150e6 * 6.7), 1e-18);
  EXPECT_NEAR(*material.fabric_invariant(state), 0.0, 1e-15);
}

TEST(NetworkMaterial, TangentMatchesFiniteDifferencesOfTheUpdate) {
  NetworkInitialState initial = dense();
  initial.fabric = net::axisymmetric(0.6);
  initial.normal = net::axisymmetric(1.2);
  initial.tangential = net::axisymmetric(0.1);
  initial.normal(0, 1) = initial.normal(1, 0) = 0.05;  // not coaxial
  const NetworkMaterial material(parameters(), initial, net::kDemYoungsModulus);
  const PointState start = material.initial_state(-100e3 * dealii::unit_symmetric_tensor<3>());
  SymmetricTensor2 de;  // axial compression with some shear, tension positive
  de[2][2] = -2e-3;
  de[0][0] = de[1][1] = 0.6e-3;
  de[0][2] = 0.3e-3;
  PointState end;
  const MaterialUpdate update = material.update(start, de, end);
  ASSERT_EQ(update.status, MaterialStatus::kOk) << update.message;
  const double error = checks::tangent_error(material, start, de, 1e-7);
  std::cout << "contact-network tangent vs finite differences: " << error << '\n';
  EXPECT_LT(error, 1e-6);
}

TEST(NetworkMaterial, OneElementDrainedTriaxialIsTheMaterialPointPrediction) {
  const NetworkMaterial material(parameters(), dense(), net::kDemYoungsModulus);
  TriaxialOptions options;
  options.width = 0.5;
  options.height = 1.0;
  options.confining_pressure = 100e3;
  options.axial_strain_end = 0.1;
  options.n_steps = 50;
  const TriaxialResult fe = run_triaxial(material, options);
  ASSERT_TRUE(fe.completed) << fe.message;
  // The same test at the material point: a drained test whose initial network is the element's.
  calibration::TestData t;
  t.name = "dense";
  t.path = calibration::TestPath::kDrainedCompression;
  for (const TriaxialStep& step : fe.steps) t.axial_strain.push_back(step.axial_strain);
  const std::size_t n = t.axial_strain.size();
  t.volumetric_strain.assign(n, 0.0);
  t.eta.assign(n, 0.0);
  t.void_ratio.assign(n, 0.58);
  t.p.assign(n, 100e3);
  t.e0 = 0.58;
  t.p0 = 100e3;
  const model::network::State<double> initial =
      material.to_model(material.initial_state(-100e3 * dealii::unit_symmetric_tensor<3>()));
  t.snapshot_axial_strain = {0.0};
  t.coordination = {initial.coordination};
  t.lambda = {initial.lambda};
  t.a_c = t.a_n = t.a_t = t.mobilisation = t.snapshot_eta = {0.0};
  net::FitOptions driver;  // the element's substeps
  driver.substep_size = model::network::kUpdateSubstepSize;
  const net::Curve point = net::predict(parameters(), t, driver);
  ASSERT_TRUE(point.complete) << point.message;
  ASSERT_EQ(point.eta.size(), n);
  for (std::size_t k = 0; k < n; ++k) {
    EXPECT_NEAR(fe.steps[k].q / fe.steps[k].p, point.eta[k], 1e-6) << "step " << k;
    EXPECT_NEAR(fe.steps[k].volumetric_strain, point.volumetric_strain[k], 1e-7) << "step " << k;
    EXPECT_NEAR(*fe.steps[k].fabric_invariant, point.a_c[k], 1e-6) << "step " << k;
  }
  std::cout << "contact-network single element at eps_a = " << fe.steps.back().axial_strain
            << ": q/p = " << fe.steps.back().q / fe.steps.back().p
            << ", eps_v = " << fe.steps.back().volumetric_strain << '\n';
}

// A boundary-value problem that is not homogeneous: rough platens make the specimen bulge, so the
// points follow different paths. Newton converges quadratically there (the tangent is exact).
TEST(NetworkMaterial, ARoughPlatenMeshConvergesQuadratically) {
  const NetworkMaterial material(parameters(), dense(), net::kDemYoungsModulus);
  TriaxialOptions options;
  options.width = 0.5;
  options.height = 1.0;
  options.cells_x = options.cells_y = 2;
  options.cells_z = 3;
  options.rough_platens = true;
  options.confining_pressure = 100e3;
  options.axial_strain_end = 0.03;
  options.n_steps = 6;
  options.solver.extrapolate_predictor = false;  // the plain first iterate shows the rate
  const TriaxialResult result = run_triaxial(material, options);
  ASSERT_TRUE(result.completed) << result.message;
  ASSERT_FALSE(result.bulge.empty());
  EXPECT_GT(result.bulge.front().radial_displacement - result.bulge.back().radial_displacement,
            0.0);  // wider at mid-height than at the rough platen
  for (const StepReport& report : result.reports) {
    const NewtonLog& log = report.attempts.back();
    ASSERT_TRUE(log.converged);
    const double last_order = checks::last_convergence_order(log, 1e-12 * log.force_scale);
    std::cout << "load " << log.load_end << ": " << log.iterations << " Newton iterations, order "
              << last_order << '\n';
    EXPECT_GT(last_order, 1.8) << "load " << log.load_end;
  }
}

// Stress test: 40 % of extension in one load step. Whatever the outcome (cut until it goes, or a
// clean stop), nothing is NaN and a stop names its reason.
TEST(NetworkMaterial, AHugeExtensionStepEndsCleanly) {
  const NetworkMaterial material(parameters(), dense(), net::kDemYoungsModulus);
  TriaxialOptions options;
  options.width = 0.5;
  options.height = 1.0;
  options.confining_pressure = 100e3;
  options.axial_strain_end = -0.4;
  options.n_steps = 1;
  options.solver.max_cuts = 6;
  const TriaxialResult result = run_triaxial(material, options);
  std::cout << (result.completed ? "completed" : "stopped: " + result.message) << '\n';
  if (!result.completed) {
    EXPECT_FALSE(result.message.empty());
  }
  ASSERT_FALSE(result.steps.empty());
  for (const TriaxialStep& step : result.steps) {
    EXPECT_TRUE(std::isfinite(step.p) && std::isfinite(step.q) &&
                std::isfinite(step.volumetric_strain));
    EXPECT_GT(step.p, 0.0);
  }
}

// fe-check with a contact-network parameter file: the element against the material point and the
// mesh against the element pass their verification tolerances on a DEM run's network; without a
// DEM run there is no initial network, refused by name.
TEST(NetworkMaterial, FeCheckVerifiesTheElementAgainstTheMaterialPoint) {
  FeCheckOptions options;
  options.parameters_path =
      std::string(SFFCAL_SOURCE_DIR) + "/bench/reference/network_paper_params.json";
  options.output_folder = ::testing::TempDir() + "network_fe_check";
  std::filesystem::remove_all(options.output_folder);
  options.max_strain = 0.04;
  options.steps = 8;
  try {
    run_fe_check(options, [](const std::string&) {});
    FAIL() << "a contact-network check without a DEM run was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--dem"), std::string::npos) << e.what();
  }
  options.dem_runs = {std::string(SFFCAL_SOURCE_DIR) +
                      "/tests/data/reference/matrix/iso_dense_100kPa.h5"};
  const FeCheckResult result = run_fe_check(options, [](const std::string& line) {
    std::cout << line << '\n';
  });
  EXPECT_TRUE(result.runs_completed);
  int verification = 0, dem = 0;
  for (const FeCheckRow& row : result.checks) {
    (row.verification ? verification : dem)++;
    if (row.verification) {
      EXPECT_TRUE(row.pass) << row.check << ' ' << row.quantity << ' ' << row.value;
    }
  }
  EXPECT_EQ(verification, 4);  // element vs driver, mesh vs element: q and eps_v
  EXPECT_EQ(dem, 2);
  EXPECT_NE(result.exit_code(), 1);
  EXPECT_TRUE(std::filesystem::exists(options.output_folder + "/iso_dense_100kPa/element.csv"));
  std::filesystem::remove_all(options.output_folder);
}

TEST(NetworkMaterial, RefusesNonPhysicalInputByName) {
  NetworkInitialState bad = dense();
  bad.coordination = 0.0;
  EXPECT_THROW(NetworkMaterial(parameters(), bad, net::kDemYoungsModulus), std::invalid_argument);
  model::network::Parameters<double> p = parameters();
  p.kappa = -1.0;
  try {
    NetworkMaterial material(p, dense(), net::kDemYoungsModulus);
    FAIL() << "a negative kappa was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("kappa"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fe_model
