// The weight that turns a sum over contacts into a direction average (sff-theory.md §3):
// <g>_Omega = (1/4 pi) int g(n) dOmega ~ (1/N_c) sum_c g(n_c) w(n_c), w = 1 / (4 pi E(n)).
// To second order E = (1 + n.A.n) / 4 pi. That form needs 1 + n.A.n clearly positive: where the
// smallest principal value of A is -0.9 or less (1 + n.A.n <= 0.1 for some n), the estimators
// fall back to the binned density of equal-area cells about A's principal axes (§8).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "sff/contacts.h"
#include "sff/direction_cells.h"

namespace sff {

class DirectionWeight {
 public:
  /// The binned fallback uses equal-area cells with about this many contacts each (at least 41
  /// cells, at most 4001): fine cells keep the bias of a density that varies within a cell small.
  static constexpr double kContactsPerCell = 50.0;
  /// The smallest 1 + lambda_min(A) for which the second-order weight is used.
  static constexpr double kMinSecondOrderDensity = 0.1;

  DirectionWeight(ContactSpan contacts, const Eigen::Matrix3d& fabric_a);
  /// w(n) for a unit normal n; 0 in an empty cell of the binned fallback (no contact there).
  double operator()(const Eigen::Vector3d& n) const;
  /// True when the binned fallback is in use.
  bool binned() const { return !cell_weight_.empty(); }
  /// 1 + lambda_min(A): the smallest second-order density times 4 pi.
  double min_density() const { return min_density_; }

 private:
  Eigen::Matrix3d fabric_a_;
  double min_density_ = 1.0;
  DirectionCells cells_{3};
  std::vector<double> cell_weight_;  ///< N_c Omega_cell / (4 pi n_cell); empty: second order
};

}  // namespace sff
