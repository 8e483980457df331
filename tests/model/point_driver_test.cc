// The material-point driver of any model (model/point_driver.h): linear elasticity against its
// closed form, ACST against ACST's own driver on the same path, and the errors it names.
#include "model/point_driver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <stdexcept>
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
  DrainedTriaxialPath path;
  path.lateral_stress = 150e3;
  path.axial_strain_end = 0.01;
  path.steps = 8;
  const DriverPath result = drive_drained_triaxial(*behaviour, {}, path);
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

// ACST through its Behaviour and this driver, against ACST's own driver (material_point.h) with
// the same integration options (the driver's: error control at 1e-7): both converge on the same
// discrete equations, so they agree to their Newton tolerances (1e-10 p here, 1e-8 p there) and
// the integration's noise.
TEST(PointDriver, AcstAgreesWithItsOwnDriver) {
  const acst::Parameters<double> par = testing::toyoura();
  const acst::DriverOptions own;
  const double p0 = 100e3, e0 = 0.8;
  const acst::PathResult<double> reference = acst::drained_triaxial(
      par, acst::isotropic_state(p0, e0, Eigen::Matrix3d::Zero().eval()), 0.05, 50, own);
  ASSERT_EQ(reference.status, UpdateStatus::kOk);

  const auto behaviour = acst::make_behaviour(par, own.integration);
  std::vector<double> inputs(7, 0.0);
  inputs[0] = e0;  // void_ratio, then an isotropic (zero) fabric
  DrainedTriaxialPath path;
  path.lateral_stress = p0;
  path.axial_strain_end = 0.05;
  path.steps = 50;
  const DriverPath result = drive_drained_triaxial(*behaviour, inputs, path);
  ASSERT_TRUE(result.completed) << result.message;
  ASSERT_EQ(result.points.size(), reference.rows.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < result.points.size(); ++k) {
    const Eigen::Matrix3d& s = result.points[k].stress;
    const double q = s(2, 2) - 0.5 * (s(0, 0) + s(1, 1));
    EXPECT_NEAR(result.points[k].strain(2, 2), reference.rows[k].axial_strain, 1e-15);
    worst = std::max(worst, std::abs(q - reference.rows[k].q) / p0);
    EXPECT_NEAR(result.points[k].strain.trace(), reference.rows[k].volumetric_strain, 1e-7);
  }
  std::cout << "max |q - q_own| / p0 = " << worst << '\n';
  EXPECT_LT(worst, 1e-8);
  EXPECT_GT(reference.rows.back().q, 0.5 * p0);  // the path did load the specimen
}

TEST(PointDriver, NamesWhatIsWrongWithThePathOrTheInputs) {
  const auto elastic = find_model("linear_elastic").make({}, {1e8, 0.25});
  DrainedTriaxialPath path;
  path.steps = 0;
  EXPECT_THROW(drive_drained_triaxial(*elastic, {}, path), std::invalid_argument);
  path.steps = 4;
  path.lateral_stress = -1.0;
  EXPECT_THROW(drive_drained_triaxial(*elastic, {}, path), std::invalid_argument);
  path.lateral_stress = 100e3;
  try {
    drive_drained_triaxial(*elastic, {0.7}, path);
    FAIL() << "one input too many was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("linear_elastic"), std::string::npos) << e.what();
  }
  // ACST with a void ratio it cannot carry: its initial_state names the input.
  const auto acst = acst::make_behaviour(testing::toyoura());
  std::vector<double> inputs(7, 0.0);
  inputs[0] = -0.5;
  EXPECT_THROW(drive_drained_triaxial(*acst, inputs, path), InvalidInput);
}

}  // namespace
}  // namespace model
