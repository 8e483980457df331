#include "sff/directional.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace sff {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Running weighted sums of one quantity in one bin.
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

// Averages over a band with cos theta uniform in [c0, c1] (uniform solid angle).
double mean_cos2(double c0, double c1) { return (c0 * c0 + c0 * c1 + c1 * c1) / 3.0; }
double mean_cos4(double c0, double c1) {
  return (std::pow(c1, 5) - std::pow(c0, 5)) / (5.0 * (c1 - c0));
}
// n.T.n averaged over the azimuth and the band (off-diagonal terms average out).
double band_quadratic_form(const Eigen::Matrix3d& t, double c0, double c1) {
  const double c2 = mean_cos2(c0, c1);
  return t(2, 2) * c2 + 0.5 * (t(0, 0) + t(1, 1)) * (1.0 - c2);
}
double band_legendre2(double c0, double c1) { return 1.5 * mean_cos2(c0, c1) - 0.5; }
double band_legendre4(double c0, double c1) {
  return (35.0 * mean_cos4(c0, c1) - 30.0 * mean_cos2(c0, c1) + 3.0) / 8.0;
}
// Band averages of sin*cos and sin*cos^3 (antiderivatives in c = cos theta).
double mean_sin_cos(double c0, double c1) {
  auto f = [](double c) { return -std::pow(1.0 - c * c, 1.5) / 3.0; };
  return (f(c1) - f(c0)) / (c1 - c0);
}
double mean_sin_cos3(double c0, double c1) {
  auto f = [](double c) {
    const double u = 1.0 - c * c;
    return -std::pow(u, 1.5) / 3.0 + std::pow(u, 2.5) / 5.0;
  };
  return (f(c1) - f(c0)) / (c1 - c0);
}
// dP2/dtheta = -3 sin cos and dP4/dtheta = -(5/2) sin cos (7 cos^2 - 3), band-averaged.
double band_dlegendre2(double c0, double c1) { return -3.0 * mean_sin_cos(c0, c1); }
double band_dlegendre4(double c0, double c1) {
  return -2.5 * (7.0 * mean_sin_cos3(c0, c1) - 3.0 * mean_sin_cos(c0, c1));
}

// Least squares y ~ X c; returns c.
Eigen::VectorXd least_squares(const Eigen::MatrixXd& x, const Eigen::VectorXd& y) {
  return x.colPivHouseholderQr().solve(y);
}

TruncationFit compare(const Eigen::VectorXd& measured, const Eigen::VectorXd& form,
                      const Eigen::VectorXd& error, int fitted_parameters,
                      const Eigen::MatrixXd& legendre_basis, int second_column, int fourth_column) {
  TruncationFit fit;
  const Eigen::VectorXd residual = measured - form;
  const double mean = measured.mean();
  const double total = (measured.array() - mean).square().sum();
  fit.r_squared = total > 0.0 ? 1.0 - residual.squaredNorm() / total : 0.0;
  fit.relative_l2 = measured.norm() > 0.0 ? residual.norm() / measured.norm() : 0.0;
  double chi2 = 0.0;
  int used = 0;
  for (Eigen::Index k = 0; k < measured.size(); ++k) {
    if (!(error[k] > 0.0)) continue;
    chi2 += residual[k] * residual[k] / (error[k] * error[k]);
    ++used;
  }
  const int dof = used - fitted_parameters;
  fit.chi2_per_dof = dof > 0 ? chi2 / dof : 0.0;
  const Eigen::VectorXd c = least_squares(legendre_basis, measured);
  fit.fourth_order_ratio =
      c[second_column] != 0.0 ? std::abs(c[fourth_column]) / std::abs(c[second_column]) : 0.0;
  return fit;
}

}  // namespace

