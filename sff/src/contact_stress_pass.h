// Internal: the pass over the contacts that sums the contact form of the Love-Weber stress
// (contact_stress), with a look at every record on the way, so that the analysis of contacts given
// from outside checks them without a pass of its own (the records are read once from memory).
#pragma once

#include <cstddef>

#include <Eigen/Core>

#include "sff/contacts.h"
#include "sff/tensors.h"

namespace sff::internal {

/// (1/V) sum sym(l (x) f) over the body-body contacts of non-zero weight [Pa]; look(k, contact) is
/// called for every contact, walls included, before it is summed.
template <class Look>
Eigen::Matrix3d contact_stress_pass(ContactSpan contacts, double volume, Look&& look) {
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const ContactRecord& c = contacts[k];
    look(k, c);
    const double w = contacts.weight(k);
    if (is_wall_contact(c) || w == 0.0) continue;
    sum.noalias() += (w * branch_of(c)) * force_of(c).transpose();
  }
  return sym(sum) / volume;
}

}  // namespace sff::internal
