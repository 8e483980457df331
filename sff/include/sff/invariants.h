// Frame-independent invariants of the SFF tensors (issue 18): what keeps its meaning when the
// major principal stress is not along z (extension, true triaxial, a tilted fabric). The
// triaxial scalars t(T) = T_zz - (T_xx + T_yy)/2 of tensors.h are taken about z; these are not.
#pragma once

#include <Eigen/Core>

namespace sff {

struct TensorInvariants {
  double mean = 0.0;       ///< tr T / 3
  double magnitude = 0.0;  ///< sqrt(3/2 T':T'), T' the deviator (q = sqrt(3 J2) of a stress)
  /// Lode angle of T' [deg] in [0, 60]: 0 with one major principal value and two equal minor ones
  /// (triaxial compression of a stress), 60 with one minor and two equal major (extension);
  /// cos 3 theta = (3 sqrt(3) / 2) J3 / J2^(3/2). 0 when T' = 0.
  double lode_deg = 0.0;
  Eigen::Vector3d values = Eigen::Vector3d::Zero();  ///< principal values, descending
  /// Unit principal directions, the columns in the order of `values` (each up to its sign).
  Eigen::Matrix3d directions = Eigen::Matrix3d::Identity();
};
/// Of a symmetric tensor.
TensorInvariants tensor_invariants(const Eigen::Matrix3d& t);

/// T':S' / (|T'| |S'|) in [-1, 1] of the deviators: 1 when T' points where S' does (e.g. a
/// fabric aligned with the stress), 0 when either deviator vanishes.
double alignment(const Eigen::Matrix3d& t, const Eigen::Matrix3d& s);

/// The triaxial scalar about a unit axis n: n.T.n - (tr T - n.T.n) / 2 (t(T) for n = z).
double triaxial_about(const Eigen::Matrix3d& t, const Eigen::Vector3d& n);

}  // namespace sff
