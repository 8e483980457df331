// Checks shared by the material tests: an adapter's tangent against centred differences of its
// own update, and the convergence order of a Newton record.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>

#include "fe_model/material.h"
#include "fe_model/solver_options.h"

namespace fe_model::checks {

/// max |C : dir - FD| / max |C : dir| over the six strain directions (symmetric unit tensors),
/// centred differences of step h about the increment de.
inline double tangent_error(const Material& material, const PointState& start,
                            const SymmetricTensor2& de, double h) {
  PointState end;
  const MaterialUpdate update = material.update(start, de, end);
  EXPECT_NE(update.status, MaterialStatus::kFailed) << update.message;
  double max_error = 0.0, max_entry = 0.0;
  for (unsigned int k = 0; k < 3; ++k)
    for (unsigned int l = k; l < 3; ++l) {
      SymmetricTensor2 dir;
      dir[k][l] = 1.0;  // a symmetric tensor: moves eps_kl and eps_lk together
      PointState plus, minus;
      material.update(start, de + h * dir, plus);
      material.update(start, de - h * dir, minus);
      const SymmetricTensor2 fd = (plus.stress - minus.stress) / (2.0 * h);
      const SymmetricTensor2 exact = update.tangent * dir;
      max_error = std::max(max_error, (fd - exact).norm());
      max_entry = std::max(max_entry, exact.norm());
    }
  return max_error / max_entry;
}

/// The order log(r_k+1/r_k)/log(r_k/r_k-1) of the last triple of a Newton record whose newest
/// residual is above `floor` (pre-asymptotic iterates give lower estimates); 0 if none. Each
/// estimate is printed to `out` if given.
inline double last_convergence_order(const NewtonLog& log, double floor,
                                     std::ostream* out = nullptr) {
  double order = 0.0;
  const auto& r = log.residual_norms;
  for (std::size_t k = 1; k + 1 < r.size(); ++k) {
    if (r[k + 1] < floor) break;
    order = std::log(r[k + 1] / r[k]) / std::log(r[k] / r[k - 1]);
    if (out) *out << "  order estimate at k = " << k + 1 << ": " << order << '\n';
  }
  return order;
}

}  // namespace fe_model::checks
