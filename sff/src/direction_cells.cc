#include "sff/direction_cells.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>

#include "sff/statistics.h"
#include "sffcal/constants.h"

namespace sff {
namespace {

using sffcal::kPi;

int nearest_even(double x) { return 2 * static_cast<int>(std::lround(0.5 * x)); }

}  // namespace

// The cap has the area of one cell (2 pi / N of the hemisphere's 2 pi), so it ends at
// z = 1 - 1/N. The collars are about as tall as a cell is wide; the number of cells above each
// collar's lower edge is rounded to an even number and the edge then placed where that many cells
// fill the area exactly (the area above z is 2 pi (1 - z)), so that every cell has area 2 pi / N.
DirectionCells::DirectionCells(int num_cells, const Eigen::Matrix3d& frame)
    : num_cells_(num_cells), frame_(frame) {
  if (num_cells < 3 || num_cells % 2 == 0)
    throw StatisticsError("direction cells: the number of cells must be odd and at least 3, not " +
                          std::to_string(num_cells));
  if (!((frame.transpose() * frame - Eigen::Matrix3d::Identity()).norm() < 1e-9))
    throw StatisticsError("direction cells: the frame is not orthonormal");
  const double n = num_cells;
  const double cap_edge = std::acos(1.0 - 1.0 / n);
  const double cell_size = std::sqrt(2.0 * kPi / n);
  const int num_collars = std::max(1, static_cast<int>(std::lround((0.5 * kPi - cap_edge) / cell_size)));
  collars_.push_back({1.0 - 1.0 / n, 1.0, 0, 1});
  const int rest = num_cells - 1;
  int above = 0;  // cells in the collars placed so far
  for (int i = 1; i <= num_collars; ++i) {
    const double edge = cap_edge + i * (0.5 * kPi - cap_edge) / num_collars;
    int total = i == num_collars ? rest : nearest_even(n * (1.0 - std::cos(edge)) - 1.0);
    total = std::min(rest, std::max(above + 2, total));
    if (total == above) continue;
    collars_.push_back({1.0 - (1.0 + total) / n, 1.0 - (1.0 + above) / n, 1 + above, total - above});
    above = total;
  }
  collars_.back().z_low = 0.0;
}

DirectionCells DirectionCells::principal(int num_cells, const Eigen::Matrix3d& tensor) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(0.5 * (tensor + tensor.transpose()));
  // Ascending eigenvalues: the major axis is the last column, the cap's axis.
  return DirectionCells(num_cells, solver.eigenvectors());
}

double DirectionCells::solid_angle() const { return 4.0 * kPi / num_cells_; }

Eigen::Vector3d DirectionCells::to_frame(const Eigen::Vector3d& n, double& sign) const {
  const Eigen::Vector3d local = frame_.transpose() * n;
  sign = local.z() < 0.0 ? -1.0 : 1.0;
  return sign * local;
}

int DirectionCells::cell_of_folded(const Eigen::Vector3d& folded) const {
  const double z = std::clamp(folded.z(), 0.0, 1.0);
  std::size_t k = 0;
  while (k + 1 < collars_.size() && z < collars_[k].z_low) ++k;
  const Collar& c = collars_[k];
  if (c.count == 1) return c.first;
  double phi = std::atan2(folded.y(), folded.x());
  if (phi < 0.0) phi += 2.0 * kPi;
  const int sector = std::min(c.count - 1, static_cast<int>(phi / (2.0 * kPi) * c.count));
  return c.first + sector;
}

int DirectionCells::cell_of(const Eigen::Vector3d& n) const {
  double sign = 1.0;
  return cell_of_folded(to_frame(n, sign));
}

// Over a cell z and phi are independent and uniform (the solid angle is dz dphi), so each entry of
// n n = (s cos phi, s sin phi, z)^2, s = sqrt(1 - z^2), is a product of a z-average and a
// phi-average.
Eigen::Matrix3d DirectionCells::mean_dyad(int k) const {
  if (k < 0 || k >= num_cells_) throw StatisticsError("direction cells: no cell " + std::to_string(k));
  const auto collar = std::find_if(collars_.begin(), collars_.end(),
                                   [&](const Collar& c) { return k < c.first + c.count; });
  const double z0 = collar->z_low, z1 = collar->z_high, dz = z1 - z0;
  const double zz = (z0 * z0 + z0 * z1 + z1 * z1) / 3.0;
  auto zs_antiderivative = [](double z) { return -std::pow(1.0 - z * z, 1.5) / 3.0; };
  const double zs = (zs_antiderivative(z1) - zs_antiderivative(z0)) / dz;
  const double p0 = 2.0 * kPi * (k - collar->first) / collar->count;
  const double dp = 2.0 * kPi / collar->count, p1 = p0 + dp;
  const double c = (std::sin(p1) - std::sin(p0)) / dp, s = (std::cos(p0) - std::cos(p1)) / dp;
  const double cc = 0.5 + (std::sin(2.0 * p1) - std::sin(2.0 * p0)) / (4.0 * dp);
  const double cs = (std::sin(p1) * std::sin(p1) - std::sin(p0) * std::sin(p0)) / (2.0 * dp);
  const double ss = 1.0 - cc;
  Eigen::Matrix3d m;
  m << (1.0 - zz) * cc, (1.0 - zz) * cs, zs * c,
       (1.0 - zz) * cs, (1.0 - zz) * ss, zs * s,
       zs * c, zs * s, zz;
  return m;
}

}  // namespace sff
