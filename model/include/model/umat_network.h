/* The contact-network model of sffcal (model/network_model.h, docs/network-model.md) behind
 * the Abaqus/Standard UMAT calling convention (docs/fe.md, "The UMAT entry"). Conventions as for
 * the ACST entry (model/umat.h): tension positive, engineering shear strains, component
 * order 11, 22, 33, 12, 13, 23 (NTENS = 6) or 11, 22, 33, 12 (NTENS = 4), stresses in Pa.
 * libsffcal_umat.so's umat_ calls this entry for a material whose name (CMNAME) begins with
 * CONTACT_NETWORK (in any case), sffcal_umat (ACST) for any other.
 *
 * PROPS (NPROPS = 20, or 39 to 48 with E and the parameters), tensors in 11, 22, 33, 12, 13, 23:
 *   PROPS(1)       initial void ratio e_0
 *   PROPS(2)       initial coordination number Z_0
 *   PROPS(3..8)    initial fabric anisotropy A_0 (deviatoric)
 *   PROPS(9..14)   initial normal-force anisotropy F_0 (deviatoric)
 *   PROPS(15..20)  initial tangential-force anisotropy F^t_0 (deviatoric)
 *   PROPS(21)      the grains' Young's modulus E [Pa] that normalises Lambda
 *   PROPS(22..39)  the 18 parameters kappa, z_c, zeta, k_z, c_v, a_cs, a_z, k_a, f_cs, f_z, k_f,
 *                  t_cs, t_z, k_t, d_z, d_a, n_r, n_z (docs/network-model.md); with NPROPS = 20,
 *                  E and the parameters are read instead from the parameter file (JSON, written
 *                  by `sffcal calibrate --model network`) named by the environment variable
 *                  SFFCAL_NETWORK_PARAMETERS.
 *   PROPS(40)      c_t, the Lode factor of the tangential anisotropy (docs/network-model.md Eq.
 *                  N2b); 1 (no Lode dependence) when NPROPS = 39.
 *   PROPS(41)      c_l, the coordination's gain with the normal force as a share of the critical
 *                  line's zeta, d ln Z = c_l zeta d ln Lambda (docs/network-model.md Eq. N5b);
 *                  0 (none) when NPROPS < 41.
 *   PROPS(42)      n_kappa, the exponent of the normal force's stiffness in Lambda,
 *                  d ln Lambda = (Lambda/Lambda_ref)^(n_kappa - 1) (kappa/3)(...)
 *                  (docs/network-model.md Eq. N6); 1 (ln Lambda linear in the strain) when
 *                  NPROPS < 42.
 *   PROPS(43..45)  d_psi, e_gamma, lambda_e, the critical void ratio line of the dilatancy, D gains
 *                  d_psi (e_c - e) with e_c = e_gamma - lambda_e ln(Lambda/Lambda_ref)
 *                  (docs/network-model.md Eq. N7b); those not given: d_psi = 0 (no line),
 *                  e_gamma = 0.8, lambda_e = 0.
 *   PROPS(46)      w_psi, the void ratio's weight in the anisotropies' targets, which follow
 *                  xi - w_psi (e - e_c) (docs/network-model.md Eq. N2c); 0 (xi alone) when
 *                  NPROPS < 46.
 *   PROPS(47)      r_i, how fast the fabric's inherent part fades, as a share of k_a
 *                  (docs/network-model.md Eq. N2d); 1 (with the rest of the fabric) when
 *                  NPROPS < 47. The initial fabric A_0 is all inherent.
 *   PROPS(48)      n_ra, the fabric's rate exponent in the over-coordination over n_r: A
 *                  relaxes at k_a exp((n_r + n_ra) xi) (docs/network-model.md Eq. N3b); 0 (at
 *                  the forces' rate factor) when NPROPS < 48.
 * The mean normal force Lambda is set at the first increment so that the SFF stress of the initial
 * network has the mean stress of STRESS; from then on STRESS is the SFF stress of the state, whose
 * deviator is the one the anisotropies carry (the initial STRESS's deviator is not kept).
 * STATEV (NSTATV >= SFFCAL_UMAT_NETWORK_NSTATV), compression positive:
 *   STATEV(1)      0 before the first increment, 1 after
 *   STATEV(2)      void ratio e
 *   STATEV(3)      coordination number Z
 *   STATEV(4)      Lambda, the mean normal contact force over E d^2 (sff-theory.md §4)
 *   STATEV(5..10)  A
 *   STATEV(11..16) F
 *   STATEV(17..22) F^t
 *   STATEV(23)     RK4 substeps of the last update
 *   STATEV(24..29) A_i, the fabric's inherent part (Eq. N2d)
 * DDSDDE: the exact consistent tangent (unsymmetric). The tensors of STATEV are turned by DROT
 * (Delta R X Delta R^T) before each increment. A failed update (more than 10,000 substeps, or a
 * state that leaves the admissible range) leaves STRESS and STATEV unchanged, DDSDDE the tangent
 * of a zero increment at the start; it, a bad PROPS, NTENS or parameter file, or an argument or
 * answer that is not finite set PNEWDT to at most 0.5, with a message on stderr and in sffcal_umat_last_message(). The layout is the
 * network's description (model/descriptor.h) through the body every model's UMAT shares.
 */
