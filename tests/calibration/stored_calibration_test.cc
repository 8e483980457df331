// Calibration regression (issue 7): the stored reduced DEM runs of the reference matrix, fitted
// again with the options the stored parameter file was made with (tests/data/reference/
// calibration/README.md), give the stored parameters within their reported standard errors.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "calibration/fit.h"

namespace calibration {
namespace {

const std::string kData = std::string(SFFCAL_SOURCE_DIR) + "/tests/data/reference/";

// The stored fit: `sffcal calibrate` on these runs with --starts 1 --points 20 (README there).
const std::vector<std::string> kRuns = {"matrix/iso_dense_100kPa.h5", "matrix/iso_dense_300kPa.h5",
                                        "matrix/iso_loose_100kPa.h5"};

TEST(StoredCalibration, StoredRunsGiveTheStoredParametersWithinTheirErrors) {
  std::ifstream in(kData + "calibration/parameters.json");
  ASSERT_TRUE(in) << "cannot read " << kData << "calibration/parameters.json";
  const nlohmann::json stored = nlohmann::json::parse(in);

  std::vector<TestData> tests;
  for (const std::string& run : kRuns) tests.push_back(read_run_file(kData + run));
  FitOptions options;
  options.starts = 1;
  options.max_points = 20;
  const CalibrationResult result = calibrate(tests, options);

  int compared = 0;
  for (int i = 0; i < kNumFitParameters; ++i) {
    const std::string name = fit_parameter_names()[i];
    if (name == "a_cs") continue;  // stored under fabric_normalisation, compared below
    const nlohmann::json& entry = stored.at("parameters").at(name);
    if (entry.at("fixed").get<bool>() || entry.at("standard_error").is_null()) continue;
    const double value = entry.at("value").get<double>();
    const double error = entry.at("standard_error").get<double>();
    const double refitted = result.values[i];
    std::printf("%-8s stored %11.5g +- %-10.3g refitted %11.5g  (%+.3f standard errors)\n", name.c_str(), value,
                error, refitted, (refitted - value) / error);
    EXPECT_LE(std::abs(refitted - value), error) << name;
    ++compared;
  }
  EXPECT_GE(compared, 8);  // the free parameters of the stages
  const nlohmann::json& a_cs = stored.at("fabric_normalisation").at("a_cs");
  const double a_cs_refitted = result.values[fit_parameter_index("a_cs")];
  EXPECT_LE(std::abs(a_cs_refitted - a_cs.at("value").get<double>()), a_cs.at("standard_error").get<double>());
}

}  // namespace
}  // namespace calibration
