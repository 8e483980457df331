// Specimen preparation: random insertion, optional gravity deposition at a loading angle,
// isotropic compaction to p'0 with a friction that sets the density (searched for a target
// void ratio if asked), or a packing loaded from CSV.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>

#include "dem/run_config.h"
#include "dem/simulation.h"

namespace dem {

struct PreparationReport {
  std::string method;
  double compaction_friction = 0.0;
  int friction_trials = 0;            ///< compactions run by the void-ratio search
  double void_ratio = 0.0;            ///< at p'0
  double coordination_number = 0.0;
  CompactionResult compaction;
  std::int64_t deposition_steps = 0;
  Eigen::Vector3d bedding_normal = Eigen::Vector3d::UnitZ();  ///< where the loading angle puts it
  Eigen::Vector3d fabric_major = Eigen::Vector3d::Zero();     ///< contact-normal fabric
  Eigen::Vector3d axis_minor = Eigen::Vector3d::Zero();       ///< particle-axis fabric
  std::string describe() const;
};

/// Messages for a long preparation (one line per stage or trial).
using ProgressLog = std::function<void(const std::string&)>;

/// Prepares the specimen the config describes; the returned simulation holds it at p'0 with the
/// preparation's friction and damping, its six walls servo-controlled. `compaction_progress`
/// is called at every acceptance check of every compaction.
Simulation prepare_specimen(const RunConfig& config, PreparationReport* report,
                            const ProgressLog& log = nullptr,
                            const CompactionProgress& compaction_progress = nullptr);

/// The engine settings of preparation: the config's engine with the preparation's local damping
/// and servo speed.
SimulationOptions preparation_engine(const RunConfig& config);

/// Brings a prepared specimen isotropically to `pressure` [Pa] (a specimen prepared at another
/// p'0 than the test's sigma_3), with the preparation's engine and the shearing friction. Throws
/// std::runtime_error when the compaction does not settle.
SimulationState reconsolidate(SimulationState specimen, const RunConfig& config, double pressure);

/// Unit normal of the bedding plane for a loading angle: the plane contains X and makes
/// `alpha` with the Y axis, so the normal is (0, -sin alpha, cos alpha) (Z for alpha = 0).
Eigen::Vector3d bedding_normal(double loading_angle_deg);

/// Fabric tensor (1/N) sum n n of the body-body contact normals.
Eigen::Matrix3d contact_normal_fabric(const Simulation& simulation);
/// (1/N) sum e e of the clump axes.
Eigen::Matrix3d particle_axis_fabric(const Particles& particles);

/// Reads a packing from CSV (format in docs/config.md): bodies and the box [lo, hi]. A sphere
/// may overlap a wall of the box by up to `max_overlap_ratio` of its radius (as wall contacts
/// under load do). Throws std::invalid_argument naming the line at fault, or the body, the wall
/// and the overlap.
Particles load_csv_packing(const std::string& path, const GrainSpec& grains, Eigen::Vector3d* lo,
                           Eigen::Vector3d* hi,
                           double max_overlap_ratio = SimulationOptions{}.max_overlap_ratio);
/// The same from the text of a packing file; `path` (where it came from) begins every message.
Particles parse_csv_packing(const std::string& text, const std::string& path,
                            const GrainSpec& grains, Eigen::Vector3d* lo, Eigen::Vector3d* hi,
                            double max_overlap_ratio = SimulationOptions{}.max_overlap_ratio);

}  // namespace dem
