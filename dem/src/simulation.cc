#include "dem/simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "dem/critical_step.h"
#include "dem/rigid_body.h"

namespace dem {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Cundall's local damping: each component loses alpha |F_k| against the sign of its velocity.
inline Eigen::Vector3d locally_damped(const Eigen::Vector3d& f, const Eigen::Vector3d& v,
                                      double alpha) {
  Eigen::Vector3d out = f;
  for (int k = 0; k < 3; ++k) {
    if (v[k] > 0.0) out[k] -= alpha * std::abs(f[k]);
    else if (v[k] < 0.0) out[k] += alpha * std::abs(f[k]);
  }
  return out;
}

}  // namespace

std::string SceneFeatures::describe() const {
  std::string s = clumps ? "clumps" : "spheres";
  if (friction) s += ", grain friction";
  if (wall_friction) s += ", wall friction";
  if (gravity) s += ", gravity";
  if (local_damping) s += ", local damping";
  if (viscous_damping) s += ", contact damping";
  if (!rotation()) s += ", no rotation";
  return s;
}

std::string SimulationOptions::validate() const {
  std::ostringstream error;
  if (!(time_step >= 0.0 && std::isfinite(time_step)))
    error << "time_step must be >= 0 (0 = automatic), got " << time_step << " s; ";
  if (!(time_step_safety > 0.0 && time_step_safety <= 1.0))
    error << "time_step_safety must lie in (0, 1], got " << time_step_safety << "; ";
  if (!(skin_ratio > 0.0 && skin_ratio <= 2.0))
    error << "skin_ratio must lie in (0, 2], got " << skin_ratio << "; ";
  if (sort_every_builds < 0) error << "sort_every_builds must be >= 0; ";
  if (min_parallel_items < 1) error << "min_parallel_items must be >= 1; ";
  if (!gravity.allFinite()) error << "gravity must be finite; ";
  if (!(local_damping >= 0.0 && local_damping < 1.0))
    error << "local_damping must lie in [0, 1), got " << local_damping << "; ";
  if (!(density_scaling >= 1.0 && std::isfinite(density_scaling)))
    error << "density_scaling must be >= 1, got " << density_scaling << "; ";
  if (!(max_overlap_ratio > 0.0 && max_overlap_ratio < 1.0))
    error << "max_overlap_ratio must lie in (0, 1), got " << max_overlap_ratio << "; ";
  // The servo's loop at this step (an explicit step is at most the critical one: checked at 1).
  error << servo.validate(time_step > 0.0 ? 1.0 : time_step_safety);
  return error.str();
}

Simulation::Simulation(Particles particles, std::vector<Wall> walls, ContactParameters contact,
                       SimulationOptions options)
    : particles_(std::move(particles)),
      walls_(std::move(walls)),
      contact_(contact),
      options_(std::move(options)) {
  initialise();
  particles_.update_sphere_positions();
  ContactList candidates;
  candidates.build(particles_, walls_, skin_, nullptr, options_.min_parallel_items);
  refuse_deep_initial_overlaps(candidates);
  set_time_step(candidates, /*running=*/false);
  last_step_dt_ = dt_;
}

