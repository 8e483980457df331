// The two forms of the contact-network model's tensors (network_model.h): a full 3x3 matrix (the
// FE update, any strain path) and a diagonal alone (the fit's triaxial paths: from an axisymmetric
// start under diagonal strain increments every tensor of the state stays diagonal, exactly). The
// model's laws are written once, in the operations below, for both; on the diagonal form the fit
// carries a Jet of one derivative per parameter through 3 components instead of 9 (issue 19: the
// fit's time).
//
// Needs only Eigen; templated on the scalar type (double or a ceres::Jet).
#pragma once

#include <Eigen/Core>

#include <array>
#include <cmath>

namespace model::network {

template <typename T>
using Tensor = Eigen::Matrix<T, 3, 3>;

/// A tensor whose principal axes are the coordinate axes, stored as its diagonal d.
template <typename T>
struct DiagonalTensor {
  std::array<T, 3> d;

  static DiagonalTensor Zero() { return {{T(0.0), T(0.0), T(0.0)}}; }
};

template <typename T>
DiagonalTensor<T> operator+(const DiagonalTensor<T>& x, const DiagonalTensor<T>& y) {
  return {{x.d[0] + y.d[0], x.d[1] + y.d[1], x.d[2] + y.d[2]}};
}

template <typename T>
DiagonalTensor<T> operator-(const DiagonalTensor<T>& x, const DiagonalTensor<T>& y) {
  return {{x.d[0] - y.d[0], x.d[1] - y.d[1], x.d[2] - y.d[2]}};
}

template <typename T>
DiagonalTensor<T> operator*(const T& a, const DiagonalTensor<T>& x) {
  return {{a * x.d[0], a * x.d[1], a * x.d[2]}};
}

// The operations of the laws, for each form. Sums over the diagonal run d0 + (d1 + d2), the
// order of Eigen's unrolled sum of three terms.

template <typename T>
T trace(const Tensor<T>& x) {
  return x.trace();
}
template <typename T>
T trace(const DiagonalTensor<T>& x) {
  return x.d[0] + (x.d[1] + x.d[2]);
}

/// x : y.
template <typename T>
T contract(const Tensor<T>& x, const Tensor<T>& y) {
  return (x.array() * y.array()).sum();
}
template <typename T>
T contract(const DiagonalTensor<T>& x, const DiagonalTensor<T>& y) {
  return x.d[0] * y.d[0] + (x.d[1] * y.d[1] + x.d[2] * y.d[2]);
}

/// tr(x^3) of a deviator x, as 3 det x (Cayley-Hamilton: tr x^3 = 3 det x where tr x = 0): 10
/// products where x x x takes 54.
template <typename T>
T deviator_cube_trace(const Tensor<T>& x) {
  return T(3.0) * (x(0, 0) * (x(1, 1) * x(2, 2) - x(1, 2) * x(2, 1)) -
                   x(0, 1) * (x(1, 0) * x(2, 2) - x(1, 2) * x(2, 0)) +
                   x(0, 2) * (x(1, 0) * x(2, 1) - x(1, 1) * x(2, 0)));
}
template <typename T>
T deviator_cube_trace(const DiagonalTensor<T>& x) {
  return T(3.0) * (x.d[0] * (x.d[1] * x.d[2]));
}

/// sym(x y) = (x y + (x y)^T) / 2.
template <typename T>
Tensor<T> symmetric_product(const Tensor<T>& x, const Tensor<T>& y) {
  const Tensor<T> xy = x * y;
  return T(0.5) * (xy + xy.transpose());
}
template <typename T>
DiagonalTensor<T> symmetric_product(const DiagonalTensor<T>& x, const DiagonalTensor<T>& y) {
  return {{x.d[0] * y.d[0], x.d[1] * y.d[1], x.d[2] * y.d[2]}};
}

/// x + a I.
template <typename T>
Tensor<T> plus_isotropic(Tensor<T> x, const T& a) {
  for (int i = 0; i < 3; ++i) x(i, i) += a;
  return x;
}
template <typename T>
DiagonalTensor<T> plus_isotropic(DiagonalTensor<T> x, const T& a) {
  for (int i = 0; i < 3; ++i) x.d[i] += a;
  return x;
}

/// The component xx (the lateral one of a triaxial path about z).
template <typename T>
T lateral_component(const Tensor<T>& x) {
  return x(0, 0);
}
template <typename T>
T lateral_component(const DiagonalTensor<T>& x) {
  return x.d[0];
}

/// t(X) = X_zz - (X_xx + X_yy)/2 (sff-theory.md §3).
template <typename T>
T triaxial_part(const Tensor<T>& x) {
  return x(2, 2) - T(0.5) * (x(0, 0) + x(1, 1));
}
template <typename T>
T triaxial_part(const DiagonalTensor<T>& x) {
  return x.d[2] - T(0.5) * (x.d[0] + x.d[1]);
}

/// f applied to every component.
template <typename R, typename T, typename F>
Tensor<R> map_components(const Tensor<T>& x, F f) {
  return x.unaryExpr(f);
}
template <typename R, typename T, typename F>
DiagonalTensor<R> map_components(const DiagonalTensor<T>& x, F f) {
  return {{f(x.d[0]), f(x.d[1]), f(x.d[2])}};
}

inline bool all_finite(const Tensor<double>& x) { return x.allFinite(); }
inline bool all_finite(const DiagonalTensor<double>& x) {
  return std::isfinite(x.d[0]) && std::isfinite(x.d[1]) && std::isfinite(x.d[2]);
}

}  // namespace model::network
