#include "sff/statistics.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "contact_stress_pass.h"
#include "force_moments.h"
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
  return internal::contact_stress_pass(contacts, volume, [](std::size_t, const ContactRecord&) {});
}

Eigen::Matrix3d particle_stress(ContactSpan contacts, const std::vector<Eigen::Vector3d>& centroids,
                                double volume) {
  if (!(volume > 0.0)) throw StatisticsError("particle_stress: the volume must be positive");
  auto centroid = [&](std::int64_t id) -> const Eigen::Vector3d& {
    if (id < 0 || static_cast<std::size_t>(id) >= centroids.size())
      throw StatisticsError("particle_stress: a contact names body " + std::to_string(id) +
                            " outside the centroid list");
    return centroids[static_cast<std::size_t>(id)];
  };
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (const ContactRecord& c : contacts) {
    const Eigen::Vector3d point(c.point[0], c.point[1], c.point[2]), f = force_of(c);
    sum.noalias() -= (point - centroid(c.body_b)) * f.transpose();  // force f on B
    if (!is_wall_contact(c)) sum.noalias() += (point - centroid(c.body_a)) * f.transpose();  // -f on A
  }
  return sym(sum) / volume;
}

Eigen::Matrix3d wall_contact_stress(ContactSpan contacts, const std::vector<Eigen::Vector3d>& centroids,
                                    double volume) {
  std::vector<ContactRecord> walls;
  for (const ContactRecord& c : contacts)
    if (is_wall_contact(c)) walls.push_back(c);
  return particle_stress(ContactSpan(walls), centroids, volume);
}

std::size_t count_body_contacts(ContactSpan contacts) {
  std::size_t n = 0;
  for (const ContactRecord& c : contacts) n += !is_wall_contact(c);
  return n;
}

Eigen::Matrix3d fabric_tensor(ContactSpan contacts) {
  Eigen::Matrix3d phi = Eigen::Matrix3d::Zero();
  const double n = for_each_body_contact(contacts, [&](const ContactRecord& c, double w) {
    const Eigen::Vector3d normal = normal_of(c);
    phi.noalias() += (w * normal) * normal.transpose();
  });
  if (!(n > 0.0)) throw StatisticsError("fabric_tensor: no body-body contacts");
  return phi / n;
}

Eigen::Matrix3d fabric_anisotropy(const Eigen::Matrix3d& fabric) { return 7.5 * dev(fabric); }

double ForceScale::factor(const ContactRecord& c) const {
  return branch_of(c).dot(normal_of(c)) / (2.0 * youngs_modulus * mean_solid_volume);
}

namespace internal {

ForceMoments accumulate_force_moments(ContactSpan contacts, const DirectionWeight& weight,
                                      const ForceScale& scale, double friction) {
  if (!(scale.youngs_modulus > 0.0 && scale.mean_solid_volume > 0.0))
    throw StatisticsError("the force scale needs E > 0 and v_bar > 0");
  ForceMoments m;
  m.count = for_each_body_contact(contacts, [&](const ContactRecord& c, double w) {
    const Eigen::Vector3d normal = normal_of(c), ft = tangential_of(c);
    const double factor = scale.factor(c);
    const double direction_weight = weight(normal);
    const double f_hat = c.normal_force * factor;
    m.normal.noalias() += (w * f_hat * direction_weight * normal) * normal.transpose();
    m.tangential.noalias() += (w * factor * ft) * normal.transpose();
    const double ft_norm = ft.norm();
    if (friction > 0.0 && ft_norm > 0.0 && c.normal_force > 0.0) {
      const double xi = std::min(1.0, ft_norm / (friction * c.normal_force));
      if (xi > 0.999) m.sliding += w;
      const Eigen::Matrix3d tn = (ft / ft_norm) * normal.transpose();
      m.weighted_mobilisation.noalias() += (w * xi * f_hat) * tn;
      m.mobilisation.noalias() += (w * xi * direction_weight) * tn;
    }
  });
  if (!(m.count > 0.0)) throw StatisticsError("no body-body contacts");
  return m;
}

}  // namespace internal

NormalForceStatistics normal_force_statistics(ContactSpan contacts, const Eigen::Matrix3d& fabric_a,
                                              const ForceScale& scale) {
  const internal::ForceMoments m =
      internal::accumulate_force_moments(contacts, DirectionWeight(contacts, fabric_a), scale, 0.0);
  return normal_force_statistics(m);
}

NormalForceStatistics normal_force_statistics(const internal::ForceMoments& m) {
  NormalForceStatistics s;
  const Eigen::Matrix3d moment = m.normal / m.count;
  s.lambda = moment.trace();
  if (!(s.lambda > 0.0)) throw StatisticsError("normal_force_statistics: the mean normal force is not positive");
  s.anisotropy = (7.5 / s.lambda) * dev(moment);
  return s;
}

Eigen::Matrix3d tangential_force_tensor(ContactSpan contacts, double lambda,
                                        const ForceScale& scale) {
  if (!(lambda > 0.0)) throw StatisticsError("tangential_force_tensor: Lambda must be positive");
  return tangential_force_tensor(
      internal::accumulate_force_moments(contacts, DirectionWeight(contacts, Eigen::Matrix3d::Zero()),
                                         scale, 0.0),
      lambda);
}

Eigen::Matrix3d tangential_force_tensor(const internal::ForceMoments& m, double lambda) {
  return sym(m.tangential) / (lambda * m.count);
}

}  // namespace sff