Simulation::Simulation(SimulationState state, ContactParameters contact,
                       SimulationOptions options)
    : particles_(std::move(state.particles)),
      walls_(std::move(state.walls)),
      contact_(contact),
      options_(std::move(options)),
      contacts_(std::move(state.contacts)),
      time_(state.time),
      step_count_(state.step_count),
      rebuild_due_(state.rebuild_due) {
  initialise();
  max_sphere_move_ = state.max_sphere_move;
  if (state.servo.size() != walls_.size())
    throw std::invalid_argument("Simulation: the saved state needs one servo state per wall");
  const std::string contact_error =
      contacts_.check(particles_.num_spheres(), static_cast<int>(walls_.size()));
  if (!contact_error.empty())
    throw std::invalid_argument("Simulation: the saved contact list: " + contact_error);
  servo_ = std::move(state.servo);
  const int slots = contacts_.num_slots();
  slots_.assign(slots, SlotResult{});
  // The step of the restored list is the one the run was using (the same list, the same sum);
  // a state without a list gets the estimate of the list its first step will build.
  if (contacts_.num_builds() > 0 &&
      static_cast<int>(contacts_.build_position.size()) == particles_.num_spheres()) {
    set_time_step(contacts_, /*running=*/false);
  } else {
    ContactList candidates;
    candidates.build(particles_, walls_, skin_, nullptr, options_.min_parallel_items);
    set_time_step(candidates, /*running=*/false);
  }
  // A state is saved between steps, after which the step changes only at the next list build:
  // the last step had the length of the present one.
  last_step_dt_ = dt_;
  check_restored_motion();
}

// A state from outside (a checkpoint, a CSV packing with velocities): its servo must be finite,
// and no body may move or turn the surface of one of its spheres by more than that sphere's
// radius in one step. A run cannot get there (its overlaps would have stopped it as unstable),
// the contact law's increments assume far less, and an angular momentum of 1e300 ran on, finite.
void Simulation::check_restored_motion() const {
  for (std::size_t w = 0; w < servo_.size(); ++w)
    if (!std::isfinite(servo_[w].last_move) || !std::isfinite(servo_[w].integral))
      throw std::invalid_argument("Simulation: the saved servo state of wall " +
                                  std::to_string(w) + " is not finite");
  const Particles& P = particles_;
  for (int b = 0; b < P.num_bodies(); ++b) {
    const double inertia =
        std::min(P.inertia_axial[b], P.inertia_transverse[b]) * options_.density_scaling;
    const double spin = P.angular_momentum[b].stableNorm() / inertia;  // an upper bound [rad/s]
    const double speed = P.velocity[b].stableNorm();
    for (int s = P.first_sphere[b]; s < P.first_sphere[b] + P.num_body_spheres[b]; ++s) {
      const double r = P.sphere_radius[s];
      const double move = (speed + spin * (std::abs(P.sphere_offset[s]) + r)) * dt_;
      if (move <= r) continue;
      std::ostringstream msg;
      msg << "Simulation: the state to start from moves a sphere of body " << P.id[b] << " by "
          << move << " m in one step (speed " << speed << " m/s, spin up to " << spin
          << " rad/s, time step " << dt_ << " s), more than its radius " << r
          << " m: not a state a run reaches";
      throw std::invalid_argument(msg.str());
    }
  }
}

SimulationState Simulation::state() const {
  SimulationState s;
  s.particles = particles_;
  s.walls = walls_;
  s.contacts = contacts_;
  s.time = time_;
  s.step_count = step_count_;
  s.rebuild_due = rebuild_due_;
  s.max_sphere_move = max_sphere_move_;
  s.servo = servo_;
  return s;
}

