// The calibration of the paper-size runs (docs/calibration.md, "Fit to paper-size runs") from
// their committed reduced CSV pairs, bench/reference/<name>_series.csv and <name>_sff.csv (the
// full run files are not committed; `sffcal calibrate` reads run files).
//
// usage: paper_fit FITTED... [--hold-out HELD...] [--threads N] [--range NAME=LOW:HIGH ...]
//   e.g. build/bench/paper_fit dense_100kPa loose_200kPa --hold-out dense_300kPa
// Prints the summary of `sffcal calibrate` (errors per test, parameters, stages).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "calibration/fit.h"
#include "reference_tests.h"

int main(int argc, char** argv) {
  try {
    std::vector<std::string> fitted, held, ranges;
    int threads = 2;
    bool holding = false;
    for (int k = 1; k < argc; ++k) {
      const std::string a = argv[k];
      if (a == "--hold-out") {
        holding = true;
      } else if (a == "--threads" && k + 1 < argc) {
        threads = std::atoi(argv[++k]);
      } else if (a == "--range" && k + 1 < argc) {
        ranges.push_back(argv[++k]);
      } else {
        (holding ? held : fitted).push_back(a);
      }
    }
    if (fitted.empty()) {
      std::fprintf(stderr, "usage: paper_fit FITTED... [--hold-out HELD...] [--threads N] "
                           "[--range NAME=LOW:HIGH ...]\n");
      return 2;
    }
    calibration::FitOptions options;
    options.threads = threads;
    for (const std::string& range : ranges) calibration::set_search_range(options, range);
    calibration::CalibrationResult result = calibration::calibrate(bench::read_reference_tests(fitted), options);
    calibration::predict(bench::read_reference_tests(held), options, result);
    std::printf("%s", calibration::summary_markdown(result).c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "paper_fit: %s\n", e.what());
    return 1;
  }
}
