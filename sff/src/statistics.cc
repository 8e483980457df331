#include "sff/statistics.h"

#include <algorithm>
#include <cmath>

#include "sff/tensors.h"

namespace sff {

double signed_invariant(const Eigen::Matrix3d& deviator) {
  const double magnitude = std::sqrt(1.5 * deviator.squaredNorm());
  return triaxial(deviator) < 0.0 ? -magnitude : magnitude;
}

StressInvariants triaxial_invariants(const Eigen::Matrix3d& sigma) {
  StressInvariants s;
  s.p = sigma.trace() / 3.0;
  s.q = triaxial(sigma);
  s.eta = s.p != 0.0 ? s.q / s.p : 0.0;
  s.friction_angle = std::asin(std::clamp(3.0 * s.eta / (6.0 + s.eta), -1.0, 1.0));
  return s;
}

Eigen::Matrix3d contact_stress(ContactSpan contacts, double volume) {
  if (!(volume > 0.0)) throw StatisticsError("contact_stress: the volume must be positive");
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (const ContactRecord& c : contacts) {
    if (is_wall_contact(c)) continue;
    sum.noalias() += branch_of(c) * force_of(c).transpose();
  }
  return sym(sum) / volume;
}

std::size_t count_body_contacts(ContactSpan contacts) {
  std::size_t n = 0;
  for (const ContactRecord& c : contacts) n += !is_wall_contact(c);
  return n;
}

Eigen::Matrix3d fabric_tensor(ContactSpan contacts) {
  Eigen::Matrix3d phi = Eigen::Matrix3d::Zero();
  std::size_t n = 0;
  for (const ContactRecord& c : contacts) {
    if (is_wall_contact(c)) continue;
    const Eigen::Vector3d normal = normal_of(c);
    phi.noalias() += normal * normal.transpose();
    ++n;
  }
  if (n == 0) throw StatisticsError("fabric_tensor: no body-body contacts");
  return phi / static_cast<double>(n);
}

Eigen::Matrix3d fabric_anisotropy(const Eigen::Matrix3d& fabric) { return 7.5 * dev(fabric); }

double ForceScale::factor(const ContactRecord& c) const {
  return branch_of(c).dot(normal_of(c)) / (2.0 * youngs_modulus * mean_solid_volume);
}

namespace {

// 1 / (1 + n.A.n), refused where the second-order density is not positive (sff-theory.md §8).
double inverse_density_weight(const Eigen::Matrix3d& a, const Eigen::Vector3d& n) {
  const double w = 1.0 + n.dot(a * n);
  if (!(w > 0.1))
    throw StatisticsError(
        "the fabric anisotropy is too strong for second-order weights (1 + n.A.n <= 0.1); use "
        "binned estimates");
  return 1.0 / w;
}

}  // namespace

NormalForceStatistics normal_force_statistics(ContactSpan contacts, const Eigen::Matrix3d& fabric_a,
                                              const ForceScale& scale) {
  if (!(scale.youngs_modulus > 0.0 && scale.mean_solid_volume > 0.0))
    throw StatisticsError("normal_force_statistics: the force scale needs E > 0 and v_bar > 0");
  Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
  std::size_t n = 0;
  for (const ContactRecord& c : contacts) {
    if (is_wall_contact(c)) continue;
    const Eigen::Vector3d normal = normal_of(c);
    const double f_hat = c.normal_force * scale.factor(c);
    moment.noalias() += (f_hat * inverse_density_weight(fabric_a, normal)) * normal * normal.transpose();
    ++n;
  }
  if (n == 0) throw StatisticsError("normal_force_statistics: no body-body contacts");
  moment /= static_cast<double>(n);
  NormalForceStatistics s;
  s.lambda = moment.trace();
  if (!(s.lambda > 0.0)) throw StatisticsError("normal_force_statistics: the mean normal force is not positive");
  s.anisotropy = (7.5 / s.lambda) * dev(moment);
  return s;
}

Eigen::Matrix3d tangential_force_tensor(ContactSpan contacts, double lambda,
                                        const ForceScale& scale) {
  if (!(lambda > 0.0)) throw StatisticsError("tangential_force_tensor: Lambda must be positive");
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  std::size_t n = 0;
  for (const ContactRecord& c : contacts) {
    if (is_wall_contact(c)) continue;
    sum.noalias() += (scale.factor(c) * tangential_of(c)) * normal_of(c).transpose();
    ++n;
  }
  if (n == 0) throw StatisticsError("tangential_force_tensor: no body-body contacts");
  return sym(sum) / (lambda * static_cast<double>(n));
}

}  // namespace sff
