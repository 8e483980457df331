#include "dem/triaxial.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "sffcal/final_window.h"
#include "sffcal/format_number.h"

namespace dem {
namespace {

// The series of a triaxial run. Stresses compression positive [Pa], strains compression
// positive [-], wall positions [m], energy [J].
const std::vector<std::string> kSeriesNames = {
    "step", "time", "axial_strain", "lateral_strain_x", "lateral_strain_y",
    "volumetric_strain", "void_ratio",
    "wall_stress_xx", "wall_stress_yy", "wall_stress_zz",
    "sigma_1", "sigma_3", "p", "q", "eta",
    "contact_stress_xx", "contact_stress_yy", "contact_stress_zz",
    "contact_stress_yz", "contact_stress_xz", "contact_stress_xy",
    "contact_p", "contact_q", "coordination_number", "inertial_number",
    "unbalanced_force_ratio", "kinetic_energy", "lateral_stress_error",
    "wall_x_lower", "wall_x_upper", "wall_y_lower", "wall_y_upper", "wall_z_lower", "wall_z_upper"};

std::size_t column(const std::string& name) {
  return static_cast<std::size_t>(
      std::find(kSeriesNames.begin(), kSeriesNames.end(), name) - kSeriesNames.begin());
}

// Change of the least-squares line through (x, y)[from..] between the first and last x.
double fitted_change(const std::vector<double>& x, const std::vector<double>& y,
                     std::size_t from) {
  const double n = static_cast<double>(x.size() - from);
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (std::size_t k = from; k < x.size(); ++k) {
    sx += x[k];
    sy += y[k];
    sxx += x[k] * x[k];
    sxy += x[k] * y[k];
  }
  const double denominator = n * sxx - sx * sx;
  if (!(denominator > 0.0)) return HUGE_VAL;
  return (n * sxy - sx * sy) / denominator * (x.back() - x[from]);
}

// The critical-state test on (strain, eta, second): the fitted lines through eta and through the
// second quantity (the volumetric strain, or p / p0 on the undrained paths) both flat to within
// their tolerances over the last critical_window of strain.
bool stationary_over_window(const std::vector<double>& strain, const std::vector<double>& eta,
                            const std::vector<double>& second, double second_tolerance,
                            const TriaxialOptions& options, std::size_t* window_start) {
  if (strain.empty()) {
    if (window_start) *window_start = 0;
    return false;
  }
  const double last = strain.back();
  const std::size_t start = sffcal::final_window_start(strain, options.critical_window);
  const bool full_window = start > 0;
  if (window_start) *window_start = full_window ? start : strain.size();
  if (!full_window || last < options.critical_min_strain) return false;
  return std::abs(fitted_change(strain, eta, start)) < options.critical_eta_change &&
         std::abs(fitted_change(strain, second, start)) < second_tolerance;
}

}  // namespace

const std::vector<std::string>& triaxial_series_names() { return kSeriesNames; }

bool is_critical_state(const std::vector<double>& strain, const std::vector<double>& eta,
                       const std::vector<double>& volume, const TriaxialOptions& options,
                       std::size_t* window_start) {
  return stationary_over_window(strain, eta, volume, options.critical_volume_change, options,
                                window_start);
}

bool is_critical_state_at_constant_volume(const std::vector<double>& strain,
                                          const std::vector<double>& eta,
                                          const std::vector<double>& mean_stress_ratio,
                                          const TriaxialOptions& options,
                                          std::size_t* window_start) {
  std::size_t start = 0;
  const bool stationary = stationary_over_window(strain, eta, mean_stress_ratio,
                                                 options.critical_mean_stress_change, options, &start);
  if (window_start) *window_start = start;
  // A specimen that lost its mean stress (static liquefaction) has no q/p to be critical at.
  for (std::size_t k = start; k < mean_stress_ratio.size(); ++k)
    if (!(mean_stress_ratio[k] >= kMinCriticalMeanStressRatio)) return false;
  return stationary;
}

std::string TriaxialOptions::validate() const {
  std::ostringstream e;
  if (!(confining_stress > 0.0)) e << "confining_stress must be positive [Pa]; ";
  if (!(strain_rate > 0.0)) e << "strain_rate must be positive [1/s]; ";
  if (!(max_axial_strain > 0.0 && max_axial_strain < 0.9))
    e << "max_axial_strain must lie in (0, 0.9); ";
  // An interval below 1e-9 of strain means nothing physically, and one below the rounding of the
  // strain (1e-320) never advances the next row: the run would loop on one row for ever.
  for (const auto& [name, value] : {std::pair{"output_strain_interval", output_strain_interval},
                                    {"snapshot_strain_interval", snapshot_strain_interval},
                                    {"checkpoint_strain_interval", checkpoint_strain_interval}})
    if (!(value >= kMinStrainInterval && value <= 1.0))
      e << name << " must lie in [" << kMinStrainInterval << ", 1], not " << value << "; ";
  if (!(critical_window > 0.0)) e << "critical_window must be positive; ";
  if (!(critical_eta_change > 0.0)) e << "critical_eta_change must be positive; ";
  if (!(critical_volume_change > 0.0)) e << "critical_volume_change must be positive; ";
  if (!(critical_mean_stress_change > 0.0)) e << "critical_mean_stress_change must be positive; ";
  if (uses_b(path)) {
    if (!(b >= 0.0 && b <= 1.0)) e << "b must lie in [0, 1] (got " << b << "); ";
  } else if (b != 0.0) {
    e << "b = " << b << " is read only by path = \"true_triaxial\", not \""
      << loading_path_name(path) << "\"; ";
  }
  if (undrained_lateral == UndrainedLateral::kEqualStresses && !holds_volume(path))
    e << "undrained_lateral = \"equal_stresses\" is read only by the undrained paths, not \""
      << loading_path_name(path) << "\"; ";
  return e.str();
}

TriaxialTest::TriaxialTest(Simulation& simulation, const TriaxialOptions& options)
    : sim_(simulation), options_(options) {
  const std::string error = options_.validate();
  if (!error.empty()) throw std::invalid_argument("triaxial: " + error);
  if (!sim_.has_box()) throw std::invalid_argument("triaxial: the specimen needs a box of six walls");
  auto extent = [&](int axis) {
    return sim_.walls()[sim_.box_wall(axis, true)].position -
           sim_.walls()[sim_.box_wall(axis, false)].position;
  };
  height0_ = extent(2);
  width0_[0] = extent(0);
  width0_[1] = extent(1);
  volume0_ = sim_.box_volume();
  test_start_step_ = sim_.step_count();
  const GrainTotals totals = grain_totals(sim_.particles());
  solid_volume_ = totals.solid_volume;
  mean_density_ = totals.mass / totals.solid_volume;
  mean_diameter_ = totals.mean_diameter;

  direction_ = axial_direction(options_.path);
  for (int axis = 0; axis < 2; ++axis)
    for (bool upper : {false, true}) {
      Wall& w = sim_.walls()[sim_.box_wall(axis, upper)];
      w.mode = holds_volume(options_.path) ? WallMode::kVelocity : WallMode::kStress;
      w.target_stress = options_.confining_stress;
      w.velocity = 0.0;
    }
  drive_platens();
  const double steps_needed = options_.max_axial_strain / (options_.strain_rate * sim_.time_step());
  if (!(steps_needed <= kMaxTestSteps)) {
    std::ostringstream msg;
    msg << "triaxial: strain_rate " << options_.strain_rate << " /s at the time step "
        << sim_.time_step() << " s needs " << steps_needed << " steps to reach axial strain "
        << options_.max_axial_strain << " (more than " << kMaxTestSteps
        << "): raise strain_rate";
    throw std::invalid_argument(msg.str());
  }
  // And at most one output interval, and a tenth of the whole test, per step: faster, the platens
  // outrun the rows and the limit (strain_rate 1e9 ended at axial strain 32 against a limit of
  // 0.02, with a negative void ratio).
  const double per_step = options_.strain_rate * sim_.time_step();
  const double most = std::min(options_.output_strain_interval, 0.1 * options_.max_axial_strain);
  if (!(per_step <= most)) {
    std::ostringstream msg;
    msg << "triaxial: strain_rate " << options_.strain_rate << " /s at the time step "
        << sim_.time_step() << " s strains the specimen by " << per_step
        << " a step, more than the output interval or a tenth of max_axial_strain ("
        << most << "): lower strain_rate";
    throw std::invalid_argument(msg.str());
  }
  initial_void_ratio_ = void_ratio();
  if (!(std::isfinite(initial_void_ratio_) && initial_void_ratio_ > 0.0 &&
        std::isfinite(mean_density_) && mean_density_ > 0.0)) {
    std::ostringstream msg;
    msg << "triaxial: the specimen's void ratio " << initial_void_ratio_ << " or grain density "
        << mean_density_ << " kg/m^3 is not positive and finite (box volume " << volume0_
        << " m^3, solid volume " << solid_volume_ << " m^3)";
    throw std::invalid_argument(msg.str());
  }
}

GrainTotals grain_totals(const Particles& p) {
  std::vector<int> order(static_cast<std::size_t>(p.num_bodies()));
  for (int b = 0; b < p.num_bodies(); ++b) order[static_cast<std::size_t>(b)] = b;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return p.id[a] < p.id[b]; });
  GrainTotals totals;
  double diameter = 0.0;
  for (int b : order) {
    totals.solid_volume += p.volume[b];
    totals.mass += p.mass[b];
    diameter += 2.0 * p.sphere_radius[p.first_sphere[b]];
  }
  totals.mean_diameter = diameter / std::max(p.num_bodies(), 1);
  for (double x : {totals.solid_volume, totals.mass, totals.mean_diameter})
    if (!(std::isfinite(x) && x > 0.0)) {
      std::ostringstream msg;
      msg << "the grains' solid volume " << totals.solid_volume << " m^3, mass " << totals.mass
          << " kg or mean diameter " << totals.mean_diameter
          << " m is not positive and finite: check grains.min_diameter, max_diameter and density";
      throw std::invalid_argument(msg.str());
    }
  return totals;
}

