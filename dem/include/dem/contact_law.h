// The paper's contact law as pure kernels: a linear normal spring and an incremental tangential
// spring with Coulomb slip, whose stored force is carried with the rotating contact frame.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <string>

namespace dem {

/// Material constants of the grain contacts (SI).
struct ContactParameters {
  double youngs_modulus = 150e6;   ///< E [Pa], the same for every grain
  double stiffness_ratio = 0.5;    ///< xi = k_t / k_n
  double friction = 0.5773502691896257;  ///< mu = tan 30 deg between grains
  double wall_friction = 0.0;      ///< mu between grains and walls (0: frictionless walls)
  double normal_damping_ratio = 0.0;  ///< viscous dashpot as a fraction of critical, 0 = off

  /// Empty when valid; otherwise names the bad parameter and its allowed range.
  std::string validate() const;
};

/// Normal stiffness of two spheres, K = 2 E1 E2 r1 r2 / (E1 r1 + E2 r2) [N/m].
inline double normal_stiffness(double e1, double r1, double e2, double r2) {
  return 2.0 * e1 * e2 * r1 * r2 / (e1 * r1 + e2 * r2);
}

/// The same law with equal moduli: K = 2 E r1 r2 / (r1 + r2).
inline double normal_stiffness(double e, double r1, double r2) {
  return 2.0 * e * r1 * r2 / (r1 + r2);
}

/// A wall is a sphere of infinite radius: the limit r2 -> inf of the law is K = 2 E1 r1,
/// whatever the wall's own modulus.
inline double wall_normal_stiffness(double e, double r) { return 2.0 * e * r; }

/// Carries a stored tangential force with the contact frame over one step: the tilt that takes
/// the old normal to the new one (the minimal rotation, written as two reflections), then the
/// twirl by `twirl_angle` about the new normal (the mean spin of the two bodies times dt).
/// The magnitude is preserved exactly, so a rigid-body rotation of a contact leaves |f_t|
/// unchanged and rotates f_t with it (Kuhn & Daouadji 2018, the objective 3D linear-frictional
/// contact).
inline Eigen::Vector3d rotate_with_contact_frame(const Eigen::Vector3d& tangential,
                                                 const Eigen::Vector3d& old_normal,
                                                 const Eigen::Vector3d& new_normal,
                                                 double twirl_angle) {
  const double magnitude2 = tangential.squaredNorm();
  if (magnitude2 == 0.0) return tangential;
  const double c = old_normal.dot(new_normal);
  // Reflection pair v - (v·n1)/(1+c) (n0+n1): exact rotation for v ⟂ n0, c > -1.
  Eigen::Vector3d v = tangential - tangential.dot(old_normal) * old_normal;
  if (c > -0.5) {  // a normal cannot turn by more than 120 degrees in one stable step
    v -= (v.dot(new_normal) / (1.0 + c)) * (old_normal + new_normal);
  }
  v += twirl_angle * new_normal.cross(v);
  v -= v.dot(new_normal) * new_normal;
  const double v2 = v.squaredNorm();
  return v2 > 0.0 ? v * std::sqrt(magnitude2 / v2) : v;
}

/// Coulomb limit |f_t| <= mu |f_n| by radial return of the elastic trial force (the backward-
/// Euler return map of a linear elastic-perfectly plastic spring, evaluated with the end-of-step
/// normal force, so slip that starts or stops inside a step is consistent).
/// Returns true when the contact slides.
inline bool apply_coulomb_limit(Eigen::Vector3d& tangential, double limit) {
  const double t2 = tangential.squaredNorm();
  if (t2 <= limit * limit) return false;
  tangential *= limit / std::sqrt(t2);
  return true;
}

}  // namespace dem