void Simulation::initialise() {
  std::string error = contact_.validate() + options_.validate() + particles_.check();
  if (particles_.num_bodies() == 0) error += "the scene has no bodies; ";
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const Wall& wall = walls_[w];
    if (wall.axis < 0 || wall.axis > 2) error += "wall " + std::to_string(w) + " axis not 0-2; ";
    if (!std::isfinite(wall.position) || !std::isfinite(wall.velocity))
      error += "wall " + std::to_string(w) + " position or velocity not finite; ";
    if (wall.mode == WallMode::kStress && !(wall.target_stress >= 0.0))
      error += "wall " + std::to_string(w) + " target_stress must be >= 0; ";
  }
  if (!error.empty()) throw std::invalid_argument("Simulation: " + error);
  find_box_walls();
  for (const Wall& wall : walls_)
    if (wall.mode == WallMode::kStress && !has_box())
      throw std::invalid_argument(
          "Simulation: a stress-controlled wall needs a full box of six walls to define its "
          "area");

  features_.clumps = particles_.has_clumps();
  features_.friction = contact_.friction > 0.0;
  features_.wall_friction = contact_.wall_friction > 0.0 && !walls_.empty();
  features_.gravity = options_.gravity.squaredNorm() > 0.0;
  features_.local_damping = options_.local_damping > 0.0;
  features_.viscous_damping = contact_.normal_damping_ratio > 0.0;

  double r_max = 0.0;
  for (int b = 0; b < particles_.num_bodies(); ++b) {
    const double r = particles_.sphere_radius[particles_.first_sphere[b]];
    if (!(r > 0.0)) throw std::invalid_argument("Simulation: a sphere radius is not positive");
    r_max = std::max(r_max, r);
  }
  skin_ = options_.skin_ratio * 2.0 * r_max;
  one_contact_dt_ = one_contact_time_step(particles_, contact_, options_.density_scaling);
  wall_force_.assign(walls_.size(), 0.0);
  wall_stiffness_.assign(walls_.size(), 0.0);
  servo_.assign(walls_.size(), ServoState{});
}

void Simulation::set_time_step(const ContactList& list, bool running) {
  stability_ = stability_limit(particles_, walls_, list, contact_, options_.density_scaling,
                               options_.min_parallel_items);
  // Without candidates no contact can form before the next build; a body's first contact then
  // bounds the step of the build after.
  const bool any_candidate = std::isfinite(stability_.time_step());
  critical_dt_ = (any_candidate ? stability_.time_step() : one_contact_dt_) *
                 damped_limit_factor(options_.local_damping,
                                     any_candidate ? stability_.modal_damping_ratio
                                                   : contact_.normal_damping_ratio);
  const double previous_dt = dt_;
  dt_ = options_.time_step > 0.0 ? options_.time_step : options_.time_step_safety * critical_dt_;
  if (!(dt_ > 0.0 && std::isfinite(dt_))) {
    std::ostringstream msg;
    msg << "Simulation: the time step is not positive and finite (" << dt_
        << " s): check the grain masses, sizes and youngs_modulus";
    throw std::invalid_argument(msg.str());
  }
  // The servo carries displacements per step: keep the wall speeds they stand for.
  if (running && previous_dt > 0.0 && dt_ != previous_dt) {
    const double scale = dt_ / previous_dt;
    for (ServoState& servo : servo_) {
      servo.last_move *= scale;
      servo.integral *= scale;
    }
  }
  if (dt_ > critical_dt_) {
    std::ostringstream msg;
    msg << "Simulation: time_step " << dt_ << " s exceeds the critical step " << critical_dt_
        << " s, leapfrog's limit 2/omega_max of the bodies on their contact springs"
        << (running ? " (at step " + std::to_string(step_count_) + ", after the contacts changed)"
                    : "")
        << ", past which the run is unstable; use time_step_safety (default "
        << SimulationOptions{}.time_step_safety
        << ", which follows the contacts) or a smaller time_step";
    if (running) throw std::runtime_error(msg.str());
    throw std::invalid_argument(msg.str());
  }
}

