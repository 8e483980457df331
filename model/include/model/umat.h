/* The ACST model of sffcal behind the Abaqus/Standard UMAT calling convention (docs/fe.md, "The
 * UMAT entry"). C linkage, every argument by pointer as Fortran passes it, CMNAME's length last.
 * libsffcal_umat.so's umat_ calls this entry for every material whose name does not begin with
 * CONTACT_NETWORK (those go to the contact-network entry, model/umat_network.h).
 *
 * Conventions of the UMAT interface: tension positive; engineering shear strains (gamma = 2 eps);
 * component order 11, 22, 33, 12, 13, 23 (NDI = 3, NSHR = 3, NTENS = 6), or 11, 22, 33, 12 for
 * plane strain and axisymmetric elements (NDI = 3, NSHR = 1, NTENS = 4; eps_13 = eps_23 = 0).
 * Stresses in the units of the parameter file's reference pressure: Pa.
 *
 * PROPS (NPROPS = 7, or 22 to 25 with the parameters):
 *   PROPS(1)      initial void ratio e_0
 *   PROPS(2..7)   initial model fabric F_0 (deviatoric), components 11, 22, 33, 12, 13, 23
 *   PROPS(8..22)  the 15 parameters G0, nu, M_c, c, e_gamma, lambda_c, xi, m, h0, c_h, n_b, A0,
 *                 n_d, e_A, k_F (docs/model.md §5); with NPROPS = 7 they are read instead from
 *                 the parameter file (JSON, docs/model.md) named by the environment variable
 *                 SFFCAL_ACST_PARAMETERS. NPROPS from 8 to 21, or above 25, is refused.
 *   PROPS(23)     n_b_loose (docs/model.md Eq. 7); 0 (the model without it) when NPROPS < 23.
 *   PROPS(24)     n_G (docs/model.md Eq. 1); 1/2 (the model without it) when NPROPS < 24.
 *   PROPS(25)     n_F (docs/model.md Eq. 16); 0 (the model without it) when NPROPS < 25.
 * STATEV (NSTATV >= SFFCAL_UMAT_NSTATV), compression positive, tensors in 11, 22, 33, 12, 13, 23:
 *   STATEV(1)      0 before the first increment (the state is then set from STRESS and PROPS:
 *                  alpha = alpha_in = s/p of the initial stress), 1 after
 *   STATEV(2)      void ratio e
 *   STATEV(3..8)   back-stress ratio alpha
 *   STATEV(9..14)  alpha_in (alpha at the last load reversal)
 *   STATEV(15..20) fabric F
 *   STATEV(21)     status of the last update: 0 ok, 1 unreliable
 *   STATEV(22)     substeps of the last update
 * DDSDDE(i, j) = d dSTRESS(i) / d dSTRAN(j), the consistent tangent (unsymmetric).
 * The tensors of STATEV are turned by DROT (Delta R X Delta R^T) before each increment.
 * The layout is the ACST model's description (model/descriptor.h) through the body every model's
 * UMAT shares (model/src/umat_body.cc).
 * An update that fails, or is unreliable (its error estimate above the model's bound: the
 * increment is too large), sets PNEWDT to at most 0.5 (Abaqus repeats the increment with a smaller
 * one); a failed update leaves STRESS and STATEV unchanged, DDSDDE the elastic stiffness at the
 * start. A bad PROPS, NTENS or parameter file, a STRESS, DSTRAN, STATEV or DROT that is not finite,
 * or an update whose answer is not finite, is reported the same way, with a message on stderr and
 * in sffcal_umat_last_message().
 * SSE, SPD, SCD, RPL and the temperature terms are not touched.
 */
#ifndef SFFCAL_MODEL_UMAT_H_
#define SFFCAL_MODEL_UMAT_H_

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Zero-based offsets into STATEV and PROPS. */
enum {
  SFFCAL_UMAT_STATE_INITIALISED = 0,
  SFFCAL_UMAT_STATE_VOID_RATIO = 1,
  SFFCAL_UMAT_STATE_ALPHA = 2,
  SFFCAL_UMAT_STATE_ALPHA_IN = 8,
  SFFCAL_UMAT_STATE_FABRIC = 14,
  SFFCAL_UMAT_STATE_STATUS = 20,
  SFFCAL_UMAT_STATE_SUBSTEPS = 21,
  SFFCAL_UMAT_NSTATV = 22,
  SFFCAL_UMAT_PROP_VOID_RATIO = 0,
  SFFCAL_UMAT_PROP_FABRIC = 1,
  SFFCAL_UMAT_PROP_PARAMETERS = 7,
  SFFCAL_UMAT_NPROPS_STATE = 7,
  SFFCAL_UMAT_NPROPS_ALL = 22,  /* the 15 parameters of the first version */
  SFFCAL_UMAT_NPROPS_MAX = 25   /* and n_b_loose, n_G, n_F */
};

void sffcal_umat(double* stress, double* statev, double* ddsdde, double* sse, double* spd,
                 double* scd, double* rpl, double* ddsddt, double* drplde, double* drpldt,
                 const double* stran, const double* dstran, const double* time,
                 const double* dtime, const double* temp, const double* dtemp,
                 const double* predef, const double* dpred, const char* cmname, const int* ndi,
                 const int* nshr, const int* ntens, const int* nstatv, const double* props,
                 const int* nprops, const double* coords, const double* drot, double* pnewdt,
                 const double* celent, const double* dfgrd0, const double* dfgrd1,
                 const int* noel, const int* npt, const int* layer, const int* kspt,
                 const int* kstep, const int* kinc, size_t cmname_length);

/* Why the calling thread's last call did not succeed cleanly ("" after a clean update). */
const char* sffcal_umat_last_message(void);

#ifdef __cplusplus
}
#endif

#endif /* SFFCAL_MODEL_UMAT_H_ */
