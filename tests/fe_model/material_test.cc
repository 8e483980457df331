// Material-level tests: linear elasticity and the test materials, tangents against central
// finite differences of the update.
#include "fe_model/material.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "test_materials.h"

namespace fe_model {
namespace {

// max |C_ijkl - d stress_ij / d de_kl| / max |C|, by central differences on the six independent
// strain components (a shear perturbation h on de_kl and de_lk together is half the derivative
// sum, matching the minor-symmetric tangent).
double tangent_error(const Material& material, const PointState& start, const SymmetricTensor2& de,
                     double h) {
  PointState end;
  const MaterialUpdate update = material.update(start, de, end);
  double max_error = 0.0, max_entry = 0.0;
  for (unsigned int k = 0; k < 3; ++k)
    for (unsigned int l = k; l < 3; ++l) {
      SymmetricTensor2 dir;
      dir[k][l] = 1.0;  // sets (k,l) and (l,k)
      PointState plus, minus;
      material.update(start, de + h * dir, plus);
      material.update(start, de - h * dir, minus);
      const SymmetricTensor2 fd = (plus.stress - minus.stress) / (2.0 * h);
      const SymmetricTensor2 analytic = update.tangent * dir;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j) {
          max_error = std::max(max_error, std::abs(fd[i][j] - analytic[i][j]));
          max_entry = std::max(max_entry, std::abs(analytic[i][j]));
        }
    }
  return max_error / max_entry;
}

SymmetricTensor2 some_increment(double scale) {
  SymmetricTensor2 de;
  de[0][0] = 1.0;
  de[1][1] = -0.4;
  de[2][2] = -2.0;
  de[0][1] = 0.3;
  de[0][2] = -0.6;
  de[1][2] = 0.25;
  return scale * de;
}

TEST(LinearElasticMaterial, LameStress) {
  const LinearElasticMaterial material(200e6, 0.25);
  EXPECT_DOUBLE_EQ(material.mu(), 80e6);
  EXPECT_DOUBLE_EQ(material.lambda(), 80e6);
  const PointState start = material.initial_state(-100e3 * dealii::unit_symmetric_tensor<3>());
  PointState end;
  SymmetricTensor2 de;
  de[2][2] = -1e-3;  // uniaxial strain
  const MaterialUpdate update = material.update(start, de, end);
  EXPECT_EQ(update.status, MaterialStatus::kOk);
  EXPECT_NEAR(end.stress[2][2], -100e3 - (80e6 + 160e6) * 1e-3, 1e-6);
  EXPECT_NEAR(end.stress[0][0], -100e3 - 80e6 * 1e-3, 1e-6);
  EXPECT_DOUBLE_EQ(end.strain[2][2], -1e-3);
}

TEST(LinearElasticMaterial, RejectsBadParametersByName) {
  EXPECT_THROW(LinearElasticMaterial(-1.0, 0.3), std::invalid_argument);
  try {
    LinearElasticMaterial(1e6, 0.5);
    FAIL() << "nu = 0.5 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("Poisson"), std::string::npos);
  }
}

TEST(LinearElasticMaterial, TangentMatchesFiniteDifferences) {
  const LinearElasticMaterial material(50e6, 0.3);
  const PointState start = material.initial_state(-50e3 * dealii::unit_symmetric_tensor<3>());
  EXPECT_LT(tangent_error(material, start, some_increment(1e-3), 1e-6), 1e-8);
}

TEST(HypoelasticTestMaterial, TangentMatchesFiniteDifferences) {
  const testing::HypoelasticTestMaterial material(0.005, 100.0);
  PointState start = material.initial_state(-100e3 * dealii::unit_symmetric_tensor<3>());
  start.stress[2][2] -= 40e3;
  start.stress[0][1] = 5e3;
  const double error = tangent_error(material, start, some_increment(1e-3), 1e-8);
  RecordProperty("fd_tangent_error", std::to_string(error));
  EXPECT_LT(error, 1e-6);
}

TEST(FailingTestMaterial, FailsAboveThresholdOnly) {
  const LinearElasticMaterial elastic(50e6, 0.3);
  const testing::FailingTestMaterial material(elastic, 1e-3);
  const PointState start = material.initial_state(SymmetricTensor2());
  PointState end;
  EXPECT_EQ(material.update(start, some_increment(1e-4), end).status, MaterialStatus::kOk);
  EXPECT_EQ(material.update(start, some_increment(1e-2), end).status, MaterialStatus::kFailed);
}

TEST(MaterialStatus, WorstAndNames) {
  EXPECT_EQ(worst(MaterialStatus::kOk, MaterialStatus::kUnreliable), MaterialStatus::kUnreliable);
  EXPECT_EQ(worst(MaterialStatus::kFailed, MaterialStatus::kUnreliable), MaterialStatus::kFailed);
  EXPECT_STREQ(to_string(MaterialStatus::kUnreliable), "unreliable");
}

}  // namespace
}  // namespace fe_model
