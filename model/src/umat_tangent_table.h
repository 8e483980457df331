// The unsymmetric part of each integration point's last DDSDDE, kept for a client that assembles
// only the symmetric part of a user material's tangent. CalculiX does (umat_abaqus.f keeps
// (D + D^T)/2), and the models' tangents are far from symmetric: without the rest, Newton loses
// its quadratic rate and diverges on rough-platen meshes (docs/fe.md, "CalculiX").
// scripts/calculix/sffcal_e_c3d_unsym.f reads the table back while ccx assembles its unsymmetric
// matrix. Only libsffcal_umat_calculix.so keeps it.
#ifndef SFFCAL_MODEL_UMAT_TANGENT_TABLE_H_
#define SFFCAL_MODEL_UMAT_TANGENT_TABLE_H_

namespace model::umat_detail {

/// Keeps (D - D^T)/2 of the ntens x ntens DDSDDE (column-major, as Fortran lays it) of element
/// noel's point npt (both from 1). Safe to call from several threads; throws nothing (it is called
/// from Fortran): where it cannot keep a part (memory), it says so once on stderr and the table
/// stops asking for the unsymmetric path (sffcal_umat_unsymmetric_wanted() = 0).
void keep_unsymmetric_part(int noel, int npt, const double* ddsdde, int ntens) noexcept;

}  // namespace model::umat_detail

// The Fortran interface (gfortran's names: lower case, one trailing underscore; INTEGER is int).
extern "C" {
/// found = 1 where element noel has a kept tangent at any point, else 0.
void sffcal_umat_has_unsymmetric_part_(const int* noel, int* found);
/// d(6, 6) (column-major) = (D - D^T)/2 of element noel's point npt, found = 1; or found = 0 and
/// d untouched where that point has none.
void sffcal_umat_unsymmetric_part_(const int* noel, const int* npt, double* d, int* found);
/// 1 where a tangent has been kept and the environment does not set
/// SFFCAL_CCX_SYMMETRIC_TANGENT=1 (the symmetrised tangent alone, as the unpatched ccx), else 0.
/// Any other value than 0 or 1 stops the program (exit 2) naming it.
int sffcal_umat_unsymmetric_wanted(void);
}

#endif  // SFFCAL_MODEL_UMAT_TANGENT_TABLE_H_