void Simulation::refuse_deep_initial_overlaps(const ContactList& candidates) const {
  // An input overlap beyond the limit would stop the first step as "unstable"; say instead which
  // bodies the input put inside each other. Shallower overlaps are pushed apart by the dynamics.
  const Particles& P = particles_;
  const double limit = options_.max_overlap_ratio;
  auto refuse = [&](const std::string& what, double ratio) {
    std::ostringstream msg;
    msg << "Simulation: " << what << " overlap by " << ratio
        << " of the smaller sphere radius at the start (limit max_overlap_ratio " << limit
        << "); move them apart or make them smaller";
    throw std::invalid_argument(msg.str());
  };
  for (int p = 0; p < candidates.num_pairs(); ++p) {
    const int i = candidates.pair_i[p], j = candidates.pair_j[p];
    const double ri = P.sphere_radius[i], rj = P.sphere_radius[j];
    const double ratio =
        (ri + rj - (P.sphere_position[j] - P.sphere_position[i]).norm()) / std::min(ri, rj);
    if (ratio > limit)
      refuse("bodies " + std::to_string(P.id[P.sphere_body[i]]) + " and " +
                 std::to_string(P.id[P.sphere_body[j]]),
             ratio);
  }
  for (int k = 0; k < candidates.num_wall_candidates(); ++k) {
    const int s = candidates.wall_sphere[k], w = candidates.wall_index[k];
    const Wall& wall = walls_[w];
    const double along = P.sphere_position[s][wall.axis] - wall.position;
    const double ratio = 1.0 - (wall.upper ? -along : along) / P.sphere_radius[s];
    if (ratio > limit)
      refuse("body " + std::to_string(P.id[P.sphere_body[s]]) + " and wall " + std::to_string(w),
             ratio);
  }
}

void Simulation::find_box_walls() {
  int found[3][2] = {{-1, -1}, {-1, -1}, {-1, -1}};
  for (int w = 0; w < static_cast<int>(walls_.size()); ++w) {
    int& slot = found[walls_[w].axis][walls_[w].upper ? 1 : 0];
    if (slot >= 0) return;  // two walls on one side: not a box
    slot = w;
  }
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side)
      if (found[a][side] < 0) return;
  std::copy(&found[0][0], &found[0][0] + 6, &box_walls_[0][0]);
}

double Simulation::box_volume() const {
  if (!has_box()) return 0.0;
  double v = 1.0;
  for (int a = 0; a < 3; ++a)
    v *= walls_[box_walls_[a][1]].position - walls_[box_walls_[a][0]].position;
  return v;
}

double Simulation::wall_area(int w) const {
  if (!has_box()) return 0.0;
  double area = 1.0;
  for (int a = 0; a < 3; ++a)
    if (a != walls_[w].axis)
      area *= walls_[box_walls_[a][1]].position - walls_[box_walls_[a][0]].position;
  return area;
}

double Simulation::wall_stress(int axis) const {
  const int lower = box_wall(axis, false), upper = box_wall(axis, true);
  return 0.5 * (wall_force_[lower] / wall_area(lower) + wall_force_[upper] / wall_area(upper));
}

void Simulation::rebuild_contacts() {
  std::vector<int> old_to_new;
  const bool sort_now = options_.sort_every_builds > 0 &&
                        contacts_.num_builds() % options_.sort_every_builds == 0;
  if (sort_now) old_to_new = particles_.sort_spatially(skin_ / options_.skin_ratio + skin_);
  contacts_.build(particles_, walls_, skin_, sort_now ? &old_to_new : nullptr,
                  options_.min_parallel_items);
  const int slots = contacts_.num_slots();
  slots_.assign(slots, SlotResult{});
  rebuild_due_ = false;
  set_time_step(contacts_, /*running=*/true);
}

