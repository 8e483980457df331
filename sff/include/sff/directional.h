// Directional statistics (sff-theory.md §6.2, general form; issue 18): how well the second-order
// (tensor) forms describe the contact-normal density, the mean normal force and the mean
// tangential force by direction, on equal-area cells of the whole sphere, and the size of the
// fourth-order terms the SFF equation truncates. Also the rose-diagram table for plots.
#pragma once

#include <vector>

#include "sff/contacts.h"
#include "sff/direction_cells.h"
#include "sff/statistics.h"

namespace sff {

/// How well a second-order form describes one quantity binned by direction.
struct TruncationFit {
  double r_squared = 0.0;        ///< 1 - SS_res / SS_tot over the cells
  double relative_l2 = 0.0;      ///< |measured - form| / |measured| over the cells
  double chi2_per_dof = 0.0;     ///< with the cells' standard errors (Poisson for the density)
  /// Amplitude of the fourth-order spherical harmonics over that of the second-order ones
  /// (Kanatani 1984), from contact moments, not from the cells; for an axisymmetric quantity it
  /// is |c4| / |c2| of its Legendre series c2 P2 + c4 P4 (of the potential whose surface gradient
  /// the tangential field is). Rotation invariant; corrected for the sampling noise, which alone
  /// would give about 9 / sqrt(N_c) / |c2| (9 fourth-order components).
  double fourth_order_ratio = 0.0;
};

/// The three quantities against their second-order forms, each averaged over a cell: the density
/// E = (1 + n.A.n) / 4 pi; the normal force Lambda (1 + n.F.n); the tangential force
/// Lambda (a n - (n.a.n) n) (Ouadfel-Rothenburg), a = 5 sym <f_hat_t (x) n>_Omega / Lambda. The
/// tangential force is compared as a vector in the cells' frame. Laid out in the principal frame
/// of the stress (DirectionCells::principal), the statistics do not depend on the lab frame.
struct TruncationCheck {
  TruncationFit density, normal_force, tangential_force;
};
TruncationCheck truncation_check(ContactSpan contacts, const ForceScale& scale,
                                 const Eigen::Matrix3d& fabric_a, double lambda,
                                 const Eigen::Matrix3d& normal_f, const DirectionCells& cells);

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
