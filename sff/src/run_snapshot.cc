#include "sff/run_snapshot.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "sffcal/clump_geometry.h"

namespace sff {
namespace {

// Solid volume from the spheres: a body's two spheres give its centre distance.
double solid_volume(const runfile::Snapshot& s) {
  std::map<std::int64_t, std::vector<std::size_t>> spheres_of;
  for (std::size_t k = 0; k < s.spheres.size(); ++k) spheres_of[s.sphere_body[k]].push_back(k);
  double total = 0.0;
  for (const auto& [body, list] : spheres_of) {
    const auto& a = s.spheres[list.front()];
    double distance = 0.0;
    if (list.size() == 2) {
      const auto& b = s.spheres[list.back()];
      distance = std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                           (a[2] - b[2]) * (a[2] - b[2]));
    }
    total += sffcal::two_sphere_union_volume(a[3], distance);
  }
  return total;
}

}  // namespace

SnapshotInput snapshot_input(const runfile::Snapshot& s, const runfile::RunPhysics& physics) {
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, force[3] = {0, 0, 0};
  int walls = 0;
  for (const runfile::WallRecord& w : s.walls) {
    (w.upper ? hi : lo)[w.axis] = w.position;
    force[w.axis] += 0.5 * w.normal_force;  // mean of the axis' two walls
    ++walls;
  }
  if (walls != 6) throw std::runtime_error("the snapshot does not hold a box of six walls");
  const double size[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};

  SnapshotInput in;
  in.contacts = ContactSpan(s.contacts);
  in.volume = size[0] * size[1] * size[2];
  for (int a = 0; a < 3; ++a) in.wall_stress[a] = force[a] * size[a] / in.volume;  // F / area
  in.solid_volume = solid_volume(s);
  in.num_bodies = static_cast<int>(s.particles.size());
  in.centroids.assign(s.particles.size(), Eigen::Vector3d::Zero());
  for (const runfile::ParticleRecord& p : s.particles) {
    if (p.id < 0 || p.id >= in.num_bodies)
      throw std::runtime_error("the snapshot has body id " + std::to_string(p.id) + " outside 0.." +
                               std::to_string(in.num_bodies - 1));
    in.centroids[static_cast<std::size_t>(p.id)] = {p.position[0], p.position[1], p.position[2]};
  }
  in.youngs_modulus = physics.youngs_modulus;
  in.friction = physics.friction;
  return in;
}

}  // namespace sff
