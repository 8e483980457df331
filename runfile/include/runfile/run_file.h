// The run file: one self-describing HDF5 file per DEM run, the contract between the DEM and
// every later stage. This library is the only code of the project that touches HDF5. Layout
// (schema version kSchemaVersion, documented in docs/run-file.md):
//
//   /                 attributes: schema_version, program, program_version, kind, seed,
//                     config (the full config text), units, sign_convention
//   /physics          attributes: the run's physical constants (RunPhysics), SI      [schema 2]
//   /summary          attributes: how the test ended (TestSummary)                   [schema 2]
//   /loading          attributes: the test's loading path and axis controls (LoadingRecord);
//                     absent from a specimen file and from files before it (drained compression)
//   /series/<name>    one extendible 1-D float64 dataset per scalar history, all one length
//   /snapshots/<nnnnnn>/  attributes step, time, axial_strain; datasets
//                     particles (compound ParticleRecord), spheres (N_s x 4: x, y, z, radius),
//                     sphere_body (N_s, body id), contacts (compound ContactRecord),
//                     walls (compound WallRecord); periodic_cell (2 x 3: lower and upper
//                     corners) where the specimen is periodic (an imported run)
//   /checkpoint/      an engine state in the writer's layout (StateWriter), with the series
//                     length and snapshot count at that moment
//   /analysis/<table>/<column>  tables of analysis results
//
// Files of schema 1 (no /physics, the summary as a note) are still read: their physics comes
// from the stored config text (stored_physics.cc).
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

#include "runfile/records.h"

namespace runfile {

inline constexpr std::int64_t kSchemaVersion = 2;
inline constexpr std::int64_t kOldestReadableSchema = 1;

/// The run's physical constants, SI (stored as attributes of /physics).
struct RunPhysics {
  double youngs_modulus = 0.0;   ///< E of the grains [Pa]
  double stiffness_ratio = 0.0;  ///< k_t / k_n
  double friction = 0.0;         ///< mu between grains while shearing
  double wall_friction = 0.0;    ///< mu between grains and walls
  double grain_density = 0.0;    ///< [kg/m^3], before density scaling
  double density_scaling = 1.0;  ///< mass scaling of the run (>= 1)
};

/// How a test loads the specimen (stored as attributes of /loading): the path's name (the DEM's
/// config spelling, e.g. "undrained_extension") and, in words, what holds each axis.
struct LoadingRecord {
  std::string path;
  std::array<std::string, 3> axis_control;  ///< x, y, z
  double strain_rate = 0.0;       ///< of the platens [1/s], > 0 (the direction is in the path)
  double confining_stress = 0.0;  ///< sigma_3, or p0 on the constant-p paths [Pa]
  double b = 0.0;                 ///< (sigma_2 - sigma_3) / (sigma_1 - sigma_3) (true triaxial)
};

struct RunMetadata {
  std::string kind;             ///< "triaxial", "specimen", ...
  std::string config_text;      ///< the full configuration the run was made with
  std::uint64_t seed = 0;
  std::string program_version;
  RunPhysics physics = {};
  /// A test's loading (written when `path` is not empty; read back empty where /loading is absent).
  LoadingRecord loading = {};
  std::int64_t schema_version = kSchemaVersion;  ///< of the file it was read from
};

/// Above this inertial number a shear test is no longer quasi-static (GDR MiDi, Eur. Phys. J. E 14,
/// 341, 2004; da Cruz et al., Phys. Rev. E 72, 021309, 2005). The DEM's I: docs/dem.md, "Inertial
/// number".
inline constexpr double kQuasiStaticInertialNumber = 1e-3;

/// How a triaxial test ended (stored as attributes of /summary).
struct TestSummary {
  bool reached_critical_state = false;  ///< else the maximum axial strain stopped it
  double axial_strain = 0.0;
  double peak_eta = 0.0, peak_eta_strain = 0.0;
  double critical_eta = 0.0;  ///< mean q/p over the final window (critical if reached)
  double initial_void_ratio = 0.0, final_void_ratio = 0.0;
  double worst_lateral_error = 0.0;   ///< max |sigma_wall - target| / target (docs/run-file.md)
  double max_inertial_number = 0.0;
  std::int64_t steps = 0;
  double wall_seconds = 0.0;
  /// One line for a log.
  std::string describe() const;
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
  /// A periodic specimen's cell, an orthogonal box: its lower and upper corners [m]; empty where
  /// walls bound the specimen (the project's DEM). Written by `sffcal import`.
  std::vector<std::array<double, 3>> periodic_cell;
};

/// Driver-level values stored with a checkpoint (strain references, stage, counters).
using CheckpointExtras = std::map<std::string, double>;

/// Writes one checkpoint beside the previous one; commit() swaps it in, so a run killed while
/// writing keeps the previous checkpoint. The arrays' names and meaning belong to the writer.
/// The RunFile that began it must stay where it is (not moved) until the writer is gone.
/// Element types: double, std::int32_t, std::int64_t, std::uint8_t.
class StateWriter {
 public:
  StateWriter(StateWriter&&) noexcept;
  ~StateWriter();
  void attribute(const std::string& name, double value);
  void attribute(const std::string& name, std::int64_t value);
  void extras(const CheckpointExtras& extras);
  /// `rows` x `columns` elements in row-major order (columns = 0: a 1-D dataset).
  template <typename T>
  void array(const std::string& name, const T* data, std::size_t rows, std::size_t columns = 0);
  void walls(const std::vector<WallRecord>& walls);
  /// Replaces the file's checkpoint with this one and flushes the file.
  void commit();

