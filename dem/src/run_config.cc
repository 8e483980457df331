#include "dem/run_config.h"
#include "sffcal/read_text_file.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace dem {
namespace {

// Default configuration, with every key documented. parse_run_config(this) == RunConfig{}
// (checked in a test), so the text and the struct defaults cannot drift apart.
constexpr const char* kDefaultText = R"(# sffcal DEM configuration. SI units (m, kg, s, Pa) unless a key says otherwise.
seed = 1          # random seed of the packing (reported in the run file)
threads = 0       # OpenMP threads, 0 = all cores
bodies = 1000     # number of grains

[grains]
min_diameter = 3.0e-5          # sphere diameter range [m] (paper: 0.03-0.07 mm)
max_diameter = 7.0e-5
centre_distance_ratio = 0.5    # clump sphere spacing / diameter (0.5: length 1.5 d; 0: spheres)
density = 2650.0               # [kg/m^3]

[contact]
youngs_modulus = 1.5e8         # E [Pa]; K = 2 E1 E2 r1 r2 / (E1 r1 + E2 r2)
stiffness_ratio = 0.5          # k_t / k_n
friction = 0.5773502691896257  # tan 30 deg, during shearing
wall_friction = 0.0            # frictionless walls
normal_damping_ratio = 0.0     # contact dashpot, fraction of critical

[engine]
time_step = 0.0                # [s]; 0 = time_step_safety x critical step
time_step_safety = 0.7         # fraction of the critical step (measured choice: docs/config.md)
skin_ratio = 0.1               # Verlet skin / largest diameter
sort_every_builds = 10         # spatial re-sort of the bodies every N list builds
local_damping = 0.0            # Cundall damping during shearing
density_scaling = 1.0          # mass scaling (>= 1), reported
max_overlap_ratio = 0.25       # overlap / radius that stops a run as unstable
servo_gain = 0.8               # wall servo: fraction of the stiffness-estimated correction
servo_blend = 0.5              # wall servo: weight of this step's move against the last
servo_integral_time = 10.0     # wall servo: integral time constant [critical steps]; 0 = off

[preparation]
method = "compaction"          # "compaction", "deposition" (gravity at loading_angle_deg), "csv"
pressure = 1.0e5               # isotropic p'0 [Pa]
compaction_friction = 0.1      # friction while compacting: lower gives a denser specimen
target_void_ratio = 0.0        # > 0: search the compaction friction for this void ratio
void_ratio_tolerance = 0.01
loading_angle_deg = 0.0        # deposition: bedding plane contains X, at this angle to Y [deg]
deposition_gravity = 9810.0    # deposition gravity [m/s^2] (1000 g; see docs/dem.md)
deposition_damping = 0.3       # Cundall damping while the deposited bed settles
csv = ""                       # packing file for method = "csv" (see docs/config.md)
servo_max_speed = 0.5          # cap on the wall speed while compacting [m/s]
local_damping = 0.7            # Cundall damping while preparing
stress_tolerance = 0.01        # accepted |sigma_wall - p'0| / p'0
max_unbalanced_force = 1.0e-3  # accepted unbalanced-force ratio
max_steps = 2000000            # give up (error) after this many compaction steps

[triaxial]
path = "drained_compression"   # drained_compression | drained_extension | constant_p_compression |
                               # undrained_compression | undrained_extension | true_triaxial (docs/dem.md)
confining_stress = 0.0         # sigma_3, or p0 on the constant-p paths [Pa]; 0 = the preparation pressure
b = 0.0                        # true_triaxial: (sigma_2 - sigma_3) / (sigma_1 - sigma_3) in [0, 1], sigma_2 on y
undrained_lateral = "equal_strains"  # undrained paths: equal_strains (both widths alike) | equal_stresses
                               # (sigma_x = sigma_y at constant volume, as in a cell: for deposits)
strain_rate = 100.0            # axial strain rate [1/s]; within the seed scatter of 20 /s (paper: 0.06 m/s on a 3 mm cube), bench/RESULTS.md
servo_max_speed = 0.5          # cap on the lateral wall speed [m/s]
max_axial_strain = 0.45
output_strain_interval = 0.002 # a series row every this much axial strain
snapshot_strain_interval = 0.05
checkpoint_strain_interval = 0.02
critical_window = 0.1          # critical state: over this axial strain window ...
critical_eta_change = 0.05     # ... the fitted line through q/p changes less than this
critical_volume_change = 0.005 # ... and through the volumetric strain less than this
critical_mean_stress_change = 0.05  # undrained paths: ... and through p / p0 less than this
critical_min_strain = 0.2      # not before this |axial strain|
)";

