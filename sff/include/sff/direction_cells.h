// Equal-area cells of contact directions (sff-theory.md §6.2, general form; issue 18): a polar cap
// about a chosen axis and collars of equal cells. A contact direction n and -n are one direction,
// so the cells cover the upper hemisphere of their frame and each stands for a pair of antipodal
// patches of the whole sphere. Laid out in the principal frame of a tensor (the stress), the
// binned statistics do not depend on the lab frame: rotating a snapshot rotates the cells with it.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace sff {

class DirectionCells {
 public:
  /// `num_cells` odd and >= 3 (the cap and collars of an even number of cells each, so that the
  /// partition is symmetric under a sign change of any frame axis). The columns of `frame` are
  /// orthonormal axes; the cap is about the third.
  explicit DirectionCells(int num_cells, const Eigen::Matrix3d& frame = Eigen::Matrix3d::Identity());

  /// Cells about the principal axes of a symmetric tensor, the cap about the major one.
  static DirectionCells principal(int num_cells, const Eigen::Matrix3d& tensor);

  int size() const { return num_cells_; }
  const Eigen::Matrix3d& frame() const { return frame_; }
  /// Solid angle of one cell with its antipode: 4 pi / size() [sr].
  double solid_angle() const;

  /// n (unit, lab frame) in the cells' frame, folded onto the upper hemisphere; `sign` is -1
  /// where it was folded (a vector field odd in n, such as the tangential force, flips with it).
  Eigen::Vector3d to_frame(const Eigen::Vector3d& n, double& sign) const;
  /// The cell of a direction already in the cells' frame and folded (to_frame).
  int cell_of_folded(const Eigen::Vector3d& folded) const;
  /// The cell of a unit direction in the lab frame.
  int cell_of(const Eigen::Vector3d& n) const;

  /// Average of n (x) n over cell k with the uniform (solid-angle) measure, in the cells' frame:
  /// the cell average of a quadratic form n.T.n is (R^T T R) : mean_dyad(k), R = frame().
  Eigen::Matrix3d mean_dyad(int k) const;

 private:
  struct Collar {
    double z_low, z_high;  ///< bounds of n.e3 in the cells' frame
    int first, count;      ///< index of its first cell, number of cells
  };
  int num_cells_;
  Eigen::Matrix3d frame_;
  std::vector<Collar> collars_;  ///< the cap first (one cell), then downwards to the equator
};

}  // namespace sff
