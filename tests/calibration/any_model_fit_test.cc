// The fit of any registered model over its description (calibration/any_model_fit.h): the third
// model (linear elasticity) fitted to drained tests made from its own closed form recovers its
// parameters from the middle of their search ranges; its outputs are its parameter file; a test on
// another path is refused by name.
#include "calibration/any_model_fit.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/parameter_file.h"

namespace calibration {
namespace {

// Drained compression of linear elasticity from p0: q = E eps_a, p = p0 + q / 3,
// eps_v = (1 - 2 nu) eps_a, at rows to 2 % axial strain.
TestData elastic_test(const std::string& name, double E, double nu, double p0) {
  TestData t;
  t.name = name;
  t.source = name + ".h5";
  t.p0 = p0;
  t.e0 = 0.7;
  for (int k = 0; k <= 40; ++k) {
    const double axial = 0.02 * k / 40.0, q = E * axial, p = p0 + q / 3.0;
    t.axial_strain.push_back(axial);
    t.eta.push_back(q / p);
    t.volumetric_strain.push_back((1.0 - 2.0 * nu) * axial);
    t.void_ratio.push_back(0.7);
    t.p.push_back(p);
  }
  return t;
}

TEST(AnyModelFit, TheThirdModelRecoversItsOwnParameters) {
  const double E = 4.0e7, nu = 0.27;
  const model::ModelDescription& elastic = model::find_model("linear_elastic");
  const std::vector<TestData> fitted = {elastic_test("a", E, nu, 100e3),
                                        elastic_test("b", E, nu, 300e3)};
  const std::vector<TestData> held_out = {elastic_test("c", E, nu, 200e3)};
  AnyModelFitResult result = fit_any_model(elastic, fitted);
  ASSERT_TRUE(result.usable) << result.termination;
  ASSERT_EQ(result.values.parameters.size(), 2u);
  EXPECT_NEAR(result.values.parameters[0], E, 1e-6 * E) << result.termination;
  EXPECT_NEAR(result.values.parameters[1], nu, 1e-6) << result.termination;
  EXPECT_LT(result.final_cost, 1e-12 * result.initial_cost);
  const std::vector<AnyModelTestError> predicted =
      any_model_errors(elastic, result.values, held_out, false);
  result.errors.insert(result.errors.end(), predicted.begin(), predicted.end());
  ASSERT_EQ(result.errors.size(), 3u);
  for (const AnyModelTestError& e : result.errors) {
    EXPECT_EQ(e.rows, 40) << e.name;
    EXPECT_LT(e.eta_rms, 1e-7) << e.name;
    EXPECT_LT(e.volumetric_rms, 1e-9) << e.name;
  }
  EXPECT_FALSE(result.errors.back().fitted);

  // The outputs: the model's parameter file, read back by the one reader.
  const std::string folder = ::testing::TempDir() + "any_model_fit_" + std::to_string(::getpid());
  std::filesystem::remove_all(folder);
  const std::string summary = write_any_model_fit_outputs(folder, elastic, fitted, held_out, result,
                                                          {}, "test", "any_model_fit_test");
  EXPECT_NE(summary.find("youngs_modulus"), std::string::npos) << summary;
  const model::ParameterValues read =
      model::read_parameter_file(folder + "/parameters.json", "linear_elastic");
  EXPECT_EQ(read.parameters, result.values.parameters);
  EXPECT_TRUE(std::filesystem::exists(folder + "/c_curves.csv"));
  std::filesystem::remove_all(folder);
}

TEST(AnyModelFit, RefusesATestOnAnotherPathByName) {
  TestData t = elastic_test("undrained_one", 4e7, 0.27, 100e3);
  t.path = TestPath::kUndrainedCompression;
  try {
    fit_any_model(model::find_model("linear_elastic"), {t});
    FAIL() << "an undrained test was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("undrained_one"), std::string::npos) << e.what();
  }
  EXPECT_THROW(fit_any_model(model::find_model("linear_elastic"), {}), std::invalid_argument);
}

}  // namespace
}  // namespace calibration
