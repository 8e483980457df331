// Internal: the one pass over the contacts that accumulates every force moment of sff-theory.md
// §3 and §5 (normal, tangential, mobilisation), shared by the public estimators so that the
// bootstrap pays for one pass per resample instead of one per tensor.
#pragma once

#include <Eigen/Core>

#include "sff/contacts.h"
#include "sff/direction_weight.h"
#include "sff/statistics.h"

namespace sff::internal {

struct ForceMoments {
  double count = 0.0;                                     ///< weighted N_c
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();       ///< sum f_hat_n n n w(n)
  Eigen::Matrix3d tangential = Eigen::Matrix3d::Zero();   ///< sum f_hat_t n (not symmetrised)
  Eigen::Matrix3d weighted_mobilisation = Eigen::Matrix3d::Zero();  ///< sum xi f_hat_n tau n
  Eigen::Matrix3d mobilisation = Eigen::Matrix3d::Zero();  ///< sum xi tau n w(n)
  double sliding = 0.0;                                   ///< weighted count with xi > 0.999
};

/// w is the direction weight (second order or binned). friction <= 0 skips the mobilisation
/// moments.
ForceMoments accumulate_force_moments(ContactSpan contacts, const DirectionWeight& weight,
                                      const ForceScale& scale, double friction);

}  // namespace sff::internal
