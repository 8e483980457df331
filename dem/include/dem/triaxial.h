// Triaxial-cell tests along a loading path (loading_path.h): the platens (z walls) driven at a
// constant strain rate, the lateral walls servo-held at the path's stresses or moved at constant
// volume, until the critical state or a maximum axial strain. Drained compression (sigma_3 held,
// platens closing) is the paper's test and the default.
// Strains are engineering strains from the wall positions, compression positive:
// eps_a = (H0 - H) / H0, eps_x = (W0 - W) / W0, eps_v = (V0 - V) / V0 (eps_a < 0 in extension).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dem/loading_path.h"
#include "dem/run_file_io.h"
#include "dem/simulation.h"

namespace dem {

/// The smallest output, snapshot and checkpoint interval of axial strain accepted.
constexpr double kMinStrainInterval = 1e-9;
/// The most steps a test may need at its strain rate (the paper-size test needs about 1e6).
constexpr double kMaxTestSteps = 1e9;
/// Below this p / p0 anywhere in the window an undrained test is not at a critical state but
/// liquefied (q/p is then the noise of a few contacts).
constexpr double kMinCriticalMeanStressRatio = 0.01;

struct TriaxialOptions {
  LoadingPath path = LoadingPath::kDrainedCompression;
  /// sigma_3 held on the lateral walls on the drained paths, p0 on the constant-p ones [Pa]
  double confining_stress = 100e3;
  /// True triaxial: (sigma_2 - sigma_3) / (sigma_1 - sigma_3) in [0, 1], sigma_2 on y; 0 elsewhere.
  double b = 0.0;
  /// Undrained paths: how the lateral axes share the volume (equal strains, or sigma_x = sigma_y as
  /// in a cell, which a deposit's unequal lateral axes need); the others refuse equal stresses.
  UndrainedLateral undrained_lateral = UndrainedLateral::kEqualStrains;
  /// Axial strain rate [1/s]. The paper: 20 /s (0.06 m/s on 3 mm); 100 /s stays within the seed
  /// scatter of it at 100 kPa (bench/RESULTS.md, "Run time against error"): keep I < 1e-3 elsewhere.
  double strain_rate = 100.0;
  double max_axial_strain = 0.45;    ///< stop at this |eps_a| if no critical state was found
  double output_strain_interval = 2e-3;    ///< a /series row every this much axial strain
  double snapshot_strain_interval = 0.05;  ///< a snapshot every this much axial strain
  double checkpoint_strain_interval = 0.02;  ///< a checkpoint every this much axial strain
  /// Critical state: over the last `critical_window` of axial strain, the least-squares lines
  /// through q/p and through the volumetric strain change by less than `critical_eta_change` and
  /// `critical_volume_change` (a fit, not the raw range, so the fluctuations of a small specimen
  /// do not hide a stationary state), once the axial strain exceeds `critical_min_strain`.
  double critical_window = 0.1;
  double critical_eta_change = 0.05;
  double critical_volume_change = 0.005;
  /// On the undrained paths (no volume change) the mean stress takes the volume's place: its
  /// line through p / p0 must change by less than this.
  double critical_mean_stress_change = 0.05;
  double critical_min_strain = 0.2;

