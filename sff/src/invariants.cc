#include "sff/invariants.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "sff/tensors.h"
#include "sffcal/constants.h"

namespace sff {

TensorInvariants tensor_invariants(const Eigen::Matrix3d& t) {
  TensorInvariants inv;
  const Eigen::Matrix3d s = sym(t);
  inv.mean = s.trace() / 3.0;
  const Eigen::Matrix3d d = dev(s);
  const double j2 = 0.5 * d.squaredNorm();
  inv.magnitude = std::sqrt(3.0 * j2);
  if (j2 > 0.0) {
    const double c = 1.5 * std::sqrt(3.0) * d.determinant() / std::pow(j2, 1.5);
    inv.lode_deg = std::acos(std::clamp(c, -1.0, 1.0)) / 3.0 * sffcal::kDegreesPerRadian;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(s);  // ascending
  for (int k = 0; k < 3; ++k) {
    inv.values[k] = eigen.eigenvalues()[2 - k];
    inv.directions.col(k) = eigen.eigenvectors().col(2 - k);
  }
  return inv;
}

double alignment(const Eigen::Matrix3d& t, const Eigen::Matrix3d& s) {
  const Eigen::Matrix3d a = dev(sym(t)), b = dev(sym(s));
  const double norms = a.norm() * b.norm();
  return norms > 0.0 ? (a.cwiseProduct(b)).sum() / norms : 0.0;
}

double triaxial_about(const Eigen::Matrix3d& t, const Eigen::Vector3d& n) {
  const double along = n.dot(t * n);
  return along - 0.5 * (t.trace() - along);
}

}  // namespace sff
