// The DEM engine: bodies, walls, contacts and the time loop.
//
// One step (leapfrog, velocities at half steps, as in PFC):
//   1. rebuild the candidate contacts if some sphere or wall moved more than the skin allows;
//   2. contact forces at positions x(t) with velocities v(t - dt/2): linear normal spring,
//      incremental tangential spring carried with the contact frame, Coulomb slip;
//   3. sum forces and torques per body in a fixed order (no atomics, no thread-dependent sums);
//   4. v(t + dt/2), L(t + dt/2) from them (optional local damping and gravity), then x(t + dt)
//      and the exact free rotation of a symmetric top over dt;
//   5. move the walls: at their velocity, or by the servo towards their target stress.
#pragma once

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "dem/contact_law.h"
#include "dem/contact_list.h"
#include "dem/critical_step.h"
#include "dem/particles.h"
#include "dem/records.h"
#include "dem/scene_features.h"
#include "dem/wall.h"

namespace dem {

struct SimulationOptions {
  /// Time step [s]; 0 picks time_step_safety x the critical step, refreshed at every list
  /// build. An explicit step must stay below the critical step all along the run.
  double time_step = 0.0;
  /// Fraction of the critical step used when time_step is 0.
  double time_step_safety = 0.7;
  /// Verlet skin as a fraction of the largest sphere diameter.
  double skin_ratio = 0.1;
  /// Re-sort the bodies in space every this many list builds (0: never).
  int sort_every_builds = 10;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  ///< [m/s^2]
  /// Cundall's local non-viscous damping coefficient alpha in [0, 1); 0 = off.
  double local_damping = 0.0;
  /// Density scaling factor (>= 1): the dynamics use every mass and inertia times this factor,
  /// which enlarges the stable step by its square root (reported; Particles keep true masses).
  /// Gravity acts on the scaled mass too, so weights are scaled as well.
  double density_scaling = 1.0;
  /// A step whose largest overlap exceeds this fraction of the smaller radius is an error.
  double max_overlap_ratio = 0.25;
  ServoParameters servo;
  /// Loops over fewer items than this run on one thread: a small scene is faster without the
  /// fork/join, and oversubscribed cores (parallel tests) do not spin.
  int min_parallel_items = 2048;

  std::string validate() const;
};

/// Wall-clock seconds spent in each phase of the step.
struct PhaseTimings {
  double detection = 0.0;
  double forces = 0.0;
  double integration = 0.0;
  double total() const { return detection + forces + integration; }
};

/// Everything a run needs to continue bit for bit: bodies in their current memory order, walls,
/// the contact list with its history and build reference, and the step counters.
struct SimulationState {
  Particles particles;
  std::vector<Wall> walls;
  ContactList contacts;
  double time = 0.0;
  std::int64_t step_count = 0;
  bool rebuild_due = true;
  double max_sphere_move = 0.0;
  std::vector<ServoState> servo;  ///< the servo state of each wall
};

class Simulation {
 public:
  /// Takes the bodies and walls and checks every parameter; throws std::invalid_argument naming
  /// the bad one, and refuses a time step above the critical step.
  Simulation(Particles particles, std::vector<Wall> walls, ContactParameters contact,
             SimulationOptions options);

  /// Continues a run from a saved state (see `state()`); the options and contact law must be
  /// those of the original run for the continuation to be identical.
  Simulation(SimulationState state, ContactParameters contact, SimulationOptions options);

  /// A copy of the full state, for checkpoints.
  SimulationState state() const;

  void step();
  void run(std::int64_t num_steps);

  double time() const { return time_; }
  std::int64_t step_count() const { return step_count_; }
  double time_step() const { return dt_; }
  /// The critical step of the current candidate contacts: leapfrog's limit 2/omega_max of the
  /// bodies on their contact springs (critical_step.h), refreshed at every list build (the
  /// one-contact limit where no body has a candidate), lowered for damping (damped_limit_factor).
  /// The time step follows it (time_step_safety x it) unless time_step is explicit.
  double critical_time_step() const { return critical_dt_; }
  /// The estimate behind critical_time_step() and its brackets, at the last list build.
  const StabilityLimit& stability() const { return stability_; }
  const SceneFeatures& features() const { return features_; }
  const Particles& particles() const { return particles_; }
  Particles& particles() { return particles_; }
  const std::vector<Wall>& walls() const { return walls_; }
  std::vector<Wall>& walls() { return walls_; }
  const ContactParameters& contact_parameters() const { return contact_; }
  const SimulationOptions& options() const { return options_; }
  const ContactList& contacts() const { return contacts_; }
  const PhaseTimings& timings() const { return timings_; }

