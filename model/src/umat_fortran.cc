// The UMAT entry under the name Abaqus/Standard calls on Linux (umat_, the Fortran convention),
// for the shared library sffcal_umat. It only forwards, by the material's name, to
// sffcal_umat_network (a name beginning with CONTACT_NETWORK, model/umat_network.h) or
// sffcal_umat (ACST, model/umat.h): kept out of the model library so that linking
// sffcal::model never defines a umat_ of its own.
#include "model/umat.h"
#include "model/umat_network.h"

extern "C" void umat_(double* stress, double* statev, double* ddsdde, double* sse, double* spd,
                      double* scd, double* rpl, double* ddsddt, double* drplde, double* drpldt,
                      const double* stran, const double* dstran, const double* time,
                      const double* dtime, const double* temp, const double* dtemp,
                      const double* predef, const double* dpred, const char* cmname,
                      const int* ndi, const int* nshr, const int* ntens, const int* nstatv,
                      const double* props, const int* nprops, const double* coords,
                      const double* drot, double* pnewdt, const double* celent,
                      const double* dfgrd0, const double* dfgrd1, const int* noel,
                      const int* npt, const int* layer, const int* kspt, const int* kstep,
                      const int* kinc, size_t cmname_length) {
  const auto entry = sffcal_umat_is_network_material(cmname, cmname_length) ? sffcal_umat_network
                                                                           : sffcal_umat;
  entry(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, stran, dstran, time,
        dtime, temp, dtemp, predef, dpred, cmname, ndi, nshr, ntens, nstatv, props, nprops, coords,
        drot, pnewdt, celent, dfgrd0, dfgrd1, noel, npt, layer, kspt, kstep, kinc, cmname_length);
}
