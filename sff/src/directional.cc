#include "sff/directional.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Dense>

#include "sff/direction_weight.h"
#include "sff/tensors.h"
#include "sffcal/constants.h"

namespace sff {
namespace {

using sffcal::kPi;

// Running weighted sums of one quantity in one cell.
struct Moments {
  double weight = 0.0, sum = 0.0, sum_squares = 0.0;
  void add(double w, double x) {
    weight += w;
    sum += w * x;
    sum_squares += w * x * x;
  }
  double mean() const { return weight > 0.0 ? sum / weight : 0.0; }
  double standard_error() const {
    if (weight <= 1.0) return 0.0;
    const double variance = std::max(0.0, sum_squares / weight - mean() * mean());
    return std::sqrt(variance / weight);
  }
};

// A symmetric fourth-order tensor by its 15 distinct entries (i <= j <= k <= l), what the
// moments accumulate per contact; expanded to all 81 entries once, for the harmonic part.
constexpr std::array<std::array<int, 4>, 15> kDistinct = {{
    {0, 0, 0, 0}, {0, 0, 0, 1}, {0, 0, 0, 2}, {0, 0, 1, 1}, {0, 0, 1, 2}, {0, 0, 2, 2},
    {0, 1, 1, 1}, {0, 1, 1, 2}, {0, 1, 2, 2}, {0, 2, 2, 2}, {1, 1, 1, 1}, {1, 1, 1, 2},
    {1, 1, 2, 2}, {1, 2, 2, 2}, {2, 2, 2, 2}}};
using SymmetricTensor4 = std::array<double, 15>;
using Tensor4 = std::array<double, 81>;
int index4(int i, int j, int k, int l) { return 27 * i + 9 * j + 3 * k + l; }

// t += w sym(v (x) n (x) n (x) n): the average over the four places of v (n (x) n (x) n is
// symmetric already). v = n gives w n (x) n (x) n (x) n.
void add_dyad4(SymmetricTensor4& t, double w, const Eigen::Vector3d& v, const Eigen::Vector3d& n) {
  for (std::size_t m = 0; m < kDistinct.size(); ++m) {
    const auto [i, j, k, l] = kDistinct[m];
    t[m] += 0.25 * w *
            (v[i] * n[j] * n[k] * n[l] + n[i] * v[j] * n[k] * n[l] + n[i] * n[j] * v[k] * n[l] +
             n[i] * n[j] * n[k] * v[l]);
  }
}

Tensor4 expand(const SymmetricTensor4& t) {
  Tensor4 full{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) {
          std::array<int, 4> sorted = {i, j, k, l};
          std::sort(sorted.begin(), sorted.end());
          const auto m = std::find(kDistinct.begin(), kDistinct.end(), sorted) - kDistinct.begin();
          full[index4(i, j, k, l)] = t[static_cast<std::size_t>(m)];
        }
  return full;
}

// Frobenius norm of the harmonic (fully traceless) part of a symmetric fourth-order tensor T:
// H = T - (6/7) S(delta, T2) + (3/35) tr(T2) S(delta, delta), T2_ij = T_ijkk, S the symmetrised
// products (Kanatani 1984; on the unit sphere T::nnnn = H::nnnn + (6/7) dev(T2):nn + tr(T2)/5).
double harmonic_norm4(const SymmetricTensor4& distinct) {
  const Tensor4 t = expand(distinct);
  Eigen::Matrix3d t2 = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) t2(i, j) += t[index4(i, j, k, k)];
  const double trace = t2.trace();
  auto d = [](int a, int b) { return a == b ? 1.0 : 0.0; };
  double squares = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) {
          const double s_t2 = (d(i, j) * t2(k, l) + d(i, k) * t2(j, l) + d(i, l) * t2(j, k) +
                               d(j, k) * t2(i, l) + d(j, l) * t2(i, k) + d(k, l) * t2(i, j)) /
                              6.0;
          const double s_dd = (d(i, j) * d(k, l) + d(i, k) * d(j, l) + d(i, l) * d(j, k)) / 3.0;
          const double h = t[index4(i, j, k, l)] - (6.0 / 7.0) * s_t2 + (3.0 / 35.0) * trace * s_dd;
          squares += h * h;
        }
  return std::sqrt(squares);
}

