// Everything sff computes for one snapshot (sff-theory.md §8), from its contact records.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "sff/contacts.h"

namespace sff {

struct SnapshotInput {
  ContactSpan contacts;        ///< body-body and wall contacts of the snapshot
  double volume = 0.0;         ///< box volume [m^3]
  double solid_volume = 0.0;   ///< sum of the body volumes [m^3]
  int num_bodies = 0;
  double youngs_modulus = 150e6;  ///< [Pa], for the force normalisation
  double friction = 0.5773502691896257;  ///< grain friction mu, for the mobilisation
};

struct SnapshotAnalysis {
  double p = 0.0, q = 0.0, eta = 0.0;     ///< contact stress (body-body contacts) [Pa]
  double void_ratio = 0.0;
  double coordination = 0.0;              ///< Z = 2 N_c / N_p
  double mechanical_coordination = 0.0;   ///< Z_m, rattlers (< 2 contacts) removed
  double lambda = 0.0;
  double a_c = 0.0, a_n = 0.0, a_t = 0.0, m = 0.0;  ///< t() of A, F, F^t, M
  double eta_sff = 0.0;        ///< from the full tensor equation C0
  double eta_concise = 0.0;    ///< concise triaxial form
  double eta_decoupled = 0.0;  ///< (2/5)(a_c + a_n) + (3/5) mu m
  double eta_exact = 0.0;      ///< exact decoupled form
  double sff_error = 0.0;      ///< |sigma_SFF - sigma| / |sigma| (Frobenius)
  double branch_ratio = 0.0;   ///< |R_b| / |sigma|
  double sliding_fraction = 0.0;
  Eigen::Matrix3d stress = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d fabric = Eigen::Matrix3d::Zero();      ///< A
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();      ///< F
  Eigen::Matrix3d tangential = Eigen::Matrix3d::Zero();  ///< F^t
  Eigen::Matrix3d mobilisation = Eigen::Matrix3d::Zero();  ///< M
};

/// Throws StatisticsError where a statistic is undefined (no contacts, no force).
SnapshotAnalysis analyse_snapshot(const SnapshotInput& input);

/// Z_m: iteratively drops bodies with fewer than two body-body contacts, then 2 N_c / N_p.
double mechanical_coordination(ContactSpan contacts, int num_bodies);

/// Solid volume of a two-sphere clump (equal spheres of radius r, centres s apart; s = 0 for a
/// sphere): 8 pi r^3 / 3 - pi (4r + s)(2r - s)^2 / 12.
double clump_volume(double radius, double centre_distance);

/// The scalar columns of the per-snapshot table, and one row of it.
const std::vector<std::string>& analysis_columns();
std::vector<double> analysis_row(const SnapshotAnalysis& a);

}  // namespace sff
