// The configuration of a DEM run (specimen preparation and triaxial test), read from TOML.
// Every key has a default that reproduces the paper's setting; unknown keys and out-of-range
// values are errors naming the key. Units are SI except where a key's name says otherwise
// (`loading_angle_deg`). docs/config.md lists every key.
#pragma once

#include <cstdint>
#include <string>

#include "dem/compaction.h"
#include "dem/contact_law.h"
#include "dem/packing.h"
#include "dem/simulation.h"
#include "dem/triaxial.h"
#include "runfile/run_file.h"

namespace dem {

enum class PreparationMethod { kCompaction, kDeposition, kCsv };

struct PreparationConfig {
  PreparationMethod method = PreparationMethod::kCompaction;
  double pressure = 100e3;               ///< p'0 of the isotropic compaction [Pa]
  double compaction_friction = 0.1;      ///< friction while compacting: lower is denser
  /// When > 0, the compaction friction is searched so that the void ratio at p'0 meets this.
  double target_void_ratio = 0.0;
  double void_ratio_tolerance = 0.01;
  double loading_angle_deg = 0.0;        ///< bedding plane angle to the Y axis (deposition)
  double deposition_gravity = 9810.0;    ///< [m/s^2]; 1000 g, see docs/dem.md
  double deposition_damping = 0.3;       ///< Cundall damping while the bed settles
  std::string csv_path;                  ///< packing to load (method = "csv")
  double servo_max_speed = 0.5;          ///< [m/s]
  double local_damping = 0.7;
  CompactionOptions compaction;          ///< target_stress is taken from `pressure`
};

/// Upper bounds of the configuration's counts: far beyond any machine this code runs on (10^7
/// clumps are a thousand paper-size specimens, several GB of state), they stop a mistyped number
/// before it becomes an allocation failure or a wrapped integer.
inline constexpr int kMaxBodies = 10'000'000;
inline constexpr int kMaxThreads = 1024;

struct RunConfig {
  std::uint64_t seed = 1;
  int threads = 0;  ///< 0: all cores; at most kMaxThreads
  int num_bodies = 1000;  ///< at most kMaxBodies
  GrainSpec grains;
  ContactParameters contact;  ///< `friction` applies in shearing
  SimulationOptions engine;   ///< local_damping applies in shearing
  PreparationConfig preparation;
  TriaxialOptions triaxial;
  std::string text;           ///< the TOML text it was read from (stored in the run file)
};

/// What to do with a key this version does not know: a user's config is refused, a config stored
/// in a run file by another version is read for the keys it shares.
enum class UnknownKeys { kError, kIgnore };

/// Parses TOML text; throws std::invalid_argument naming the offending key.
RunConfig parse_run_config(const std::string& toml_text, const std::string& source = "config",
                           UnknownKeys unknown = UnknownKeys::kError);
RunConfig load_run_config(const std::string& path);

/// The metadata of a run file made with `config`: its text, seed and physical constants.
runfile::RunMetadata run_metadata(const std::string& kind, const RunConfig& config,
                                  const std::string& program_version);

/// A fully commented TOML file with every key at its default.
std::string default_run_config_text();

}  // namespace dem
