/* The material-point driver (model/material_point.h) behind C linkage, as the reference
 * the UMAT C test (umat_test.c) is checked against. */
#ifndef SFFCAL_TESTS_UMAT_REFERENCE_H_
#define SFFCAL_TESTS_UMAT_REFERENCE_H_

#ifdef __cplusplus
extern "C" {
#endif

/* The 17 ACST parameters of a parameter file, in the order of model/umat.h (PROPS 8..24).
 * Returns 0, or -1 with the reason in message (of length message_size). */
int reference_parameters(const char* parameter_file, double* parameters, char* message,
                         int message_size);

/* Drained triaxial compression by the material-point driver (FE-default integration, the lateral
 * stress converged to 1e-12 p): from the isotropic stress p0 [Pa] at void ratio e0 and the model
 * fabric diag(-f/sqrt(6), -f/sqrt(6), 2f/sqrt(6)), eps_zz to axial_strain_end (compression
 * positive) in `increments` equal steps. Writes q [Pa] and eps_v (compression positive) after each
 * increment (arrays of `increments`). Returns 0, or -1 when an increment did not converge. */
int reference_drained_triaxial(const double* parameters, double p0, double e0, double f,
                               double axial_strain_end, int increments, double* q,
                               double* volumetric_strain);

#ifdef __cplusplus
}
#endif

#endif
