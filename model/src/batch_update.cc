// Many points of one model in one call (batch_update.h).
#include "model/batch_update.h"

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace model {

std::vector<std::pair<std::size_t, std::string>> update_points(const Behaviour& behaviour,
                                                               const PointBatch& batch) {
  const std::size_t m =
      static_cast<std::size_t>(slot_components(behaviour.description().state()));
  // The arrays are C-ordered 3 x 3 blocks: row-major maps (the tensors are symmetric, but the
  // increment need not be given so).
  using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  std::vector<std::pair<std::size_t, std::string>> messages;
  for (std::size_t k = 0; k < batch.points; ++k) {
    const Eigen::Matrix3d stress = Eigen::Map<const RowMajor3>(batch.stress + 9 * k);
    const Eigen::Matrix3d increment = Eigen::Map<const RowMajor3>(batch.increment + 9 * k);
    const PointUpdate update =
        behaviour.update(stress, batch.state + m * k, increment, batch.state_end + m * k);
    Eigen::Map<RowMajor3>(batch.stress_end + 9 * k) = update.stress;
    if (batch.tangent)
      Eigen::Map<Eigen::Matrix<double, 9, 9, Eigen::RowMajor>>(batch.tangent + 81 * k) =
          update.tangent;
    batch.status[k] = static_cast<int>(update.status);
    if (batch.step_ratio) batch.step_ratio[k] = update.step_ratio;
    if (update.status != UpdateStatus::kOk) messages.emplace_back(k, update.message);
  }
  return messages;
}

}  // namespace model
