// The material-point driver of any model (model/point_driver.h): linear elasticity against its
// closed forms (drained compression and extension, undrained), ACST against ACST's own driver on
// the same paths, and the errors it names.
#include "model/point_driver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/acst_model.h"
#include "model/material_point.h"
#include "toyoura.h"

namespace model {
namespace {

// Drained triaxial compression of linear elasticity: with sigma_xx = sigma_yy held,
// sigma_zz - sigma_3 = E eps_zz and eps_v = (1 - 2 nu) eps_zz, exactly.
TEST(PointDriver, LinearElasticityFollowsItsClosedForm) {
  const double E = 2.5e8, nu = 0.2;
  const auto behaviour = find_model("linear_elastic").make({}, {E, nu});
  TriaxialPath path;
  path.lateral_stress = 150e3;
  path.axial_strain_end = 0.01;
  path.steps = 8;
  const DriverPath result = drive_triaxial(*behaviour, {}, path);
  ASSERT_TRUE(result.completed) << result.message;
  ASSERT_EQ(result.points.size(), 9u);
  for (const DriverPoint& point : result.points) {
    const double axial = point.strain(2, 2);
    EXPECT_NEAR(point.stress(2, 2) - path.lateral_stress, E * axial, 1e-9 * E * 0.01);
    EXPECT_NEAR(point.stress(0, 0), path.lateral_stress, 1e-10 * path.lateral_stress);
    EXPECT_NEAR(point.stress(1, 1), path.lateral_stress, 1e-10 * path.lateral_stress);
    EXPECT_NEAR(point.strain.trace(), (1.0 - 2.0 * nu) * axial, 1e-12);
    EXPECT_LE(point.newton_iterations, 2);  // one linear solve, then the check
  }
  EXPECT_NEAR(result.points.back().strain(2, 2), 0.01, 1e-15);
}

// Drained extension of linear elasticity: the same closed form with eps_zz < 0 (q < 0).
TEST(PointDriver, LinearElasticityInDrainedExtension) {
  const double E = 2.5e8, nu = 0.2;
  const auto behaviour = find_model("linear_elastic").make({}, {E, nu});
  TriaxialPath path;
  path.lateral_stress = 150e3;
  path.axial_strain_end = -0.004;
  path.steps = 4;
  const DriverPath result = drive_triaxial(*behaviour, {}, path);
  ASSERT_TRUE(result.completed) << result.message;
  for (const DriverPoint& point : result.points) {
    const double axial = point.strain(2, 2);
    EXPECT_NEAR(point.stress(2, 2) - path.lateral_stress, E * axial, 1e-9 * E * 0.004);
    EXPECT_NEAR(point.stress(0, 0), path.lateral_stress, 1e-10 * path.lateral_stress);
    EXPECT_NEAR(point.strain.trace(), (1.0 - 2.0 * nu) * axial, 1e-12);
  }
  EXPECT_NEAR(result.points.back().strain(2, 2), -0.004, 1e-15);
  EXPECT_LT(result.points.back().stress(2, 2), path.lateral_stress);
}

// Undrained linear elasticity: eps = eps_zz diag(-1/2, -1/2, 1) is deviatoric, so p stays sigma_3
// and q = 2 G (3/2) eps_zz = 3 G eps_zz, with no Newton iteration.
TEST(PointDriver, LinearElasticityUndrainedKeepsItsVolumeAndMeanStress) {
  const double E = 2.5e8, nu = 0.2, G = E / (2.0 * (1.0 + nu));
  const auto behaviour = find_model("linear_elastic").make({}, {E, nu});
  TriaxialPath path;
  path.drainage = Drainage::kUndrained;
  path.lateral_stress = 150e3;
  for (double end : {0.01, -0.01}) {
    path.axial_strain_end = end;
    path.steps = 5;
    const DriverPath result = drive_triaxial(*behaviour, {}, path);
    ASSERT_TRUE(result.completed) << result.message;
    for (const DriverPoint& point : result.points) {
      const Eigen::Matrix3d& s = point.stress;
      EXPECT_NEAR(point.strain.trace(), 0.0, 1e-17);
      EXPECT_NEAR(point.strain(0, 0), -0.5 * point.strain(2, 2), 1e-17);
      EXPECT_NEAR(s.trace() / 3.0, path.lateral_stress, 1e-9 * path.lateral_stress);
      EXPECT_NEAR(s(2, 2) - 0.5 * (s(0, 0) + s(1, 1)), 3.0 * G * point.strain(2, 2), 1e-9 * G * 0.01);
      EXPECT_EQ(point.newton_iterations, 0);
    }
    EXPECT_NEAR(result.points.back().strain(2, 2), end, 1e-15);
  }
}

// ACST through its Behaviour and this driver, against ACST's own drivers (material_point.h:
// drained_triaxial, with a negative end strain in extension, and undrained_triaxial) with the same
// integration options (the driver's: error control at 1e-7): both converge on the same discrete
// equations, so they agree to their Newton tolerances (1e-10 p here, 1e-8 p there) and the
// integration's noise; undrained, neither iterates and they agree exactly.
TEST(PointDriver, AcstAgreesWithItsOwnDriver) {
  const acst::Parameters<double> par = testing::toyoura();
  const acst::DriverOptions own;
  const double p0 = 100e3, e0 = 0.8;
  const auto initial = acst::isotropic_state(p0, e0, Eigen::Matrix3d::Zero().eval());
  const auto behaviour = acst::make_behaviour(par, own.integration);
  std::vector<double> inputs(7, 0.0);
  inputs[0] = e0;
  struct Case {
    Drainage drainage;
    double end;
  };
  for (const Case& c : {Case{Drainage::kDrained, 0.05}, Case{Drainage::kDrained, -0.05},
                        Case{Drainage::kUndrained, 0.05}, Case{Drainage::kUndrained, -0.05}}) {
    SCOPED_TRACE(std::string(to_string(c.drainage)) + " to " + std::to_string(c.end));
    const acst::PathResult<double> reference =
        c.drainage == Drainage::kUndrained ? acst::undrained_triaxial(par, initial, c.end, 50, own)
                                           : acst::drained_triaxial(par, initial, c.end, 50, own);
    ASSERT_EQ(reference.status, UpdateStatus::kOk);
    TriaxialPath path;
    path.drainage = c.drainage;
    path.lateral_stress = p0;
    path.axial_strain_end = c.end;
    path.steps = 50;
    const DriverPath result = drive_triaxial(*behaviour, inputs, path);
    ASSERT_TRUE(result.completed) << result.message;
    ASSERT_EQ(result.points.size(), reference.rows.size());
    double worst = 0.0;
    for (std::size_t k = 0; k < result.points.size(); ++k) {
      const Eigen::Matrix3d& s = result.points[k].stress;
      const double q = s(2, 2) - 0.5 * (s(0, 0) + s(1, 1));
      worst = std::max(worst, std::abs(q - reference.rows[k].q) / p0);
      worst = std::max(worst, std::abs(s.trace() / 3.0 - reference.rows[k].p) / p0);
      EXPECT_NEAR(result.points[k].strain(2, 2), reference.rows[k].axial_strain, 1e-15);
      EXPECT_NEAR(result.points[k].strain.trace(), reference.rows[k].volumetric_strain, 1e-7);
    }
    std::cout << "max |(q, p) - (q, p)_own| / p0 = " << worst << '\n';
    EXPECT_LT(worst, 1e-8);
    // The path did load the specimen, in the direction asked.
    EXPECT_GT(std::abs(reference.rows.back().q), 0.2 * p0);
    EXPECT_EQ(reference.rows.back().q > 0.0, c.end > 0.0);
  }
}

TEST(PointDriver, NamesWhatIsWrongWithThePathOrTheInputs) {
  const auto elastic = find_model("linear_elastic").make({}, {1e8, 0.25});
  TriaxialPath path;
  path.steps = 0;
  EXPECT_THROW(drive_triaxial(*elastic, {}, path), std::invalid_argument);
  path.steps = 4;
  path.lateral_stress = -1.0;
  EXPECT_THROW(drive_triaxial(*elastic, {}, path), std::invalid_argument);
  path.lateral_stress = 100e3;
  try {
    drive_triaxial(*elastic, {0.7}, path);
    FAIL() << "one input too many was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("linear_elastic"), std::string::npos) << e.what();
  }
  EXPECT_EQ(parse_drainage("undrained"), Drainage::kUndrained);
  EXPECT_THROW(parse_drainage("Undrained"), std::invalid_argument);
  // ACST with a void ratio it cannot carry: its initial_state names the input.
  const auto acst = acst::make_behaviour(testing::toyoura());
  std::vector<double> inputs(7, 0.0);
  inputs[0] = -0.5;
  EXPECT_THROW(drive_triaxial(*acst, inputs, path), InvalidInput);
}

}  // namespace
}  // namespace model
