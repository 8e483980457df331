// What the binding files share (python/bindings/*.cc): the arrays they read and write and the
// check of a tensor given from Python.
#pragma once

#include <pybind11/numpy.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace sffcal_python {

/// A C-ordered double array (converted where it is not; a structured array is never converted).
using Array = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;
/// numpy's (3, 3) blocks are row-major.
using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

inline pybind11::array_t<double> matrix_array(const Eigen::Matrix3d& m) {
  pybind11::array_t<double> out({3, 3});
  Eigen::Map<RowMajor3>(out.mutable_data()) = m;
  return out;
}

/// Whether a 3x3 tensor (row-major at v) is finite and symmetric (to 1e-12 of its largest entry).
inline bool finite_symmetric(const double* v) {
  double largest = 0.0;
  for (int i = 0; i < 9; ++i) {
    if (!std::isfinite(v[i])) return false;
    largest = std::max(largest, std::abs(v[i]));
  }
  return std::abs(v[1] - v[3]) <= 1e-12 * largest && std::abs(v[2] - v[6]) <= 1e-12 * largest &&
         std::abs(v[5] - v[7]) <= 1e-12 * largest;
}

}  // namespace sffcal_python
