// Observables of a Simulation, computed only when asked for (an output step), never in step().
#include <algorithm>
#include <cmath>

#include "dem/parallel.h"
#include "dem/simulation.h"

namespace dem {

int Simulation::num_touching_pairs() const {
  const int np = contacts_.num_pairs();
  return deterministic_sum(np, 0, [&](int begin, int end) {
    int n = 0;
    for (int p = begin; p < end; ++p) n += slots_[p].overlap > 0.0;
    return n;
  });
}

Eigen::Matrix3d Simulation::contact_stress(bool include_walls) const {
  const double volume = box_volume();
  if (!(volume > 0.0)) return Eigen::Matrix3d::Zero();
  const Particles& P = particles_;
  const ContactList& C = contacts_;
  // sigma = (1/V) sum_c sym(l^c (x) f^c), l the branch vector between the body centroids.
  const Eigen::Matrix3d sum =
      deterministic_sum(C.num_pairs(), Eigen::Matrix3d::Zero().eval(), [&](int begin, int end) {
        Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
        for (int p = begin; p < end; ++p) {
          if (slots_[p].overlap == 0.0) continue;
          const Eigen::Vector3d branch =
              P.position[P.sphere_body[C.pair_j[p]]] - P.position[P.sphere_body[C.pair_i[p]]];
          s.noalias() += branch * slots_[p].force.transpose();
        }
        return s;
      });
  Eigen::Matrix3d total = sum;
  if (include_walls) {
    for (int k = 0; k < C.num_wall_candidates(); ++k) {
      const int slot = C.num_pairs() + k;
      if (slots_[slot].overlap == 0.0) continue;
      const int s = C.wall_sphere[k];
      const Eigen::Vector3d n = walls_[C.wall_index[k]].inward_normal();
      // Minus the lever from the centroid to the contact point (the wall plays body A).
      const Eigen::Vector3d lever = (P.sphere_radius[s] - 0.5 * slots_[slot].overlap) * n -
                                    (P.sphere_position[s] - P.position[P.sphere_body[s]]);
      total.noalias() += lever * slots_[slot].force.transpose();
    }
  }
  return 0.5 * (total + total.transpose()) / volume;
}

double Simulation::kinetic_energy() const {
  const Particles& P = particles_;
  return deterministic_sum(P.num_bodies(), 0.0, [&](int begin, int end) {
    double e = 0.0;
    for (int b = begin; b < end; ++b)
      e += 0.5 * options_.density_scaling * P.mass[b] * P.velocity[b].squaredNorm() +
           0.5 * P.angular_momentum[b].dot(P.angular_velocity[b]);
    return e;
  });
}

double Simulation::unbalanced_force_ratio() const {
  const Particles& P = particles_;
  const Eigen::Vector3d gravity = options_.gravity;
  const double net = deterministic_sum(P.num_bodies(), 0.0, [&](int begin, int end) {
    double s = 0.0;
    for (int b = begin; b < end; ++b)
      s += (P.force[b] + P.mass[b] * gravity).norm();  // the true weight, as integrate() applies
    return s;
  });
  int touching = 0;
  const double contact = deterministic_sum(contacts_.num_slots(), 0.0, [&](int begin, int end) {
    double s = 0.0;
    for (int k = begin; k < end; ++k) s += slots_[k].force.norm();
    return s;
  });
  for (const SlotResult& r : slots_) touching += r.overlap > 0.0;
  if (touching == 0) return net > 0.0 ? 1.0 : 0.0;
  return (net / P.num_bodies()) / (contact / touching);
}

double Simulation::max_friction_utilisation() const {
  double worst = 0.0;
  for (int k = 0; k < contacts_.num_slots(); ++k) {
    if (slots_[k].overlap == 0.0) continue;
    const bool wall = k >= contacts_.num_pairs();
    const double mu = wall ? contact_.wall_friction : contact_.friction;
    const Eigen::Vector3d n =
        wall ? walls_[contacts_.wall_index[k - contacts_.num_pairs()]].inward_normal()
             : contacts_.pair_normal[k];
    const double fn = slots_[k].force.dot(n);
    const double ft = (slots_[k].force - fn * n).norm();
    if (ft == 0.0) continue;
    worst = std::max(worst, mu > 0.0 && fn > 0.0 ? ft / (mu * fn) : HUGE_VAL);
  }
  return worst;
}

std::vector<ContactRecord> Simulation::contact_records(bool include_walls) const {
  const Particles& P = particles_;
  const ContactList& C = contacts_;
  std::vector<ContactRecord> records;
  auto fill_force = [&](ContactRecord& r, int slot, const Eigen::Vector3d& n) {
    const Eigen::Vector3d& f = slots_[slot].force;
    const double fn = f.dot(n);
    const Eigen::Vector3d ft = f - fn * n;
    r.overlap = slots_[slot].overlap;
    r.normal_force = fn;
    r.sliding = slots_[slot].sliding;
    for (int k = 0; k < 3; ++k) {
      r.normal[k] = n[k];
      r.tangential_force[k] = ft[k];
    }
  };
  for (int p = 0; p < C.num_pairs(); ++p) {
    if (slots_[p].overlap == 0.0) continue;
    const int i = C.pair_i[p], j = C.pair_j[p];
    const int a = P.sphere_body[i], b = P.sphere_body[j];
    const Eigen::Vector3d& n = C.pair_normal[p];
    const Eigen::Vector3d point =
        P.sphere_position[i] + (P.sphere_radius[i] - 0.5 * slots_[p].overlap) * n;
    const Eigen::Vector3d branch = P.position[b] - P.position[a];
    ContactRecord r;
    r.body_a = P.id[a];
    r.body_b = P.id[b];
    for (int k = 0; k < 3; ++k) {
      r.point[k] = point[k];
      r.branch[k] = branch[k];
    }
    fill_force(r, p, n);
    records.push_back(r);
  }
  if (!include_walls) return records;
  for (int k = 0; k < C.num_wall_candidates(); ++k) {
    const int slot = C.num_pairs() + k;
    if (slots_[slot].overlap == 0.0) continue;
    const int s = C.wall_sphere[k], w = C.wall_index[k];
    const Eigen::Vector3d n = walls_[w].inward_normal();
    const Eigen::Vector3d point =
        P.sphere_position[s] - (P.sphere_radius[s] - 0.5 * slots_[slot].overlap) * n;
    ContactRecord r;
    r.body_b = P.id[P.sphere_body[s]];
    r.wall = w;
    for (int d = 0; d < 3; ++d) r.point[d] = point[d];
    fill_force(r, slot, n);
    records.push_back(r);
  }
  return records;
}

MacroRecord Simulation::macro_record() const {
  MacroRecord m;
  m.step = step_count_;
  m.time = time_;
  if (has_box()) {
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        const int w = box_walls_[a][side];
        m.wall_position[2 * a + side] = walls_[w].position;
        m.wall_force[2 * a + side] = wall_force_[w];
      }
  }
  const Eigen::Matrix3d sigma = contact_stress();
  m.contact_stress = {sigma(0, 0), sigma(1, 1), sigma(2, 2), sigma(1, 2), sigma(0, 2), sigma(0, 1)};
  m.volume = box_volume();
  m.num_contacts = num_touching_pairs();
  m.coordination_number = 2.0 * static_cast<double>(m.num_contacts) / particles_.num_bodies();
  m.kinetic_energy = kinetic_energy();
  m.unbalanced_force_ratio = unbalanced_force_ratio();
  return m;
}

}  // namespace dem
