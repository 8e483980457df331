// Triaxial compression and extension of one point of any model, drained or undrained
// (point_driver.h).
#include "model/point_driver.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "model/parameter_field.h"

namespace model {

const char* to_string(Drainage drainage) {
  return drainage == Drainage::kDrained ? "drained" : "undrained";
}

Drainage parse_drainage(const std::string& text) {
  if (text == "drained") return Drainage::kDrained;
  if (text == "undrained") return Drainage::kUndrained;
  throw std::invalid_argument("drainage '" + text + "': drained or undrained");
}

DriverPath drive_triaxial(const Behaviour& behaviour, const std::vector<double>& inputs,
                          const TriaxialPath& path) {
  if (path.steps < 1) throw std::invalid_argument("triaxial path: steps must be >= 1");
  if (!(path.lateral_stress > 0.0) || !std::isfinite(path.lateral_stress))
    throw std::invalid_argument("triaxial path: the lateral stress must be positive [Pa]");
  if (!std::isfinite(path.axial_strain_end) || path.axial_strain_end == 0.0 ||
      std::abs(path.axial_strain_end) > kMaxTriaxialStrain)
    throw std::invalid_argument("triaxial path: the end axial strain must be non-zero and at most " +
                                format_number(kMaxTriaxialStrain) +
                                " in size (negative: extension)");
  if (!(path.stress_tolerance > 0.0))
    throw std::invalid_argument("triaxial path: the stress tolerance must be positive");
  const ModelDescription& description = behaviour.description();
  if (static_cast<int>(inputs.size()) != slot_components(description.initial_inputs()))
    throw std::invalid_argument("triaxial path: " + std::to_string(inputs.size()) +
                                " initial inputs given, model '" + description.name() +
                                "' takes " +
                                std::to_string(slot_components(description.initial_inputs())));

  const double sigma_3 = path.lateral_stress;
  DriverPath result;
  DriverPoint point;
  point.state.assign(static_cast<std::size_t>(slot_components(description.state())), 0.0);
  point.stress = behaviour.initial_state(sigma_3 * Eigen::Matrix3d::Identity(), inputs.data(),
                                         point.state.data());
  result.points.push_back(point);

  const double d_axial = path.axial_strain_end / path.steps;
  const bool drained = path.drainage == Drainage::kDrained;
  // Drained: the last increment's lateral strains, the next's guess; undrained: the prescribed
  // ones, tr = 0.
  Eigen::Vector2d lateral =
      drained ? Eigen::Vector2d::Zero() : Eigen::Vector2d::Constant(-0.5 * d_axial).eval();
  std::vector<double> end_state(point.state.size());
  for (int step = 1; step <= path.steps; ++step) {
    const DriverPoint& start = result.points.back();
    Eigen::Matrix3d increment = Eigen::Matrix3d::Zero();
    increment(2, 2) = d_axial;
    PointUpdate update;
    bool converged = false;
    int iterations = 0;
    for (; iterations <= path.max_newton_iterations; ++iterations) {
      increment(0, 0) = lateral(0);
      increment(1, 1) = lateral(1);
      update = behaviour.update(start.stress, start.state.data(), increment, end_state.data());
      if (update.status == UpdateStatus::kFailed) break;
      if (!drained) {
        converged = true;
        break;
      }
      const Eigen::Vector2d residual(update.stress(0, 0) - sigma_3, update.stress(1, 1) - sigma_3);
      const double scale = std::max(update.stress.trace() / 3.0, sigma_3);
      if (residual.lpNorm<Eigen::Infinity>() <= path.stress_tolerance * scale) {
        converged = true;
        break;
      }
      // d sigma_ii / d eps_jj at row 3 i + i, column 3 j + j (descriptor.h, PointUpdate).
      Eigen::Matrix2d jacobian;
      jacobian << update.tangent(0, 0), update.tangent(0, 4), update.tangent(4, 0),
          update.tangent(4, 4);
      const Eigen::FullPivLU<Eigen::Matrix2d> lu(jacobian);
      if (!lu.isInvertible()) break;
      lateral -= lu.solve(residual);
    }
    if (!converged) {
      result.message = update.status == UpdateStatus::kFailed
                           ? "the update failed at step " + std::to_string(step) + ": " +
                                 update.message
                           : "no lateral strain holds sigma_3 at step " + std::to_string(step) +
                                 " (Newton did not converge)";
      return result;
    }
    DriverPoint next;
    next.strain = start.strain + increment;
    next.stress = update.stress;
    next.state = end_state;
    next.status = update.status;
    next.newton_iterations = iterations;
    result.points.push_back(std::move(next));
  }
  result.completed = true;
  return result;
}

}  // namespace model
