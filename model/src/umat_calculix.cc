// The UMAT entry for CalculiX (umat_, linked into the ccx that scripts/build_calculix.sh builds):
// the body of umat_fortran.cc without DROT. CalculiX hands a user material everything in the
// material's own axes: under the name ABAQUS... the second Piola-Kirchhoff stress and the
// Green-Lagrange strain (umat_abaqus.f, DROT the identity), under ABAQUSNL... the stress R^T sigma R
// and the logarithmic strain of the stretch U (umat_abaqusnl.f, DROT the increment's rotation for
// information). Turning the tensor state by DROT there as well turns it twice: an element turned
// by 45 degrees and compressed left the turned answer by 1 % (examples/calculix/rotated_element.py
// --nl; 1.2e-7 without the turn of the state).
#include <cstddef>

#include "umat_common.h"

extern "C" void umat_(double* stress, double* statev, double* ddsdde, double* /*sse*/,
                      double* /*spd*/, double* /*scd*/, double* /*rpl*/, double* /*ddsddt*/,
                      double* /*drplde*/, double* /*drpldt*/, const double* /*stran*/,
                      const double* dstran, const double* /*time*/, const double* /*dtime*/,
                      const double* /*temp*/, const double* /*dtemp*/, const double* /*predef*/,
                      const double* /*dpred*/, const char* cmname, const int* ndi,
                      const int* nshr, const int* ntens, const int* nstatv,
                      const double* props, const int* nprops, const double* /*coords*/,
                      const double* /*drot*/, double* pnewdt, const double* /*celent*/,
                      const double* /*dfgrd0*/, const double* /*dfgrd1*/, const int* noel,
                      const int* npt, const int* /*layer*/, const int* /*kspt*/,
                      const int* /*kstep*/, const int* /*kinc*/, size_t cmname_length) {
  static constexpr double kMaterialAxes[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  model::umat_detail::umat_body(model::umat_detail::umat_model(cmname, cmname_length), stress,
                                statev, ddsdde, dstran, ndi, nshr, ntens, nstatv, props, nprops,
                                kMaterialAxes, pnewdt, noel, npt);
}
