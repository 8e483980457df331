// The contact-network model (docs/network-model.md) fitted to DEM tests' micro histories, then
// each test predicted on its own loading path (issue 19, point 2). A test is a paper-size run's
// committed reduced CSV pair by name (bench/reference/<name>_series.csv and <name>_sff.csv) or a
// run file (.h5) analysed by `sffcal sff`.
//
// usage: network_fit FITTED... [--hold-out HELD...] [--threads N] [--starts N] [--hold NAME]...
//                    [--predicted-only] [--substep-size S] [--anisotropy-scale S] --out DIR
//   (--hold NAME: the parameter held at its start value, e.g. c_t at 1: no Lode dependence;
//    --substep-size: FitOptions::substep_size, for timing the fit against its paths' error;
//    --anisotropy-scale: FitOptions::anisotropy_scale, the weight of a_c and a_n in the fit)
//   e.g. build/bench/network_fit dense_100kPa loose_200kPa --hold-out dense_300kPa --out out/n1
// Writes what `sffcal calibrate --model network` writes (network::write_fit_outputs: the
// parameter file with the fit's record, <name>_network.csv per test, summary.md) into DIR, which
// must not exist yet, and prints the summary: per test the RMS errors along the DEM's strain
// path (the fit's objective) and of the prediction, and the parameters with standard errors.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "calibration/network_fit.h"
#include "reference_tests.h"

int main(int argc, char** argv) {
  namespace net = calibration::network;
  try {
    std::vector<std::string> fitted, held;
    std::string out_dir;
    net::FitOptions options;
    options.threads = 2;
    options.starts = 4;
    bool holding = false;
    for (int k = 1; k < argc; ++k) {
      const std::string a = argv[k];
      if (a == "--hold-out") {
        holding = true;
      } else if (a == "--threads" && k + 1 < argc) {
        options.threads = std::atoi(argv[++k]);
      } else if (a == "--starts" && k + 1 < argc) {
        options.starts = std::atoi(argv[++k]);
      } else if (a == "--hold" && k + 1 < argc) {
        options.held.push_back(argv[++k]);
      } else if (a == "--predicted-only") {
        options.first_stage = false;
      } else if (a == "--substep-size" && k + 1 < argc) {
        options.substep_size = std::atof(argv[++k]);
      } else if (a == "--anisotropy-scale" && k + 1 < argc) {
        options.anisotropy_scale = std::atof(argv[++k]);
      } else if (a == "--out" && k + 1 < argc) {
        out_dir = argv[++k];
      } else {
        (holding ? held : fitted).push_back(a);
      }
    }
    if (fitted.empty() || out_dir.empty()) {
      std::fprintf(stderr, "usage: network_fit FITTED... [--hold-out HELD...] [--threads N] "
                           "[--starts N] [--hold NAME]... [--predicted-only] [--substep-size S] "
                           "[--anisotropy-scale S] --out DIR\n");
      return 2;
    }
    if (!(options.anisotropy_scale > 0.0) || !(options.substep_size > 0.0))
      throw std::runtime_error("--anisotropy-scale and --substep-size must be positive numbers");
    if (std::filesystem::exists(out_dir))
      throw std::runtime_error("output folder " + out_dir + " exists (not overwritten)");
    std::vector<calibration::TestData> fit_tests = bench::read_reference_tests(fitted),
                                        held_tests = bench::read_reference_tests(held);
    for (auto* list : {&fit_tests, &held_tests})
      for (calibration::TestData& t : *list) t = net::with_closing_normal_anisotropy(std::move(t));
    calibration::check_unique_names(fit_tests, held_tests);
    options.progress = [](const std::string& line) {
      std::printf("%s\n", line.c_str());
      std::fflush(stdout);
    };
    const net::FitResult result = net::fit(fit_tests, net::default_start(fit_tests), options);
    std::string command_line;
    for (int k = 0; k < argc; ++k) command_line += (k ? " " : "") + std::string(argv[k]);
    std::printf("\n%s\n%s", result.report.c_str(),
                net::write_fit_outputs(out_dir, fit_tests, held_tests, result, options,
                                       SFFCAL_VERSION, command_line)
                    .c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "network_fit: %s\n", e.what());
    return 1;
  }
}
