#include "dem/contact_list.h"

#include <algorithm>
#include <cmath>
#include <omp.h>
#include <sstream>
#include <stdexcept>

namespace dem {
namespace {

// History of one touching contact, keyed for the merge into the rebuilt list.
struct SavedHistory {
  std::uint64_t key;
  Eigen::Vector3d tangential;
  Eigen::Vector3d normal;
};

std::uint64_t pair_key(int i, int j) {
  return static_cast<std::uint64_t>(i) << 32 | static_cast<std::uint32_t>(j);
}

}  // namespace

void ContactList::build(const Particles& particles, const std::vector<Wall>& walls, double skin,
                        const std::vector<int>* old_to_new, int min_parallel_items) {
  if (!(skin > 0.0)) throw std::invalid_argument("ContactList: the Verlet skin must be positive");
  skin_ = skin;
  const int ns = particles.num_spheres();
  auto renumber = [&](int s) { return old_to_new ? (*old_to_new)[s] : s; };

  // Save the touching contacts under their (possibly renumbered) keys. A pair whose order flips
  // swaps A and B, so its force on B and its normal change sign.
  std::vector<SavedHistory> saved_pairs;
  for (int p = 0; p < num_pairs(); ++p) {
    if (!pair_touching[p]) continue;
    int i = renumber(pair_i[p]), j = renumber(pair_j[p]);
    double sign = 1.0;
    if (i > j) std::swap(i, j), sign = -1.0;
    saved_pairs.push_back({pair_key(i, j), sign * pair_tangential[p], sign * pair_normal[p]});
  }
  std::sort(saved_pairs.begin(), saved_pairs.end(),
            [](const SavedHistory& a, const SavedHistory& b) { return a.key < b.key; });
  std::vector<SavedHistory> saved_walls;
  for (int k = 0; k < num_wall_candidates(); ++k) {
    if (!wall_touching[k]) continue;
    saved_walls.push_back({pair_key(renumber(wall_sphere[k]), wall_index[k]), wall_tangential[k],
                           Eigen::Vector3d::Zero()});
  }
  std::sort(saved_walls.begin(), saved_walls.end(),
            [](const SavedHistory& a, const SavedHistory& b) { return a.key < b.key; });

  double r_max = 0.0;
  for (double r : particles.sphere_radius) r_max = std::max(r_max, r);
  build_cell_grid(particles, 2.0 * r_max + skin);
  find_pairs(particles, skin, min_parallel_items);
  find_wall_candidates(particles, walls, skin);

  // Merge the saved history into the new lists (both sorted by key).
  const int np = num_pairs();
  pair_tangential.assign(np, Eigen::Vector3d::Zero());
  pair_normal.assign(np, Eigen::Vector3d::Zero());
  pair_touching.assign(np, 0);
  std::size_t cursor = 0;
  for (int p = 0; p < np && cursor < saved_pairs.size(); ++p) {
    const std::uint64_t key = pair_key(pair_i[p], pair_j[p]);
    while (cursor < saved_pairs.size() && saved_pairs[cursor].key < key) ++cursor;
    if (cursor < saved_pairs.size() && saved_pairs[cursor].key == key) {
      pair_tangential[p] = saved_pairs[cursor].tangential;
      pair_normal[p] = saved_pairs[cursor].normal;
      pair_touching[p] = 1;
    }
  }
  const int nw = num_wall_candidates();
  wall_tangential.assign(nw, Eigen::Vector3d::Zero());
  wall_touching.assign(nw, 0);
  cursor = 0;
  for (int k = 0; k < nw && cursor < saved_walls.size(); ++k) {
    const std::uint64_t key = pair_key(wall_sphere[k], wall_index[k]);
    while (cursor < saved_walls.size() && saved_walls[cursor].key < key) ++cursor;
    if (cursor < saved_walls.size() && saved_walls[cursor].key == key) {
      wall_tangential[k] = saved_walls[cursor].tangential;
      wall_touching[k] = 1;
    }
  }

  build_incidence(ns);
  build_position = particles.sphere_position;
  build_wall_position.clear();
  for (const Wall& w : walls) build_wall_position.push_back(w.position);
  ++num_builds_;
}

void ContactList::build_cell_grid(const Particles& particles, double cell_size) {
  const int ns = particles.num_spheres();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(0.0), hi = lo;
  if (ns > 0) lo = hi = particles.sphere_position[0];
  for (const auto& x : particles.sphere_position) {
    if (!x.allFinite())
      throw std::runtime_error("ContactList: a sphere position is not finite (the run blew up)");
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  // A sparse scene (a few bodies in a large box) would need far more cells than spheres: coarser
  // cells keep the grid small and still hold every candidate pair in neighbouring cells.
  const double max_cells = 64.0 * std::max(ns, 1) + 1024.0;
  const Eigen::Vector3d extent = (hi - lo).array() + cell_size;
  cell_size = std::max(cell_size, std::cbrt(extent.prod() / max_cells));
  cell_size_ = cell_size;
  grid_origin_ = lo;
  // A scene a million cells long (a body at 1e20 m in a packing row or an edited checkpoint)
  // is no granular assembly; refused before the cell count overflows an int.
  constexpr double kMaxCellsPerAxis = 1e6;
  for (int k = 0; k < 3; ++k)
    if (!((hi[k] - lo[k]) / cell_size < kMaxCellsPerAxis)) {
      std::ostringstream message;
      message << "ContactList: the spheres span " << hi[k] - lo[k] << " m along axis " << k
              << " (from " << lo[k] << " to " << hi[k] << " m), more than a million contact "
              << "cells of " << cell_size << " m: a body lies far outside the specimen";
      throw std::runtime_error(message.str());
    }
  std::int64_t num_cells = 1;
  for (int k = 0; k < 3; ++k) {
    dims_[k] = std::max(1, static_cast<int>((hi[k] - lo[k]) / cell_size) + 1);
    num_cells *= dims_[k];
  }
  sphere_cell_.resize(ns);
  cell_start_.assign(static_cast<std::size_t>(num_cells) + 1, 0);
  for (int s = 0; s < ns; ++s) {
    const Eigen::Vector3d c = (particles.sphere_position[s] - lo) / cell_size;
    const int cx = std::min(static_cast<int>(c.x()), dims_[0] - 1);
    const int cy = std::min(static_cast<int>(c.y()), dims_[1] - 1);
    const int cz = std::min(static_cast<int>(c.z()), dims_[2] - 1);
    sphere_cell_[s] = (cz * dims_[1] + cy) * dims_[0] + cx;
    ++cell_start_[sphere_cell_[s] + 1];
  }
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_spheres_.resize(ns);
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (int s = 0; s < ns; ++s) cell_spheres_[fill[sphere_cell_[s]]++] = s;
}

void ContactList::find_pairs(const Particles& particles, double skin,
                             int min_parallel_items) {
  const int ns = particles.num_spheres();
  const auto& x = particles.sphere_position;
  const auto& radius = particles.sphere_radius;
  const auto& body = particles.sphere_body;
  const int nthreads = ns >= min_parallel_items ? omp_get_max_threads() : 1;
  std::vector<std::vector<int>> local_i(nthreads), local_j(nthreads);

  // Each thread takes one contiguous range of i (static schedule), so concatenating the
  // per-thread lists in thread order gives the serial order: same result for any thread count.
#pragma omp parallel num_threads(nthreads)
  {
    const int t = omp_get_thread_num();
    std::vector<int>& li = local_i[t];
    std::vector<int>& lj = local_j[t];
    std::vector<int> partners;
#pragma omp for schedule(static)
    for (int i = 0; i < ns; ++i) {
      const int c = sphere_cell_[i];
      const int cx = c % dims_[0], cy = (c / dims_[0]) % dims_[1], cz = c / (dims_[0] * dims_[1]);
      partners.clear();
      for (int dz = -1; dz <= 1; ++dz) {
        const int z = cz + dz;
        if (z < 0 || z >= dims_[2]) continue;
        for (int dy = -1; dy <= 1; ++dy) {
          const int y = cy + dy;
          if (y < 0 || y >= dims_[1]) continue;
          for (int dx = -1; dx <= 1; ++dx) {
            const int xx = cx + dx;
            if (xx < 0 || xx >= dims_[0]) continue;
            const int cell = (z * dims_[1] + y) * dims_[0] + xx;
            for (int k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
              const int j = cell_spheres_[k];
              if (j <= i || body[j] == body[i]) continue;
              const double reach = radius[i] + radius[j] + skin;
              if ((x[j] - x[i]).squaredNorm() < reach * reach) partners.push_back(j);
            }
          }
        }
      }
      std::sort(partners.begin(), partners.end());
      for (int j : partners) {
        li.push_back(i);
        lj.push_back(j);
      }
    }
  }
  pair_i.clear();
  pair_j.clear();
  for (int t = 0; t < nthreads; ++t) {
    pair_i.insert(pair_i.end(), local_i[t].begin(), local_i[t].end());
    pair_j.insert(pair_j.end(), local_j[t].begin(), local_j[t].end());
  }
}

void ContactList::find_wall_candidates(const Particles& particles,
                                       const std::vector<Wall>& walls, double skin) {
  wall_sphere.clear();
  wall_index.clear();
  const int ns = particles.num_spheres();
  const int nw = static_cast<int>(walls.size());
  for (int s = 0; s < ns; ++s) {
    for (int w = 0; w < nw; ++w) {
      const Wall& wall = walls[w];
      const double along = particles.sphere_position[s][wall.axis] - wall.position;
      const double gap = (wall.upper ? -along : along) - particles.sphere_radius[s];
      if (gap < skin) {
        wall_sphere.push_back(s);
        wall_index.push_back(w);
      }
    }
  }
}

std::string ContactList::check(int num_spheres, int num_walls) const {
  std::ostringstream e;
  const std::size_t np = pair_i.size(), nw = wall_sphere.size();
  if (pair_j.size() != np || pair_tangential.size() != np || pair_normal.size() != np ||
      pair_touching.size() != np)
    e << "the pair arrays have different lengths (pair_i " << np << "); ";
  if (wall_index.size() != nw || wall_tangential.size() != nw || wall_touching.size() != nw)
    e << "the wall-candidate arrays have different lengths (wall_sphere " << nw << "); ";
  if (!build_position.empty() && static_cast<int>(build_position.size()) != num_spheres)
    e << "build_position has " << build_position.size() << " entries for " << num_spheres
      << " spheres; ";
  if (!build_wall_position.empty() && static_cast<int>(build_wall_position.size()) != num_walls)
    e << "build_wall_position has " << build_wall_position.size() << " entries for " << num_walls
      << " walls; ";
  if (!e.str().empty()) return e.str();
  for (std::size_t p = 0; p < np; ++p)
    if (pair_i[p] < 0 || pair_j[p] <= pair_i[p] || pair_j[p] >= num_spheres ||
        !pair_tangential[p].allFinite() || !pair_normal[p].allFinite()) {
      e << "pair " << p << " (spheres " << pair_i[p] << ", " << pair_j[p]
        << ") is out of range of the " << num_spheres << " spheres or its history is not finite; ";
      break;
    }
  for (std::size_t k = 0; k < nw; ++k)
    if (wall_sphere[k] < 0 || wall_sphere[k] >= num_spheres || wall_index[k] < 0 ||
        wall_index[k] >= num_walls || !wall_tangential[k].allFinite()) {
      e << "wall candidate " << k << " (sphere " << wall_sphere[k] << ", wall " << wall_index[k]
        << ") is out of range or its history is not finite; ";
      break;
    }
  for (const Eigen::Vector3d& x : build_position)
    if (!x.allFinite()) {
      e << "a build position is not finite; ";
      break;
    }
  return e.str();
}

void ContactList::restore(double skin, std::int64_t num_builds, int num_spheres) {
  skin_ = skin;
  num_builds_ = num_builds;
  build_incidence(num_spheres);
}

void ContactList::build_incidence(int num_spheres) {
  const int np = num_pairs();
  incidence_offset.assign(num_spheres + 1, 0);
  for (int p = 0; p < np; ++p) {
    ++incidence_offset[pair_i[p] + 1];
    ++incidence_offset[pair_j[p] + 1];
  }
  for (int s : wall_sphere) ++incidence_offset[s + 1];
  for (int s = 0; s < num_spheres; ++s) incidence_offset[s + 1] += incidence_offset[s];
  incidence.resize(incidence_offset[num_spheres]);
  std::vector<int> fill(incidence_offset.begin(), incidence_offset.end() - 1);
  // Slots are visited in increasing order, so each sphere's list is sorted: a fixed summation
  // order for the forces on it whatever the thread count.
  for (int p = 0; p < np; ++p) {
    incidence[fill[pair_i[p]]++] = 2 * p;
    incidence[fill[pair_j[p]]++] = 2 * p + 1;
  }
  for (int k = 0; k < num_wall_candidates(); ++k)
    incidence[fill[wall_sphere[k]]++] = 2 * (np + k) + 1;
}

}  // namespace dem
