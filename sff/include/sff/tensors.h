// Small tensor helpers shared by the SFF statistics. Compression positive; z is the loading axis.
#pragma once

#include <Eigen/Core>

namespace sff {

inline Eigen::Matrix3d sym(const Eigen::Matrix3d& t) { return 0.5 * (t + t.transpose()); }

inline Eigen::Matrix3d dev(const Eigen::Matrix3d& t) {
  return t - (t.trace() / 3.0) * Eigen::Matrix3d::Identity();
}

/// Triaxial scalar t(T) = T_zz - (T_xx + T_yy) / 2 (sff-theory.md §1).
inline double triaxial(const Eigen::Matrix3d& t) { return t(2, 2) - 0.5 * (t(0, 0) + t(1, 1)); }

/// Invariant magnitude sign(t(T)) sqrt(3/2 T:T) of a deviatoric tensor, for non-coaxial states.
double signed_invariant(const Eigen::Matrix3d& deviator);

/// Mean stress, deviator q = t(sigma), stress ratio and mobilised friction angle [rad] of a
/// (near-)axisymmetric stress: phi = asin(3 eta / (6 + eta)).
struct StressInvariants {
  double p = 0.0, q = 0.0, eta = 0.0, friction_angle = 0.0;
};
StressInvariants triaxial_invariants(const Eigen::Matrix3d& sigma);

}  // namespace sff
