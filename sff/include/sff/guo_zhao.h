// The anisotropy coefficients in the convention of Guo & Zhao (2013, Comput. Geotech. 47:1-15,
// after Ouadfel & Rothenburg 2001), beside this project's normalised forces (sff-theory.md §3):
// raw forces, and the branch length as a fourth directional quantity. With direction averages
// <g>_Omega (direction_weight.h):
//   f_n(n) = f_0 (1 + n.a^n.n),   f_0 = tr <f_n n n>,  a^n = (15 / 2) dev <f_n n n> / f_0;
//   f_t(n) = f_0 (a^t n - (n.a^t.n) n),                a^t = 5 sym <f_t (x) n> / f_0;
//   l(n)   = l_0 (1 + n.a^l.n),   l_0 = tr <l n n>,    a^l = (15 / 2) dev <l n n> / l_0;
// l = l.n, the branch length the normalised force f_hat = f l / (2 E v_bar) also uses. To first
// order, sigma = (N_c l_0 f_0 / 3V) [I + (2/5)(A + a^n + a^l) + (3/5) a^t].
// Today's a_n (of f_hat ~ f_n l) carries the branch-length anisotropy; a^n here does not.
#pragma once

#include <Eigen/Core>

#include "sff/contacts.h"
#include "sff/direction_weight.h"

namespace sff {

struct GuoZhaoAnisotropy {
  double mean_normal_force = 0.0;    ///< f_0 [N]
  double mean_branch_length = 0.0;   ///< l_0 [m]
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();      ///< a^n
  Eigen::Matrix3d tangential = Eigen::Matrix3d::Zero();  ///< a^t
  Eigen::Matrix3d branch = Eigen::Matrix3d::Zero();      ///< a^l
  /// The first-order stress bracket I + (2/5)(A + a^n + a^l) + (3/5) a^t (its q/p is eta_gz).
  Eigen::Matrix3d bracket(const Eigen::Matrix3d& fabric_a) const;
};

/// Throws StatisticsError without body-body contacts or with f_0 or l_0 not positive.
GuoZhaoAnisotropy guo_zhao_anisotropy(ContactSpan contacts, const DirectionWeight& weight);

}  // namespace sff
