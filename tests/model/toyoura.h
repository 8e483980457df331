// Toyoura-sand-like parameters for the tests: DM04 Table 1 values, with e_A and k_F of ours and
// n_b_loose = 0, n_G = 1/2 and n_F = 0 (DM04's bounding slope and elasticity, LD12's fabric rate;
// docs/model.md, "Parameters").
#pragma once

#include <cstdio>
#include <string>

#include "model/acst_model.h"

namespace model::testing {

template <typename T = double>
acst::Parameters<T> toyoura() {
  return acst::Parameters<T>{T(125.0), T(0.05),  T(1.25), T(0.712), T(0.934), T(0.019), T(0.7), T(0.01),
                       T(7.05),  T(0.968), T(1.1),  T(0.704), T(3.5),   T(0.1),   T(5.0),
                       T(0.0),   T(0.5),  T(0.0)};
}

/// The initial mean stress of the tests [Pa].
constexpr double kP0 = 100e3;

/// A number in the %.3e format, for messages.
inline std::string scientific(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3e", x);
  return buffer;
}

}  // namespace model::testing