#ifndef SFFCAL_MODEL_UMAT_NETWORK_H_
#define SFFCAL_MODEL_UMAT_NETWORK_H_

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Zero-based offsets into STATEV and PROPS. */
enum {
  SFFCAL_UMAT_NETWORK_STATE_INITIALISED = 0,
  SFFCAL_UMAT_NETWORK_STATE_VOID_RATIO = 1,
  SFFCAL_UMAT_NETWORK_STATE_COORDINATION = 2,
  SFFCAL_UMAT_NETWORK_STATE_LAMBDA = 3,
  SFFCAL_UMAT_NETWORK_STATE_FABRIC = 4,
  SFFCAL_UMAT_NETWORK_STATE_NORMAL = 10,
  SFFCAL_UMAT_NETWORK_STATE_TANGENTIAL = 16,
  SFFCAL_UMAT_NETWORK_STATE_SUBSTEPS = 22,
  SFFCAL_UMAT_NETWORK_STATE_INHERENT = 23,
  SFFCAL_UMAT_NETWORK_NSTATV = 29,
  SFFCAL_UMAT_NETWORK_PROP_VOID_RATIO = 0,
  SFFCAL_UMAT_NETWORK_PROP_COORDINATION = 1,
  SFFCAL_UMAT_NETWORK_PROP_FABRIC = 2,
  SFFCAL_UMAT_NETWORK_PROP_NORMAL = 8,
  SFFCAL_UMAT_NETWORK_PROP_TANGENTIAL = 14,
  SFFCAL_UMAT_NETWORK_PROP_YOUNGS_MODULUS = 20,
  SFFCAL_UMAT_NETWORK_PROP_PARAMETERS = 21,
  SFFCAL_UMAT_NETWORK_NPROPS_STATE = 20,
  SFFCAL_UMAT_NETWORK_NPROPS_ALL = 39,  /* the first version's 18 parameters */
  SFFCAL_UMAT_NETWORK_NPROPS_MAX = 48   /* and c_t, c_l, n_kappa, d_psi, e_gamma, lambda_e, w_psi,
                                           r_i, n_ra */
};

void sffcal_umat_network(double* stress, double* statev, double* ddsdde, double* sse,
                         double* spd, double* scd, double* rpl, double* ddsddt, double* drplde,
                         double* drpldt, const double* stran, const double* dstran,
                         const double* time, const double* dtime, const double* temp,
                         const double* dtemp, const double* predef, const double* dpred,
                         const char* cmname, const int* ndi, const int* nshr, const int* ntens,
                         const int* nstatv, const double* props, const int* nprops,
                         const double* coords, const double* drot, double* pnewdt,
                         const double* celent, const double* dfgrd0, const double* dfgrd1,
                         const int* noel, const int* npt, const int* layer, const int* kspt,
                         const int* kstep, const int* kinc, size_t cmname_length);

/* Nonzero where the material name (CMNAME, of length cmname_length, blank padded as Fortran
 * passes it) chooses the contact-network entry: it begins with CONTACT_NETWORK in any case. */
int sffcal_umat_is_network_material(const char* cmname, size_t cmname_length);

#ifdef __cplusplus
}
#endif

#endif /* SFFCAL_MODEL_UMAT_NETWORK_H_ */
