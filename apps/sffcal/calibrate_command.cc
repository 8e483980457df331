#include "calibrate_command.h"

#include <chrono>
#include <cstdio>
#include <exception>

#include "calibration/fit.h"

namespace sffcal {

int calibrate_command(const std::vector<std::string>& run_paths,
                      const CalibrateCommandOptions& options, const std::string& command_line) {
  try {
    calibration::FitOptions fit;
    fit.stages = calibration::parse_stages(options.stages);
    fit.loss = calibration::parse_loss(options.loss);
    fit.starts = options.starts;
    fit.seed = options.seed;
    fit.max_points = options.max_points;
    fit.verbose = options.verbose;
    std::vector<calibration::TestData> tests;
    for (const std::string& path : run_paths) {
      tests.push_back(calibration::read_run_file(path));
      const calibration::TestData& t = tests.back();
      std::printf("read %s: %zu rows, %zu snapshots, p0 = %.0f Pa, e0 = %.4f, a_c0 = %.4f, mu = %.4f\n",
                  path.c_str(), t.axial_strain.size(), t.a_c.size(), t.p0, t.e0, t.a_c0, t.friction);
    }
    const auto start = std::chrono::steady_clock::now();
    const calibration::CalibrationResult result = calibration::calibrate(tests, fit);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string summary = calibration::write_calibration_outputs(
        options.output_folder, tests, result, fit, SFFCAL_VERSION, command_line);
    std::printf("\n%s\ncalibrated in %.1f s; outputs in %s (plot: scripts/plot_calibration.py %s)\n",
                summary.c_str(), seconds, options.output_folder.c_str(),
                options.output_folder.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sffcal calibrate: %s\n", e.what());
    return 1;
  }
}

}  // namespace sffcal
