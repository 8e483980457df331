#include "sff/assumption_checks.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <Eigen/Eigenvalues>

#include "sff/tensors.h"
#include "sffcal/constants.h"

namespace sff {
namespace {

std::vector<double> ranks(const std::vector<double>& x) {
  std::vector<std::size_t> order(x.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  std::vector<double> r(x.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && x[order[j + 1]] == x[order[i]]) ++j;
    const double mean_rank = 0.5 * static_cast<double>(i + j);
    for (std::size_t k = i; k <= j; ++k) r[order[k]] = mean_rank;
    i = j + 1;
  }
  return r;
}

}  // namespace

double pearson_correlation(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size() || x.size() < 2) return 0.0;
  const double n = static_cast<double>(x.size());
  const double mx = std::accumulate(x.begin(), x.end(), 0.0) / n;
  const double my = std::accumulate(y.begin(), y.end(), 0.0) / n;
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sxy += (x[k] - mx) * (y[k] - my);
    sxx += (x[k] - mx) * (x[k] - mx);
    syy += (y[k] - my) * (y[k] - my);
  }
  return sxx > 0.0 && syy > 0.0 ? sxy / std::sqrt(sxx * syy) : 0.0;
}

double spearman_correlation(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size() || x.size() < 2) return 0.0;
  return pearson_correlation(ranks(x), ranks(y));
}

BranchCheck branch_check(ContactSpan contacts) {
  std::vector<double> angles, lengths, forces;
  for_each_body_contact(contacts, [&](const ContactRecord& c, double) {
    const Eigen::Vector3d l = branch_of(c), n = normal_of(c);
    const double length = l.norm();
    if (!(length > 0.0)) return;
    angles.push_back(std::acos(std::clamp(l.dot(n) / length, -1.0, 1.0)) * sffcal::kDegreesPerRadian);
    lengths.push_back(l.dot(n));
    forces.push_back(c.normal_force);
  });
  if (angles.empty()) throw StatisticsError("branch_check: no body-body contacts with a branch vector");
  BranchCheck check;
  check.mean_angle_deg = std::accumulate(angles.begin(), angles.end(), 0.0) / static_cast<double>(angles.size());
  std::vector<double> sorted = angles;
  const auto p95 = static_cast<std::ptrdiff_t>(0.95 * static_cast<double>(sorted.size() - 1));
  std::nth_element(sorted.begin(), sorted.begin() + p95, sorted.end());
  check.p95_angle_deg = sorted[static_cast<std::size_t>(p95)];
  check.pearson_length_force = pearson_correlation(lengths, forces);
  check.spearman_length_force = spearman_correlation(lengths, forces);
  return check;
}

IndependenceCheck independence_check(ContactSpan contacts, double friction, const ForceScale& scale,
                                     double lambda, const Eigen::Matrix3d& normal_f,
                                     const Eigen::Matrix3d& weighted_mobilisation,
                                     const Eigen::Matrix3d& mobilisation_tensor,
                                     const DirectionCells& cells) {
  if (!(friction > 0.0)) throw StatisticsError("independence_check: friction must be positive");
  constexpr std::size_t kMinimumCell = 30;
  const auto num_cells = static_cast<std::size_t>(cells.size());
  std::vector<std::vector<double>> xi(num_cells), force(num_cells);
  Eigen::Matrix3d decoupled = Eigen::Matrix3d::Zero();
  const double n = for_each_body_contact(contacts, [&](const ContactRecord& c, double w) {
    const Eigen::Vector3d normal = normal_of(c), ft = tangential_of(c);
    const double ft_norm = ft.norm();
    const double mobilised =
        c.normal_force > 0.0 ? std::min(1.0, ft_norm / (friction * c.normal_force)) : 0.0;
    const auto cell = static_cast<std::size_t>(cells.cell_of(normal));
    xi[cell].push_back(mobilised);
    force[cell].push_back(c.normal_force * scale.factor(c));
    if (ft_norm > 0.0 && mobilised > 0.0)
      decoupled.noalias() +=
          (w * mobilised * (1.0 + normal.dot(normal_f * normal)) / ft_norm) * ft * normal.transpose();
  });
  if (!(n > 0.0 && lambda > 0.0)) throw StatisticsError("independence_check: no body-body contacts");
  IndependenceCheck check;
  double counted = 0.0;
  for (std::size_t b = 0; b < num_cells; ++b) {
    if (xi[b].size() < kMinimumCell) continue;
    const double rho = spearman_correlation(xi[b], force[b]);
    check.mean_spearman += rho * static_cast<double>(xi[b].size());
    counted += static_cast<double>(xi[b].size());
    check.max_abs_spearman = std::max(check.max_abs_spearman, std::abs(rho));
  }
  if (counted > 0.0) check.mean_spearman /= counted;
  decoupled = sym(decoupled) / n;
  const double norm = weighted_mobilisation.norm();
  if (norm > 0.0) {
    check.coupling_error = (weighted_mobilisation - decoupled).norm() / norm;
    check.leading_order_error = (weighted_mobilisation - mobilisation_tensor / 5.0).norm() / norm;
  }
  return check;
}

