// Directional statistics by bins (sff-theory.md §6.2): the binned contact-normal density, mean
// normal force and mean tangential force, their second-order (tensor) forms, and the size of the
// fourth-order terms the SFF equation truncates. Also the rose-diagram table for plots.
#pragma once

#include <vector>

#include "sff/contacts.h"
#include "sff/statistics.h"

namespace sff {

/// One band of directions about the loading axis z: |cos theta| in [cos_low, cos_high), both
/// hemispheres (n and -n are the same contact direction). Bands are equal in cos theta, hence
/// equal in solid angle.
struct DirectionalBin {
  double cos_low = 0.0, cos_high = 0.0;
  double count = 0.0;                ///< weighted number of contacts
  double density = 0.0;              ///< E(n): count / (N_c * solid angle) [1/sr]
  double normal_force = 0.0;         ///< mean f_hat_n
  double normal_force_error = 0.0;   ///< standard error of that mean
  double tangential_force = 0.0;     ///< mean meridional component f_hat_t . e_theta
  double tangential_force_error = 0.0;
};

/// The bands of a snapshot's body-body contacts (default 18, as in sff-theory.md §6.2).
std::vector<DirectionalBin> directional_bins(ContactSpan contacts, const ForceScale& scale,
                                             int num_bins = 18);

/// How well a second-order form describes one binned quantity.
struct TruncationFit {
  double r_squared = 0.0;        ///< 1 - SS_res / SS_tot of the second-order form
  double relative_l2 = 0.0;      ///< |measured - form| / |measured| over the bins
  double chi2_per_dof = 0.0;     ///< with the bins' standard errors (Poisson for the density)
  double fourth_order_ratio = 0.0;  ///< |c4| / |c2| of a least-squares Legendre fit to 4th order
};

/// The three quantities against their second-order forms. Density: E = (1 + n.A.n)/4pi;
/// normal force: Lambda (1 + n.F.n) (both averaged over each band and over the azimuth);
/// tangential force: the meridional field -(3/2) g sin(theta) cos(theta) with g fitted by least
/// squares (the second-order Ouadfel-Rothenburg form), against a fit with the dP4/dtheta term.
struct TruncationCheck {
  TruncationFit density, normal_force, tangential_force;
};
TruncationCheck truncation_check(const std::vector<DirectionalBin>& bins,
                                 const Eigen::Matrix3d& fabric_a, double lambda,
                                 const Eigen::Matrix3d& normal_f);

/// Rose diagram in the Y-Z plane (the plane of the loading axis and of the bedding tilt): the
/// normals' projected angle psi = atan2(n_z, n_y) folded into [0, 180) deg, in equal sectors.
struct RoseSector {
  double psi_low_deg = 0.0, psi_high_deg = 0.0;
  double fraction = 0.0;       ///< share of the contacts in the sector
  double normal_force = 0.0;   ///< mean f_hat_n of those contacts
};
std::vector<RoseSector> rose_diagram(ContactSpan contacts, const ForceScale& scale,
                                     int num_sectors = 36);

}  // namespace sff