template <bool kClumps, bool kFriction, bool kViscous>
void Simulation::compute_pair_forces() {
  const Particles& P = particles_;
  ContactList& C = contacts_;
  const int np = C.num_pairs();
  const double young = contact_.youngs_modulus;
  const double xi = contact_.stiffness_ratio, mu = contact_.friction;
  // The tangential increment is the displacement of the last step, v(t - dt/2) times its length.
  const double beta = contact_.normal_damping_ratio, dt = last_step_dt_;
  double worst_ratio = 0.0;
#pragma omp parallel for schedule(static) reduction(max : worst_ratio) \
    if (np >= options_.min_parallel_items)
  for (int p = 0; p < np; ++p) {
    const int i = C.pair_i[p], j = C.pair_j[p];
    const double ri = P.sphere_radius[i], rj = P.sphere_radius[j];
    const Eigen::Vector3d d = P.sphere_position[j] - P.sphere_position[i];
    const double reach = ri + rj, d2 = d.squaredNorm();
    if (d2 >= reach * reach) {
      if (C.pair_touching[p]) {  // separation erases the tangential history
        C.pair_touching[p] = 0;
        C.pair_tangential[p].setZero();
        slots_[p] = SlotResult{};
      }
      continue;
    }
    const double dist = std::sqrt(d2);
    const Eigen::Vector3d n = d / dist;
    const double overlap = reach - dist;
    const double k = normal_stiffness(young, ri, rj);
    double fn = k * overlap;
    Eigen::Vector3d ft = Eigen::Vector3d::Zero();
    bool sliding = false;
    if constexpr (kFriction || kViscous) {
      // Without clumps, sphere s is body s and the levers lie along the normal.
      const int a = kClumps ? P.sphere_body[i] : i, b = kClumps ? P.sphere_body[j] : j;
      Eigen::Vector3d lever_a = (ri - 0.5 * overlap) * n, lever_b = -(rj - 0.5 * overlap) * n;
      if constexpr (kClumps) {
        const Eigen::Vector3d point = P.sphere_position[i] + lever_a;
        lever_a = point - P.position[a];
        lever_b = point - P.position[b];
      }
      const Eigen::Vector3d v_rel = P.velocity[b] + P.angular_velocity[b].cross(lever_b) -
                                    P.velocity[a] - P.angular_velocity[a].cross(lever_a);
      const double vn = v_rel.dot(n);
      if constexpr (kViscous) {
        const double m_red =
            options_.density_scaling * P.mass[a] * P.mass[b] / (P.mass[a] + P.mass[b]);
        fn = std::max(0.0, fn - 2.0 * beta * std::sqrt(m_red * k) * vn);
      }
      if constexpr (kFriction) {
        if (C.pair_touching[p]) {
          const double twirl = 0.5 * dt * (P.angular_velocity[a] + P.angular_velocity[b]).dot(n);
          ft = rotate_with_contact_frame(C.pair_tangential[p], C.pair_normal[p], n, twirl);
        }
        ft -= (xi * k * dt) * (v_rel - vn * n);
        sliding = apply_coulomb_limit(ft, mu * fn);
        C.pair_tangential[p] = ft;
      }
    }
    C.pair_normal[p] = n;
    C.pair_touching[p] = 1;
    slots_[p].force = fn * n + ft;
    slots_[p].moment = n.cross(ft);
    slots_[p].overlap = overlap;
    slots_[p].sliding = sliding;
    worst_ratio = std::max(worst_ratio, overlap / std::min(ri, rj));
  }
  if (worst_ratio > options_.max_overlap_ratio) report_deep_pair_overlap(worst_ratio);
}

void Simulation::report_deep_pair_overlap(double worst_ratio) const {
  // The pair to name, found again serially (this runs once, when the run stops).
  const Particles& P = particles_;
  const ContactList& C = contacts_;
  int worst = 0;
  double largest = -1.0;
  for (int p = 0; p < C.num_pairs(); ++p) {
    const double ratio =
        slots_[p].overlap / std::min(P.sphere_radius[C.pair_i[p]], P.sphere_radius[C.pair_j[p]]);
    if (ratio > largest) largest = ratio, worst = p;
  }
  report_deep_overlap("bodies " + std::to_string(P.id[P.sphere_body[C.pair_i[worst]]]) + " and " +
                          std::to_string(P.id[P.sphere_body[C.pair_j[worst]]]),
                      worst_ratio);
}