std::vector<DirectionalBin> directional_bins(ContactSpan contacts, const ForceScale& scale,
                                             int num_bins) {
  if (num_bins < 3) throw StatisticsError("directional_bins: at least 3 bins");
  std::vector<Moments> normal(static_cast<std::size_t>(num_bins)),
      tangential(static_cast<std::size_t>(num_bins));
  const double total = for_each_body_contact(contacts, [&](const ContactRecord& c, double w) {
    Eigen::Vector3d n = normal_of(c), ft = tangential_of(c);
    if (n.z() < 0.0) n = -n, ft = -ft;  // the same contact seen from the other body
    const auto k = static_cast<std::size_t>(std::min(num_bins - 1, static_cast<int>(n.z() * num_bins)));
    const double factor = scale.factor(c);
    normal[k].add(w, c.normal_force * factor);
    const double s = std::hypot(n.x(), n.y());
    if (s > 1e-12) {
      const Eigen::Vector3d e_theta(n.z() * n.x() / s, n.z() * n.y() / s, -s);
      tangential[k].add(w, factor * ft.dot(e_theta));
    }
  });
  if (!(total > 0.0)) throw StatisticsError("directional_bins: no body-body contacts");
  std::vector<DirectionalBin> bins(static_cast<std::size_t>(num_bins));
  const double solid_angle = 4.0 * kPi / num_bins;
  for (std::size_t k = 0; k < bins.size(); ++k) {
    DirectionalBin& b = bins[k];
    b.cos_low = static_cast<double>(k) / num_bins;
    b.cos_high = static_cast<double>(k + 1) / num_bins;
    b.count = normal[k].weight;
    b.density = b.count / (total * solid_angle);
    b.normal_force = normal[k].mean();
    b.normal_force_error = normal[k].standard_error();
    b.tangential_force = tangential[k].mean();
    b.tangential_force_error = tangential[k].standard_error();
  }
  return bins;
}

TruncationCheck truncation_check(const std::vector<DirectionalBin>& bins,
                                 const Eigen::Matrix3d& fabric_a, double lambda,
                                 const Eigen::Matrix3d& normal_f) {
  const auto n = static_cast<Eigen::Index>(bins.size());
  double total = 0.0;
  for (const DirectionalBin& b : bins) total += b.count;
  if (n < 3 || !(total > 0.0)) throw StatisticsError("truncation_check: empty bins");
  Eigen::VectorXd density(n), density_form(n), density_error(n);
  Eigen::VectorXd force(n), force_form(n), force_error(n);
  Eigen::VectorXd shear(n), shear_error(n);
  Eigen::MatrixXd legendre(n, 3), dlegendre(n, 2);
  for (Eigen::Index k = 0; k < n; ++k) {
    const DirectionalBin& b = bins[static_cast<std::size_t>(k)];
    const double c0 = b.cos_low, c1 = b.cos_high;
    const double solid_angle = 4.0 * kPi * (c1 - c0);
    density[k] = b.density;
    density_form[k] = (1.0 + band_quadratic_form(fabric_a, c0, c1)) / (4.0 * kPi);
    density_error[k] = std::sqrt(b.count) / (total * solid_angle);  // Poisson
    force[k] = b.normal_force;
    force_form[k] = lambda * (1.0 + band_quadratic_form(normal_f, c0, c1));
    force_error[k] = b.normal_force_error;
    shear[k] = b.tangential_force;
    shear_error[k] = b.tangential_force_error;
    legendre.row(k) << 1.0, band_legendre2(c0, c1), band_legendre4(c0, c1);
    dlegendre.row(k) << band_dlegendre2(c0, c1), band_dlegendre4(c0, c1);
  }
  TruncationCheck check;
  check.density = compare(density, density_form, density_error, 1, legendre, 1, 2);
  check.normal_force = compare(force, force_form, force_error, 1, legendre, 1, 2);
  const Eigen::VectorXd g = least_squares(dlegendre.leftCols(1), shear);
  check.tangential_force = compare(shear, dlegendre.leftCols(1) * g, shear_error, 1, dlegendre, 0, 1);
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