  /// Compressive normal force the bodies exert on each wall at the last step [N].
  const std::vector<double>& wall_forces() const { return wall_force_; }
  /// Each wall's stiffness as its servo reads it at the last step [N/m]: the sum over its
  /// contacts of the normal spring's and, with dashpots, the dashpot's force per unit of a wall
  /// move made over one step (coefficient / time step).
  const std::vector<double>& wall_stiffnesses() const { return wall_stiffness_; }

  /// True when the walls form a box (one lower and one upper wall on each axis).
  bool has_box() const { return box_walls_[0][0] >= 0; }
  /// Index in walls() of the box wall on `axis` at its lower or upper end (needs has_box()).
  int box_wall(int axis, bool upper) const { return box_walls_[axis][upper ? 1 : 0]; }
  /// Mean compressive stress on the two box walls normal to `axis` [Pa].
  double wall_stress(int axis) const;
  /// Box volume and the area of wall w's face, from the wall positions [m^3], [m^2].
  double box_volume() const;
  double wall_area(int w) const;

  // ---- observables, computed only when asked for (see observables.cc) ----
  MacroRecord macro_record() const;
  std::vector<ContactRecord> contact_records(bool include_walls = true) const;
  /// Love–Weber stress over the box volume, compression positive [Pa]. Body–body contacts use
  /// the branch vector between centroids (the contact form). With `include_walls`, each wall
  /// contact adds its lever from the body centroid to the contact point (the particle form),
  /// which in equilibrium equals the stress the walls carry; without, the layer between the
  /// outermost centroids and the walls is missing and the stress is lower by about 2 r / L.
  Eigen::Matrix3d contact_stress(bool include_walls = false) const;
  double kinetic_energy() const;
  double unbalanced_force_ratio() const;
  int num_touching_pairs() const;
  /// Largest tangential-to-normal force ratio over touching contacts divided by the friction
  /// coefficient (<= 1 up to round-off when the Coulomb limit holds).
  double max_friction_utilisation() const;

 private:
  void rebuild_contacts();
  template <bool kClumps, bool kFriction, bool kViscous>
  void compute_pair_forces();
  template <bool kWallFriction, bool kViscous>
  void compute_wall_forces();
  template <bool kClumps, bool kMoments>
  void sum_body_forces();
  template <bool kClumps, bool kRotation, bool kGravity, bool kDamping>
  void integrate();
  void move_walls();
  void schedule_rebuild_if_needed();
  void find_box_walls();
  void initialise();  ///< validation, features, critical step, scratch arrays
  /// Throws std::invalid_argument naming the bodies (or body and wall) of an initial overlap
  /// beyond max_overlap_ratio.
  void refuse_deep_initial_overlaps(const ContactList& candidates) const;
  /// The critical step of `list` (stability_limit; the one-contact limit without candidates) and
  /// the time step from it; refuses an explicit time step above it (invalid_argument before the
  /// run, runtime_error while `running`).
  void set_time_step(const ContactList& list, bool running);
  /// Refuses a state from outside whose servo is not finite or whose bodies move too far in a step.
  void check_restored_motion() const;
  /// Throws the "unstable run" error for an overlap beyond the limit, naming `what` overlaps
  /// (two bodies, or a body and a wall) and the stress on the walls.
  [[noreturn]] void report_deep_overlap(const std::string& what, double ratio) const;
  /// The same for the deepest sphere pair, found again serially.
  [[noreturn]] void report_deep_pair_overlap(double worst_ratio) const;

  Particles particles_;
  std::vector<Wall> walls_;
  ContactParameters contact_;
  SimulationOptions options_;
  SceneFeatures features_;
  ContactList contacts_;
  double dt_ = 0.0, critical_dt_ = 0.0, one_contact_dt_ = 0.0, skin_ = 0.0;
  StabilityLimit stability_;
  double last_step_dt_ = 0.0;  ///< length of the last completed step [s]
  double time_ = 0.0;
  double max_sphere_move_ = 0.0;  ///< since the last list build [m]
  std::int64_t step_count_ = 0;
  bool rebuild_due_ = true;
  int box_walls_[3][2] = {{-1, -1}, {-1, -1}, {-1, -1}};

  /// What one contact slot (as in ContactList) produced this step: one cache line, so the
  /// per-body force sums fetch one line per contact.
  struct alignas(64) SlotResult {
    Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< force on body B [N]
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();  ///< normal x force, for the torques [N]
    double overlap = 0.0;                              ///< [m], 0 when not touching
    std::uint8_t sliding = 0;
  };
  std::vector<SlotResult> slots_;
  std::vector<double> wall_force_, wall_stiffness_;
  std::vector<ServoState> servo_;
  PhaseTimings timings_;
};

}  // namespace dem