using Setter = std::function<void(const toml::node&, const std::string& key)>;

double number(const toml::node& node, const std::string& key) {
  if (auto v = node.value<double>()) return *v;
  throw std::invalid_argument(key + " must be a number");
}

Setter real(double& target) {
  return [&target](const toml::node& n, const std::string& key) {
    const double v = number(n, key);
    if (!std::isfinite(v)) throw std::invalid_argument(key + " must be finite");
    target = v;
  };
}

// An integer key in [min_value, max_value], the upper bound at most what the target type holds:
// range-checked before the narrowing (2^32 + 80 bodies must not run 80).
template <typename Int>
Setter integer(Int& target, long long min_value,
               long long max_value = static_cast<long long>(
                   std::min<unsigned long long>(std::numeric_limits<Int>::max(),
                                                std::numeric_limits<long long>::max()))) {
  return [&target, min_value, max_value](const toml::node& n, const std::string& key) {
    // An integer node first: toml++ converts a float node (1e118) to an integer by a cast whose
    // result is undefined outside the integer's range.
    if (!n.is_integer()) throw std::invalid_argument(key + " must be an integer");
    const auto v = n.value<long long>();
    if (!v) throw std::invalid_argument(key + " must be an integer");
    if (*v < min_value || *v > max_value)
      throw std::invalid_argument(key + " must be in [" + std::to_string(min_value) + ", " +
                                  std::to_string(max_value) + "] (got " + std::to_string(*v) +
                                  ")");
    target = static_cast<Int>(*v);
  };
}

Setter text(std::string& target) {
  return [&target](const toml::node& n, const std::string& key) {
    if (!n.is_string()) throw std::invalid_argument(key + " must be a string");
    target = *n.value<std::string>();
  };
}

