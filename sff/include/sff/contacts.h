// A read-only view of contact records, the only input of the SFF statistics (sff never includes
// a dem/ engine header: the records come from the run file or from the engine in memory).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "dem/records.h"

namespace sff {

using dem::ContactRecord;

/// Pointer and count of contact records (std::span before C++20).
class ContactSpan {
 public:
  ContactSpan() = default;
  ContactSpan(const ContactRecord* data, std::size_t size) : data_(data), size_(size) {}
  ContactSpan(const std::vector<ContactRecord>& v) : data_(v.data()), size_(v.size()) {}  // NOLINT
  const ContactRecord* begin() const { return data_; }
  const ContactRecord* end() const { return data_ + size_; }
  std::size_t size() const { return size_; }
  const ContactRecord& operator[](std::size_t k) const { return data_[k]; }

 private:
  const ContactRecord* data_ = nullptr;
  std::size_t size_ = 0;
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

}  // namespace sff
