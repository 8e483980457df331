// The stress-force-fabric equation (sff-theory.md §4) and its decoupled force term (§5).
#pragma once

#include <Eigen/Core>

#include "sff/contacts.h"
#include "sff/statistics.h"

namespace sff {

/// The state the SFF equation maps to a stress.
struct SffState {
  double youngs_modulus = 150e6;  ///< E [Pa]
  double coordination = 0.0;      ///< Z = 2 N_c / N_p
  double void_ratio = 0.0;        ///< e
  double lambda = 0.0;            ///< mean normalised normal force
  Eigen::Matrix3d fabric = Eigen::Matrix3d::Zero();      ///< A
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();      ///< F
  Eigen::Matrix3d tangential = Eigen::Matrix3d::Zero();  ///< F^t
};

/// sigma_SFF = (E Z Lambda / (1 + e)) [I/3 + (2/15)(A + F) + (2/105) tr(FA) I + (8/105) sym(FA)
/// + F^t]  (He & Cai 2019, eq. C0; the product terms from the sixth-order isotropic moment).
Eigen::Matrix3d sff_stress(const SffState& state);

/// The concise triaxial form for axisymmetric, coaxial A, F, F^t with a = t(A), f = t(F),
/// t = t(F^t): eta = [(2/5)(a + f) + (8/105) a f + 3 t] / [1 + (4/45) a f].
double concise_eta(double a, double f, double t);

/// The normal-force anisotropy f with which the concise form gives a measured stress ratio:
/// concise_eta(a, f, t) = eta, f = (eta - (2/5) a - 3 t) / ((2/5) + (8/105) a - (4/45) a eta)
/// (the concise form solved for f; it is linear in f over its denominator). Where the SFF
/// equation's truncation leaves the stress ratio of the measured a, f, t off the contacts' one,
/// this f closes it (the contact-network model's data, docs/network-model.md, "State and
/// stress"). Throws StatisticsError where no f gives eta (the bracket's coefficient of f not
/// positive, far outside any granular state) or an input is not finite.
double concise_normal_anisotropy(double a, double t, double eta);

/// Contact mobilisation (§5): xi = |f_t| / (mu f_n) in [0, 1], tau the unit tangential direction.
struct Mobilisation {
  Eigen::Matrix3d weighted = Eigen::Matrix3d::Zero();  ///< T_m: F^t = mu T_m exactly
  Eigen::Matrix3d tensor = Eigen::Matrix3d::Zero();    ///< M = 5 (1/N_c) sum xi sym(tau n) / (1 + n.A.n)
  double sliding_fraction = 0.0;                       ///< share of contacts with xi > 0.999
};
Mobilisation mobilisation(ContactSpan contacts, const Eigen::Matrix3d& fabric_a, double lambda,
                          double friction, const ForceScale& scale);
/// The same from moments already accumulated (internal use: one pass for all tensors).
Mobilisation mobilisation(const internal::ForceMoments& moments, double lambda);

/// The terms of the decoupled stress ratio (He et al. 2016, Eq. 27): eta ~ (2/5) a_c + (2/5) a_n
/// + (3/5) mu m (python/sffcal/sff_plots.py's decomposition_terms is the same split).
struct DecoupledTerms {
  double fabric = 0.0;        ///< (2/5) a_c
  double normal_force = 0.0;  ///< (2/5) a_n
  double mobilisation = 0.0;  ///< (3/5) mu m
};
inline DecoupledTerms decoupled_terms(double a_c, double a_n, double friction, double m) {
  return {0.4 * a_c, 0.4 * a_n, 0.6 * friction * m};
}

/// Decoupled stress ratio: eta ~ (2/5)(a_c + a_n) + (3/5) mu m, the sum of decoupled_terms.
inline double decoupled_eta(double a_c, double a_n, double friction, double m) {
  return 0.4 * (a_c + a_n) + 0.6 * friction * m;
}

/// Its exact counterpart without Fourier truncation (branch parallel to the normal):
/// eta = 3 [t(N') + mu Lambda t(T_m)] / tr N', N' = (1/N_c) sum f_hat_n n n.
double exact_decoupled_eta(ContactSpan contacts, double friction, double lambda,
                           const Eigen::Matrix3d& weighted_mobilisation, const ForceScale& scale);

/// Branch remainder R_b = (1/V) sum sym((l - (l.n) n) (x) f): zero for spheres; the part of the
/// contact stress that the SFF equation leaves out for clumps.
Eigen::Matrix3d branch_remainder(ContactSpan contacts, double volume);

}  // namespace sff
