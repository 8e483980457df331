// Candidate contacts (a Verlet list built from a cell grid) and the history each contact
// carries from step to step (its tangential force and last normal).
//
// Layout, as in LAMMPS' granular pair styles: sphere pairs form a half list (i < j, spheres of
// different bodies) sorted by (i, j); the history arrays run parallel to it. Wall candidates form
// a second list sorted by (sphere, wall). Every candidate owns one "slot": pairs take slots
// [0, num_pairs()), wall candidates [num_pairs(), num_slots()). The incidence lists give, for each
// sphere, its slots encoded as 2 * slot + (1 if the sphere is body B of that contact).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "dem/particles.h"
#include "dem/wall.h"

namespace dem {

class ContactList {
 public:
  /// Rebuilds the candidate lists for the current positions with a Verlet skin `skin` [m] and
  /// carries over the history of the contacts that were touching. `old_to_new`, when the
  /// spheres were re-ordered since the last build, maps each old sphere index to its new one.
  /// Loops over fewer than `min_parallel_items` spheres run on one thread.
  void build(const Particles& particles, const std::vector<Wall>& walls, double skin,
             const std::vector<int>* old_to_new = nullptr, int min_parallel_items = 1);

  int num_pairs() const { return static_cast<int>(pair_i.size()); }
  int num_wall_candidates() const { return static_cast<int>(wall_sphere.size()); }
  int num_slots() const { return num_pairs() + num_wall_candidates(); }
  double skin() const { return skin_; }

  /// Sphere and wall positions at the last build: the Verlet trigger measures from these.
  std::vector<Eigen::Vector3d> build_position;
  std::vector<double> build_wall_position;

  // ---- sphere pairs: topology, then history ----
  std::vector<int> pair_i, pair_j;
  std::vector<Eigen::Vector3d> pair_tangential;  ///< stored tangential force on j [N]
  std::vector<Eigen::Vector3d> pair_normal;      ///< unit normal i -> j at the last step
  std::vector<std::uint8_t> pair_touching;       ///< overlapping at the last step

  // ---- wall candidates ----
  std::vector<int> wall_sphere, wall_index;
  std::vector<Eigen::Vector3d> wall_tangential;  ///< stored tangential force on the sphere [N]
  std::vector<std::uint8_t> wall_touching;

  // ---- incidence (CSR over spheres) ----
  std::vector<int> incidence_offset, incidence;

  std::int64_t num_builds() const { return num_builds_; }

  /// Restores a list read back from a checkpoint: the topology and history arrays must already
  /// be filled and pass check() (an edited or damaged file must not send an index out of range);
  /// this sets the counters and derives the incidence lists.
  void restore(double skin, std::int64_t num_builds, int num_spheres);

  /// What is inconsistent (empty if nothing): history arrays parallel to their lists, sphere and
  /// wall indices in range, pairs i < j, histories and build positions finite.
  std::string check(int num_spheres, int num_walls) const;

 private:
  void build_cell_grid(const Particles& particles, double cell_size);
  void find_pairs(const Particles& particles, double skin, int min_parallel_items);
  void find_wall_candidates(const Particles& particles, const std::vector<Wall>& walls,
                            double skin);
  void build_incidence(int num_spheres);

  double skin_ = 0.0;
  std::int64_t num_builds_ = 0;
  // Cell grid: spheres sorted by cell (counting sort), cell c holds
  // cell_spheres_[cell_start_[c] .. cell_start_[c+1]).
  Eigen::Vector3d grid_origin_ = Eigen::Vector3d::Zero();
  double cell_size_ = 0.0;
  int dims_[3] = {0, 0, 0};
  std::vector<int> cell_start_, cell_spheres_, sphere_cell_;
};

}  // namespace dem
