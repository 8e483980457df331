// What the two UMAT entries (model/umat.h: ACST and the contact-network model) share: the
// conversions between the UMAT's component order and 3x3 tensors, the check of the element
// layout, and the report of a failed update through PNEWDT and sffcal_umat_last_message().
#ifndef SFFCAL_CALIBRATION_UMAT_COMMON_H_
#define SFFCAL_CALIBRATION_UMAT_COMMON_H_

#include <Eigen/Core>

#include <cstdlib>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>

namespace model::umat_detail {

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

/// Records the message, prints it on stderr with the element and point, and sets PNEWDT to at
/// most 0.5 (Abaqus repeats the increment with a smaller one).
void report(const std::string& message, const int* noel, const int* npt, double* pnewdt);

/// The file named by the environment variable `variable`, read by read(path) once per path and
/// kept (thread-safe; a new path is read anew). Throws std::runtime_error with unset_message where
/// the variable is unset or empty, or with the message read threw (on every call).
template <typename Value, typename Read>
Value read_file_once(const char* variable, const char* unset_message, Read read) {
  static std::mutex mutex;
  static std::string path_read, error;
  static Value cached;
  const char* path = std::getenv(variable);
  if (!path || !*path) throw std::runtime_error(unset_message);
  const std::lock_guard<std::mutex> lock(mutex);
  if (path_read != path) {
    path_read = path;
    error.clear();
    try {
      cached = read(path_read);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  if (!error.empty()) throw std::runtime_error(error);
  return cached;
}

}  // namespace model::umat_detail

#endif  // SFFCAL_CALIBRATION_UMAT_COMMON_H_
