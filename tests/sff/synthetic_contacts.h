// Hand-built contact records for the SFF tests.
#pragma once

#include <Eigen/Core>
#include <random>

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

}  // namespace sff::testing
