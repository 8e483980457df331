// A batch of ACST-or-any-model updates timed in C++ (model::update_points), the reference of the
// Python API's batch update (bench/python/model_batch.py runs both, alternated, on the same
// batch: the Python call's overhead as a ratio). The batch: n points at the initial state of
// sigma_3 = 100 kPa with the void ratio 0.8 and every other input zero, point k strained by
// a_k diag(-1/2, -1/2, 1), a_k = 1e-4 (1 + (k mod 97) / 97) (the script builds the same numbers).
//
//   build/bench/model_batch PARAMETERS.json N REPEATS   # prints one time [s] per repeat
#include <Eigen/Core>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "model/batch_update.h"
#include "model/descriptor.h"
#include "model/parameter_file.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: model_batch PARAMETERS.json N REPEATS\n");
    return 2;
  }
  try {
    const model::ParameterValues values = model::read_parameter_file(argv[1]);
    const std::size_t n = std::stoul(argv[2]);
    const int repeats = std::stoi(argv[3]);
    const model::ModelDescription& d = model::find_model(values.model);
    const std::unique_ptr<model::Behaviour> behaviour = d.make(values.constants, values.parameters);
    const std::size_t m = static_cast<std::size_t>(model::slot_components(d.state()));
    std::vector<double> inputs(static_cast<std::size_t>(model::slot_components(d.initial_inputs())), 0.0);
    const int void_ratio = model::slot_offset(d.initial_inputs(), "void_ratio");
    if (void_ratio >= 0) inputs[static_cast<std::size_t>(void_ratio)] = 0.8;
    std::vector<double> state0(m);
    const Eigen::Matrix3d stress0 =
        behaviour->initial_state(100e3 * Eigen::Matrix3d::Identity(), inputs.data(), state0.data());

    std::vector<double> stress(9 * n), state(m * n), increment(9 * n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      for (int i = 0; i < 9; ++i) stress[9 * k + i] = stress0(i / 3, i % 3);
      for (std::size_t j = 0; j < m; ++j) state[m * k + j] = state0[j];
      const double a = 1e-4 * (1.0 + static_cast<double>(k % 97) / 97.0);
      increment[9 * k + 0] = -0.5 * a;
      increment[9 * k + 4] = -0.5 * a;
      increment[9 * k + 8] = a;
    }
    std::vector<double> stress_end(9 * n), state_end(m * n), step_ratio(n);
    std::vector<int> status(n);
    model::PointBatch batch{n, stress.data(), state.data(), increment.data(), stress_end.data(),
                            state_end.data(), nullptr, status.data(), step_ratio.data()};
    for (int r = 0; r < repeats; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      model::update_points(*behaviour, batch);
      std::printf("%.6f\n",
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    // A checksum the script compares with its own: the two ran the same batch.
    double sum = 0.0;
    for (double x : stress_end) sum += x;
    std::printf("checksum %.17g\n", sum);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "model_batch: %s\n", e.what());
    return 1;
  }
  return 0;
}
