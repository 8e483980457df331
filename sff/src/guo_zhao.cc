#include "sff/guo_zhao.h"

#include "sff/statistics.h"
#include "sff/tensors.h"

namespace sff {

Eigen::Matrix3d GuoZhaoAnisotropy::bracket(const Eigen::Matrix3d& fabric_a) const {
  return Eigen::Matrix3d::Identity() + 0.4 * (fabric_a + normal + branch) + 0.6 * tangential;
}

GuoZhaoAnisotropy guo_zhao_anisotropy(ContactSpan contacts, const DirectionWeight& weight) {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero(), tangential = Eigen::Matrix3d::Zero(),
                  branch = Eigen::Matrix3d::Zero();
  const double count = for_each_body_contact(contacts, [&](const ContactRecord& c, double w) {
    const Eigen::Vector3d n = normal_of(c);
    const double wn = w * weight(n);
    const Eigen::Matrix3d nn = n * n.transpose();
    normal.noalias() += (wn * c.normal_force) * nn;
    tangential.noalias() += (wn * tangential_of(c)) * n.transpose();
    branch.noalias() += (wn * branch_of(c).dot(n)) * nn;
  });
  if (!(count > 0.0)) throw StatisticsError("guo_zhao_anisotropy: no body-body contacts");
  GuoZhaoAnisotropy g;
  g.mean_normal_force = normal.trace() / count;
  g.mean_branch_length = branch.trace() / count;
  if (!(g.mean_normal_force > 0.0 && g.mean_branch_length > 0.0))
    throw StatisticsError("guo_zhao_anisotropy: the mean normal force or branch length is not positive");
  g.normal = 7.5 * dev(normal) / normal.trace();
  g.tangential = 5.0 * sym(tangential) / (count * g.mean_normal_force);
  g.branch = 7.5 * dev(branch) / branch.trace();
  return g;
}

}  // namespace sff