// One coefficient tensor of the harmonic series, estimated by a weighted mean over contacts
// c = sum s_k x_k / S of per-contact tensors x_k (s_k the contacts' weights).
struct CoefficientEstimate {
  double norm = 0.0;          ///< |c|
  double sum_s2_x2 = 0.0;     ///< sum s_k^2 |x_k|^2
  double sum_s2 = 0.0, sum_s = 0.0;
  /// |c|^2 less its sampling variance sum s_k^2 |x_k - c|^2 / S^2: |c_hat|^2 exceeds |c|^2 by that
  /// much on average, which would make the ratio of N contacts at least about 9 / sqrt(N).
  double debiased_square() const {
    const double variance = (sum_s2_x2 - norm * norm * sum_s2) / (sum_s * sum_s);
    return norm * norm - variance;
  }
};

// Amplitude of the degree-4 part over that of the degree-2 part of D2:nn + D4::nnnn on the
// sphere: (2l+1)/(4 pi) int (D_l . n^l)^2 dOmega is (2/3)|D2|^2 and (8/35)|D4|^2 for harmonic
// D_l, i.e. |c_l| of a Legendre series c_l P_l. Bias-corrected; 0 without a second-order part.
double fourth_over_second(const CoefficientEstimate& second, const CoefficientEstimate& fourth) {
  const double second_power = (2.0 / 3.0) * second.debiased_square();
  const double fourth_power = (8.0 / 35.0) * std::max(0.0, fourth.debiased_square());
  return second_power > 0.0 ? std::sqrt(fourth_power / second_power) : 0.0;
}

// measured, form and error: one row per cell, one column per component.
TruncationFit compare(const Eigen::MatrixXd& measured, const Eigen::MatrixXd& form,
                      const Eigen::MatrixXd& error, int fitted_parameters, double fourth_order_ratio) {
  TruncationFit fit;
  const Eigen::MatrixXd residual = measured - form;
  const Eigen::RowVectorXd mean = measured.colwise().mean();
  const double total = (measured.rowwise() - mean).squaredNorm();
  fit.r_squared = total > 0.0 ? 1.0 - residual.squaredNorm() / total : 0.0;
  fit.relative_l2 = measured.norm() > 0.0 ? residual.norm() / measured.norm() : 0.0;
  double chi2 = 0.0;
  int used = 0;
  for (Eigen::Index k = 0; k < measured.size(); ++k) {
    if (!(error(k) > 0.0)) continue;
    chi2 += residual(k) * residual(k) / (error(k) * error(k));
    ++used;
  }
  const int dof = used - fitted_parameters;
  fit.chi2_per_dof = dof > 0 ? chi2 / dof : 0.0;
  fit.fourth_order_ratio = fourth_order_ratio;
  return fit;
}

}  // namespace

