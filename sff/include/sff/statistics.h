// The SFF estimators of sff-theory.md §§2-3: average stress, fabric and anisotropy tensors, and
// the normal and tangential force statistics. Pure functions of contact records; wall contacts
// are skipped wherever a statistic is defined on body-body contacts only.
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <vector>

#include "sff/contacts.h"

namespace sff {

/// Contact form of the Love-Weber stress over body-body contacts, (1/V) sum sym(l (x) f) [Pa]
/// (weighted: the stress a sub-network carries).
Eigen::Matrix3d contact_stress(ContactSpan contacts, double volume);

/// Particle form of the Love-Weber stress over all contacts, walls included:
/// -(1/V) sum_p sum_{c in p} sym((x^c - x^p) (x) f^{c->p}) [Pa]. centroids[id] is the centroid of
/// body id. Equals contact_stress + wall_contact_stress identically (sff-theory.md T2).
Eigen::Matrix3d particle_stress(ContactSpan contacts, const std::vector<Eigen::Vector3d>& centroids,
                                double volume);

/// The wall contacts' share of the particle form: -(1/V) sum sym((x^c - x^p) (x) f) over them.
Eigen::Matrix3d wall_contact_stress(ContactSpan contacts, const std::vector<Eigen::Vector3d>& centroids,
                                    double volume);

/// Number of body-body contacts (unweighted).
std::size_t count_body_contacts(ContactSpan contacts);

/// Fabric tensor phi = (1/N_c) sum n (x) n (trace 1).
Eigen::Matrix3d fabric_tensor(ContactSpan contacts);

/// Anisotropy tensor A = (15/2) dev(phi): E(n) = (1 + n.A.n) / 4 pi to second order.
Eigen::Matrix3d fabric_anisotropy(const Eigen::Matrix3d& fabric);

/// Normalisation of forces (sff-theory.md §3, [PROP]): f_hat = f l / (2 E v_bar), with
/// l = branch . normal, E the grain modulus, v_bar the mean solid volume per body.
struct ForceScale {
  double youngs_modulus = 150e6;    ///< [Pa]
  double mean_solid_volume = 0.0;   ///< [m^3]
  double factor(const ContactRecord& c) const;
};

/// Normal-force statistics: N = (1/N_c) sum f_hat_n n n w(n), Lambda = tr N,
/// F = 15 / (2 Lambda) dev N, so that the mean normal force by direction is Lambda (1 + n.F.n);
/// w(n) = 1 / (1 + n.A.n), or the binned weight of direction_weight.h for a very strong fabric.
struct NormalForceStatistics {
  double lambda = 0.0;
  Eigen::Matrix3d anisotropy = Eigen::Matrix3d::Zero();  ///< F
};
NormalForceStatistics normal_force_statistics(ContactSpan contacts, const Eigen::Matrix3d& fabric_a,
                                              const ForceScale& scale);

namespace internal {
struct ForceMoments;
}
/// The same from moments already accumulated (internal use: one pass for all tensors).
NormalForceStatistics normal_force_statistics(const internal::ForceMoments& moments);

/// Tangential-force tensor F^t = (1 / (Lambda N_c)) sum sym(f_hat_t (x) n) (traceless).
Eigen::Matrix3d tangential_force_tensor(ContactSpan contacts, double lambda,
                                        const ForceScale& scale);
/// The same from moments already accumulated (internal use).
Eigen::Matrix3d tangential_force_tensor(const internal::ForceMoments& moments, double lambda);

/// Thrown for statistics that are undefined (no contacts, Lambda = 0, a non-finite tensor).
struct StatisticsError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace sff