void TriaxialTest::drive_platens() {
  // The strain rate refers to the initial height: constant platen speed, closing in compression
  // and parting in extension.
  const double platen_speed = 0.5 * direction_ * options_.strain_rate * height0_;
  Wall& bottom = sim_.walls()[sim_.box_wall(2, false)];
  Wall& top = sim_.walls()[sim_.box_wall(2, true)];
  bottom.mode = top.mode = WallMode::kVelocity;
  bottom.velocity = platen_speed;
  top.velocity = -platen_speed;
}

namespace {
// The gain of the lateral servo that holds sigma_x = sigma_y at constant volume
// (update_lateral_walls).
constexpr double kEqualStressesGain = 0.5;
}  // namespace

std::array<std::array<double, 2>, 4> TriaxialTest::take_lateral_readings() {
  if (resumed_lateral_) return *std::exchange(resumed_lateral_, std::nullopt);
  std::array<std::array<double, 2>, 4> readings{};
  for (int k = 0; k < 4; ++k) {
    const int w = lateral_wall(k);
    readings[static_cast<std::size_t>(k)] = {sim_.wall_forces()[w], sim_.wall_stiffnesses()[w]};
  }
  return readings;
}

void TriaxialTest::update_lateral_walls(double axial_stress) {
  auto& walls = sim_.walls();
  if (holds_volume(options_.path)) {
    // Each lateral width set, at the end of the coming step, to one that keeps the volume with
    // the height the platens will have then: V = V0 to rounding at every step.
    const double dt = sim_.time_step();
    const Wall& bottom = walls[sim_.box_wall(2, false)];
    const Wall& top = walls[sim_.box_wall(2, true)];
    const double height_next =
        (top.position + top.velocity * dt) - (bottom.position + bottom.velocity * dt);
    std::array<double, 2> width{}, target{};
    for (int axis = 0; axis < 2; ++axis) {
      width[axis] = walls[sim_.box_wall(axis, true)].position -
                    walls[sim_.box_wall(axis, false)].position;
      target[axis] = constant_volume_width(width0_[axis], height0_, height_next);
    }
    if (options_.undrained_lateral == UndrainedLateral::kEqualStresses) {
      // sigma_x = sigma_y: each lateral wall's servo proposes a move towards the mean lateral
      // stress; the proposals set the widths' ratio, and the volume their product. The forces
      // are the last step's, so the loop runs a step behind them. Proportional at gain g, on
      // walls of equal stiffness k against a rigid specimen, the x walls move out by
      // g (sigma_x - sigma_y) A / 2k and the y walls in alike (the projection keeps both
      // moves), so e = sigma_x - sigma_y obeys e' = e - g e_(last step): z^2 - z + g = 0, stable
      // for g < 1, critically damped at 1/4, a softer specimen damps it more. At 0.5 an error
      // decays by 0.71 a step; on the deposit of the test
      // (LoadingPath.UndrainedEqualStressesHoldsADepositsLateralStressesTogether) |sigma_x -
      // sigma_y| stayed within 0.0093 p, against 0.021 p at 0.25, and the engine's servo (gain
      // 0.8, its blend and integral) swung the lateral stresses between 0.2 p and 1.8 p.
      ServoParameters servo = sim_.options().servo;
      servo.gain = kEqualStressesGain;
      servo.blend = 1.0;         // no memory of the last move ...
      servo.integral_time = 0.0; // ... nor an integral: the servo state stays empty
      const auto readings = take_lateral_readings();
      double mean = 0.0;
      for (int k = 0; k < 4; ++k) mean += 0.25 * readings[k][0] / sim_.wall_area(lateral_wall(k));
      std::array<double, 2> proposed = width;
      for (int k = 0; k < 4; ++k) {
        ServoState stateless;
        proposed[k / 2] -= servo_displacement(servo, readings[k][0],
                                              mean * sim_.wall_area(lateral_wall(k)),
                                              readings[k][1], dt, sim_.critical_time_step(),
                                              stateless);
      }
      target = widths_of_area(volume0_ / height_next, proposed[0] / proposed[1]);
    }
    for (int axis = 0; axis < 2; ++axis) {
      const double speed = 0.5 * (target[axis] - width[axis]) / dt;
      walls[sim_.box_wall(axis, false)].velocity = -speed;
      walls[sim_.box_wall(axis, true)].velocity = speed;
    }
    return;
  }
  const std::array<double, 2> targets =
      lateral_targets(options_.path, options_.confining_stress, options_.b, axial_stress);
  for (int axis = 0; axis < 2; ++axis) {
    if (!(targets[axis] > 0.0)) {
      std::ostringstream msg;
      msg << "triaxial: path " << loading_path_name(options_.path) << " asks for a lateral stress of "
          << targets[axis] << " Pa on axis " << "xy"[axis] << " at an axial stress of "
          << axial_stress << " Pa: the specimen cannot keep p0 = "
          << options_.confining_stress << " Pa at this q";
      throw std::runtime_error(msg.str());
    }
    for (bool upper : {false, true}) walls[sim_.box_wall(axis, upper)].target_stress = targets[axis];
  }
}

