// Bootstrap confidence intervals of the triaxial coefficients (sff-theory.md §6.6): resample the
// body-body contacts with replacement, recompute A, F, F^t and M, and take percentile intervals.
#pragma once

#include <cstdint>

#include "sff/contacts.h"
#include "sff/statistics.h"

namespace sff {

struct Interval {
  double estimate = 0.0;  ///< from all contacts
  double low = 0.0;       ///< 2.5 % percentile of the resamples
  double high = 0.0;      ///< 97.5 % percentile
};

struct BootstrapIntervals {
  Interval a_c, a_n, a_t, m;
  int resamples = 0;
  std::uint64_t seed = 0;
};

/// Seeded and reproducible: resample r draws from its own generator seeded by (seed, r), so the
/// result does not depend on the number of threads.
BootstrapIntervals bootstrap_coefficients(ContactSpan contacts, const ForceScale& scale,
                                          double friction, int resamples = 200,
                                          std::uint64_t seed = 1);

}  // namespace sff
