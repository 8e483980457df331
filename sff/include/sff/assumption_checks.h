// Statistical checks of the assumptions behind the SFF equation (sff-theory.md §6 items 1, 3, 4)
// and the strong/weak contact split. Pure functions of contact records.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "sff/contacts.h"
#include "sff/direction_cells.h"
#include "sff/statistics.h"

namespace sff {

/// Pearson correlation of paired samples (0 when either has no spread).
double pearson_correlation(const std::vector<double>& x, const std::vector<double>& y);
/// Spearman rank correlation (ties get their mean rank).
double spearman_correlation(const std::vector<double>& x, const std::vector<double>& y);

/// §6.1: how far the branch vectors are from the normals, and whether branch length and normal
/// force are correlated (the SFF equation assumes l parallel to n and l independent of f_n).
struct BranchCheck {
  double mean_angle_deg = 0.0;   ///< mean angle between l and n
  double p95_angle_deg = 0.0;    ///< its 95th percentile
  double pearson_length_force = 0.0;   ///< corr(l.n, f_n)
  double spearman_length_force = 0.0;
};
BranchCheck branch_check(ContactSpan contacts);

/// §6.3: is the contact mobilisation xi independent of the normal force in each direction?
struct IndependenceCheck {
  double mean_spearman = 0.0;      ///< count-weighted mean over the direction cells of corr(xi, f_n)
  double max_abs_spearman = 0.0;   ///< largest |corr| over cells with >= 30 contacts
  /// |T_m - T_m^dec| / |T_m|, T_m^dec = (1/N_c) sum xi (1 + n.F.n) sym(tau n): the error of
  /// replacing each contact's normal force by its direction's mean.
  double coupling_error = 0.0;
  double leading_order_error = 0.0;  ///< |T_m - M/5| / |T_m|
};
IndependenceCheck independence_check(ContactSpan contacts, double friction, const ForceScale& scale,
                                     double lambda, const Eigen::Matrix3d& normal_f,
                                     const Eigen::Matrix3d& weighted_mobilisation,
                                     const Eigen::Matrix3d& mobilisation_tensor,
                                     const DirectionCells& cells);

/// Major principal direction (unit eigenvector of the largest eigenvalue) of a symmetric tensor.
Eigen::Vector3d major_direction(const Eigen::Matrix3d& t);
/// Angle between two axes (directions without sign), in [0, 90] deg.
double axis_angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

/// §6.4: angles of the major principal axes of A, F, F^t and M from that of the stress.
struct CoaxialityCheck {
  double fabric_deg = 0.0, normal_deg = 0.0, tangential_deg = 0.0, mobilisation_deg = 0.0;
};
CoaxialityCheck coaxiality_check(const Eigen::Matrix3d& stress, const Eigen::Matrix3d& fabric_a,
                                 const Eigen::Matrix3d& normal_f, const Eigen::Matrix3d& tangential,
                                 const Eigen::Matrix3d& mobilisation_tensor);

/// Strong and weak networks: contacts whose normalised normal force is above / at most the mean.
struct StrongWeakSplit {
  double strong_fraction = 0.0;  ///< share of the body-body contacts that are strong
  double a_c_strong = 0.0, a_c_weak = 0.0;  ///< t(A) of each network
  double strong_q_share = 0.0;   ///< q carried by the strong contacts / q of all
  double weak_p_share = 0.0;     ///< p carried by the weak contacts / p of all
};
StrongWeakSplit strong_weak_split(ContactSpan contacts, const ForceScale& scale, double volume);

}  // namespace sff