void check(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

// The TOML text as a table; throws std::invalid_argument naming the source, line and column of a
// syntax error.
toml::table parse_toml(const std::string& toml_text, const std::string& source) {
  try {
    return toml::parse(toml_text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << source << ": TOML syntax error at line " << e.source().begin.line << ", column "
        << e.source().begin.column << ": " << e.description();
    throw std::invalid_argument(msg.str());
  }
}

RunConfig config_from_table(const toml::table& table, const std::string& toml_text,
                            const std::string& source, UnknownKeys unknown);

}  // namespace

RunConfig parse_run_config(const std::string& toml_text, const std::string& source,
                           UnknownKeys unknown) {
  return config_from_table(parse_toml(toml_text, source), toml_text, source, unknown);
}

namespace {

// The config a parsed table sets (the text is kept for the run file).
RunConfig config_from_table(const toml::table& table, const std::string& toml_text,
                            const std::string& source, UnknownKeys unknown) {
  RunConfig c;
  c.text = toml_text;
  std::string method = "compaction";
  std::string path = loading_path_name(c.triaxial.path);
  std::string undrained_lateral = undrained_lateral_name(c.triaxial.undrained_lateral);
  double servo_prep = c.preparation.servo_max_speed;
  double servo_shear = 0.5;
  const std::map<std::string, Setter> setters = {
      {"seed", integer(c.seed, 0)},
      {"threads", integer(c.threads, 0, kMaxThreads)},
      {"bodies", integer(c.num_bodies, 2, kMaxBodies)},
      {"grains.min_diameter", real(c.grains.min_diameter)},
      {"grains.max_diameter", real(c.grains.max_diameter)},
      {"grains.centre_distance_ratio", real(c.grains.centre_distance_ratio)},
      {"grains.density", real(c.grains.density)},
      {"contact.youngs_modulus", real(c.contact.youngs_modulus)},
      {"contact.stiffness_ratio", real(c.contact.stiffness_ratio)},
      {"contact.friction", real(c.contact.friction)},
      {"contact.wall_friction", real(c.contact.wall_friction)},
      {"contact.normal_damping_ratio", real(c.contact.normal_damping_ratio)},
      {"engine.time_step", real(c.engine.time_step)},
      {"engine.time_step_safety", real(c.engine.time_step_safety)},
      {"engine.skin_ratio", real(c.engine.skin_ratio)},
      {"engine.sort_every_builds", integer(c.engine.sort_every_builds, 0)},
      {"engine.local_damping", real(c.engine.local_damping)},
      {"engine.density_scaling", real(c.engine.density_scaling)},
      {"engine.max_overlap_ratio", real(c.engine.max_overlap_ratio)},
      {"engine.servo_gain", real(c.engine.servo.gain)},
      {"engine.servo_blend", real(c.engine.servo.blend)},
      {"engine.servo_integral_time", real(c.engine.servo.integral_time)},
      {"preparation.method", text(method)},
      {"preparation.pressure", real(c.preparation.pressure)},
      {"preparation.compaction_friction", real(c.preparation.compaction_friction)},
      {"preparation.target_void_ratio", real(c.preparation.target_void_ratio)},
      {"preparation.void_ratio_tolerance", real(c.preparation.void_ratio_tolerance)},
      {"preparation.loading_angle_deg", real(c.preparation.loading_angle_deg)},
      {"preparation.deposition_gravity", real(c.preparation.deposition_gravity)},
      {"preparation.deposition_damping", real(c.preparation.deposition_damping)},
      {"preparation.csv", text(c.preparation.csv_path)},
      {"preparation.servo_max_speed", real(servo_prep)},
      {"preparation.local_damping", real(c.preparation.local_damping)},
      {"preparation.stress_tolerance", real(c.preparation.compaction.stress_tolerance)},
      {"preparation.max_unbalanced_force", real(c.preparation.compaction.max_unbalanced_force)},
      {"preparation.max_steps", integer(c.preparation.compaction.max_steps, 1)},
      {"triaxial.path", text(path)},
      {"triaxial.confining_stress", real(c.triaxial.confining_stress)},
      {"triaxial.b", real(c.triaxial.b)},
      {"triaxial.undrained_lateral", text(undrained_lateral)},
      {"triaxial.strain_rate", real(c.triaxial.strain_rate)},
      {"triaxial.servo_max_speed", real(servo_shear)},
      {"triaxial.max_axial_strain", real(c.triaxial.max_axial_strain)},
      {"triaxial.output_strain_interval", real(c.triaxial.output_strain_interval)},
      {"triaxial.snapshot_strain_interval", real(c.triaxial.snapshot_strain_interval)},
      {"triaxial.checkpoint_strain_interval", real(c.triaxial.checkpoint_strain_interval)},
      {"triaxial.critical_window", real(c.triaxial.critical_window)},
      {"triaxial.critical_eta_change", real(c.triaxial.critical_eta_change)},
      {"triaxial.critical_volume_change", real(c.triaxial.critical_volume_change)},
      {"triaxial.critical_mean_stress_change", real(c.triaxial.critical_mean_stress_change)},
      {"triaxial.critical_min_strain", real(c.triaxial.critical_min_strain)},
  };
  const std::string where = source + ": ";
  c.triaxial.confining_stress = 0.0;
  auto apply = [&](const std::string& key, const toml::node& value) {
    const auto it = setters.find(key);
    if (it == setters.end()) {
      if (unknown == UnknownKeys::kIgnore) return;
      throw std::invalid_argument(where + "unknown key '" + key + "'");
    }
    try {
      it->second(value, key);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(where + e.what());
    }
  };
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    if (const toml::table* section = node.as_table()) {
      for (const auto& [sub, value] : *section) apply(name + "." + std::string(sub.str()), value);
    } else {
      apply(name, node);
    }
  }

  if (method == "compaction") c.preparation.method = PreparationMethod::kCompaction;
  else if (method == "deposition") c.preparation.method = PreparationMethod::kDeposition;
  else if (method == "csv") c.preparation.method = PreparationMethod::kCsv;
  else
    throw std::invalid_argument(where + "preparation.method must be \"compaction\", \"deposition\" or "
                                "\"csv\" (got \"" + method + "\")");
  try {
    c.triaxial.path = parse_loading_path(path);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where + "triaxial.path: " + e.what());
  }
  try {
    c.triaxial.undrained_lateral = parse_undrained_lateral(undrained_lateral);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where + "triaxial.undrained_lateral: " + e.what());
  }
  c.preparation.servo_max_speed = servo_prep;
  c.engine.servo.max_speed = servo_shear;
  c.preparation.compaction.target_stress = c.preparation.pressure;
  if (c.triaxial.confining_stress == 0.0) c.triaxial.confining_stress = c.preparation.pressure;

  // Range checks, each naming its key.
  const GrainSpec& g = c.grains;
  check(g.min_diameter > 0.0, where + "grains.min_diameter must be positive [m]");
  check(g.max_diameter >= g.min_diameter, where + "grains.max_diameter must be >= grains.min_diameter");
  check(g.centre_distance_ratio >= 0.0 && g.centre_distance_ratio < 1.0,
        where + "grains.centre_distance_ratio must lie in [0, 1)");
  check(g.density > 0.0, where + "grains.density must be positive [kg/m^3]");
  const std::string contact_error = c.contact.validate();
  check(contact_error.empty(), where + "contact: " + contact_error);
  const std::string engine_error = c.engine.validate();
  check(engine_error.empty(), where + "engine: " + engine_error);
  const PreparationConfig& p = c.preparation;
  check(p.pressure > 0.0, where + "preparation.pressure must be positive [Pa]");
  check(p.compaction_friction >= 0.0 && p.compaction_friction <= 10.0,
        where + "preparation.compaction_friction must lie in [0, 10]");
  check(p.target_void_ratio >= 0.0, where + "preparation.target_void_ratio must be >= 0");
  check(p.void_ratio_tolerance > 0.0, where + "preparation.void_ratio_tolerance must be positive");
  check(std::abs(p.loading_angle_deg) <= 90.0,
        where + "preparation.loading_angle_deg must lie in [-90, 90]");
  check(p.deposition_gravity > 0.0, where + "preparation.deposition_gravity must be positive");
  check(p.deposition_damping >= 0.0 && p.deposition_damping < 1.0,
        where + "preparation.deposition_damping must lie in [0, 1)");
  check(p.method != PreparationMethod::kCsv || !p.csv_path.empty(),
        where + "preparation.csv must name a file when preparation.method = \"csv\"");
  check(p.servo_max_speed > 0.0, where + "preparation.servo_max_speed must be positive [m/s]");
  check(p.local_damping >= 0.0 && p.local_damping < 1.0,
        where + "preparation.local_damping must lie in [0, 1)");
  check(p.compaction.stress_tolerance > 0.0, where + "preparation.stress_tolerance must be positive");
  check(p.compaction.max_unbalanced_force > 0.0,
        where + "preparation.max_unbalanced_force must be positive");
  const std::string triaxial_error = c.triaxial.validate();
  check(triaxial_error.empty(), where + "triaxial: " + triaxial_error);
  return c;
}

}  // namespace