TruncationCheck truncation_check(ContactSpan contacts, const ForceScale& scale,
                                 const Eigen::Matrix3d& fabric_a, double lambda,
                                 const Eigen::Matrix3d& normal_f, const DirectionCells& cells) {
  if (!(lambda > 0.0)) throw StatisticsError("truncation_check: Lambda must be positive");
  const DirectionWeight weight(contacts, fabric_a);
  // Pass 1: the moments of the second- and fourth-order coefficients (Kanatani 1984), and the
  // Ouadfel-Rothenburg tensor of the tangential field. Per contact, |dev(n n)|^2 = 2/3,
  // |H(n n n n)|^2 = 8/35 and, for f_t normal to n, |sym(f_t n)|^2 = |f_t|^2 / 2 and
  // |H(sym(f_t n n n))|^2 = |f_t|^2 / 7: the sampling variances need only these scalars.
  SymmetricTensor4 density4{}, force4{}, shear4{};
  Eigen::Matrix3d density2 = Eigen::Matrix3d::Zero(), force2 = Eigen::Matrix3d::Zero(),
                  shear2 = Eigen::Matrix3d::Zero();
  double sum_s2 = 0.0, force_squares = 0.0, shear_squares = 0.0;
  const double total = for_each_body_contact(contacts, [&](const ContactRecord& c, double w) {
    const Eigen::Vector3d n = normal_of(c);
    const double factor = scale.factor(c), direction_weight = weight(n);
    const double f_hat = c.normal_force * factor;
    const Eigen::Vector3d ft_hat = factor * tangential_of(c);
    density2.noalias() += (w * n) * n.transpose();
    add_dyad4(density4, w, n, n);
    force2.noalias() += (w * direction_weight * f_hat * n) * n.transpose();
    add_dyad4(force4, w * direction_weight * f_hat, n, n);
    shear2.noalias() += (w * direction_weight * ft_hat) * n.transpose();
    add_dyad4(shear4, w * direction_weight, ft_hat, n);
    sum_s2 += w * w;
    force_squares += std::pow(w * direction_weight * f_hat, 2);
    shear_squares += std::pow(w * direction_weight, 2) * ft_hat.squaredNorm();
  });
  if (!(total > 0.0)) throw StatisticsError("truncation_check: no body-body contacts");
  // Coefficients: D2 = (15/2) dev N2 and D4 = (315/8) H(N4) for the density and the normal force;
  // the tangential field's potential has (5/2) sym T1 and (63/8) H(sym T3) (sff-theory.md §6.2).
  auto estimate = [&](double coefficient, double tensor_norm, double per_contact_square,
                      double squares) {
    return CoefficientEstimate{coefficient * tensor_norm / total,
                               coefficient * coefficient * per_contact_square * squares, sum_s2,
                               total};
  };
  constexpr double kD2 = 7.5, kD4 = 315.0 / 8.0, kT2 = 2.5, kT4 = 63.0 / 8.0;
  const double density_ratio =
      fourth_over_second(estimate(kD2, dev(density2).norm(), 2.0 / 3.0, sum_s2),
                         estimate(kD4, harmonic_norm4(density4), 8.0 / 35.0, sum_s2));
  const double force_ratio =
      fourth_over_second(estimate(kD2, dev(force2).norm(), 2.0 / 3.0, force_squares),
                         estimate(kD4, harmonic_norm4(force4), 8.0 / 35.0, force_squares));
  const double shear_ratio =
      fourth_over_second(estimate(kT2, sym(shear2).norm(), 0.5, shear_squares),
                         estimate(kT4, harmonic_norm4(shear4), 1.0 / 7.0, shear_squares));
  const Eigen::Matrix3d shear_tensor = 5.0 * sym(shear2) / (total * lambda);

  // Pass 2: the cells, in their own (folded) frame.
  const Eigen::Matrix3d& frame = cells.frame();
  const Eigen::Matrix3d a_local = frame.transpose() * fabric_a * frame;
  const Eigen::Matrix3d f_local = frame.transpose() * normal_f * frame;
  const Eigen::Matrix3d t_local = frame.transpose() * shear_tensor * frame;
  const auto num_cells = static_cast<std::size_t>(cells.size());
  std::vector<Moments> force(num_cells);
  std::vector<std::array<Moments, 3>> shear(num_cells);
  std::vector<double> force_form(num_cells, 0.0);
  std::vector<Eigen::Vector3d> shear_form(num_cells, Eigen::Vector3d::Zero());
  for_each_body_contact(contacts, [&](const ContactRecord& c, double w) {
    double sign = 1.0;
    const Eigen::Vector3d n = cells.to_frame(normal_of(c), sign);
    const auto k = static_cast<std::size_t>(cells.cell_of_folded(n));
    const double factor = scale.factor(c);
    force[k].add(w, c.normal_force * factor);
    force_form[k] += w * lambda * (1.0 + n.dot(f_local * n));
    const Eigen::Vector3d ft = sign * factor * (frame.transpose() * tangential_of(c));
    for (int i = 0; i < 3; ++i) shear[k][static_cast<std::size_t>(i)].add(w, ft[i]);
    const Eigen::Vector3d tn = t_local * n;
    shear_form[k] += w * lambda * (tn - n.dot(tn) * n);
  });
  const auto rows = static_cast<Eigen::Index>(num_cells);
  Eigen::MatrixXd density(rows, 1), density_form(rows, 1), density_error(rows, 1);
  std::vector<Eigen::Index> occupied;
  for (Eigen::Index k = 0; k < rows; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const double count = force[kk].weight;
    density(k) = count / (total * cells.solid_angle());
    density_form(k) = (1.0 + (a_local.cwiseProduct(cells.mean_dyad(static_cast<int>(k)))).sum()) / (4.0 * kPi);
    density_error(k) = std::sqrt(count) / (total * cells.solid_angle());  // Poisson
    if (count > 0.0) occupied.push_back(k);
  }
  const auto used = static_cast<Eigen::Index>(occupied.size());
  Eigen::MatrixXd normal(used, 1), normal_form(used, 1), normal_error(used, 1);
  Eigen::MatrixXd tangential(used, 3), tangential_form(used, 3), tangential_error(used, 3);
  for (Eigen::Index r = 0; r < used; ++r) {
    const auto k = static_cast<std::size_t>(occupied[static_cast<std::size_t>(r)]);
    normal(r) = force[k].mean();
    normal_form(r) = force_form[k] / force[k].weight;
    normal_error(r) = force[k].standard_error();
    for (int i = 0; i < 3; ++i) {
      tangential(r, i) = shear[k][static_cast<std::size_t>(i)].mean();
      tangential_form(r, i) = shear_form[k][i] / force[k].weight;
      tangential_error(r, i) = shear[k][static_cast<std::size_t>(i)].standard_error();
    }
  }
  TruncationCheck check;
  check.density = compare(density, density_form, density_error, 5, density_ratio);
  check.normal_force = compare(normal, normal_form, normal_error, 6, force_ratio);
  check.tangential_force = compare(tangential, tangential_form, tangential_error, 5, shear_ratio);
  return check;
}

