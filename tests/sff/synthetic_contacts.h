// Hand-built contact records for the SFF tests.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <random>
#include <vector>

#include "sff/contacts.h"

namespace sff::testing {

/// A body-body contact with normal n, normal force fn, tangential force ft and branch vector
/// (the normal itself when no branch is given: normalisation factor (l.n)/(2 E v_bar) = 1 for
/// the unit scale E = 1/2, v_bar = 1).
inline ContactRecord make_contact(const Eigen::Vector3d& n, double fn,
                                  const Eigen::Vector3d& ft = Eigen::Vector3d::Zero(),
                                  const Eigen::Vector3d& branch = Eigen::Vector3d::Zero()) {
  ContactRecord c;
  c.body_a = 0;
  c.body_b = 1;
  const Eigen::Vector3d l = branch.squaredNorm() > 0.0 ? branch : n;
  for (int k = 0; k < 3; ++k) {
    c.normal[k] = n[k];
    c.branch[k] = l[k];
    c.tangential_force[k] = ft[k];
  }
  c.normal_force = fn;
  return c;
}

inline Eigen::Vector3d random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> gauss;
  return Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
}

/// Normals with density E(n) proportional to 1 + b2 P2(cos theta) + b4 P4(cos theta) about z,
/// by rejection sampling.
inline std::vector<Eigen::Vector3d> legendre_normals(double b2, int count, std::uint64_t seed,
                                                     double b4 = 0.0) {
  auto density = [&](double c) {
    const double c2 = c * c;
    return 1.0 + b2 * 0.5 * (3.0 * c2 - 1.0) + b4 * (35.0 * c2 * c2 - 30.0 * c2 + 3.0) / 8.0;
  };
  double top = 0.0;
  for (int k = 0; k <= 1000; ++k) top = std::max(top, density(k / 1000.0));
  top *= 1.01;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector3d> normals;
  while (static_cast<int>(normals.size()) < count) {
    const Eigen::Vector3d n = random_unit(rng);
    if (unit(rng) * top < density(n.z())) normals.push_back(n);
  }
  return normals;
}

}  // namespace sff::testing