double TriaxialTest::axial_strain() const {
  const double h = sim_.walls()[sim_.box_wall(2, true)].position -
                   sim_.walls()[sim_.box_wall(2, false)].position;
  return (height0_ - h) / height0_;
}

double TriaxialTest::void_ratio() const { return sim_.box_volume() / solid_volume_ - 1.0; }

std::vector<double> TriaxialTest::series_row() const {
  const auto& walls = sim_.walls();
  auto extent = [&](int axis) {
    return walls[sim_.box_wall(axis, true)].position - walls[sim_.box_wall(axis, false)].position;
  };
  const double sxx = sim_.wall_stress(0), syy = sim_.wall_stress(1), szz = sim_.wall_stress(2);
  const double s1 = szz, s3 = 0.5 * (sxx + syy);
  const double p = (s1 + 2.0 * s3) / 3.0, q = s1 - s3;
  // Against each servo-held wall's own target (the path's; sigma_x = sigma_y undrained: the
  // mean lateral stress, while it is at least kMinCriticalMeanStressRatio p0: a liquefied
  // specimen's walls carry the noise of a few contacts); 0 where the walls follow the volume
  // alone.
  const bool equal_stresses = holds_volume(options_.path) &&
                              options_.undrained_lateral == UndrainedLateral::kEqualStresses;
  double lateral_error = 0.0;
  for (int axis = 0; axis < 2; ++axis)
    for (bool upper : {false, true}) {
      const int w = sim_.box_wall(axis, upper);
      if (walls[w].mode != WallMode::kStress && !equal_stresses) continue;
      const double stress = sim_.wall_forces()[w] / sim_.wall_area(w);
      const double target = equal_stresses ? s3 : walls[w].target_stress;
      const double least =
          equal_stresses ? kMinCriticalMeanStressRatio * options_.confining_stress : 0.0;
      if (target > least)
        lateral_error = std::max(lateral_error, std::abs(stress - target) / target);
    }
  const Eigen::Matrix3d c = sim_.contact_stress(false);
  const double cp = c.trace() / 3.0, cq = c(2, 2) - 0.5 * (c(0, 0) + c(1, 1));
  const MacroRecord m = sim_.macro_record();
  const double inertial =
      p > 0.0 ? options_.strain_rate * mean_diameter_ *
                    std::sqrt(sim_.options().density_scaling * mean_density_ / p)
              : 0.0;
  return {static_cast<double>(sim_.step_count()), sim_.time(), axial_strain(),
          (width0_[0] - extent(0)) / width0_[0], (width0_[1] - extent(1)) / width0_[1],
          (volume0_ - sim_.box_volume()) / volume0_, void_ratio(),
          sxx, syy, szz, s1, s3, p, q, p > 0.0 ? q / p : 0.0,
          c(0, 0), c(1, 1), c(2, 2), c(1, 2), c(0, 2), c(0, 1), cp, cq,
          m.coordination_number, inertial, m.unbalanced_force_ratio, m.kinetic_energy,
          lateral_error,
          walls[sim_.box_wall(0, false)].position, walls[sim_.box_wall(0, true)].position,
          walls[sim_.box_wall(1, false)].position, walls[sim_.box_wall(1, true)].position,
          walls[sim_.box_wall(2, false)].position, walls[sim_.box_wall(2, true)].position};
}

