#include "dem/rigid_body.h"

#include <cmath>
#include <stdexcept>

#include "sffcal/clump_geometry.h"
#include "sffcal/constants.h"

namespace dem {
namespace {

using sffcal::kPi;

// Antiderivatives in u = z - s/2 (the distance from the nearer sphere centre along the axis)
// of the slice integrands, with slice radius^2 = r^2 - u^2 and h = s/2 (the area's own,
// sffcal::sphere_slice_area_integral, with the volume in common/include/sffcal/clump_geometry.h).
double slice_area_squared_integral(double r, double u) {
  const double u3 = u * u * u;
  return r * r * r * r * u - 2.0 * r * r * u3 / 3.0 + u3 * u * u / 5.0;
}

// Integral of (r^2 - u^2)(u + h)^2 du: the transverse moment's parallel-axis part.
double slice_area_times_z2_integral(double r, double h, double u) {
  const double r2 = r * r, u2 = u * u, u3 = u2 * u;
  return r2 * u3 / 3.0 + h * r2 * u2 + h * h * r2 * u - u3 * u2 / 5.0 - h * u2 * u2 / 2.0 -
         h * h * u3 / 3.0;
}

// The unit quaternion of a rotation by `angle` about the unit vector `axis`. A step turns a grain
// by a tiny angle (|angle| < 1e-3 rad is typical), where the Taylor series of sin and cos of
// x = angle/2 through the x^9 and x^8 terms is exact to far below one ulp (the first omitted
// terms are under (1/32)^10/10! = 2.5e-22 relative for |x| <= 1/32) and costs a few
// multiplications instead of libm's sin and cos, which ran twice per clump and step (perf:
// 4.5 % of a shearing step, issue 16). Larger angles go to libm.
Eigen::Quaterniond rotation(double angle, const Eigen::Vector3d& axis) {
  const double x = 0.5 * angle;
  double s, c;
  if (std::abs(x) <= 1.0 / 32.0) {
    const double x2 = x * x;
    // Horner forms with the coefficients folded at compile time (no divisions at run time).
    constexpr double s3 = -1.0 / 6, s5 = 1.0 / 120, s7 = -1.0 / 5040, s9 = 1.0 / 362880;
    constexpr double c2 = -1.0 / 2, c4 = 1.0 / 24, c6 = -1.0 / 720, c8 = 1.0 / 40320;
    s = x + x * x2 * (s3 + x2 * (s5 + x2 * (s7 + x2 * s9)));
    c = 1.0 + x2 * (c2 + x2 * (c4 + x2 * (c6 + x2 * c8)));
  } else {
    s = std::sin(x);
    c = std::cos(x);
  }
  return Eigen::Quaterniond(c, s * axis.x(), s * axis.y(), s * axis.z());
}

}  // namespace

MassProperties two_sphere_union_properties(double radius, double centre_distance,
                                           double density) {
  if (!(radius > 0.0) || !(centre_distance >= 0.0) || !(centre_distance < 2.0 * radius) ||
      !(density > 0.0)) {
    throw std::invalid_argument(
        "two_sphere_union_properties: need radius > 0, 0 <= centre_distance < 2 radius and "
        "density > 0");
  }
  const double r = radius, h = 0.5 * centre_distance;
  // Each half (z >= 0) is the slab u in [-h, r] of the sphere centred at z = h.
  auto span = [&](auto&& antiderivative) { return antiderivative(r) - antiderivative(-h); };
  const double area2 = span([&](double u) { return slice_area_squared_integral(r, u); });
  const double area_z2 = span([&](double u) { return slice_area_times_z2_integral(r, h, u); });

  MassProperties p;
  p.volume = sffcal::two_sphere_union_volume(r, centre_distance);
  p.mass = density * p.volume;
  // A disc of radius a and mass dm: a^2 dm / 2 about its axis, a^2 dm / 4 about a diameter.
  p.inertia_axial = 2.0 * density * kPi * area2 / 2.0;
  p.inertia_transverse = 2.0 * density * kPi * (area2 / 4.0 + area_z2);
  return p;
}

MassProperties sphere_properties(double radius, double density) {
  return two_sphere_union_properties(radius, 0.0, density);
}

Eigen::Quaterniond rotate_symmetric_top(const Eigen::Quaterniond& orientation,
                                        const Eigen::Vector3d& angular_momentum,
                                        double inertia_axial, double inertia_transverse,
                                        double dt) {
  const double l_norm = angular_momentum.norm();
  if (l_norm == 0.0) return orientation;
  const Eigen::Vector3d axis = body_axis(orientation);
  const double precession_angle = dt * l_norm / inertia_transverse;
  const double spin_angle =
      dt * angular_momentum.dot(axis) * (1.0 / inertia_axial - 1.0 / inertia_transverse);
  const Eigen::Quaterniond precession = rotation(precession_angle, angular_momentum / l_norm);
  // The spin is about the body axis, i.e. applied on the right in the body frame.
  const Eigen::Quaterniond spin = rotation(spin_angle, Eigen::Vector3d::UnitX());
  return (precession * orientation * spin).normalized();
}

}  // namespace dem
