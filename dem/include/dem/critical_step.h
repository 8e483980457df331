// The stability limit of the time step: leapfrog's 2 / omega_max of the assembled system.
//
// Linearised about the list's last build, the bodies (6 degrees of freedom each, mass m and
// inertia tensor J) are held by linear springs, one per contact they can make before the next
// list build (every Verlet candidate, touching or not: linear springs do not depend on the
// overlap, and a pair further apart than the skin cannot touch before the list is rebuilt). A
// contact with normal n at point c gives the spring K_c = k_n n n^T + k_t (I - n n^T) (k_t = xi
// k_n where the scene has friction, else 0) acting on the relative displacement of the two
// bodies at c, so that the translations and rotations of neighbours are coupled. Leapfrog
// (velocity Verlet) is stable for dt < 2 / omega_max with omega_max^2 the largest eigenvalue of
// M^-1/2 K M^-1/2 (e.g. Hairer, Lubich & Wanner, Geometric Numerical Integration, 2006, I.5);
// damping lowers that limit (damped_limit_factor).
//
// The largest eigenvalue is estimated by a fixed number of Lanczos iterations (Golub & Van Loan,
// Matrix Computations, 4th ed., 10.1) from a start vector that depends only on the list, so the
// same list always gives the same step (a checkpoint resumes bit-identically). Its largest Ritz
// value is a lower bound of lambda_max; two brackets check it: every body's own 3x3 blocks
// (translation, rotation) are principal submatrices, so lambda_max is at least the largest of their
// eigenvalues (Cauchy interlacing), and since (a - b)^T K (a - b) <= 2 (a^T K a + b^T K b), K is
// at most twice its block diagonal, so lambda_max <= 2 max over bodies of lambda_max(M_b^-1/2 D_b
// M_b^-1/2), bounded in turn by the 3x3 blocks and the Frobenius norm of their coupling. The
// Coulomb cap is left out: it only softens a contact.
#pragma once

#include <vector>

#include "dem/contact_law.h"
#include "dem/contact_list.h"
#include "dem/particles.h"
#include "dem/wall.h"

namespace dem {

struct StabilityLimit {
  double omega_max = 0.0;    ///< the estimate of the largest angular frequency [rad/s]
  double omega_lower = 0.0;  ///< the largest frequency of one body's own blocks (<= omega_max)
  double omega_upper = 0.0;  ///< the bound from twice the block diagonal (>= omega_max)
  int iterations = 0;        ///< Lanczos iterations done (fewer where the Krylov space closed)
  /// With contact dashpots: the damping ratio of the top mode (the Ritz vector of omega_max), at
  /// least the contacts' own ratio. A mode can be damped more than one contact is: in a chain
  /// of equal spheres the neighbours move against each other, so each dashpot sees twice the
  /// velocity as each spring the stretch, at sqrt(2) times the pair's frequency: 1.41 times the
  /// ratio. 0 without dashpots.
  double modal_damping_ratio = 0.0;
  /// Leapfrog's limit 2 / omega_max [s]; infinity where no body has a candidate contact.
  double time_step() const;
  /// The step that is stable by the bound alone, 2 / omega_upper [s].
  double guaranteed_time_step() const;
};

/// Iterations of the estimate at each list build: with 16 the step lay within 2e-4 of the
/// converged limit on jammed clump packings of 1000 and 4000 bodies and 1.2e-3 on 10,000
/// (bench/RESULTS.md, "The stability limit").
constexpr int kStabilityIterations = 16;

/// The stability limit of the candidate contacts of `list`, from the geometry of its last build
/// (its build positions). Masses and inertias are multiplied by `density_scaling`. Loops over
/// fewer than `min_parallel_items` bodies or slots run on one thread; the result does not depend
/// on the number of threads.
StabilityLimit stability_limit(const Particles& particles, const std::vector<Wall>& walls,
                               const ContactList& list, const ContactParameters& contact,
                               double density_scaling, int min_parallel_items,
                               int iterations = kStabilityIterations);

/// The factor damping takes off the undamped limit 2/omega_max. A mode damped at a fraction zeta
/// of critical (StabilityLimit::modal_damping_ratio): sqrt(1 + zeta^2) - zeta (central
/// differences with viscous damping, Belytschko, Liu & Moran, Nonlinear Finite Elements, 2000,
/// 6.3.3). Cundall's local damping alpha opposes the motion with alpha |F|, so a body
/// decelerating on a spring feels up to (1 + alpha) times its force, as on a spring (1 + alpha)
/// times stiffer: 1 / sqrt(1 + alpha) (the exact limit of one body on a spring, simulated).
double damped_limit_factor(double local_damping, double damping_ratio);

/// Leapfrog's limit for a body's first contact, where no body has a candidate yet (a gas, the
/// start of a deposition): 2 sqrt(m_eff / (2 k)) for the lightest body against the stiffest
/// contact it can make (a wall; 2 for a pair of such bodies moving against each other), m_eff the
/// smallest of the mass and the rotational inertias over squared lever arms.
double one_contact_time_step(const Particles& particles, const ContactParameters& contact,
                             double density_scaling);

}  // namespace dem
