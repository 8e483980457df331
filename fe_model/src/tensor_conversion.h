// Conversions between deal.II's symmetric tensors and Eigen matrices, and the row-major packing
// of 3x3 matrices into PointState::internal_variables, shared by the material adapters.
#ifndef FE_MODEL_TENSOR_CONVERSION_H_
#define FE_MODEL_TENSOR_CONVERSION_H_

#include <Eigen/Core>
#include <vector>

#include "fe_model/material.h"

namespace fe_model::internal {

inline Eigen::Matrix3d to_eigen(const SymmetricTensor2& t) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = t[i][j];
  return m;
}

/// The symmetric part of m.
inline SymmetricTensor2 to_deal(const Eigen::Matrix3d& m) {
  SymmetricTensor2 t;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = i; j < 3; ++j) t[i][j] = 0.5 * (m(i, j) + m(j, i));
  return t;
}

inline void pack(const Eigen::Matrix3d& m, std::vector<double>& v, std::size_t offset) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) v[offset + static_cast<std::size_t>(3 * i + j)] = m(i, j);
}

inline Eigen::Matrix3d unpack(const std::vector<double>& v, std::size_t offset) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = v[offset + static_cast<std::size_t>(3 * i + j)];
  return m;
}

}  // namespace fe_model::internal

#endif  // FE_MODEL_TENSOR_CONVERSION_H_
