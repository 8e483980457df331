// The run file: one self-describing HDF5 file per DEM run, the contract between the DEM and
// every later stage. Layout (schema version kRunFileSchemaVersion, documented in docs/run-file.md):
//
//   /                 attributes: schema_version, program, program_version, kind, seed,
//                     config (the full config text), units, sign_convention
//   /series/<name>    one extendible 1-D float64 dataset per scalar history, all one length
//   /snapshots/<nnnnnn>/  attributes step, time, axial_strain; datasets
//                     particles (compound ParticleRecord), spheres (N_s x 4: x, y, z, radius),
//                     sphere_body (N_s, body id), contacts (compound ContactRecord),
//                     walls (compound WallRecord)
//   /checkpoint/      the full engine state of the last checkpoint (internal layout), with the
//                     series length and snapshot count at that moment
//
// Errors (missing file, wrong schema, missing dataset) throw std::runtime_error naming the file
// and the object.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "dem/records.h"
#include "dem/simulation.h"

namespace dem {

inline constexpr std::int64_t kRunFileSchemaVersion = 1;

struct RunMetadata {
  std::string kind;             ///< "triaxial", "compaction", ...
  std::string config_text;      ///< the full configuration the run was made with
  std::uint64_t seed = 0;
  std::string program_version;
};

/// Grain-scale data of one output step.
struct Snapshot {
  std::int64_t step = 0;
  double time = 0.0;          ///< [s]
  double axial_strain = 0.0;  ///< compression positive
  std::vector<ParticleRecord> particles;
  std::vector<std::array<double, 4>> spheres;  ///< x, y, z, radius [m]
  std::vector<std::int64_t> sphere_body;       ///< body id of each sphere
  std::vector<ContactRecord> contacts;         ///< body–body, then wall contacts
  std::vector<WallRecord> walls;
};

/// Collects the snapshot of the simulation's current state.
Snapshot take_snapshot(const Simulation& simulation, double axial_strain);

/// Driver-level values stored with a checkpoint (strain references, stage, counters).
using CheckpointExtras = std::map<std::string, double>;

class RunFile {
 public:
  /// Creates (or truncates) `path` with the metadata and the names of its series.
  static RunFile create(const std::string& path, const RunMetadata& metadata,
                        const std::vector<std::string>& series_names);
  /// Opens an existing run file, read-only or for appending (to resume a run).
  static RunFile open(const std::string& path, bool writable = false);

  RunFile(RunFile&&) noexcept;
  RunFile& operator=(RunFile&&) noexcept;
  ~RunFile();

  const std::string& path() const;
  RunMetadata metadata() const;

  /// A free-text root attribute (e.g. the preparation report); read_note returns "" if absent.
  void write_note(const std::string& key, const std::string& text);
  std::string read_note(const std::string& key) const;

  const std::vector<std::string>& series_names() const;
  /// Appends one row; `row` holds one value per series name, in that order.
  void append_series(const std::vector<double>& row);
  std::size_t series_length() const;
  std::vector<double> series(const std::string& name) const;

  void write_snapshot(const Snapshot& snapshot);
  int num_snapshots() const;
  Snapshot read_snapshot(int index) const;

  /// Replaces the checkpoint with this state; series and snapshots written so far are kept.
  void write_checkpoint(const SimulationState& state, const CheckpointExtras& extras);
  bool has_checkpoint() const;
  /// Reads the checkpoint and drops any series rows and snapshots written after it, so the
  /// resumed run continues the file exactly where the checkpoint left it.
  SimulationState read_checkpoint(CheckpointExtras* extras);

  /// Writes a table of analysis results as /analysis/<name>/<column> (1-D float64 datasets,
  /// one value per row), replacing any earlier table of that name.
  void write_table(const std::string& name, const std::vector<std::string>& columns,
                   const std::vector<std::vector<double>>& rows);

  /// Reads a table written by write_table: its columns in their stored order, each with its
  /// values. Throws std::runtime_error naming the file and /analysis/<name> if it is missing.
  std::vector<std::pair<std::string, std::vector<double>>> read_table(const std::string& name) const;

  /// Pushes everything written so far to disk (a killed run keeps it).
  void flush();

 private:
  struct Impl;
  explicit RunFile(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace dem
