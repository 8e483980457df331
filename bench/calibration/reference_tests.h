// Calibration tests for the bench fits: a name is a paper-size run's committed reduced CSV pair,
// bench/reference/<name>_series.csv and <name>_sff.csv (sheared with friction tan 30 degrees); a
// path ending in .h5 is a run file (calibration::read_run_file).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "calibration/fit.h"
#include "sffcal/constants.h"

namespace bench {

inline std::vector<calibration::TestData> read_reference_tests(
    const std::vector<std::string>& names) {
  const std::string folder = std::string(SFFCAL_SOURCE_DIR) + "/bench/reference/";
  const double friction = std::tan(sffcal::kPi / 6.0);  // the runs' shearing friction
  std::vector<calibration::TestData> tests;
  for (const std::string& n : names) {
    const bool run_file = n.size() > 3 && n.compare(n.size() - 3, 3, ".h5") == 0;
    tests.push_back(run_file ? calibration::read_run_file(n)
                             : calibration::read_csv_pair(folder + n + "_series.csv",
                                                          folder + n + "_sff.csv", n, friction));
  }
  return tests;
}

}  // namespace bench
