// fe-check of a model that has no setup of its own in fe-check: the third registered model
// (linear elasticity, model/src/linear_elastic.cc) runs through the model interface alone, its
// driver (model/point_driver.h), element and mesh agreeing, on plain and DEM cases, with the
// closed-form answer in the driver's file.
#include "fe_model/fe_check.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "model/parameter_file.h"

namespace fe_model {
namespace {

// The last row of a curve CSV (write_curve_csv), as numbers up to the status column.
std::vector<double> last_row(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  std::vector<double> values;
  std::istringstream fields(last);
  std::string field;
  while (std::getline(fields, field, ',') && values.size() < 7) values.push_back(std::stod(field));
  return values;
}

TEST(FeCheck, TheThirdModelRunsThroughTheModelInterfaceAlone) {
  const double E = 2.5e8, nu = 0.2;
  const std::string folder =
      ::testing::TempDir() + "fe_check_third_model_" + std::to_string(::getpid());
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  FeCheckOptions options;
  options.parameters_path = folder + "/linear_elastic.json";
  model::write_parameter_file(options.parameters_path, {"linear_elastic", {}, {E, nu}});
  options.output_folder = folder + "/out";
  options.pressures = {100e3, 200e3};
  options.dem_runs = {std::string(SFFCAL_SOURCE_DIR) +
                      "/tests/data/reference/matrix/iso_dense_100kPa.h5"};
  options.max_strain = 0.01;
  options.steps = 5;
  std::vector<std::string> log;
  const FeCheckResult result =
      run_fe_check(options, [&log](const std::string& line) { log.push_back(line); });
  ASSERT_FALSE(log.empty());
  EXPECT_NE(log.front().find("linear_elastic"), std::string::npos) << log.front();
  EXPECT_TRUE(result.runs_completed);
  int verification = 0, dem = 0;
  for (const FeCheckRow& row : result.checks) {
    (row.verification ? verification : dem)++;
    if (row.verification) {
      EXPECT_TRUE(row.pass) << row.case_name << ' ' << row.check << ' ' << row.quantity << ' '
                            << row.value;
    }
  }
  EXPECT_EQ(verification, 12);  // 3 cases x (element vs driver, mesh vs element) x (q, eps_v)
  EXPECT_EQ(dem, 2);            // linear elasticity is no granular soil: these may fail
  EXPECT_NE(result.exit_code(), 1);
  // q = E eps_a and eps_v = (1 - 2 nu) eps_a at the end of every case's driver and element.
  for (const char* c : {"p100kPa", "p200kPa", "iso_dense_100kPa"})
    for (const char* run : {"driver", "element", "mesh"}) {
      const std::vector<double> row =
          last_row(options.output_folder + "/" + c + "/" + run + ".csv");
      ASSERT_EQ(row.size(), 7u) << c << ' ' << run;
      EXPECT_NEAR(row[0], 0.01, 1e-12) << c << ' ' << run;
      EXPECT_NEAR(row[3], E * 0.01, 1e-6 * E * 0.01) << c << ' ' << run;
      EXPECT_NEAR(row[1], (1.0 - 2.0 * nu) * 0.01, 1e-9) << c << ' ' << run;
    }
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace fe_model