bool TriaxialTest::critical_state(std::size_t* window_start) const {
  return holds_volume(options_.path)
             ? is_critical_state_at_constant_volume(history_strain_, history_eta_,
                                                    history_mean_stress_, options_, window_start)
             : is_critical_state(history_strain_, history_eta_, history_volume_, options_,
                                 window_start);
}

// A checkpoint follows the row and the snapshot of its own step, after which the thresholds moved
// one interval on: the rows and snapshots the file keeps with it (its series_length and
// num_snapshots) must end there. Counts edited or damaged would drop or repeat rows and snapshots.
void TriaxialTest::check_output_counters(const RunFile& file) const {
  auto refuse = [](const std::string& why) {
    throw std::invalid_argument("triaxial: the checkpoint does not follow the rows and snapshots "
                                "the file keeps with it: " + why);
  };
  // A row falls within a step of its threshold, and a step is at most an output interval
  // (TriaxialTest's bound): the next threshold lies within one and a half intervals after it.
  auto follows = [](double last, double next, double interval) {
    return last < next && next <= last + 1.5 * interval;
  };
  if (history_strain_.empty()) refuse("it keeps no series row");
  const double last_row = history_strain_.back();
  if (!follows(last_row, next_output_, options_.output_strain_interval))
    refuse("the last of its " + std::to_string(history_strain_.size()) +
           " series rows is at axial strain " + sffcal::format_number(last_row) +
           ", and its next row is due at " + sffcal::format_number(next_output_) +
           " (one output interval on: " +
           sffcal::format_number(options_.output_strain_interval) + ")");
  const int snapshots = file.num_snapshots();
  if (snapshots < 1) refuse("it keeps no snapshot (the first is taken with the first row)");
  const double last_snapshot = direction_ * file.read_snapshot(snapshots - 1).axial_strain;
  if (!(last_snapshot < next_snapshot_ &&
        next_snapshot_ <= last_snapshot + options_.snapshot_strain_interval * (1.0 + 1e-9)))
    refuse("the last of its " + std::to_string(snapshots) + " snapshots is at axial strain " +
           sffcal::format_number(last_snapshot) + ", and its next is due at " +
           sffcal::format_number(next_snapshot_) + " (within one snapshot interval, " +
           sffcal::format_number(options_.snapshot_strain_interval) + ", after it)");
}

