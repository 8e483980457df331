// The critical time step from the stiffness each body carries through its candidate contacts.
//
// A body on springs of total stiffness matrix K oscillates at most at sqrt(lambda_max(M^-1 K)).
// Per body this sums the stiffnesses of every contact it can make before the next list build
// (the Verlet candidates, touching or not): for translation K_t = sum k_t I + (k_n - k_t) n n^T,
// for rotation about the centroid K_r = sum k_t (|l|^2 I - l l^T) + (k_n - k_t) (l x n)(l x n)^T
// with l the lever to the contact point (k_t = 0 where the scene has no friction), and takes the larger of lambda_max(K_t) / m and
// lambda_max(J^-1/2 K_r J^-1/2) (J the inertia tensor), as YADE's GlobalStiffnessTimeStepper
// sums per-body stiffnesses (here with the exact largest eigenvalue instead of per-axis sums).
// The body's step is 1/sqrt of that; the scene's is the smallest over the bodies. It is an
// estimate, not a bound: neighbours moving against each other (up to sqrt(2) in frequency,
// Gershgorin), the coupling of a body's translation and rotation through a frictional contact
// (ignored here, as in YADE) and a contact dashpot all raise the true frequency above it, against
// leapfrog's limit of 2/omega. Safety 1 was measured stable on jammed frictional packings and in
// triaxial shear (docs/dem.md, "Time step and stability").
#pragma once

#include <vector>

#include "dem/contact_law.h"
#include "dem/contact_list.h"
#include "dem/particles.h"
#include "dem/wall.h"

namespace dem {

/// sqrt(1 / the largest squared frequency) over the bodies with candidate contacts [s], from the
/// geometry of the list's last build (its build positions), so the same list always gives the
/// same step; infinity when no body has a candidate. Masses and inertias are multiplied by
/// `density_scaling`. Loops over fewer than `min_parallel_items` bodies run on one thread.
double stiffness_critical_step(const Particles& particles, const std::vector<Wall>& walls,
                               const ContactList& contacts, const ContactParameters& contact,
                               double density_scaling, int min_parallel_items);

/// The bound of a body's first contact: sqrt(m_eff / k) of the lightest body on the stiffest
/// contact it can have (a wall), m_eff the smallest of the mass and the rotational inertias over
/// squared lever arms. Holds where a body has no candidates yet (a gas, a deposition).
double one_contact_critical_step(const Particles& particles, const ContactParameters& contact,
                                 double density_scaling);

}  // namespace dem
