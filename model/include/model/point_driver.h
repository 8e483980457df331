// The material-point driver of any registered model (model/descriptor.h): drained triaxial
// compression of one point through Behaviour::update alone, the lateral strains found by Newton on
// the consistent tangent. It is what fe-check runs beside the element for a model that has no
// driver of its own; ACST (material_point.h) and the contact-network model (network_path.h) keep
// theirs, which a fit differentiates with respect to the parameters.
//
// Conventions: compression positive, stress in Pa, tensor shear components.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "model/descriptor.h"
#include "model/update_status.h"

namespace model {

/// Drained triaxial compression along z: sigma_xx = sigma_yy held at lateral_stress, eps_zz to
/// axial_strain_end in equal increments, no shear strain.
struct DrainedTriaxialPath {
  double lateral_stress = 100e3;  ///< sigma_3 [Pa], also the initial isotropic stress
  double axial_strain_end = 0.05;
  int steps = 50;
  /// Newton converged when both lateral stresses are within this * max(p, sigma_3) of sigma_3.
  double stress_tolerance = 1e-10;
  int max_newton_iterations = 50;
};

/// One converged increment (the first: the initial state).
struct DriverPoint {
  Eigen::Matrix3d strain = Eigen::Matrix3d::Zero();  ///< total, from the start of the path
  Eigen::Matrix3d stress = Eigen::Matrix3d::Zero();  ///< [Pa]
  std::vector<double> state;                          ///< laid out as the description's state()
  UpdateStatus status = UpdateStatus::kOk;
  int newton_iterations = 0;
};

struct DriverPath {
  std::vector<DriverPoint> points;
  bool completed = false;
  std::string message;  ///< why the path stopped, where it did
};

/// Drives one point of `behaviour` with the initial inputs `inputs` (laid out as the description's
/// initial_inputs()) along the path. Stops with completed = false and a message where an update
/// fails or Newton does not converge; throws std::invalid_argument for a path that is not
/// (steps < 1, a tolerance not positive, a lateral stress not positive or not finite) and what
/// Behaviour::initial_state throws for inputs that are not physical.
DriverPath drive_drained_triaxial(const Behaviour& behaviour, const std::vector<double>& inputs,
                                  const DrainedTriaxialPath& path);

}  // namespace model