CheckpointExtras TriaxialTest::extras() const {
  CheckpointExtras x = {{"height0", height0_}, {"width0_x", width0_[0]}, {"width0_y", width0_[1]},
          {"volume0", volume0_}, {"next_output", next_output_},
          {"next_snapshot", next_snapshot_}, {"next_checkpoint", next_checkpoint_},
          {"worst_lateral_error", worst_lateral_error_}, {"peak_eta", peak_eta_},
          {"peak_eta_strain", peak_eta_strain_}, {"max_inertial_number", max_inertial_number_},
          {"initial_void_ratio", initial_void_ratio_},
          {"test_start_step", static_cast<double>(test_start_step_)},
          // What the last step left on the platens: the first lateral targets after a resume
          // (a restored engine has no wall forces until it steps).
          {"axial_stress", sim_.wall_stress(2)}};
  // And on the lateral walls, which sigma_x = sigma_y at constant volume reads.
  for (int k = 0; k < 4; ++k) {
    const int w = lateral_wall(k);
    x["lateral_force_" + std::to_string(k)] = sim_.wall_forces()[w];
    x["lateral_stiffness_" + std::to_string(k)] = sim_.wall_stiffnesses()[w];
  }
  return x;
}

TriaxialSummary TriaxialTest::run(RunFile* file,
                                  const std::function<void(const TriaxialProgress&)>& progress,
                                  const CheckpointExtras* resumed) {
  const auto start = std::chrono::steady_clock::now();
  const std::int64_t start_step = sim_.step_count();
  // The inertial number's warning, said once per run with the next progress call.
  std::string inertial_warning;
  bool inertial_warned = false;
  double resumed_axial_stress = std::numeric_limits<double>::quiet_NaN();
  if (resumed) {
    const CheckpointExtras& x = *resumed;
    // A checkpoint of another kind (a specimen's, from preparation) lacks the test's state.
    auto need = [&](const char* name) {
      const auto it = x.find(name);
      if (it == x.end())
        throw std::invalid_argument(std::string("triaxial: the checkpoint has no '") + name +
                                    "': it is not a triaxial test's (a specimen file?)");
      if (!std::isfinite(it->second))
        throw std::invalid_argument(std::string("triaxial: the checkpoint's '") + name +
                                    "' is not finite");
      return it->second;
    };
    // The references strains are measured against (zero: a test that never advances) and the
    // counters' thresholds, checked as data from outside.
    auto need_at_least = [&](const char* name, double low, bool strict) {
      const double value = need(name);
      if (strict ? !(value > low) : !(value >= low))
        throw std::invalid_argument(std::string("triaxial: the checkpoint's '") + name + "' = " +
                                    sffcal::format_number(value) + " must be " +
                                    (strict ? "above " : "at least ") + sffcal::format_number(low));
      return value;
    };
    height0_ = need_at_least("height0", 0.0, true);
    width0_[0] = need_at_least("width0_x", 0.0, true);
    width0_[1] = need_at_least("width0_y", 0.0, true);
    volume0_ = need_at_least("volume0", 0.0, true);
    next_output_ = need_at_least("next_output", 0.0, false);
    next_snapshot_ = need_at_least("next_snapshot", 0.0, false);
    next_checkpoint_ = need_at_least("next_checkpoint", 0.0, false);
    worst_lateral_error_ = need_at_least("worst_lateral_error", 0.0, false);
    peak_eta_ = need("peak_eta");
    peak_eta_strain_ = need("peak_eta_strain");
    max_inertial_number_ = need_at_least("max_inertial_number", 0.0, false);
    initial_void_ratio_ = need_at_least("initial_void_ratio", 0.0, true);
    // Checkpoints before this key counted the summary's steps from the resume.
    if (x.count("test_start_step")) {
      const double first = need_at_least("test_start_step", 0.0, false);
      if (!(first <= static_cast<double>(sim_.step_count())))
        throw std::invalid_argument("triaxial: the checkpoint's 'test_start_step' lies after its "
                                    "step count");
      test_start_step_ = static_cast<std::int64_t>(first);
    }
    if (x.count("axial_stress")) {  // older checkpoints lack it; the drained paths do not use it
      const double axial_stress = need("axial_stress");
      if (lateral_targets_follow_axial_stress(options_.path)) resumed_axial_stress = axial_stress;
    }
    // Older checkpoints lack them; only equal stresses reads them.
    if (x.count("lateral_force_0")) {
      std::array<std::array<double, 2>, 4> readings{};
      for (int k = 0; k < 4; ++k)
        readings[static_cast<std::size_t>(k)] = {
            need_at_least(("lateral_force_" + std::to_string(k)).c_str(), 0.0, false),
            need_at_least(("lateral_stiffness_" + std::to_string(k)).c_str(), 0.0, false)};
      resumed_lateral_ = readings;
    } else if (holds_volume(options_.path) &&
               options_.undrained_lateral == UndrainedLateral::kEqualStresses) {
      throw std::invalid_argument("triaxial: the checkpoint has no lateral wall forces, which "
                                  "undrained_lateral = \"equal_stresses\" needs to resume");
    }
    drive_platens();
    if (file) {
      history_strain_ = file->series("axial_strain");
      for (double& e : history_strain_) e *= direction_;
      history_eta_ = file->series("eta");
      history_volume_ = file->series("volumetric_strain");
      history_mean_stress_ = file->series("p");
      for (double& p : history_mean_stress_) p /= options_.confining_stress;
      check_output_counters(*file);
    }
  }
  // The paths whose lateral walls follow the platens or the axial stress are set step by step;
  // on the others the lateral servo targets stay put and the steps run in batches.
  const bool step_by_step =
      holds_volume(options_.path) || lateral_targets_follow_axial_stress(options_.path);
  // The first row needs the wall forces of a step taken with the platens moving. A specimen
  // restored from its file holds no forces before its first step: its targets are then those
  // of the path's start, q = 0 (with sigma_z 0, b = 1 would ask for sigma_y = 0).
  if (!resumed) {
    const double axial_stress = sim_.wall_stress(2);
    if (step_by_step)
      update_lateral_walls(axial_stress > 0.0 ? axial_stress : options_.confining_stress);
    sim_.step();
  }
  const double platen_speed = 0.5 * options_.strain_rate * height0_;
  TriaxialSummary summary;
  for (;;) {
    // The time step follows the contacts, so the strain of one step is read afresh. Strains here
    // are |eps_a| along the path (eps_a < 0 in extension).
    const double strain_per_step = 2.0 * platen_speed * sim_.time_step() / height0_;
    const double strain = path_strain();
    // The steps run towards the next row, never past the strain limit: the last row is taken at
    // max_axial_strain whatever the output interval (an interval of 1 must not crush the
    // specimen to eps_a = 1).
    // Half the remaining steps at a time: the step follows the contacts and can grow within a
    // batch, so a whole batch could jump past the target by many steps.
    const double target = std::min(next_output_, options_.max_axial_strain);
    if (strain + 0.5 * strain_per_step < target) {
      const double remaining = (target - strain) / strain_per_step;
      const auto steps = static_cast<std::int64_t>(
          std::ceil(remaining > 2.0 ? 0.5 * remaining : remaining - 1e-9));
      if (step_by_step) {
        update_lateral_walls(std::isnan(resumed_axial_stress)
                                 ? sim_.wall_stress(2)
                                 : std::exchange(resumed_axial_stress, std::nan("")));
        sim_.step();
      } else {
        sim_.run(std::max<std::int64_t>(1, steps));
      }
      continue;
    }
    // An output step.
    if (strain + 0.5 * strain_per_step >= next_output_)
      next_output_ += options_.output_strain_interval;
    const std::vector<double> row = series_row();
    if (file) file->append_series(row);
    const double eta = row[column("eta")], eps_v = row[column("volumetric_strain")];
    worst_lateral_error_ = std::max(worst_lateral_error_, row[column("lateral_stress_error")]);
    const double inertial = row[column("inertial_number")];
    max_inertial_number_ = std::max(max_inertial_number_, inertial);
    if (inertial > runfile::kQuasiStaticInertialNumber && !inertial_warned) {
      char text[300];
      std::snprintf(text, sizeof text,
                    "inertial number %.3g at axial strain %.4f passes the quasi-static limit 1e-3 "
                    "(I = strain rate x mean diameter x sqrt(density x scaling / p), docs/dem.md): "
                    "lower engine.density_scaling or the strain rate",
                    inertial, strain);
      inertial_warning = text;
      inertial_warned = true;
    }
    if (direction_ * eta > direction_ * peak_eta_) {  // in extension the peak is the most negative
      peak_eta_ = eta;
      peak_eta_strain_ = axial_strain();
    }
    history_strain_.push_back(strain);
    history_eta_.push_back(eta);
    history_volume_.push_back(eps_v);
    history_mean_stress_.push_back(row[column("p")] / options_.confining_stress);

    std::size_t window_start = 0;
    const bool critical = critical_state(&window_start);
    const bool done = critical || strain + 0.5 * strain_per_step >= options_.max_axial_strain;

    if (file && (strain >= next_snapshot_ || done)) {
      file->write_snapshot(take_snapshot(sim_, axial_strain()));
      while (next_snapshot_ <= strain) next_snapshot_ += options_.snapshot_strain_interval;
    }
    if (file && strain >= next_checkpoint_ && !done) {
      while (next_checkpoint_ <= strain) next_checkpoint_ += options_.checkpoint_strain_interval;
      write_checkpoint(*file, sim_.state(), extras());
    }
    if (file) file->flush();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress) {
      TriaxialProgress pr;
      pr.axial_strain = strain;
      pr.target_strain = options_.max_axial_strain;
      pr.steps_per_second =
          seconds > 0.0 ? static_cast<double>(sim_.step_count() - start_step) / seconds : 0.0;
      const bool rate_known = sim_.step_count() - start_step >= 1000;
      pr.seconds_left = rate_known && pr.steps_per_second > 0.0
                            ? std::max(0.0, options_.max_axial_strain - strain) / strain_per_step /
                                  pr.steps_per_second
                            : 0.0;
      pr.eta = eta;
      pr.warning = std::move(inertial_warning);
      inertial_warning.clear();
      progress(pr);
    }
    if (done) {
      summary.reached_critical_state = critical;
      double sum = 0.0;
      const std::size_t from = window_start < history_eta_.size() ? window_start : 0;
      for (std::size_t k = from; k < history_eta_.size(); ++k) sum += history_eta_[k];
      summary.critical_eta = sum / static_cast<double>(history_eta_.size() - from);
      summary.axial_strain = axial_strain();
      break;
    }
  }
  summary.peak_eta = peak_eta_;
  summary.peak_eta_strain = peak_eta_strain_;
  summary.initial_void_ratio = initial_void_ratio_;
  summary.final_void_ratio = void_ratio();
  summary.worst_lateral_error = worst_lateral_error_;
  summary.max_inertial_number = max_inertial_number_;
  summary.steps = sim_.step_count() - test_start_step_;
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (file) file->write_summary(summary);
  return summary;
}

}  // namespace dem
