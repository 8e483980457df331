#include "sff/run_snapshot.h"

#include <stdexcept>
#include <string>

#include "runfile/snapshot_geometry.h"

namespace sff {

SnapshotInput snapshot_input(const runfile::Snapshot& s, const runfile::RunPhysics& physics) {
  SnapshotInput in;
  in.contacts = ContactSpan(s.contacts);
  in.solid_volume = runfile::solid_volume(s);
  in.num_bodies = static_cast<int>(s.particles.size());
  in.youngs_modulus = physics.youngs_modulus;
  in.friction = physics.friction;
  if (!s.periodic_cell.empty()) {  // an imported periodic run: no walls, no wall stress
    in.volume = 1.0;
    for (int a = 0; a < 3; ++a) in.volume *= s.periodic_cell[1][a] - s.periodic_cell[0][a];
    return in;
  }
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, force[3] = {0, 0, 0};
  int walls = 0;
  for (const runfile::WallRecord& w : s.walls) {
    (w.upper ? hi : lo)[w.axis] = w.position;
    force[w.axis] += 0.5 * w.normal_force;  // mean of the axis' two walls
    ++walls;
  }
  if (walls != 6)
    throw std::runtime_error("the snapshot holds neither a box of six walls nor a periodic cell");
  const double size[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
  in.volume = size[0] * size[1] * size[2];
  for (int a = 0; a < 3; ++a) in.wall_stress[a] = force[a] * size[a] / in.volume;  // F / area
  in.centroids.assign(s.particles.size(), Eigen::Vector3d::Zero());
  for (const runfile::ParticleRecord& p : s.particles) {
    if (p.id < 0 || p.id >= in.num_bodies)
      throw std::runtime_error("the snapshot has body id " + std::to_string(p.id) + " outside 0.." +
                               std::to_string(in.num_bodies - 1));
    in.centroids[static_cast<std::size_t>(p.id)] = {p.position[0], p.position[1], p.position[2]};
  }
  return in;
}

}  // namespace sff