RunConfig load_run_config(const std::string& path) {
  // A config is a few kB; 1 MB leaves room for comments and refuses /dev/zero.
  const std::string text = sffcal::read_text_file(path, std::uintmax_t{1} << 20, "config file");
  const toml::table table = parse_toml(text, path);  // parsed once
  // An empty file (or one of comments only) would run every default, 1000 bodies included: more
  // likely a wrong or truncated file than a choice. The defaults are one command away.
  if (table.empty())
    throw std::invalid_argument(path + ": the config sets no key (empty or comments only); "
                                "`sffcal config -o FILE` writes every key with its default");
  return config_from_table(table, text, path, UnknownKeys::kError);
}

std::string default_run_config_text() { return kDefaultText; }

runfile::RunMetadata run_metadata(const std::string& kind, const RunConfig& config,
                                  const std::string& program_version) {
  runfile::RunMetadata m;
  m.kind = kind;
  m.config_text = config.text;
  m.seed = config.seed;
  m.program_version = program_version;
  m.physics.youngs_modulus = config.contact.youngs_modulus;
  m.physics.stiffness_ratio = config.contact.stiffness_ratio;
  m.physics.friction = config.contact.friction;
  m.physics.wall_friction = config.contact.wall_friction;
  m.physics.grain_density = config.grains.density;
  m.physics.density_scaling = config.engine.density_scaling;
  if (kind == "triaxial") {
    const TriaxialOptions& t = config.triaxial;
    m.loading.path = loading_path_name(t.path);
    m.loading.axis_control =
        axis_controls(t.path, t.confining_stress, t.b, t.strain_rate, t.undrained_lateral);
    m.loading.strain_rate = t.strain_rate;
    m.loading.confining_stress = t.confining_stress;
    m.loading.b = t.b;
  }
  return m;
}

}  // namespace dem
