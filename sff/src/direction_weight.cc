#include "sff/direction_weight.h"

#include <algorithm>

#include <Eigen/Eigenvalues>

#include "sff/statistics.h"
#include "sffcal/constants.h"

namespace sff {

DirectionWeight::DirectionWeight(ContactSpan contacts, const Eigen::Matrix3d& fabric_a)
    : fabric_a_(fabric_a) {
  if (!fabric_a.allFinite()) throw StatisticsError("the fabric anisotropy tensor is not finite");
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(fabric_a, Eigen::EigenvaluesOnly);
  min_density_ = 1.0 + solver.eigenvalues()[0];
  if (min_density_ > kMinSecondOrderDensity) return;
  // The binned density of cell k is E_k = n_k / (N_c Omega_k); w = 1 / (4 pi E_k).
  const double total = for_each_body_contact(contacts, [](const ContactRecord&, double) {});
  const int num_cells = 2 * static_cast<int>(std::clamp(total / kContactsPerCell, 41.0, 4001.0) / 2.0) + 1;
  cells_ = DirectionCells::principal(num_cells, fabric_a);
  std::vector<double> counts(static_cast<std::size_t>(num_cells), 0.0);
  for_each_body_contact(contacts, [&](const ContactRecord& c, double w) {
    counts[static_cast<std::size_t>(cells_.cell_of(normal_of(c)))] += w;
  });
  constexpr double kFourPi = 4.0 * sffcal::kPi;
  cell_weight_.resize(counts.size());
  for (std::size_t k = 0; k < counts.size(); ++k)
    cell_weight_[k] = counts[k] > 0.0 ? total * cells_.solid_angle() / (kFourPi * counts[k]) : 0.0;
}

double DirectionWeight::operator()(const Eigen::Vector3d& n) const {
  if (binned()) return cell_weight_[static_cast<std::size_t>(cells_.cell_of(n))];
  return 1.0 / (1.0 + n.dot(fabric_a_ * n));
}

}  // namespace sff
