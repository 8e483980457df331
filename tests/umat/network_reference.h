/* The contact-network model's drained prediction (calibration/network_fit.h, predict) behind C
 * linkage, as the reference the network UMAT C test (umat_network_test.c) is checked against. */
#ifndef SFFCAL_TESTS_UMAT_NETWORK_REFERENCE_H_
#define SFFCAL_TESTS_UMAT_NETWORK_REFERENCE_H_

#ifdef __cplusplus
extern "C" {
#endif

/* E [Pa] then the 27 parameters of a contact-network parameter file, in the order of
 * model/umat_network.h (PROPS 21..48). Returns 0, or -1 with the reason in message. */
int network_reference_parameters(const char* parameter_file, double* youngs_and_parameters,
                                 char* message, int message_size);

/* Drained triaxial compression predicted by the fit's driver from the isotropic stress p0 [Pa]
 * (held on the sides), void ratio e0 and coordination z0, with the axisymmetric anisotropies
 * whose triaxial parts are a_c, a_n, a_t (x diag(-1, -1, 2) / 3) and Lambda from p0: eps_zz to
 * axial_strain_end (compression positive) in `increments` equal steps. youngs_and_parameters as
 * network_reference_parameters gives them (E must be the DEM's 150 MPa, which the driver uses).
 * Writes q [Pa] and eps_v (compression positive) after each increment. Returns 0, or -1 with the
 * reason in message. */
int network_reference_drained_triaxial(const double* youngs_and_parameters, double p0, double e0,
                                       double z0, double a_c, double a_n, double a_t,
                                       double axial_strain_end, int increments, double* q,
                                       double* volumetric_strain, char* message,
                                       int message_size);

#ifdef __cplusplus
}
#endif

#endif
