#include "sff/sff_equation.h"

#include <algorithm>
#include <cmath>

#include "sff/tensors.h"

namespace sff {

Eigen::Matrix3d sff_stress(const SffState& s) {
  const Eigen::Matrix3d& a = s.fabric;
  const Eigen::Matrix3d& f = s.normal;
  const Eigen::Matrix3d fa = f * a;
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d bracket = identity / 3.0 + (2.0 / 15.0) * (a + f) +
                                  (2.0 / 105.0) * fa.trace() * identity + (8.0 / 105.0) * sym(fa) +
                                  s.tangential;
  return (s.youngs_modulus * s.coordination * s.lambda / (1.0 + s.void_ratio)) * bracket;
}

double concise_eta(double a, double f, double t) {
  return (0.4 * (a + f) + (8.0 / 105.0) * a * f + 3.0 * t) / (1.0 + (4.0 / 45.0) * a * f);
}

Mobilisation mobilisation(ContactSpan contacts, const Eigen::Matrix3d& fabric_a, double lambda,
                          double friction, const ForceScale& scale) {
  if (!(friction > 0.0)) throw StatisticsError("mobilisation: the friction coefficient must be positive");
  if (!(lambda > 0.0)) throw StatisticsError("mobilisation: Lambda must be positive");
  Mobilisation m;
  Eigen::Matrix3d weighted = Eigen::Matrix3d::Zero(), plain = Eigen::Matrix3d::Zero();
  std::size_t n = 0, sliding = 0;
  for (const ContactRecord& c : contacts) {
    if (is_wall_contact(c)) continue;
    ++n;
    const Eigen::Vector3d ft = tangential_of(c);
    const double ft_norm = ft.norm();
    if (ft_norm == 0.0 || c.normal_force <= 0.0) continue;
    const Eigen::Vector3d normal = normal_of(c), tau = ft / ft_norm;
    const double xi = std::min(1.0, ft_norm / (friction * c.normal_force));
    sliding += xi > 0.999;
    const Eigen::Matrix3d tn = tau * normal.transpose();
    weighted.noalias() += (xi * c.normal_force * scale.factor(c)) * tn;
    const double w = 1.0 + normal.dot(fabric_a * normal);
    if (!(w > 0.1)) throw StatisticsError("mobilisation: the fabric anisotropy is too strong for second-order weights");
    plain.noalias() += (xi / w) * tn;
  }
  if (n == 0) throw StatisticsError("mobilisation: no body-body contacts");
  m.weighted = sym(weighted) / (lambda * static_cast<double>(n));
  m.tensor = 5.0 * sym(plain) / static_cast<double>(n);
  m.sliding_fraction = static_cast<double>(sliding) / static_cast<double>(n);
  return m;
}

double exact_decoupled_eta(ContactSpan contacts, double friction, double lambda,
                           const Eigen::Matrix3d& weighted_mobilisation, const ForceScale& scale) {
  Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
  std::size_t n = 0;
  for (const ContactRecord& c : contacts) {
    if (is_wall_contact(c)) continue;
    const Eigen::Vector3d normal = normal_of(c);
    moment.noalias() += (c.normal_force * scale.factor(c)) * normal * normal.transpose();
    ++n;
  }
  if (n == 0) throw StatisticsError("exact_decoupled_eta: no body-body contacts");
  moment /= static_cast<double>(n);
  return 3.0 * (triaxial(moment) + friction * lambda * triaxial(weighted_mobilisation)) /
         moment.trace();
}

Eigen::Matrix3d branch_remainder(ContactSpan contacts, double volume) {
  if (!(volume > 0.0)) throw StatisticsError("branch_remainder: the volume must be positive");
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (const ContactRecord& c : contacts) {
    if (is_wall_contact(c)) continue;
    const Eigen::Vector3d n = normal_of(c), l = branch_of(c);
    sum.noalias() += (l - l.dot(n) * n) * force_of(c).transpose();
  }
  return sym(sum) / volume;
}

}  // namespace sff