Eigen::Vector3d major_direction(const Eigen::Matrix3d& t) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(sym(t));
  return solver.eigenvectors().col(2);
}

double axis_angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double c = std::abs(a.normalized().dot(b.normalized()));
  return std::acos(std::min(1.0, c)) * sffcal::kDegreesPerRadian;
}

CoaxialityCheck coaxiality_check(const Eigen::Matrix3d& stress, const Eigen::Matrix3d& fabric_a,
                                 const Eigen::Matrix3d& normal_f, const Eigen::Matrix3d& tangential,
                                 const Eigen::Matrix3d& mobilisation_tensor) {
  const Eigen::Vector3d s = major_direction(stress);
  CoaxialityCheck check;
  check.fabric_deg = axis_angle_deg(major_direction(fabric_a), s);
  check.normal_deg = axis_angle_deg(major_direction(normal_f), s);
  check.tangential_deg = axis_angle_deg(major_direction(tangential), s);
  check.mobilisation_deg = axis_angle_deg(major_direction(mobilisation_tensor), s);
  return check;
}

StrongWeakSplit strong_weak_split(ContactSpan contacts, const ForceScale& scale, double volume) {
  double sum = 0.0;
  const double n = for_each_body_contact(
      contacts, [&](const ContactRecord& c, double w) { sum += w * c.normal_force * scale.factor(c); });
  if (!(n > 0.0)) throw StatisticsError("strong_weak_split: no body-body contacts");
  const double mean = sum / n;
  std::vector<double> strong(contacts.size(), 0.0), weak(contacts.size(), 0.0);
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const ContactRecord& c = contacts[k];
    const double w = contacts.weight(k);
    (c.normal_force * scale.factor(c) > mean ? strong : weak)[k] = w;
  }
  const ContactSpan strong_contacts = contacts.weighted(strong), weak_contacts = contacts.weighted(weak);
  StrongWeakSplit split;
  double strong_count = 0.0;
  for_each_body_contact(strong_contacts, [&](const ContactRecord&, double w) { strong_count += w; });
  split.strong_fraction = strong_count / n;
  if (strong_count > 0.0) split.a_c_strong = triaxial(fabric_anisotropy(fabric_tensor(strong_contacts)));
  if (strong_count < n) split.a_c_weak = triaxial(fabric_anisotropy(fabric_tensor(weak_contacts)));
  const Eigen::Matrix3d all = contact_stress(contacts, volume);
  const StressInvariants total = triaxial_invariants(all);
  const StressInvariants strong_part = triaxial_invariants(contact_stress(strong_contacts, volume));
  const StressInvariants weak_part = triaxial_invariants(contact_stress(weak_contacts, volume));
  if (total.q != 0.0) split.strong_q_share = strong_part.q / total.q;
  if (total.p != 0.0) split.weak_p_share = weak_part.p / total.p;
  return split;
}

}  // namespace sff