void Simulation::report_deep_overlap(const std::string& what, double ratio) const {
  std::ostringstream msg;
  msg << "unstable run at step " << step_count_ << ": " << what << " overlap by " << ratio
      << " of the smaller sphere radius (limit max_overlap_ratio " << options_.max_overlap_ratio
      << "); time step " << dt_ << " s, critical step " << critical_dt_ << " s.";
  double stress = 0.0;
  if (has_box())
    for (int w = 0; w < 6; ++w) stress += wall_force_[w] / wall_area(w) / 6.0;
  if (stress > 0.0) {
    msg << " The walls carry a mean stress of " << stress << " Pa (E / stress = "
        << contact_.youngs_modulus / stress << ").";
  }
  msg << " Either the run is unstable (reduce the time step or the loading rate) or the grains "
         "are too soft for the stress they carry (raise youngs_modulus or lower the pressure).";
  throw std::runtime_error(msg.str());
}

template <bool kWallFriction, bool kViscous>
void Simulation::compute_wall_forces() {
  const Particles& P = particles_;
  ContactList& C = contacts_;
  const int np = C.num_pairs(), nw = C.num_wall_candidates();
  const double young = contact_.youngs_modulus;
  const double xi = contact_.stiffness_ratio, mu = contact_.wall_friction;
  std::fill(wall_force_.begin(), wall_force_.end(), 0.0);
  std::fill(wall_stiffness_.begin(), wall_stiffness_.end(), 0.0);
  double worst_ratio = 0.0;
  int worst = -1;
  for (int k = 0; k < nw; ++k) {
    const int s = C.wall_sphere[k], w = C.wall_index[k], slot = np + k;
    const Wall& wall = walls_[w];
    const double r = P.sphere_radius[s];
    const double along = P.sphere_position[s][wall.axis] - wall.position;
    const double overlap = r - (wall.upper ? -along : along);
    if (overlap <= 0.0) {
      if (C.wall_touching[k]) {
        C.wall_touching[k] = 0;
        C.wall_tangential[k].setZero();
        slots_[slot] = SlotResult{};
      }
      continue;
    }
    const Eigen::Vector3d n = wall.inward_normal();
    const double stiffness = wall_normal_stiffness(young, r);
    double fn = stiffness * overlap;
    // What the servo reads as the wall's stiffness: the force a move of the wall adds over one
    // step, through the spring and, moving at move / dt, through the dashpot (without the
    // dashpot's share a servo at gain 0.8 overshot and never settled for ratios >= 0.35).
    double step_stiffness = stiffness;
    Eigen::Vector3d ft = Eigen::Vector3d::Zero();
    bool sliding = false;
    if constexpr (kWallFriction || kViscous) {
      const int b = P.sphere_body[s];
      const Eigen::Vector3d point = P.sphere_position[s] - (r - 0.5 * overlap) * n;
      Eigen::Vector3d v_rel = P.velocity[b] + P.angular_velocity[b].cross(point - P.position[b]);
      v_rel[wall.axis] -= wall.velocity;
      const double vn = v_rel.dot(n);
      if constexpr (kViscous) {
        const double dashpot = 2.0 * contact_.normal_damping_ratio *
                               std::sqrt(options_.density_scaling * P.mass[b] * stiffness);
        fn = std::max(0.0, fn - dashpot * vn);
        step_stiffness += dashpot / dt_;
      }
      if constexpr (kWallFriction) {
        if (C.wall_touching[k]) {
          const double twirl = 0.5 * last_step_dt_ * P.angular_velocity[b].dot(n);
          ft = rotate_with_contact_frame(C.wall_tangential[k], n, n, twirl);
        }
        ft -= (xi * stiffness * last_step_dt_) * (v_rel - vn * n);
        sliding = apply_coulomb_limit(ft, mu * fn);
        C.wall_tangential[k] = ft;
      }
    }
    C.wall_touching[k] = 1;
    slots_[slot].force = fn * n + ft;
    slots_[slot].moment = n.cross(ft);
    slots_[slot].overlap = overlap;
    slots_[slot].sliding = sliding;
    wall_force_[w] += fn;
    wall_stiffness_[w] += step_stiffness;
    if (overlap > worst_ratio * r) worst_ratio = overlap / r, worst = k;
  }
  // Wall contacts get the same limit and diagnostic as sphere pairs (the smaller radius is the
  // sphere's: a wall is a sphere of infinite radius).
  if (worst_ratio > options_.max_overlap_ratio) {
    report_deep_overlap("body " + std::to_string(P.id[P.sphere_body[C.wall_sphere[worst]]]) +
                            " and wall " + std::to_string(C.wall_index[worst]),
                        worst_ratio);
  }
}