  std::string validate() const;
};

/// How a test ended: the run file's record of it (stored in /summary).
using TriaxialSummary = runfile::TestSummary;

/// Progress of a running test, passed to the callback after each series row.
struct TriaxialProgress {
  double axial_strain = 0.0;
  double target_strain = 0.0;
  double steps_per_second = 0.0;
  double seconds_left = 0.0;
  double eta = 0.0;   ///< q/p
  /// Said once per run, at the first row whose inertial number passes
  /// runfile::kQuasiStaticInertialNumber (what it is and what to change); empty otherwise.
  std::string warning;
};

/// The names of the /series columns a triaxial run writes, in order.
const std::vector<std::string>& triaxial_series_names();

/// The critical-state test of TriaxialOptions on the history so far (|axial strain|, q/p and
/// volumetric strain at each output row). `window_start`, when given, receives the index of the
/// first row of the last window (the size of the history when no full window exists yet).
bool is_critical_state(const std::vector<double>& axial_strain, const std::vector<double>& eta,
                       const std::vector<double>& volumetric_strain,
                       const TriaxialOptions& options, std::size_t* window_start = nullptr);
/// The same on an undrained path: the line through p / p0 in place of the volumetric strain's,
/// against critical_mean_stress_change, and p / p0 at least kMinCriticalMeanStressRatio over the
/// window.
bool is_critical_state_at_constant_volume(const std::vector<double>& axial_strain,
                                          const std::vector<double>& eta,
                                          const std::vector<double>& mean_stress_ratio,
                                          const TriaxialOptions& options,
                                          std::size_t* window_start = nullptr);

/// Totals of the grains that a test divides by: summed in the order of the bodies' stable ids,
/// so that they are the same to the last bit whatever order the engine's spatial re-sorts left
/// the bodies in (a resumed run recomputes them from the re-sorted checkpoint).
struct GrainTotals {
  double solid_volume = 0.0;   ///< [m^3]
  double mass = 0.0;           ///< [kg], density scaling included
  double mean_diameter = 0.0;  ///< of the bodies' first spheres [m]
};

/// The totals of `particles`; throws std::invalid_argument where one is not positive and finite
/// (e.g. grains of diameter 1e-200 m, whose volumes underflow to 0).
GrainTotals grain_totals(const Particles& particles);

class TriaxialTest {
 public:
  /// `simulation` must hold a box of six walls around a prepared (compacted) specimen.
  TriaxialTest(Simulation& simulation, const TriaxialOptions& options);

  /// Runs to the end, writing series, snapshots, checkpoints and at the end the summary to
  /// `file` (may be null).
  /// If `file` holds a checkpoint the caller restored, pass `resumed` = true and the extras
  /// read with it.
  TriaxialSummary run(RunFile* file, const std::function<void(const TriaxialProgress&)>& progress,
                      const CheckpointExtras* resumed = nullptr);

  /// The current row of the series (for tests and the CLI).
  std::vector<double> series_row() const;

 private:
  double axial_strain() const;
  double path_strain() const { return direction_ * axial_strain(); }  ///< |eps_a| along the path
  /// Refuses a resumed checkpoint whose rows or snapshots do not end where its state does.
  void check_output_counters(const RunFile& file) const;
  double void_ratio() const;
  void drive_platens();
  /// Sets the lateral walls for the next step: the path's stress targets at the axial stress
  /// [Pa] the last step left, or the velocities that keep the volume (undrained).
  void update_lateral_walls(double axial_stress);
  /// The force [N] and stiffness [N/m] the last step left on each lateral wall (x lower, x upper,
  /// y lower, y upper): the engine's, or once after a resume the checkpoint's (a restored engine
  /// has none until it steps).
  std::array<std::array<double, 2>, 4> take_lateral_readings();
  /// The lateral wall k = 0..3 (x lower, x upper, y lower, y upper), its index in the walls.
  int lateral_wall(int k) const { return sim_.box_wall(k / 2, k % 2 == 1); }
  bool critical_state(std::size_t* window_start) const;
  CheckpointExtras extras() const;

  Simulation& sim_;
  TriaxialOptions options_;
  double height0_ = 0.0, width0_[2] = {0.0, 0.0}, volume0_ = 0.0, solid_volume_ = 0.0;
  double mean_diameter_ = 0.0, mean_density_ = 0.0;
  double next_output_ = 0.0, next_snapshot_ = 0.0, next_checkpoint_ = 0.0;
  double worst_lateral_error_ = 0.0, peak_eta_ = 0.0, peak_eta_strain_ = 0.0;
  double max_inertial_number_ = 0.0, initial_void_ratio_ = 0.0;
  /// The engine's step count when the test began (the specimen's steps came before it): the
  /// summary's steps count from it, a resumed run's included.
  std::int64_t test_start_step_ = 0;
  int direction_ = 1;  ///< axial_direction(options_.path)
  /// The lateral readings a resumed checkpoint holds, until the first step takes them.
  std::optional<std::array<std::array<double, 2>, 4>> resumed_lateral_;
  /// Per output row: |eps_a|, q/p, eps_v and p / p0 (the critical-state test).
  std::vector<double> history_strain_, history_eta_, history_volume_, history_mean_stress_;
};

}  // namespace dem
