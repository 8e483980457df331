// A read-only view of contact records, the only input of the SFF statistics (sff never includes
// a dem/ header: the records are the run file's, whether read from a file or from the engine in
// memory).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

#include "runfile/records.h"

namespace sff {

using runfile::ContactRecord;

/// Pointer and count of contact records (std::span before C++20), with optional per-contact
/// weights: every statistic is a weighted mean, so a bootstrap resample (integer multiplicities)
/// or a sub-network (0/1, e.g. the strong contacts) is a weighted view of the same records.
class ContactSpan {
 public:
  ContactSpan() = default;
  ContactSpan(const ContactRecord* data, std::size_t size) : data_(data), size_(size) {}
  ContactSpan(const std::vector<ContactRecord>& v) : data_(v.data()), size_(v.size()) {}  // NOLINT
  const ContactRecord* begin() const { return data_; }
  const ContactRecord* end() const { return data_ + size_; }
  std::size_t size() const { return size_; }
  const ContactRecord& operator[](std::size_t k) const { return data_[k]; }
  double weight(std::size_t k) const { return weights_ ? weights_[k] : 1.0; }

  /// The same records weighted by w (one non-negative weight per record, kept alive by the
  /// caller).
  ContactSpan weighted(const std::vector<double>& w) const {
    if (w.size() != size_) throw std::invalid_argument("ContactSpan::weighted: one weight per contact");
    ContactSpan view = *this;
    view.weights_ = w.data();
    return view;
  }

 private:
  const ContactRecord* data_ = nullptr;
  std::size_t size_ = 0;
  const double* weights_ = nullptr;
};

inline Eigen::Vector3d normal_of(const ContactRecord& c) {
  return {c.normal[0], c.normal[1], c.normal[2]};
}
inline Eigen::Vector3d branch_of(const ContactRecord& c) {
  return {c.branch[0], c.branch[1], c.branch[2]};
}
inline Eigen::Vector3d tangential_of(const ContactRecord& c) {
  return {c.tangential_force[0], c.tangential_force[1], c.tangential_force[2]};
}
/// Total force on body B: f_n n + f_t.
inline Eigen::Vector3d force_of(const ContactRecord& c) {
  return c.normal_force * normal_of(c) + tangential_of(c);
}
inline bool is_wall_contact(const ContactRecord& c) { return c.wall >= 0; }

/// Calls visit(contact, weight) for every body-body contact of non-zero weight and returns the
/// total weight (the weighted N_c). Wall contacts never enter the directional statistics.
template <class Visit>
double for_each_body_contact(ContactSpan contacts, Visit&& visit) {
  double total = 0.0;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const ContactRecord& c = contacts[k];
    const double w = contacts.weight(k);
    if (is_wall_contact(c) || w == 0.0) continue;
    visit(c, w);
    total += w;
  }
  return total;
}

}  // namespace sff