template <bool kClumps, bool kMoments>
void Simulation::sum_body_forces() {
  Particles& P = particles_;
  const ContactList& C = contacts_;
  const int nb = P.num_bodies();
#pragma omp parallel for schedule(static) if (nb >= options_.min_parallel_items)
  for (int b = 0; b < nb; ++b) {
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
    const int s_end = P.first_sphere[b] + P.num_body_spheres[b];
    for (int s = P.first_sphere[b]; s < s_end; ++s) {
      Eigen::Vector3d f_s = Eigen::Vector3d::Zero();
      for (int e = C.incidence_offset[s]; e < C.incidence_offset[s + 1]; ++e) {
        const int code = C.incidence[e], slot = code >> 1;
        // Every candidate is added, touching or not: a slot that does not touch holds zeros
        // (cleared at the list build and at separation), so the sums are the same bit for bit.
        // A test of the touching byte here was a branch that half the candidates take, in no
        // order a predictor follows: dearer than reading the zeros (bench/RESULTS.md, "third
        // step").
        if (code & 1) f_s += slots_[slot].force;
        else f_s -= slots_[slot].force;
        if constexpr (kMoments) {
          // Lever from the sphere centre to the contact point (mid-overlap): the moment is
          // -(r - overlap/2) n x f for either body of the contact.
          torque -= (P.sphere_radius[s] - 0.5 * slots_[slot].overlap) * slots_[slot].moment;
        }
      }
      force += f_s;
      if constexpr (kClumps) torque += (P.sphere_position[s] - P.position[b]).cross(f_s);
    }
    P.force[b] = force;
    P.torque[b] = torque;
  }
}

template <bool kClumps, bool kRotation, bool kGravity, bool kDamping>
void Simulation::integrate() {
  Particles& P = particles_;
  const int nb = P.num_bodies();
  const double dt = dt_, alpha = options_.local_damping;
  // Velocities live at half steps: the kick spans from the middle of the last step to the middle
  // of this one (equal to dt unless the step changed at this step's list build).
  const double kick = 0.5 * (last_step_dt_ + dt_);
  const double inv_scale = 1.0 / options_.density_scaling;  // masses and inertias scale alike
  const Eigen::Vector3d g = options_.gravity;
  const auto& reference = contacts_.build_position;
  double max_move2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : max_move2) \
    if (nb >= options_.min_parallel_items)
  for (int b = 0; b < nb; ++b) {
    // Local damping acts on the unbalanced force, weight included (Cundall): a body resting on
    // its contacts has nothing to damp.
    Eigen::Vector3d f = P.force[b];
    // The true weight: density scaling slows the dynamics, not the statics (a bed's self-weight
    // stress is the same at any scaling).
    if constexpr (kGravity) f += P.mass[b] * g;
    if constexpr (kDamping) f = locally_damped(f, P.velocity[b], alpha);
    const Eigen::Vector3d acceleration = (inv_scale / P.mass[b]) * f;
    P.velocity[b] += kick * acceleration;
    P.position[b] += dt * P.velocity[b];
    const int s0 = P.first_sphere[b];
    if constexpr (kRotation) {
      Eigen::Vector3d t = P.torque[b];
      if constexpr (kDamping) t = locally_damped(t, P.angular_velocity[b], alpha);
      P.angular_momentum[b] += kick * t;
      if (kClumps && P.num_body_spheres[b] == 2) {
        const Eigen::Vector3d& L = P.angular_momentum[b];
        const double ia = P.inertia_axial[b] * options_.density_scaling;
        const double it = P.inertia_transverse[b] * options_.density_scaling;
        P.orientation[b] = rotate_symmetric_top(P.orientation[b], L, ia, it, dt);
        const Eigen::Vector3d axis = body_axis(P.orientation[b]);
        P.angular_velocity[b] = symmetric_top_angular_velocity(L, axis, ia, it);
        for (int s = s0; s < s0 + 2; ++s) {
          P.sphere_position[s] = P.position[b] + P.sphere_offset[s] * axis;
          max_move2 = std::max(max_move2, (P.sphere_position[s] - reference[s]).squaredNorm());
        }
        continue;
      }
      // A sphere's orientation does not affect its contacts: only its spin is tracked.
      P.angular_velocity[b] = (inv_scale / P.inertia_axial[b]) * P.angular_momentum[b];
    }
    P.sphere_position[s0] = P.position[b];
    max_move2 = std::max(max_move2, (P.sphere_position[s0] - reference[s0]).squaredNorm());
  }
  if (!std::isfinite(max_move2)) {
    std::ostringstream msg;
    msg << "unstable run at step " << step_count_ << ": a body position is no longer finite; time step "
        << dt_ << " s, critical step " << critical_dt_ << " s";
    throw std::runtime_error(msg.str());
  }
  max_sphere_move_ = std::sqrt(max_move2);
}

