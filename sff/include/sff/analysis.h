// Everything sff computes for one snapshot (sff-theory.md §8), from its contact records.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "sff/assumption_checks.h"
#include "sff/bootstrap.h"
#include "sff/contacts.h"
#include "sff/directional.h"
#include "sff/guo_zhao.h"

namespace sff {

/// The directional tensors of sff-theory.md §3 and §5 from one set of (weighted) contacts.
struct DirectionalTensors {
  double lambda = 0.0;
  Eigen::Matrix3d fabric = Eigen::Matrix3d::Zero();        ///< A
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();        ///< F
  Eigen::Matrix3d tangential = Eigen::Matrix3d::Zero();    ///< F^t
  Eigen::Matrix3d weighted_mobilisation = Eigen::Matrix3d::Zero();  ///< T_m
  Eigen::Matrix3d mobilisation = Eigen::Matrix3d::Zero();  ///< M
  double sliding_fraction = 0.0;
  /// 1 + lambda_min(A); at 0.1 or less the weights are binned (direction_weight.h).
  double min_density = 1.0;
  bool binned_weights = false;
};
DirectionalTensors directional_tensors(ContactSpan contacts, const ForceScale& scale, double friction);

/// Largest principal value of a symmetric tensor, its axis (sign chosen with z >= 0) and the
/// axis' angle from the loading axis z [deg]: what a non-coaxial state (bedding at alpha) needs.
struct PrincipalAxis {
  double major = 0.0;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double tilt_deg = 0.0;
};
PrincipalAxis principal_axis(const Eigen::Matrix3d& t);

struct SnapshotInput {
  ContactSpan contacts;        ///< body-body and wall contacts of the snapshot
  double volume = 0.0;         ///< box volume [m^3]
  double solid_volume = 0.0;   ///< sum of the body volumes [m^3]
  int num_bodies = 0;
  double youngs_modulus = 150e6;  ///< [Pa], for the force normalisation
  double friction = 0.5773502691896257;  ///< grain friction mu, for the mobilisation
  /// Principal stresses the walls measure (x, y, z) [Pa]; all zero when unknown.
  Eigen::Vector3d wall_stress = Eigen::Vector3d::Zero();
  /// Body centroids indexed by body id, for the particle form with the wall contacts (empty:
  /// compare the walls with the contact form instead).
  std::vector<Eigen::Vector3d> centroids;
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
  double a_c_invariant = 0.0, a_n_invariant = 0.0, a_t_invariant = 0.0, m_invariant = 0.0;  ///< sign(t) sqrt(3/2 T:T)
  double wall_eta = 0.0;            ///< q/p of the wall stress (0 when unknown)
  /// max_i |sigma_ii - sigma_ii(walls)| / p(walls), sigma the particle form with the wall
  /// contacts (equal to the wall stress in equilibrium); the contact form without centroids.
  double wall_stress_error = 0.0;
  double wall_layer_ratio = 0.0;    ///< |wall-contact terms| / |sigma|: what the contact form misses
  /// 1 + lambda_min(A), and whether it was too small for second-order weights (sff-theory.md §8:
  /// the estimators then used binned densities; a warning for the report).
  double min_density = 1.0;
  bool binned_weights = false;
  /// The Guo & Zhao (2013) convention and the branch-length anisotropy (guo_zhao.h).
  GuoZhaoAnisotropy guo_zhao;
  double a_n_gz = 0.0, a_t_gz = 0.0, a_l = 0.0;  ///< t() of a^n, a^t, a^l
  double eta_gz = 0.0;  ///< q/p of (2/5)(A + a^n + a^l) + (3/5) a^t about I (first order)
  PrincipalAxis stress_axis, fabric_axis, normal_axis, tangential_axis, mobilisation_axis;
  Eigen::Matrix3d weighted_mobilisation = Eigen::Matrix3d::Zero();  ///< T_m
  Eigen::Matrix3d stress = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d fabric = Eigen::Matrix3d::Zero();      ///< A
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();      ///< F
  Eigen::Matrix3d tangential = Eigen::Matrix3d::Zero();  ///< F^t
  Eigen::Matrix3d mobilisation = Eigen::Matrix3d::Zero();  ///< M
};

/// Checks its input first, as it may not come from a run file (whose reader checks its snapshots:
/// runfile/src/snapshot_check.h), e.g. contacts given from Python: positive volumes, body count,
/// modulus and friction; every number finite; unit normals (to 1e-6); body ids in [0, num_bodies)
/// and a wall contact's A a wall (body_a = -1, wall >= 0); one centroid per body where given. The
/// contacts are checked in the stress's pass over them, so the check costs almost nothing.
/// Throws std::invalid_argument naming the first contact and field that is not valid, and
/// StatisticsError where a statistic is undefined (no contacts, no force).
SnapshotAnalysis analyse_snapshot(const SnapshotInput& input);

/// The statistical checks of sff-theory.md §6 for one snapshot, and the strong/weak split.
struct SnapshotChecks {
  BranchCheck branch;
  TruncationCheck truncation;
  IndependenceCheck independence;
  CoaxialityCheck coaxiality;
  StrongWeakSplit strong_weak;
  BootstrapIntervals bootstrap;
};
struct CheckOptions {
  int cells = 41;           ///< equal-area direction cells (odd) of the §6.2 and §6.3 checks
  int resamples = 200;      ///< bootstrap resamples (0: skip the bootstrap)
  std::uint64_t seed = 1;   ///< bootstrap seed
};
SnapshotChecks check_snapshot(const SnapshotInput& input, const SnapshotAnalysis& analysis,
                              const CheckOptions& options = {});

/// Z_m: iteratively drops bodies with fewer than two body-body contacts, then 2 N_c / N_p.
double mechanical_coordination(ContactSpan contacts, int num_bodies);

/// The scalar columns of the per-snapshot table, and one row of it.
const std::vector<std::string>& analysis_columns();
std::vector<double> analysis_row(const SnapshotAnalysis& a);

/// The columns of the per-snapshot table of checks, and one row of it.
const std::vector<std::string>& check_columns();
std::vector<double> check_row(const SnapshotChecks& c);

}  // namespace sff
