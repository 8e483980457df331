// Element-level checks of the ACST model behind a deal.II-free interface (issue 6): the same
// drained triaxial compression run by the material-point driver (model/material_point.h), by one
// Q1 hexahedron and by a small mesh, the comparison of those curves, and their comparison with a
// DEM curve.
//
// This header includes no deal.II header (only Eigen and model/acst_model.h), so light
// translation units such as the `sffcal fe-check` command can use fe_model without deal.II's
// compile cost; link `fe_model_acst`. deal.II programs can use fe_model/triaxial.h and
// fe_model/acst_material.h directly.
//
// Everything here is compression positive (soil mechanics): strains, p, q, the fabric F.
#ifndef FE_MODEL_ACST_CHECK_H_
#define FE_MODEL_ACST_CHECK_H_

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "model/acst_model.h"

namespace fe_model {

class Material;  // fe_model/material.h (deal.II tensors): only referred to here

/// The consolidated specimen: isotropic stress sigma_3, void ratio, model fabric F_0.
struct AcstSpecimen {
  double confining_pressure = 100e3;  ///< sigma_3 = p_0 [Pa], held during the drained test
  double void_ratio = 0.8;            ///< e_0
  Eigen::Matrix3d fabric = Eigen::Matrix3d::Zero();  ///< F_0 (deviatoric)
};

/// Drained triaxial compression along z to axial_strain_end in n_steps equal increments.
struct TriaxialLoading {
  double axial_strain_end = 0.05;
  unsigned int n_steps = 50;
  /// Integration options of the model, the same for the driver and the FE runs so that they
  /// solve the same discrete equations (the comparisons check the FE code, not the integrator).
  /// The FE default: implicit, one second-order step per increment; the update is then a smooth
  /// function of the strain increment and Newton, global or at the material point, converges to
  /// round-off (with error control, a Newton iterate that changes a substep choice moves the
  /// stress by the local error, and the 1e-8 comparisons would stall there).
  model::acst::IntegrationOptions integration;
};

/// The FE problem of fe_model/triaxial.h (one eighth of a box specimen, z axial).
struct TriaxialMeshOptions {
  unsigned int cells_x = 1, cells_y = 1, cells_z = 1;
  double width = 0.5, height = 1.0;  ///< [m]; the answer of a homogeneous test does not depend on them
  double residual_rtol = 1e-10;
  /// Absolute test ||R|| <= residual_atol ||f_int||: 1e-9, far below the 1e-8 of the checks, and
  /// above the noise of the model's substepping when error control is switched on at 1e-9
  /// (about 1e-10 ||f_int|| measured: where a Newton iterate changes one of the integrator's
  /// discrete substep choices, ||R|| cannot go lower).
  double residual_atol = 1e-9;
  int max_newton_iterations = 20;
  int max_cuts = 12;
  double wall_time_limit = 0.0;  ///< [s] of the whole run; 0: none (SolverOptions)
  bool verbose = false;          ///< Newton residuals and ratios on stdout
  std::string vtu_prefix;   ///< if not empty: <prefix>_<step:04>.vtu per converged step
};

/// One point of a triaxial curve, compression positive.
struct CurvePoint {
  double axial_strain = 0.0;
  double volumetric_strain = 0.0;
  double p = 0.0;  ///< [Pa]
  double q = 0.0;  ///< sigma_a - sigma_r [Pa]
  double void_ratio = 0.0;
  /// F : n_c with n_c = sqrt(2/3) diag(-1/2, -1/2, 1): 0 isotropic, 1 at critical state in
  /// compression (NaN where unknown, e.g. DEM series rows without a fabric).
  double fabric_invariant = 0.0;
  int newton_iterations = 0;  ///< FE: of the step's converged attempts
  int cuts = 0;               ///< FE: increment halvings in the step
  std::string status = "ok";  ///< ok / unreliable / failed (the model's status)
  /// FE: ||R_k|| of the step's last converged Newton solve (the convergence record).
  std::vector<double> residual_norms;
  double eta() const { return q / p; }
};

struct Curve {
  std::string label;            ///< "driver", "element", "mesh", "dem"
  bool completed = false;       ///< every step converged
  std::string message;          ///< why not
  std::vector<CurvePoint> points;  ///< the initial state first; converged steps only (never NaN)
  int newton_iterations = 0;    ///< FE: summed over the run
  int cuts = 0;                 ///< FE: halvings summed over the run; driver: increments retried at 1e-8 p
                                ///< or halved
  double wall_seconds = 0.0;
};

/// model::acst::drained_triaxial from model::acst::isotropic_state, with the loading's integration
/// options and a Newton tolerance of 1e-9 p on the lateral stresses.
Curve run_acst_driver_triaxial(const model::acst::Parameters<double>& parameters,
                               const AcstSpecimen& specimen, const TriaxialLoading& loading);

/// fe_model::run_triaxial with an AcstMaterial at every quadrature point. Never throws for a
/// model or Newton failure (completed = false and a message); throws std::invalid_argument for
/// bad options and std::runtime_error for an unwritable VTU file.
Curve run_acst_fe_triaxial(const model::acst::Parameters<double>& parameters,
                           const AcstSpecimen& specimen, const TriaxialLoading& loading,
                           const TriaxialMeshOptions& mesh);

/// The same FE problem with any material at every quadrature point (the contact-network model's
/// fe-check runs through it; loading.integration is the material's business, not used here).
Curve run_fe_triaxial(const Material& material, double confining_pressure,
                      const TriaxialLoading& loading, const TriaxialMeshOptions& mesh);

/// Relative errors of a curve against a reference computed at the same axial strains (same
/// steps): for x in {q, eps_v}, max_i |x_i - x_ref,i| / max_i |x_ref,i| over the common points.
struct PathError {
  double q = 0.0;
  double volumetric_strain = 0.0;
  std::size_t points = 0;  ///< compared points
  /// Largest |axial strain difference| of the compared points (0 when the steps coincide).
  double axial_strain_mismatch = 0.0;
};
PathError compare_paths(const Curve& curve, const Curve& reference);

/// RMS errors of a model curve against a DEM curve, over the DEM points with
/// axial strain in [0, the model curve's last axial strain]; the model is interpolated linearly in
/// axial strain at the DEM points.
struct DemError {
  double eta_rms = 0.0;
  double volumetric_strain_rms = 0.0;
  std::size_t points = 0;
};
DemError compare_with_dem(const Curve& model, const Curve& dem);

/// The model fabric of an axisymmetric DEM contact-normal anisotropy: A_DEM = a_c diag(-1/3, -1/3,
/// 2/3) (the axisymmetric deviatoric tensor with t(A) = A_zz - (A_xx + A_yy)/2 = a_c, the scalar
/// /analysis/sff/a_c of `sffcal sff`), F = A_DEM / a_cs (acst-model.md), a_cs being ||A_DEM|| at
/// critical state in compression. Then F : n_c = sqrt(2/3) a_c / a_cs. Throws
/// std::invalid_argument unless a_cs > 0.
Eigen::Matrix3d fabric_from_dem_anisotropy(double a_c, double a_cs);

/// The default a_cs when neither the parameter file nor the user gives one: ||A_DEM|| at critical
/// state measured on out/reference/dense_100kPa_2000.h5 (mean t(A) = 1.013 over the snapshots at
/// axial strain 0.2 .. 0.4; ||A|| = sqrt(2/3) t(A) for an axisymmetric A).
inline constexpr double kDefaultAcs = 0.827;

/// a_cs from a parameter file already read (model::read_parameter_file), if it has one: a
/// top-level key "a_cs", "fabric_normalisation.a_cs" (as `sffcal calibrate` writes it) or
/// "parameters.a_cs", either a number or an object with a numeric "value" (read from
/// ParameterValues::rest, what the file holds besides the model's values). Throws
/// std::runtime_error naming `parameter_path` for a value that is not a positive number.
std::optional<double> fabric_normalisation(const model::ParameterValues& values,
                                           const std::string& parameter_path);

/// Writes a curve as CSV: axial_strain, volumetric_strain, p, q, eta, void_ratio,
/// fabric_invariant, newton_iterations, cuts, status (compression positive, Pa). Throws
/// std::runtime_error if the file cannot be written.
void write_curve_csv(const std::string& path, const Curve& curve);

}  // namespace fe_model

#endif  // FE_MODEL_ACST_CHECK_H_
