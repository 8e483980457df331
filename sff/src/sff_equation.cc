#include "sff/sff_equation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "force_moments.h"
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

double concise_normal_anisotropy(double a, double t, double eta) {
  const double slope = 0.4 + (8.0 / 105.0) * a - (4.0 / 45.0) * a * eta;
  if (!std::isfinite(a) || !std::isfinite(t) || !std::isfinite(eta) || !(slope > 0.0)) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "no normal-force anisotropy gives the stress ratio %g with a_c = %g and a_t = %g "
                  "in the concise SFF form", eta, a, t);
    throw StatisticsError(text);
  }
  return (eta - 0.4 * a - 3.0 * t) / slope;
}

Mobilisation mobilisation(ContactSpan contacts, const Eigen::Matrix3d& fabric_a, double lambda,
                          double friction, const ForceScale& scale) {
  if (!(friction > 0.0)) throw StatisticsError("mobilisation: the friction coefficient must be positive");
  if (!(lambda > 0.0)) throw StatisticsError("mobilisation: Lambda must be positive");
  return mobilisation(
      internal::accumulate_force_moments(contacts, DirectionWeight(contacts, fabric_a), scale, friction),
      lambda);
}

Mobilisation mobilisation(const internal::ForceMoments& m, double lambda) {
  Mobilisation result;
  result.weighted = sym(m.weighted_mobilisation) / (lambda * m.count);
  result.tensor = 5.0 * sym(m.mobilisation) / m.count;
  result.sliding_fraction = m.sliding / m.count;
  return result;
}

double exact_decoupled_eta(ContactSpan contacts, double friction, double lambda,
                           const Eigen::Matrix3d& weighted_mobilisation, const ForceScale& scale) {
  Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
  const double n = for_each_body_contact(contacts, [&](const ContactRecord& c, double w) {
    const Eigen::Vector3d normal = normal_of(c);
    moment.noalias() += (w * c.normal_force * scale.factor(c) * normal) * normal.transpose();
  });
  if (!(n > 0.0)) throw StatisticsError("exact_decoupled_eta: no body-body contacts");
  moment /= n;
  return 3.0 * (triaxial(moment) + friction * lambda * triaxial(weighted_mobilisation)) /
         moment.trace();
}

Eigen::Matrix3d branch_remainder(ContactSpan contacts, double volume) {
  if (!(volume > 0.0)) throw StatisticsError("branch_remainder: the volume must be positive");
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for_each_body_contact(contacts, [&](const ContactRecord& c, double w) {
    const Eigen::Vector3d n = normal_of(c), l = branch_of(c);
    sum.noalias() += (w * (l - l.dot(n) * n)) * force_of(c).transpose();
  });
  return sym(sum) / volume;
}

}  // namespace sff