void Simulation::schedule_rebuild_if_needed() {
  double max_wall_move = 0.0;
  for (std::size_t w = 0; w < walls_.size(); ++w)
    max_wall_move = std::max(max_wall_move,
                             std::abs(walls_[w].position - contacts_.build_wall_position[w]));
  // A pair can close by twice the largest move, a sphere and a wall by the sum of theirs.
  if (2.0 * max_sphere_move_ >= skin_ || max_sphere_move_ + max_wall_move >= skin_)
    rebuild_due_ = true;
}

void Simulation::move_walls() {
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    Wall& wall = walls_[w];
    if (wall.mode == WallMode::kStress) {
      const double target = wall.target_stress * wall_area(static_cast<int>(w));
      const double inward = servo_displacement(options_.servo, wall_force_[w], target,
                                               wall_stiffness_[w], dt_, critical_dt_, servo_[w]);
      const double along = wall.upper ? -inward : inward;
      wall.velocity = along / dt_;
    }
    wall.position += wall.velocity * dt_;
  }
}

void Simulation::step() {
  auto start = Clock::now();
  if (rebuild_due_) rebuild_contacts();
  timings_.detection += seconds_since(start);

  start = Clock::now();
  with_flags([&](auto clumps, auto friction, auto viscous) {
    compute_pair_forces<decltype(clumps)::value, decltype(friction)::value,
                        decltype(viscous)::value>();
  }, features_.clumps, features_.friction, features_.viscous_damping);
  with_flags([&](auto friction, auto viscous) {
    compute_wall_forces<decltype(friction)::value, decltype(viscous)::value>();
  }, features_.wall_friction, features_.viscous_damping);
  with_flags([&](auto clumps, auto moments) {
    sum_body_forces<decltype(clumps)::value, decltype(moments)::value>();
  }, features_.clumps, features_.friction || features_.wall_friction);
  timings_.forces += seconds_since(start);

  start = Clock::now();
  with_flags([&](auto clumps, auto rotation, auto gravity, auto damping) {
    integrate<decltype(clumps)::value, decltype(rotation)::value, decltype(gravity)::value,
              decltype(damping)::value>();
  }, features_.clumps, features_.rotation(), features_.gravity, features_.local_damping);
  move_walls();
  schedule_rebuild_if_needed();
  timings_.integration += seconds_since(start);

  time_ += dt_;
  last_step_dt_ = dt_;
  ++step_count_;
}

void Simulation::run(std::int64_t num_steps) {
  for (std::int64_t n = 0; n < num_steps; ++n) step();
}

}  // namespace dem
