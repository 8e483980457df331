// Material-point driver: the ACST model under mixed stress/strain control (docs/model.md §6).
// Each increment fixes, per independent component (xx, yy, zz, xy, yz, xz), either the strain
// increment or the stress at the end of the increment; the unknown strain components are found
// by modified Newton iterations on the consistent tangent, carried from increment to increment.
// Templated on the scalar type so that a fit can differentiate whole curves w.r.t. parameters
// (T = ceres::Jet): the values come from the double Newton, the derivative parts from the
// implicit function theorem at the converged values (docs/model.md §6).
#pragma once

#include <array>
#include <string>
#include <type_traits>
#include <vector>

#include "model/acst_model.h"
#include "model/strain_derivatives.h"

namespace model::acst {

/// Voigt order of the independent components: xx, yy, zz, xy, yz, xz (tensor shear components).
inline constexpr int kVoigtI[6] = {0, 1, 2, 0, 1, 0};
inline constexpr int kVoigtJ[6] = {0, 1, 2, 1, 2, 2};

enum class Control { kStrain, kStress };

/// One increment of a general path: per component, a strain increment (tensor component,
/// compression positive) or the target stress [Pa] at the end of the increment.
struct PathStep {
  std::array<Control, 6> control{};
  std::array<double, 6> value{};
};

/// The Newton residual must stay above the noise of the adaptive integration (about
/// integration.tolerance * |sigma|, from its discrete substep choices), so the driver integrates
/// more tightly than the FE default and converges to stress_tolerance * p.
struct DriverOptions {
  IntegrationOptions integration = tight_integration();
  int max_newton_iterations = 30;
  double stress_tolerance = 1e-8;  // Newton converged when |residual| <= this * p
  /// The implicit integration with error control at 1e-7: within 1e-7 of the converged path
  /// (docs/model.md §4).
  static IntegrationOptions tight_integration() {
    return IntegrationOptions::implicit_controlled(1e-7);
  }
};

/// One output row. Strains are accumulated from the start of the path.
template <typename T>
struct PointRecord {
  T axial_strain;          // eps_zz
  T volumetric_strain;     // tr eps
  T p, q, eta;             // p [Pa], q = sigma_zz - (sigma_xx + sigma_yy)/2 [Pa], q/p
  T void_ratio;
  T psi;                   // e - e_c(p)
  T fabric_triaxial;       // F_zz - (F_xx + F_yy)/2
  T fabric_norm;           // ||F||
  UpdateStatus status;
};

template <typename T>
struct PathResult {
  std::vector<PointRecord<T>> rows;  // row 0 is the initial state
  State<T> state;                    // the last state reached
  Tensor<T> strain;                  // the total strain reached
  UpdateStatus status = UpdateStatus::kOk;  // the worst status along the path
};

/// Isotropic stress p, void ratio e, alpha = alpha_in = 0 and the given fabric.
template <typename T>
State<T> isotropic_state(const T& p, const T& void_ratio, const Tensor<T>& fabric);

/// The deviatoric tensor norm * diag(-1, -1, 2)/sqrt(6) (unit direction of triaxial compression).
template <typename T>
Tensor<T> triaxial_deviator(const T& norm);

template <typename T>
PointRecord<T> make_record(const Parameters<T>& par, const State<T>& state, const Tensor<T>& strain,
                           UpdateStatus status);

/// The Newton matrix of the driver, kept between increments: d sigma_a / d eps_b in Voigt order
/// (each shear component moving eps_kl and eps_lk together), from the last refresh.
struct NewtonWorkspace {
  bool has_tangent = false;
  Eigen::Matrix<double, 6, 6> tangent = Eigen::Matrix<double, 6, 6>::Zero();
};

/// One mixed-control increment from start. strain_increment holds the initial guess for the
/// stress-controlled components on entry and the solution on return. T = ceres::Jet<double, N>
/// or double.
template <typename T>
UpdateStatus mixed_increment(const Parameters<T>& par, const State<T>& start,
                             const std::array<Control, 6>& control,
                             const std::array<T, 6>& value, Tensor<T>& strain_increment,
                             State<T>& end, const DriverOptions& options = {});
/// The same, reusing (and refreshing) the Newton matrix in workspace; the paths pass one
/// workspace along all their increments.
template <typename T>
UpdateStatus mixed_increment(const Parameters<T>& par, const State<T>& start,
                             const std::array<Control, 6>& control,
                             const std::array<T, 6>& value, Tensor<T>& strain_increment,
                             State<T>& end, const DriverOptions& options,
                             NewtonWorkspace& workspace);

/// Drained triaxial compression (extension for a negative end strain): sigma_xx = sigma_yy held at
/// their initial values, eps_zz to axial_strain_end in equal increments, no shear strain.
template <typename T>
PathResult<T> drained_triaxial(const Parameters<T>& par, const State<T>& initial,
                               double axial_strain_end, int increments,
                               const DriverOptions& options = {});

/// Undrained (constant-volume) triaxial: eps_xx = eps_yy = -eps_zz / 2, no shear strain.
template <typename T>
PathResult<T> undrained_triaxial(const Parameters<T>& par, const State<T>& initial,
                                 double axial_strain_end, int increments,
                                 const DriverOptions& options = {});

/// Isotropic compression (or unloading) to p_end [Pa] in equal steps of p, no shear strain.
template <typename T>
PathResult<T> isotropic_compression(const Parameters<T>& par, const State<T>& initial,
                                    double p_end, int increments,
                                    const DriverOptions& options = {});

/// A general mixed path, one PathStep per increment. Stops at the first failed increment.
template <typename T>
PathResult<T> general_path(const Parameters<T>& par, const State<T>& initial,
                           const std::vector<PathStep>& steps, const DriverOptions& options = {});

/// Parses a path table: one increment per non-empty line ('#' starts a comment), six fields in
/// Voigt order, each "e:<strain increment>" or "s:<target stress in Pa>". Throws
/// std::runtime_error naming the line.
std::vector<PathStep> parse_path_table(const std::string& text);

}  // namespace model::acst

#include "model/material_point_impl.h"
