// The UMAT of every registered model: its body (umat_body.cc, laid out from the model's
// description), the conversions between the UMAT's component order and 3x3 tensors, the check of
// the element layout, and the report of a failed update through PNEWDT and
// sffcal_umat_last_message().
#ifndef SFFCAL_MODEL_UMAT_COMMON_H_
#define SFFCAL_MODEL_UMAT_COMMON_H_

#include <Eigen/Core>

#include <cstddef>
#include <stdexcept>
#include <string>

#include "model/descriptor.h"

namespace model::umat_detail {

/// The model a UMAT material name (CMNAME, blank padded) chooses: the registered model whose
/// umat_name() begins it, in any case; ACST for any other name (as before the other models).
const ModelDescription& umat_model(const char* cmname, std::size_t cmname_length);

/// One UMAT call for the model d (the arguments the body reads; model/umat.h states the rest):
///   PROPS: the initial inputs (d.initial_inputs()), then the constants that are not fixed and the
///          parameters in the order of d's tables (those added after a model's first version may
///          be left out: their value_if_absent); or the initial inputs alone, the rest from the
///          parameter file named by d.parameter_file_variable();
///   STATEV(1): 0 before the first increment (the state then from STRESS and PROPS), 1 after;
///   STATEV(2..): the state, laid out as d.state(); its tensors turned by DROT at each increment;
///   DDSDDE: the consistent tangent (unsymmetric); where the update fails, the model's stiffness
///          at the start, STRESS and STATEV left unchanged and PNEWDT at most 0.5;
///   an unreliable update is kept and asks for a smaller increment (PNEWDT at most 0.5).
void umat_body(const ModelDescription& d, double* stress, double* statev, double* ddsdde,
               const double* dstran, const int* ndi, const int* nshr, const int* ntens,
               const int* nstatv, const double* props, const int* nprops, const double* drot,
               double* pnewdt, const int* noel, const int* npt);

// Abaqus order 11, 22, 33, 12, 13, 23.
inline constexpr int kRow[6] = {0, 1, 2, 0, 0, 1};
inline constexpr int kCol[6] = {0, 1, 2, 1, 2, 2};

/// A symmetric tensor from the first n Abaqus components (the others 0), each times sign;
/// shear_scale 0.5 turns engineering shear strains into tensor ones.
Eigen::Matrix3d from_abaqus(const double* v, int n, double sign, double shear_scale);
/// The first n Abaqus components of t, times sign.
void to_abaqus(const Eigen::Matrix3d& t, double* v, int n, double sign);

/// DDSDDE(I, J) = d STRESS(I) / d DSTRAN(J) with engineering shear, from the tangent D(3i+j, 3k+l)
/// = d sigma_ij / d eps_kl symmetric in (k, l) (d sigma_ij = D(ij, kl) d gamma_kl for a shear
/// J = kl); the two sign flips of compression-positive tangents cancel.
void to_ddsdde(const Eigen::Matrix<double, 9, 9>& tangent, double* ddsdde, int n);

/// Throws std::runtime_error unless the layout is 3D (NTENS = 6) or plane strain / axisymmetric
/// (NTENS = 4) and NSTATV >= needed_statev.
void check_layout(int ndi, int nshr, int ntens, int nstatv, int needed_statev);

/// The calling thread's last message (cleared at the start of each call).
std::string& last_message();

/// Records the message, prints it on stderr with the element and point, and asks for a smaller
/// increment: PNEWDT becomes at most step_ratio (the FE code repeats the increment scaled by it),
/// and step_ratio where it came in <= 0, which is no request (CalculiX passes -1).
void report(const std::string& message, const int* noel, const int* npt, double* pnewdt,
            double step_ratio = 0.5);

}  // namespace model::umat_detail

/// The UMAT under the name Abaqus/Standard calls (the Fortran convention, CMNAME's length last):
/// the model CMNAME chooses (umat_model) through umat_body. Defined by the shared libraries'
/// source umat_fortran.cc (built once for Abaqus, once for CalculiX), never by the model library.
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
                      const int* kinc, size_t cmname_length);

#endif  // SFFCAL_MODEL_UMAT_COMMON_H_
