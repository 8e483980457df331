// The Abaqus UMAT entry of the ACST model (model/umat.h): the model-independent body
// (umat_common.h) with the ACST description, whose tables and state lay out PROPS and STATEV.
#include "model/umat.h"

#include "umat_common.h"

extern "C" void sffcal_umat(double* stress, double* statev, double* ddsdde, double* /*sse*/,
                            double* /*spd*/, double* /*scd*/, double* /*rpl*/,
                            double* /*ddsddt*/, double* /*drplde*/, double* /*drpldt*/,
                            const double* /*stran*/, const double* dstran,
                            const double* /*time*/, const double* /*dtime*/,
                            const double* /*temp*/, const double* /*dtemp*/,
                            const double* /*predef*/, const double* /*dpred*/,
                            const char* /*cmname*/, const int* ndi, const int* nshr,
                            const int* ntens, const int* nstatv, const double* props,
                            const int* nprops, const double* /*coords*/, const double* drot,
                            double* pnewdt, const double* /*celent*/, const double* /*dfgrd0*/,
                            const double* /*dfgrd1*/, const int* noel, const int* npt,
                            const int* /*layer*/, const int* /*kspt*/, const int* /*kstep*/,
                            const int* /*kinc*/, size_t /*cmname_length*/) {
  model::umat_detail::umat_body(model::find_model("acst"), stress, statev, ddsdde, dstran, ndi,
                                nshr, ntens, nstatv, props, nprops, drot, pnewdt, noel, npt);
}