std::vector<RoseSector> rose_diagram(ContactSpan contacts, const ForceScale& scale,
                                     int num_sectors) {
  if (num_sectors < 2) throw StatisticsError("rose_diagram: at least 2 sectors");
  std::vector<Moments> sectors(static_cast<std::size_t>(num_sectors));
  const double total = for_each_body_contact(contacts, [&](const ContactRecord& c, double w) {
    double psi = std::atan2(c.normal[2], c.normal[1]);
    if (psi < 0.0) psi += kPi;
    const auto k = static_cast<std::size_t>(
        std::clamp(static_cast<int>(psi / kPi * num_sectors), 0, num_sectors - 1));
    sectors[k].add(w, c.normal_force * scale.factor(c));
  });
  if (!(total > 0.0)) throw StatisticsError("rose_diagram: no body-body contacts");
  std::vector<RoseSector> rose(sectors.size());
  for (std::size_t k = 0; k < rose.size(); ++k) {
    rose[k].psi_low_deg = 180.0 * static_cast<double>(k) / num_sectors;
    rose[k].psi_high_deg = 180.0 * static_cast<double>(k + 1) / num_sectors;
    rose[k].fraction = sectors[k].weight / total;
    rose[k].normal_force = sectors[k].mean();
  }
  return rose;
}

}  // namespace sff
