// The solid volume of a two-sphere clump, defined once: the DEM's mass properties
// (dem::two_sphere_union_properties) and the SFF analysis's void ratio (sff/src/run_snapshot.cc)
// both take it from here.
#pragma once

#include "sffcal/constants.h"

namespace sffcal {

/// Antiderivative in u (the distance from a sphere's centre along the clump axis) of the area of
/// a slice of that sphere divided by pi: integral of r^2 - u^2 du.
inline double sphere_slice_area_integral(double r, double u) { return r * r * u - u * u * u / 3.0; }

/// Solid volume [m^3] of the union of two equal spheres of radius r whose centres are
/// `centre_distance` = s apart (0 <= s < 2r; s = 0: one sphere), the overlap lens counted once:
/// each half beyond the mid-plane is the slab u in [-s/2, r] of one sphere, so
/// V = 2 pi [F(r) - F(-s/2)], F = sphere_slice_area_integral; in closed form
/// 8 pi r^3 / 3 - pi (4r + s)(2r - s)^2 / 12.
inline double two_sphere_union_volume(double r, double centre_distance) {
  const double h = 0.5 * centre_distance;
  return 2.0 * kPi * (sphere_slice_area_integral(r, r) - sphere_slice_area_integral(r, -h));
}

}  // namespace sffcal
