// The UMAT entries' shared conventions (umat_common.h).
#include "umat_common.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "model/umat.h"

namespace model::umat_detail {

Eigen::Matrix3d from_abaqus(const double* v, int n, double sign, double shear_scale) {
  Eigen::Matrix3d t = Eigen::Matrix3d::Zero();
  for (int k = 0; k < n; ++k) {
    const double x = sign * v[k] * (k < 3 ? 1.0 : shear_scale);
    t(kRow[k], kCol[k]) = x;
    t(kCol[k], kRow[k]) = x;
  }
  return t;
}

void to_abaqus(const Eigen::Matrix3d& t, double* v, int n, double sign) {
  for (int k = 0; k < n; ++k) v[k] = sign * t(kRow[k], kCol[k]);
}

void to_ddsdde(const Eigen::Matrix<double, 9, 9>& tangent, double* ddsdde, int n) {
  for (int I = 0; I < n; ++I)
    for (int J = 0; J < n; ++J)
      ddsdde[I + n * J] = tangent(3 * kRow[I] + kCol[I], 3 * kRow[J] + kCol[J]);
}

void check_layout(int ndi, int nshr, int ntens, int nstatv, int needed_statev) {
  if (ndi != 3 || !((nshr == 3 && ntens == 6) || (nshr == 1 && ntens == 4)))
    throw std::runtime_error("NDI = " + std::to_string(ndi) + ", NSHR = " + std::to_string(nshr) +
                             ": only 3D (NTENS = 6) and plane strain or axisymmetric elements "
                             "(NTENS = 4) are supported");
  if (nstatv < needed_statev)
    throw std::runtime_error("NSTATV = " + std::to_string(nstatv) + ", at least " +
                             std::to_string(needed_statev) + " needed");
}

std::string& last_message() {
  thread_local std::string message;
  return message;
}

void report(const std::string& message, const int* noel, const int* npt, double* pnewdt,
            double step_ratio) {
  last_message() = message;
  std::fprintf(stderr, "sffcal_umat: element %d point %d: %s; asking for a smaller increment\n",
               noel ? *noel : -1, npt ? *npt : -1, message.c_str());
  // A PNEWDT <= 0 on entry is no request of the FE code's own (CalculiX passes -1): replace it.
  if (pnewdt) *pnewdt = *pnewdt > 0.0 ? std::min(*pnewdt, step_ratio) : step_ratio;
}

}  // namespace model::umat_detail

extern "C" const char* sffcal_umat_last_message(void) {
  return model::umat_detail::last_message().c_str();
}