 private:
  friend class RunFile;
  struct Impl;
  explicit StateWriter(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Reads the checkpoint of an open run file (which must outlive it). Values are converted to the
/// type asked for; a missing object is an error naming it and the file.
class StateReader {
 public:
  StateReader(StateReader&&) noexcept;
  ~StateReader();
  bool has(const std::string& name) const;
  double real(const std::string& name) const;
  std::int64_t integer(const std::string& name) const;
  CheckpointExtras extras() const;
  template <typename T>
  std::vector<T> array(const std::string& name) const;
  std::vector<WallRecord> walls() const;
  /// "run file PATH: read checkpoint: " + what, for the reader's own checks.
  std::string where(const std::string& what) const;

 private:
  friend class RunFile;
  struct Impl;
  explicit StateReader(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

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
  bool writable() const;
  /// The metadata; a schema-1 file's physics is read from its stored config text.
  RunMetadata metadata() const;

  /// A free-text root attribute (e.g. the preparation report); read_note returns "" if absent.
  void write_note(const std::string& key, const std::string& text);
  std::string read_note(const std::string& key) const;

  void write_summary(const TestSummary& summary);
  bool has_summary() const;
  TestSummary read_summary() const;

  const std::vector<std::string>& series_names() const;
  /// Appends one row; `row` holds one value per series name, in that order.
  void append_series(const std::vector<double>& row);
  std::size_t series_length() const;
  std::vector<double> series(const std::string& name) const;

  void write_snapshot(const Snapshot& snapshot);
  int num_snapshots() const;
  Snapshot read_snapshot(int index) const;

  /// Starts a checkpoint; series and snapshots written so far are kept with it.
  StateWriter begin_checkpoint();
  bool has_checkpoint() const;
  StateReader read_checkpoint() const;
  /// Drops any series rows and snapshots written after the checkpoint, so a resumed run
  /// continues the file exactly where the checkpoint left it.
  void rewind_to_checkpoint();

  /// Writes a table of analysis results as /analysis/<name>/<column> (1-D float64 datasets,
  /// one value per row), replacing any earlier table of that name.
  void write_table(const std::string& name, const std::vector<std::string>& columns,
                   const std::vector<std::vector<double>>& rows);
  bool has_table(const std::string& name) const;
  /// Reads a table written by write_table: its columns in their stored order, each with its
  /// values. Throws std::runtime_error naming the file and /analysis/<name> if it is missing.
  std::vector<std::pair<std::string, std::vector<double>>> read_table(const std::string& name) const;

  /// Pushes everything written so far to disk (a killed run keeps it).
  void flush();

 private:
  friend class StateWriter;
  friend class StateReader;
  struct Impl;
  explicit RunFile(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace runfile
