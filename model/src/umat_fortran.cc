// The UMAT entry under the name Abaqus/Standard calls on Linux (umat_, the Fortran convention):
// the model the material's name chooses (a registered model's umat_name() at its start, in any
// case: CONTACT_NETWORK..., LINEAR_ELASTIC...; ACST for any other name) through the
// model-independent body. Kept out of the model library so that linking sffcal::model never
// defines a umat_ of its own.
//
// Built twice. libsffcal_umat.so follows Abaqus: STRESS comes turned by the code, and the UMAT
// turns its tensor state by DROT. libsffcal_umat_calculix.so (SFFCAL_UMAT_MATERIAL_AXES) does not
// turn it: CalculiX hands a user material everything in the material's own axes, under the name
// ABAQUS... the second Piola-Kirchhoff stress and the Green-Lagrange strain (umat_abaqus.f, DROT
// the identity), under ABAQUSNL... the stress R^T sigma R and the logarithmic strain of the
// stretch U (umat_abaqusnl.f, DROT the increment's rotation for information). Turning the state
// by DROT there turns it twice: an element turned by 45 degrees and compressed left the turned
// answer by 1 % (examples/calculix/rotated_element.py --nl; 1.4e-7 without the turn). The
// CalculiX library also keeps the tangent's unsymmetric part for ccx_sffcal's unsymmetric
// assembly (umat_tangent_table.h).
#include <cstddef>

#include "umat_common.h"
#ifdef SFFCAL_UMAT_MATERIAL_AXES
#include "umat_tangent_table.h"
#endif

extern "C" void umat_(double* stress, double* statev, double* ddsdde, double* /*sse*/,
                      double* /*spd*/, double* /*scd*/, double* /*rpl*/, double* /*ddsddt*/,
                      double* /*drplde*/, double* /*drpldt*/, const double* /*stran*/,
                      const double* dstran, const double* /*time*/, const double* /*dtime*/,
                      const double* /*temp*/, const double* /*dtemp*/, const double* /*predef*/,
                      const double* /*dpred*/, const char* cmname, const int* ndi,
                      const int* nshr, const int* ntens, const int* nstatv,
                      const double* props, const int* nprops, const double* /*coords*/,
                      const double* drot, double* pnewdt, const double* /*celent*/,
                      const double* /*dfgrd0*/, const double* /*dfgrd1*/, const int* noel,
                      const int* npt, const int* /*layer*/, const int* /*kspt*/,
                      const int* /*kstep*/, const int* /*kinc*/, size_t cmname_length) {
#ifdef SFFCAL_UMAT_MATERIAL_AXES
  static constexpr double kMaterialAxes[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  drot = kMaterialAxes;
#endif
  model::umat_detail::umat_body(model::umat_detail::umat_model(cmname, cmname_length), stress,
                                statev, ddsdde, dstran, ndi, nshr, ntens, nstatv, props, nprops,
                                drot, pnewdt, noel, npt);
#ifdef SFFCAL_UMAT_MATERIAL_AXES
  model::umat_detail::keep_unsymmetric_part(*noel, *npt, ddsdde, *ntens);
#endif
}
