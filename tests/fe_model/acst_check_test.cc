// Element-level checks of the ACST model through the deal.II-free facade fe_model/acst_check.h
// (issue 6): one homogeneous Q1 element reproduces the material-point driver to
// round-off at 100, 200 and 300 kPa with Newton converging quadratically (residual ratios
// recorded), the 2x2x4 mesh gives the same answer, a ten times larger strain increment cuts (or
// fails clearly, never NaN), near-zero confinement runs or is refused by name, and the helpers of
// `sffcal fe-check` (DEM fabric mapping, DEM comparison, parameter file) do what docs/fe.md says. This file includes no deal.II header.
#include "fe_model/acst_check.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

namespace fe_model {
namespace {

// The example parameter file of the repository (DM04's Toyoura values and our fabric part).
const std::string kExampleParameters = std::string(SFFCAL_SOURCE_DIR) + "/examples/acst_toyoura.json";

model::acst::Parameters<double> parameters() {
  return model::acst::read_parameters_json(kExampleParameters);
}

// An anisotropic initial fabric (F_0 : n_c = 0.2), so that the fabric part is exercised too.
AcstSpecimen specimen(double pressure) {
  AcstSpecimen s;
  s.confining_pressure = pressure;
  s.void_ratio = 0.8;
  s.fabric = fabric_from_dem_anisotropy(0.2 * std::sqrt(1.5) * kDefaultAcs, kDefaultAcs);
  return s;
}

// Drained compression to 5 %: past the peak of this dense specimen at 100 kPa, short enough for
// the test's time budget (the ACST update with its Jet tangent costs a few ms).
TriaxialLoading loading() {
  TriaxialLoading l;
  l.axial_strain_end = 0.05;
  l.n_steps = 10;
  return l;
}

bool all_finite(const Curve& curve) {
  for (const CurvePoint& p : curve.points)
    if (!std::isfinite(p.axial_strain) || !std::isfinite(p.volumetric_strain) ||
        !std::isfinite(p.p) || !std::isfinite(p.q) || !std::isfinite(p.void_ratio) ||
        !std::isfinite(p.fabric_invariant))
      return false;
  return true;
}

// The Newton record of every step: residual ratios, and a convergence order near 2 (the model's
// Jet tangent is consistent with its update). Returns the number of steps with an order estimate.
int expect_quadratic_newton(const Curve& element) {
  int steps_with_order = 0;
  for (std::size_t i = 1; i < element.points.size(); ++i) {
    const std::vector<double>& r = element.points[i].residual_norms;
    EXPECT_GE(r.size(), 2u) << "step " << i << ": plastic steps need Newton iterations";
    EXPECT_LE(element.points[i].newton_iterations, 8) << "step " << i;
    if (i == element.points.size() - 1 || i == 1) {
      std::cout << "  step " << i << " residuals:";
      for (double v : r) std::cout << ' ' << v;
      std::cout << "\n    ratios |R_k+1|/|R_k|:";
      for (std::size_t k = 1; k < r.size(); ++k) std::cout << ' ' << r[k] / r[k - 1];
      std::cout << '\n';
    }
    // Every iteration reduces the residual.
    for (std::size_t k = 1; k < r.size(); ++k) EXPECT_LT(r[k], r[k - 1]) << "step " << i;
    // Order log(r_k+1/r_k)/log(r_k/r_k-1) over the best triple of the step, where the residual is
    // still well above the integration noise (1e-8 of the first one).
    double best_order = 0.0;
    for (std::size_t k = 2; k < r.size(); ++k) {
      if (r[k] < 1e-8 * r[0]) break;
      best_order = std::max(best_order, std::log(r[k] / r[k - 1]) / std::log(r[k - 1] / r[k - 2]));
    }
    if (best_order > 0.0) {
      ++steps_with_order;
      EXPECT_GT(best_order, 1.7) << "step " << i;
    }
  }
  return steps_with_order;
}

TEST(AcstCheck, SingleElementReproducesTheDriverAt100To300kPa) {
  const model::acst::Parameters<double> par = parameters();
  for (const double pressure : {100e3, 200e3, 300e3}) {
    SCOPED_TRACE("confining pressure " + std::to_string(pressure));
    const Curve driver = run_acst_driver_triaxial(par, specimen(pressure), loading());
    const Curve element = run_acst_fe_triaxial(par, specimen(pressure), loading(), {});
    ASSERT_TRUE(driver.completed) << driver.message;
    ASSERT_TRUE(element.completed) << element.message;
    ASSERT_EQ(element.points.size(), loading().n_steps + 1);
    ASSERT_EQ(driver.points.size(), element.points.size());
    const PathError error = compare_paths(element, driver);
    std::cout << pressure / 1e3 << " kPa: element vs driver, max rel. error q " << error.q
              << ", eps_v " << error.volumetric_strain << "; q/p at 5 % "
              << element.points.back().eta() << ", eps_v " << element.points.back().volumetric_strain
              << ", F:n_c " << element.points.back().fabric_invariant << "; element "
              << element.wall_seconds << " s, driver " << driver.wall_seconds << " s\n";
    EXPECT_LE(error.axial_strain_mismatch, 1e-14);  // the same steps, to round-off
    EXPECT_LE(error.q, 1e-8);
    EXPECT_LE(error.volumetric_strain, 1e-8);
    // The rest of the state follows (p from q and the held sigma_3; e and F from the model).
    for (std::size_t i = 0; i < driver.points.size(); ++i) {
      const CurvePoint& a = element.points[i];
      const CurvePoint& b = driver.points[i];
      EXPECT_NEAR(a.p, b.p, 1e-8 * b.p) << "step " << i;
      EXPECT_NEAR(a.void_ratio, b.void_ratio, 1e-10) << "step " << i;
      EXPECT_NEAR(a.fabric_invariant, b.fabric_invariant, 1e-8) << "step " << i;
    }
    // A meaningful path: shearing (q/p rises towards the peak), the fabric turns towards n_c.
    EXPECT_GT(element.points.back().eta(), 1.0);
    EXPECT_GT(element.points.back().fabric_invariant, element.points.front().fabric_invariant);
    // Newton converges quadratically with the model's consistent tangent (the residual ratios are
    // printed for the first and the last step).
    EXPECT_GT(expect_quadratic_newton(element), 0) << "no step had three residuals above noise";
  }
}

TEST(AcstCheck, SmallMeshGivesTheHomogeneousAnswer) {
  const model::acst::Parameters<double> par = parameters();
  TriaxialLoading short_loading = loading();  // 2x2x4 = 128 points: fewer, larger steps
  short_loading.axial_strain_end = 0.005;  // one plastic step: yield is crossed inside it
  short_loading.n_steps = 1;
  const Curve element = run_acst_fe_triaxial(par, specimen(100e3), short_loading, {});
  TriaxialMeshOptions mesh;
  mesh.cells_x = mesh.cells_y = 2;
  mesh.cells_z = 4;
  const Curve meshed = run_acst_fe_triaxial(par, specimen(100e3), short_loading, mesh);
  ASSERT_TRUE(element.completed) << element.message;
  ASSERT_TRUE(meshed.completed) << meshed.message;
  EXPECT_EQ(meshed.label, "mesh");
  const PathError error = compare_paths(meshed, element);
  std::cout << "2x2x4 mesh vs element: max rel. error q " << error.q << ", eps_v "
            << error.volumetric_strain << "; mesh " << meshed.wall_seconds << " s, "
            << meshed.newton_iterations << " Newton iterations\n";
  EXPECT_LE(error.q, 1e-8);
  EXPECT_LE(error.volumetric_strain, 1e-8);
  for (std::size_t i = 0; i < element.points.size(); ++i) {
    EXPECT_NEAR(meshed.points[i].void_ratio, element.points[i].void_ratio, 1e-10);
    EXPECT_NEAR(meshed.points[i].fabric_invariant, element.points[i].fabric_invariant, 1e-8);
  }
}

// The command's default increment is 0.3 / 100 = 0.003; ten times that is 0.03 per step. The run
// must converge through step cutting or stop with a clear message, and never produce NaN.
TEST(AcstCheck, TenfoldStrainIncrementCutsOrFailsClearlyNeverNaN) {
  const model::acst::Parameters<double> par = parameters();
  TriaxialLoading coarse;
  coarse.axial_strain_end = 0.06;
  coarse.n_steps = 2;
  TriaxialMeshOptions options;
  options.max_newton_iterations = 8;  // a tight budget, so that big increments have to be cut
  const Curve element = run_acst_fe_triaxial(par, specimen(100e3), coarse, options);
  EXPECT_TRUE(all_finite(element));
  std::cout << "tenfold increment: completed " << element.completed << ", cuts " << element.cuts
            << ", Newton " << element.newton_iterations << (element.completed ? "" : ", message: ")
            << element.message << '\n';
  if (element.completed) {
    ASSERT_EQ(element.points.size(), 3u);
    // Close to the fine-step answer at the same strain (the path is step-size dependent only
    // through the drained condition between steps).
    TriaxialLoading fine = coarse;
    fine.n_steps = 20;  // the driver: cheap
    const Curve reference = run_acst_driver_triaxial(par, specimen(100e3), fine);
    ASSERT_TRUE(reference.completed) << reference.message;
    ASSERT_EQ(reference.points.size(), 21u);
    EXPECT_NEAR(element.points.back().eta(), reference.points.back().eta(), 0.05);
    EXPECT_NEAR(element.points.back().volumetric_strain, reference.points.back().volumetric_strain,
                5e-3);
  } else {
    EXPECT_NE(element.message.find("failed"), std::string::npos) << element.message;
    EXPECT_NE(element.message.find("cuts"), std::string::npos) << element.message;
  }

  // Far beyond: one step of 30 % with at most 2 cuts cannot converge; it must say so.
  TriaxialLoading hopeless;
  hopeless.axial_strain_end = 0.3;
  hopeless.n_steps = 1;
  hopeless.integration.tolerance = 1e-6;  // it only has to fail: keep its huge increments cheap
  options.max_cuts = 2;
  options.max_newton_iterations = 4;
  const Curve failed = run_acst_fe_triaxial(par, specimen(100e3), hopeless, options);
  EXPECT_FALSE(failed.completed);
  EXPECT_TRUE(all_finite(failed));
  ASSERT_EQ(failed.points.size(), 1u);  // only the initial state
  EXPECT_NE(failed.message.find("after 2 cuts"), std::string::npos) << failed.message;
  std::cout << "hopeless increment: " << failed.message << '\n';
}

// Near-zero confinement (issue 8): at 1 kPa the element either follows the driver or stops with
// a message, never with NaN; below the model's 100 Pa floor both refuse by name. The driver may
// halve an increment here where the FE did not (or the reverse), and the drained path then
// differs by its discretisation: the comparison is to 1e-3, not to round-off.
TEST(AcstCheck, NearZeroConfinementFollowsTheDriverOrStopsClearly) {
  const model::acst::Parameters<double> par = parameters();
  TriaxialLoading short_path;
  short_path.axial_strain_end = 0.01;
  short_path.n_steps = 5;
  const Curve element = run_acst_fe_triaxial(par, specimen(1e3), short_path, TriaxialMeshOptions{});
  EXPECT_TRUE(all_finite(element));
  if (element.completed) {
    const Curve driver = run_acst_driver_triaxial(par, specimen(1e3), short_path);
    ASSERT_TRUE(driver.completed) << driver.message;
    EXPECT_NEAR(element.points.back().eta(), driver.points.back().eta(), 1e-3);
  } else {
    EXPECT_FALSE(element.message.empty());
  }
  for (const Curve& below : {run_acst_fe_triaxial(par, specimen(50.0), short_path, TriaxialMeshOptions{}),
                             run_acst_driver_triaxial(par, specimen(50.0), short_path)}) {
    EXPECT_FALSE(below.completed);
    EXPECT_TRUE(below.points.empty());
    EXPECT_NE(below.message.find("below the model's minimum mean stress"), std::string::npos)
        << below.message;
  }
  std::cout << "1 kPa: element completed " << element.completed << ", cuts " << element.cuts << ", Newton "
            << element.newton_iterations << ", " << element.wall_seconds << " s " << element.message << '\n';
}

TEST(AcstCheck, DemFabricMapping) {
  // t(A) = a_c and F = A / a_cs: F : n_c = sqrt(2/3) a_c / a_cs; deviatoric, axisymmetric.
  const Eigen::Matrix3d F = fabric_from_dem_anisotropy(0.5, 0.8);
  const double c = std::sqrt(2.0 / 3.0);
  EXPECT_NEAR(F.trace(), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(F(0, 0), F(1, 1));
  EXPECT_NEAR(F(2, 2) - 0.5 * (F(0, 0) + F(1, 1)), 0.5 / 0.8, 1e-15);
  EXPECT_NEAR(c * (F(2, 2) - 0.5 * (F(0, 0) + F(1, 1))), c * 0.5 / 0.8, 1e-15);
  // The critical state in compression, a_c = sqrt(3/2) a_cs (||A|| = a_cs), maps to F = n_c.
  const Eigen::Matrix3d critical = fabric_from_dem_anisotropy(std::sqrt(1.5) * 0.8, 0.8);
  EXPECT_NEAR(critical.norm(), 1.0, 1e-14);
  EXPECT_NEAR(critical(2, 2), 2.0 / std::sqrt(6.0), 1e-14);
  EXPECT_THROW(fabric_from_dem_anisotropy(0.5, 0.0), std::invalid_argument);
}

TEST(AcstCheck, DemComparisonInterpolatesTheModelAtTheDemStrains) {
  Curve model, dem;
  for (int i = 0; i <= 10; ++i) {  // model: q/p = 10 eps_a, eps_v = eps_a, to eps_a = 0.1
    CurvePoint p;
    p.axial_strain = 0.01 * i;
    p.p = 100e3;
    p.q = 100e3 * 10.0 * p.axial_strain;
    p.volumetric_strain = p.axial_strain;
    model.points.push_back(p);
  }
  for (int i = 0; i <= 30; ++i) {  // DEM: offsets 0.1 in q/p and 0.002 in eps_v, to 0.15
    CurvePoint p;
    p.axial_strain = 0.005 * i;
    p.p = 200e3;
    p.q = 200e3 * (10.0 * p.axial_strain + 0.1);
    p.volumetric_strain = p.axial_strain - 0.002;
    dem.points.push_back(p);
  }
  const DemError error = compare_with_dem(model, dem);
  EXPECT_EQ(error.points, 21u);  // DEM points with eps_a <= 0.1
  EXPECT_NEAR(error.eta_rms, 0.1, 1e-12);
  EXPECT_NEAR(error.volumetric_strain_rms, 0.002, 1e-12);
  EXPECT_EQ(compare_with_dem(model, model).eta_rms, 0.0);
}

TEST(AcstCheck, ExampleParameterFileAndFabricNormalisation) {
  const model::acst::Parameters<double> par = parameters();
  EXPECT_DOUBLE_EQ(par.G0, 125.0);
  EXPECT_DOUBLE_EQ(par.M_c, 1.25);
  EXPECT_DOUBLE_EQ(par.k_F, 5.0);
  const std::string example = kExampleParameters;
  EXPECT_FALSE(fabric_normalisation(model::read_parameter_file(example), example).has_value());

  const std::string path = "acst_check_test_" + std::to_string(::getpid()) + ".json";
  std::ifstream in(kExampleParameters);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t brace = text.find('{');
  {
    std::ofstream out(path);
    out << text.substr(0, brace + 1) << "\n  \"a_cs\": {\"value\": 0.9, \"unit\": \"1\"},"
        << text.substr(brace + 1);
  }
  EXPECT_DOUBLE_EQ(fabric_normalisation(model::read_parameter_file(path), path).value_or(0.0),
                   0.9);
  {
    std::ofstream out(path);
    out << text.substr(0, brace + 1) << "\n  \"a_cs\": -1," << text.substr(brace + 1);
  }
  EXPECT_THROW(fabric_normalisation(model::read_parameter_file(path), path), std::runtime_error);
  std::remove(path.c_str());
}

TEST(AcstCheck, CurveCsvHasTheDocumentedColumns) {
  Curve curve;
  curve.label = "element";
  curve.points.resize(2);
  curve.points[1].axial_strain = 0.01;
  curve.points[1].p = 120e3;
  curve.points[1].q = 60e3;
  const std::string path = "acst_check_curve_" + std::to_string(::getpid()) + ".csv";
  write_curve_csv(path, curve);
  std::ifstream in(path);
  std::string comment, header, row0, row1;
  std::getline(in, comment);
  std::getline(in, header);
  std::getline(in, row0);
  std::getline(in, row1);
  EXPECT_EQ(comment.rfind("# ", 0), 0u);
  EXPECT_EQ(header,
            "axial_strain,volumetric_strain,p,q,eta,void_ratio,fabric_invariant,newton_iterations,"
            "cuts,status");
  EXPECT_EQ(row1.rfind("0.01,0,120000,60000,0.5,", 0), 0u) << row1;
  std::remove(path.c_str());
}

}  // namespace
}  // namespace fe_model
