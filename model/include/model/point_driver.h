// The material-point driver of any registered model (model/descriptor.h): triaxial compression or
// extension of one point through Behaviour::update alone, drained (the lateral strains found by
// Newton on the consistent tangent) or undrained (constant volume, every strain prescribed). It is
// what fe-check runs beside the element for a model that has no driver of its own, what
// `sffcal point` runs for any model, and the reference of the CalculiX element decks; ACST
// (material_point.h) and the contact-network model (network_path.h) keep theirs, which a fit
// differentiates with respect to the parameters.
//
// Conventions: compression positive, stress in Pa, tensor shear components.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "model/descriptor.h"
#include "model/update_status.h"

namespace model {

/// The largest end axial strain of a path (either sign): past it the small-strain measure of the
/// models means little.
inline constexpr double kMaxTriaxialStrain = 0.6;

/// How the lateral directions are held.
enum class Drainage {
  kDrained,    ///< sigma_xx = sigma_yy held at the initial sigma_3; eps_xx, eps_yy found by Newton
  kUndrained,  ///< constant volume: eps_xx = eps_yy = -eps_zz / 2 (small strain), no Newton
};

/// A triaxial path along z from the isotropic stress sigma_3: eps_zz to axial_strain_end in equal
/// increments (positive: compression, negative: extension), no shear strain.
struct TriaxialPath {
  Drainage drainage = Drainage::kDrained;
  double lateral_stress = 100e3;  ///< sigma_3 [Pa], the initial isotropic stress
  double axial_strain_end = 0.05;
  int steps = 50;
  /// Drained: Newton converged when both lateral stresses are within this * max(p, sigma_3) of
  /// sigma_3.
  double stress_tolerance = 1e-10;
  int max_newton_iterations = 50;
};

/// One converged increment (the first: the initial state).
struct DriverPoint {
  Eigen::Matrix3d strain = Eigen::Matrix3d::Zero();  ///< total, from the start of the path
  Eigen::Matrix3d stress = Eigen::Matrix3d::Zero();  ///< [Pa]
  std::vector<double> state;                          ///< laid out as the description's state()
  UpdateStatus status = UpdateStatus::kOk;
  int newton_iterations = 0;  ///< drained: of the lateral strains; undrained: 0
};

struct DriverPath {
  std::vector<DriverPoint> points;
  bool completed = false;
  std::string message;  ///< why the path stopped, where it did
};

/// Drives one point of `behaviour` with the initial inputs `inputs` (laid out as the description's
/// initial_inputs()) along the path. Stops with completed = false and a message where an update
/// fails or Newton does not converge; throws std::invalid_argument for a path that is not
/// (steps < 1, a tolerance not positive, a lateral stress not positive or not finite, an end
/// strain of 0 or past kMaxTriaxialStrain in size) and what
/// Behaviour::initial_state throws for inputs that are not physical.
DriverPath drive_triaxial(const Behaviour& behaviour, const std::vector<double>& inputs,
                          const TriaxialPath& path);

/// The triaxial invariants of a stress (compression positive) along z: p = tr sigma / 3 and
/// q = sigma_zz - (sigma_xx + sigma_yy) / 2 [Pa].
struct TriaxialStress {
  double p = 0.0, q = 0.0;
};
inline TriaxialStress triaxial_stress(const Eigen::Matrix3d& stress) {
  return {stress.trace() / 3.0, stress(2, 2) - 0.5 * (stress(0, 0) + stress(1, 1))};
}

/// "drained" or "undrained" (the spelling of configs and the command line).
const char* to_string(Drainage drainage);
/// The inverse of to_string; throws std::invalid_argument naming `text` otherwise.
Drainage parse_drainage(const std::string& text);

}  // namespace model
