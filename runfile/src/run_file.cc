#include "runfile/run_file.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "h5.h"
#include "snapshot_check.h"
#include "runfile/stored_physics.h"
#include "sffcal/unique_name.h"

namespace runfile {
namespace {

constexpr const char* kUnits = "SI: m, kg, s, N, Pa; angles in rad";
constexpr const char* kSignConvention =
    "contact normal from body A to body B; forces act on B; normal_force > 0 in compression; "
    "stresses and strains compression positive";

std::string snapshot_name(int index) {
  char name[32];
  std::snprintf(name, sizeof(name), "/snapshots/%06d", index);
  return name;
}

// The attributes of /physics and the real attributes of /summary, named as the fields (declared
// once here for writing and reading).
constexpr std::pair<const char*, double RunPhysics::*> kPhysicsFields[] = {
    {"youngs_modulus", &RunPhysics::youngs_modulus}, {"stiffness_ratio", &RunPhysics::stiffness_ratio},
    {"friction", &RunPhysics::friction},             {"wall_friction", &RunPhysics::wall_friction},
    {"grain_density", &RunPhysics::grain_density},   {"density_scaling", &RunPhysics::density_scaling}};
constexpr std::pair<const char*, double TestSummary::*> kSummaryFields[] = {
    {"axial_strain", &TestSummary::axial_strain},
    {"peak_eta", &TestSummary::peak_eta},
    {"peak_eta_strain", &TestSummary::peak_eta_strain},
    {"critical_eta", &TestSummary::critical_eta},
    {"initial_void_ratio", &TestSummary::initial_void_ratio},
    {"final_void_ratio", &TestSummary::final_void_ratio},
    {"worst_lateral_error", &TestSummary::worst_lateral_error},
    {"max_inertial_number", &TestSummary::max_inertial_number},
    {"wall_seconds", &TestSummary::wall_seconds}};

template <typename Record, std::size_t N>
void write_fields(hid_t object, const Record& record,
                  const std::pair<const char*, double Record::*> (&fields)[N]) {
  for (const auto& [name, member] : fields) h5::write_attribute(object, name, record.*member);
}

template <typename Record, std::size_t N>
void read_fields(hid_t object, Record& record,
                 const std::pair<const char*, double Record::*> (&fields)[N]) {
  for (const auto& [name, member] : fields) record.*member = h5::read_double_attribute(object, name);
}

void write_physics(hid_t root, const RunPhysics& physics) {
  h5::Handle group = h5::create_group(root, "physics");
  write_fields(group.get(), physics, kPhysicsFields);
  h5::write_attribute(group.get(), "units",
                      std::string("youngs_modulus Pa, grain_density kg/m^3, the others 1"));
}

void write_loading(hid_t root, const LoadingRecord& loading) {
  h5::Handle group = h5::create_group(root, "loading");
  const hid_t g = group.get();
  h5::write_attribute(g, "path", loading.path);
  for (int axis = 0; axis < 3; ++axis)
    h5::write_attribute(g, std::string("axis_") + "xyz"[axis], loading.axis_control[axis]);
  h5::write_attribute(g, "strain_rate", loading.strain_rate);
  h5::write_attribute(g, "confining_stress", loading.confining_stress);
  h5::write_attribute(g, "b", loading.b);
  h5::write_attribute(g, "units", std::string("strain_rate 1/s, confining_stress Pa, b 1"));
}

LoadingRecord read_loading(hid_t root) {
  LoadingRecord loading;
  if (!h5::exists(root, "loading")) return loading;
  h5::Handle group = h5::open_group(root, "loading");
  const hid_t g = group.get();
  loading.path = h5::read_string_attribute(g, "path");
  for (int axis = 0; axis < 3; ++axis)
    loading.axis_control[axis] = h5::read_string_attribute(g, std::string("axis_") + "xyz"[axis]);
  loading.strain_rate = h5::read_double_attribute(g, "strain_rate");
  loading.confining_stress = h5::read_double_attribute(g, "confining_stress");
  loading.b = h5::read_double_attribute(g, "b");
  return loading;
}

RunPhysics read_physics(hid_t root) {
  h5::Handle group = h5::open_group(root, "physics");
  RunPhysics physics;
  read_fields(group.get(), physics, kPhysicsFields);
  return physics;
}

}  // namespace

struct RunFile::Impl {
  std::string path;
  h5::Handle file;
  std::vector<std::string> series_names;
  bool writable = false;
  std::int64_t schema_version = kSchemaVersion;
  int fd = -1;  ///< the file's descriptor where it is written (h5::file_descriptor)

  hid_t id() const { return file.get(); }
  // A full disk met halfway through a flush leaves a file HDF5 cannot open; so every write and
  // every flush first allocates the disk it may use (h5::reserve_space): the data's bytes and a
  // margin for the metadata a flush writes (object headers, index and name-table nodes: a few kB
  // per object). On a full disk it is the allocation that fails, before anything changes, and
  // the file stays that of the last flush.
  void reserve(std::uint64_t data_bytes) const {
    constexpr std::uint64_t kMetadataBytes = 64 * 1024;
    h5::reserve_space(id(), fd, data_bytes + kMetadataBytes);
  }
  // What is allocated beyond the end is given back at every flush. Kept until the file closed,
  // it cost a fifth less wall time on a run that flushes 3000 rows, but a run killed at a random
  // moment then left a file shorter than its superblock's end (bench/RESULTS.md).
  void flush() const {
    reserve(0);
    h5::check_status(H5Fflush(id(), H5F_SCOPE_GLOBAL), "flush");
    h5::release_space(id(), fd);
  }
  // Makes `object`, written unlinked, reachable at `where` in place of what was there, so that a
  // run killed at any moment finds at `where` the old object or the new one, each whole: the new
  // one reaches the disk in a flush before any link to it, and the old one is unlinked in the
  // flush that writes the new link (docs/run-file.md, "A killed run").
  void publish(hid_t object, const std::string& where) const {
    const std::size_t slash = where.rfind('/');
    if (slash != std::string::npos && !h5::exists(id(), where.substr(0, slash))) {
      const h5::Handle parent = h5::create_unlinked_group(id());  // e.g. /analysis, the first time
      publish(parent.get(), where.substr(0, slash));
    }
    flush();
    if (h5::exists(id(), where))
      h5::check_status(H5Ldelete(id(), where.c_str(), H5P_DEFAULT), "unlink the old " + where);
    h5::link(object, id(), where);
    flush();
  }
  // Wraps HDF5 failures with the file name.
  template <typename F>
  auto guard(const std::string& what, F&& f) const {
    try {
      return f();
    } catch (const std::runtime_error& e) {
      throw std::runtime_error("run file " + path + ": " + what + ": " + e.what());
    }
  }
};

RunFile::RunFile(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
RunFile::RunFile(RunFile&&) noexcept = default;
RunFile& RunFile::operator=(RunFile&&) noexcept = default;
RunFile::~RunFile() {
  if (!(impl_ && impl_->writable && impl_->file.valid())) return;
  try {
    impl_->flush();
  } catch (const std::exception&) {  // reported where the write failed
  }
}

RunFile RunFile::create(const std::string& path, const RunMetadata& metadata,
                        const std::vector<std::string>& series_names) {
  h5::silence_errors();
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->writable = true;
  impl->series_names = series_names;
  // Made under a temporary name and renamed once whole and flushed: a run killed while the
  // file is being made leaves no half-made file under the name (only PATH.partial-PID-N). The
  // name is claimed with O_EXCL, so that no file of anyone else's is ever truncated.
  const std::string partial = sffcal::claim_unique_name(path + ".partial");
  try {
    impl->guard("create", [&] {
      const h5::Handle creation = h5::crash_safe_creation_properties();
      const h5::Handle access = h5::crash_safe_access_properties();
      errno = 0;
      const hid_t created =
          H5Fcreate(partial.c_str(), H5F_ACC_TRUNC, creation.get(), access.get());
      impl->file = h5::check(created, std::string("create the file (") +
                                          (errno != 0 ? std::strerror(errno)
                                                      : "is the folder there and writable?") +
                                          ")");
      impl->fd = h5::file_descriptor(impl->id());
      impl->reserve(metadata.config_text.size());
      const hid_t root = impl->id();
      h5::write_attribute(root, "schema_version", kSchemaVersion);
      h5::write_attribute(root, "program", std::string("sffcal"));
      h5::write_attribute(root, "program_version", metadata.program_version);
      h5::write_attribute(root, "kind", metadata.kind);
      h5::write_attribute(root, "seed", static_cast<std::int64_t>(metadata.seed));
      h5::write_attribute(root, "config", metadata.config_text);
      h5::write_attribute(root, "units", std::string(kUnits));
      h5::write_attribute(root, "sign_convention", std::string(kSignConvention));
      write_physics(root, metadata.physics);
      if (!metadata.loading.path.empty()) write_loading(root, metadata.loading);
      h5::Handle series = h5::create_group(root, "series");
      std::string joined;
      for (const std::string& name : series_names) {
        h5::create_extendible(series.get(), name);
        joined += (joined.empty() ? "" : ",") + name;
      }
      h5::write_attribute(series.get(), "columns", joined);
      h5::create_group(root, "snapshots", 1024);
      impl->flush();
      if (std::rename(partial.c_str(), path.c_str()) != 0)
        throw std::runtime_error("cannot rename " + partial + " to " + path + ": " +
                                 std::strerror(errno));
      return 0;
    });
  } catch (...) {
    impl->file = h5::Handle();
    std::remove(partial.c_str());
    throw;
  }
  return RunFile(std::move(impl));
}

RunFile RunFile::open(const std::string& path, bool writable) {
  h5::silence_errors();
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->writable = writable;
  impl->guard("open", [&] {
    const h5::Handle access =
        writable ? h5::crash_safe_access_properties() : h5::Handle(H5Pcreate(H5P_FILE_ACCESS));
    impl->file = h5::check(
        H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, access.get()),
        "open the file (missing, or not an HDF5 file?)");
    if (writable) impl->fd = h5::file_descriptor(impl->id());
    impl->schema_version = h5::read_int_attribute(impl->id(), "schema_version");
    if (impl->schema_version < kOldestReadableSchema || impl->schema_version > kSchemaVersion)
      throw std::runtime_error("schema version " + std::to_string(impl->schema_version) +
                               ", this version reads " + std::to_string(kOldestReadableSchema) +
                               " to " + std::to_string(kSchemaVersion));
    h5::Handle series = h5::open_group(impl->id(), "series");
    std::stringstream columns(h5::read_string_attribute(series.get(), "columns"));
    std::string name;
    while (std::getline(columns, name, ',')) impl->series_names.push_back(name);
    return 0;
  });
  return RunFile(std::move(impl));
}

const std::string& RunFile::path() const { return impl_->path; }
bool RunFile::writable() const { return impl_->writable; }

RunMetadata RunFile::metadata() const {
  return impl_->guard("read metadata", [&] {
    RunMetadata m;
    m.kind = h5::read_string_attribute(impl_->id(), "kind");
    m.config_text = h5::read_string_attribute(impl_->id(), "config");
    m.seed = static_cast<std::uint64_t>(h5::read_int_attribute(impl_->id(), "seed"));
    m.program_version = h5::read_string_attribute(impl_->id(), "program_version");
    m.schema_version = impl_->schema_version;
    m.loading = read_loading(impl_->id());
    m.physics = impl_->schema_version >= 2
                    ? read_physics(impl_->id())
                    : physics_from_config_text(m.config_text, impl_->path + " (stored config)");
    return m;
  });
}

void RunFile::write_note(const std::string& key, const std::string& text) {
  impl_->guard("write note " + key, [&] {
    impl_->reserve(text.size());
    h5::write_attribute(impl_->id(), "note:" + key, text);
    return 0;
  });
}

std::string RunFile::read_note(const std::string& key) const {
  return impl_->guard("read note " + key, [&] {
    const std::string name = "note:" + key;
    if (H5Aexists(impl_->id(), name.c_str()) <= 0) return std::string();
    return h5::read_string_attribute(impl_->id(), name);
  });
}

const std::vector<std::string>& RunFile::series_names() const { return impl_->series_names; }

void RunFile::append_series(const std::vector<double>& row) {
  if (row.size() != impl_->series_names.size())
    throw std::invalid_argument("run file " + impl_->path + ": a series row has " +
                                std::to_string(row.size()) + " values for " +
                                std::to_string(impl_->series_names.size()) + " series");
  impl_->guard("append to /series", [&] {
    // A row that starts the series' next chunks allocates them whole (at the flush); the others
    // fall in chunks already allocated, and the flush reserves its metadata itself.
    if (series_length() % h5::kExtendibleChunkRows == 0)
      impl_->reserve(row.size() * sizeof(double) * h5::kExtendibleChunkRows);
    h5::Handle series = h5::open_group(impl_->id(), "series");
    for (std::size_t k = 0; k < row.size(); ++k)
      h5::append(series.get(), impl_->series_names[k], row[k]);
    return 0;
  });
}

std::size_t RunFile::series_length() const {
  if (impl_->series_names.empty()) return 0;
  return impl_->guard("read /series", [&] {
    h5::Handle series = h5::open_group(impl_->id(), "series");
    return h5::length(series.get(), impl_->series_names.front());
  });
}

std::vector<double> RunFile::series(const std::string& name) const {
  return impl_->guard("read /series/" + name, [&] {
    h5::Handle series = h5::open_group(impl_->id(), "series");
    if (!h5::exists(series.get(), name))
      throw std::runtime_error("no such series (columns: " +
                               h5::read_string_attribute(series.get(), "columns") + ")");
    return h5::read_dataset<double>(series.get(), name, H5T_NATIVE_DOUBLE);
  });
}

void RunFile::write_snapshot(const Snapshot& s) {
  const int index = num_snapshots();
  impl_->guard("write snapshot", [&] {
    auto bytes = [](const auto& v) { return v.size() * sizeof(v[0]); };
    impl_->reserve(bytes(s.particles) + bytes(s.spheres) + bytes(s.sphere_body) +
                   bytes(s.contacts) + bytes(s.walls));
    h5::Handle group = h5::create_unlinked_group(impl_->id());
    const hid_t g = group.get();
    h5::write_attribute(g, "step", s.step);
    h5::write_attribute(g, "time", s.time);
    h5::write_attribute(g, "axial_strain", s.axial_strain);
    h5::write_dataset(g, "particles", h5::particle_record_type().get(), s.particles.data(),
                      s.particles.size());
    h5::write_dataset(g, "spheres", H5T_NATIVE_DOUBLE, s.spheres.data(), s.spheres.size(), 4);
    h5::write_dataset(g, "sphere_body", H5T_NATIVE_INT64, s.sphere_body.data(), s.sphere_body.size());
    h5::write_dataset(g, "contacts", h5::contact_record_type().get(), s.contacts.data(),
                      s.contacts.size());
    h5::write_dataset(g, "walls", h5::wall_record_type().get(), s.walls.data(), s.walls.size());
    if (!s.periodic_cell.empty())
      h5::write_dataset(g, "periodic_cell", H5T_NATIVE_DOUBLE, s.periodic_cell.data(),
                        s.periodic_cell.size(), 3);
    impl_->publish(g, snapshot_name(index));
    return 0;
  });
}

int RunFile::num_snapshots() const {
  return impl_->guard("count snapshots", [&] {
    if (!h5::exists(impl_->id(), "snapshots")) return 0;  // a reduced file keeps none
    h5::Handle group = h5::open_group(impl_->id(), "snapshots");
    H5G_info_t info;
    h5::check_status(H5Gget_info(group.get(), &info), "read /snapshots");
    return static_cast<int>(info.nlinks);
  });
}

Snapshot RunFile::read_snapshot(int index) const {
  return impl_->guard("read snapshot " + std::to_string(index), [&] {
    if (index < 0 || index >= num_snapshots())
      throw std::runtime_error("no such snapshot (the file has " +
                               std::to_string(num_snapshots()) + ")");
    h5::Handle group = h5::open_group(impl_->id(), snapshot_name(index));
    const hid_t g = group.get();
    Snapshot s;
    s.step = h5::read_int_attribute(g, "step");
    s.time = h5::read_double_attribute(g, "time");
    s.axial_strain = h5::read_double_attribute(g, "axial_strain");
    s.particles = h5::read_dataset<ParticleRecord>(g, "particles", h5::particle_record_type().get());
    const auto flat = h5::read_dataset<double>(g, "spheres", H5T_NATIVE_DOUBLE);
    s.spheres.resize(flat.size() / 4);
    for (std::size_t k = 0; k < s.spheres.size(); ++k)
      s.spheres[k] = {flat[4 * k], flat[4 * k + 1], flat[4 * k + 2], flat[4 * k + 3]};
    s.sphere_body = h5::read_dataset<std::int64_t>(g, "sphere_body", H5T_NATIVE_INT64);
    s.contacts = h5::read_dataset<ContactRecord>(g, "contacts", h5::contact_record_type().get());
    s.walls = h5::read_dataset<WallRecord>(g, "walls", h5::wall_record_type().get());
    std::size_t cell_values = 0;
    if (h5::exists(g, "periodic_cell")) {
      const auto cell = h5::read_dataset<double>(g, "periodic_cell", H5T_NATIVE_DOUBLE);
      cell_values = cell.size();
      for (std::size_t k = 0; k + 3 <= cell.size(); k += 3)
        s.periodic_cell.push_back({cell[k], cell[k + 1], cell[k + 2]});
    }
    check_snapshot(s, flat.size(), cell_values);
    return s;
  });
}

// ---- how a test ended ----

std::string TestSummary::describe() const {
  std::ostringstream s;
  s << (reached_critical_state ? "critical state reached" : "maximum axial strain reached")
    << " at axial strain " << axial_strain << "; peak q/p " << peak_eta << " at " << peak_eta_strain
    << (reached_critical_state ? ", critical q/p " : ", final q/p (last window) ") << critical_eta
    << "; void ratio " << initial_void_ratio << " -> " << final_void_ratio
    << "; worst lateral stress error " << 100.0 * worst_lateral_error
    << " %; max inertial number " << max_inertial_number
    << (max_inertial_number > kQuasiStaticInertialNumber
            ? " (WARNING: past the quasi-static limit 1e-3: lower the strain rate or the density "
              "scaling)"
            : "")
    << "; " << steps << " steps in "
    << wall_seconds << " s";
  return s.str();
}

void RunFile::write_summary(const TestSummary& summary) {
  impl_->guard("write /summary", [&] {
    impl_->reserve(0);
    h5::Handle group = h5::create_unlinked_group(impl_->id());
    const hid_t g = group.get();
    h5::write_attribute(g, "ended", std::string(summary.reached_critical_state ? "critical_state"
                                                                              : "max_axial_strain"));
    write_fields(g, summary, kSummaryFields);
    h5::write_attribute(g, "steps", summary.steps);
    impl_->publish(g, "summary");
    return 0;
  });
}

bool RunFile::has_summary() const { return h5::exists(impl_->id(), "summary"); }

TestSummary RunFile::read_summary() const {
  return impl_->guard("read /summary", [&] {
    if (!has_summary()) throw std::runtime_error("the file has no test summary (an unfinished run?)");
    h5::Handle group = h5::open_group(impl_->id(), "summary");
    const hid_t g = group.get();
    TestSummary s;
    const std::string ended = h5::read_string_attribute(g, "ended");
    if (ended != "critical_state" && ended != "max_axial_strain")
      throw std::runtime_error("'ended' is '" + ended + "', not critical_state or max_axial_strain");
    s.reached_critical_state = ended == "critical_state";
    read_fields(g, s, kSummaryFields);
    s.steps = h5::read_int_attribute(g, "steps");
    return s;
  });
}

// ---- checkpoints ----

namespace {

template <typename T>
hid_t native_type();
template <>
hid_t native_type<double>() { return H5T_NATIVE_DOUBLE; }
template <>
hid_t native_type<std::int32_t>() { return H5T_NATIVE_INT32; }
template <>
hid_t native_type<std::int64_t>() { return H5T_NATIVE_INT64; }
template <>
hid_t native_type<std::uint8_t>() { return H5T_NATIVE_UINT8; }

constexpr const char* kCheckpoint = "checkpoint";
constexpr const char* kNewCheckpoint = "checkpoint_new";  // sffcal 0.1's name, removed if found

}  // namespace

struct StateWriter::Impl {
  RunFile* file = nullptr;
  h5::Handle group;
  bool committed = false;
  const RunFile::Impl& owner() const { return *file->impl_; }
};

StateWriter::StateWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
StateWriter::StateWriter(StateWriter&&) noexcept = default;
StateWriter::~StateWriter() = default;

void StateWriter::attribute(const std::string& name, double value) {
  impl_->owner().guard("write checkpoint", [&] {
    h5::write_attribute(impl_->group.get(), name, value);
    return 0;
  });
}

void StateWriter::attribute(const std::string& name, std::int64_t value) {
  impl_->owner().guard("write checkpoint", [&] {
    h5::write_attribute(impl_->group.get(), name, value);
    return 0;
  });
}

void StateWriter::extras(const CheckpointExtras& extras) {
  impl_->owner().guard("write checkpoint extras", [&] {
    h5::Handle extra = h5::create_group(impl_->group.get(), "extras");
    for (const auto& [key, value] : extras) h5::write_attribute(extra.get(), key, value);
    return 0;
  });
}

template <typename T>
void StateWriter::array(const std::string& name, const T* data, std::size_t rows,
                        std::size_t columns) {
  impl_->owner().guard("write checkpoint", [&] {
    impl_->owner().reserve(rows * std::max<std::size_t>(columns, 1) * sizeof(T));
    h5::write_dataset(impl_->group.get(), name, native_type<T>(), data, rows, columns);
    return 0;
  });
}

void StateWriter::walls(const std::vector<WallRecord>& walls) {
  impl_->owner().guard("write checkpoint", [&] {
    impl_->owner().reserve(walls.size() * sizeof(WallRecord));
    h5::write_dataset(impl_->group.get(), "walls", h5::wall_record_type().get(), walls.data(),
                      walls.size());
    return 0;
  });
}

void StateWriter::commit() {
  if (impl_->committed) throw std::logic_error("StateWriter::commit called twice");
  impl_->owner().guard("write checkpoint", [&] {
    impl_->owner().publish(impl_->group.get(), kCheckpoint);
    impl_->group.reset();
    return 0;
  });
  impl_->committed = true;
}

StateWriter RunFile::begin_checkpoint() {
  auto writer = std::make_unique<StateWriter::Impl>();
  writer->file = this;
  impl_->guard("write checkpoint", [&] {
    // Written unlinked and put in place of the old one by commit(): a run killed while writing
    // still has the previous checkpoint.
    impl_->reserve(0);
    const hid_t root = impl_->id();
    if (h5::exists(root, kNewCheckpoint))  // left by sffcal 0.1, which renamed it in place
      H5Ldelete(root, kNewCheckpoint, H5P_DEFAULT);
    writer->group = h5::create_unlinked_group(root);
    h5::write_attribute(writer->group.get(), "series_length",
                        static_cast<std::int64_t>(series_length()));
    h5::write_attribute(writer->group.get(), "num_snapshots",
                        static_cast<std::int64_t>(num_snapshots()));
    return 0;
  });
  return StateWriter(std::move(writer));
}

struct StateReader::Impl {
  const RunFile::Impl* owner = nullptr;
  h5::Handle group;
};

StateReader::StateReader(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
StateReader::StateReader(StateReader&&) noexcept = default;
StateReader::~StateReader() = default;

std::string StateReader::where(const std::string& what) const {
  return "run file " + impl_->owner->path + ": read checkpoint: " + what;
}

bool StateReader::has(const std::string& name) const {
  return h5::exists(impl_->group.get(), name) ||
         H5Aexists(impl_->group.get(), name.c_str()) > 0;
}

double StateReader::real(const std::string& name) const {
  return impl_->owner->guard("read checkpoint",
                             [&] { return h5::read_double_attribute(impl_->group.get(), name); });
}

std::int64_t StateReader::integer(const std::string& name) const {
  return impl_->owner->guard("read checkpoint",
                             [&] { return h5::read_int_attribute(impl_->group.get(), name); });
}

CheckpointExtras StateReader::extras() const {
  return impl_->owner->guard("read checkpoint extras", [&] {
    CheckpointExtras extras;
    h5::Handle extra = h5::open_group(impl_->group.get(), "extras");
    H5O_info_t info;
    h5::check_status(H5Oget_info2(extra.get(), &info, H5O_INFO_NUM_ATTRS), "read extras");
    for (hsize_t k = 0; k < info.num_attrs; ++k) {
      char name[256];
      H5Aget_name_by_idx(extra.get(), ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof(name),
                         H5P_DEFAULT);
      extras[name] = h5::read_double_attribute(extra.get(), name);
    }
    return extras;
  });
}

template <typename T>
std::vector<T> StateReader::array(const std::string& name) const {
  return impl_->owner->guard("read checkpoint", [&] {
    return h5::read_dataset<T>(impl_->group.get(), name, native_type<T>());
  });
}

std::vector<WallRecord> StateReader::walls() const {
  return impl_->owner->guard("read checkpoint", [&] {
    return h5::read_dataset<WallRecord>(impl_->group.get(), "walls", h5::wall_record_type().get());
  });
}

bool RunFile::has_checkpoint() const { return h5::exists(impl_->id(), kCheckpoint); }

StateReader RunFile::read_checkpoint() const {
  auto reader = std::make_unique<StateReader::Impl>();
  reader->owner = impl_.get();
  impl_->guard("read checkpoint", [&] {
    if (!has_checkpoint()) throw std::runtime_error("the file has no checkpoint");
    reader->group = h5::open_group(impl_->id(), kCheckpoint);
    return 0;
  });
  return StateReader(std::move(reader));
}

void RunFile::rewind_to_checkpoint() {
  impl_->guard("rewind to the checkpoint", [&] {
    if (!impl_->writable) throw std::runtime_error("the file is open read-only");
    impl_->reserve(0);
    h5::Handle group = h5::open_group(impl_->id(), kCheckpoint);
    // A checkpoint is written after its series rows and snapshots: it can only be behind them.
    // Counts beyond them (an edited or foreign file) would grow /series to any length.
    const std::int64_t rows = h5::read_int_attribute(group.get(), "series_length");
    const std::int64_t kept = h5::read_int_attribute(group.get(), "num_snapshots");
    if (rows < 0 || static_cast<std::uint64_t>(rows) > series_length())
      throw std::runtime_error("the checkpoint's series_length " + std::to_string(rows) +
                               " is not between 0 and the file's " +
                               std::to_string(series_length()) + " series rows");
    if (kept < 0 || kept > num_snapshots())
      throw std::runtime_error("the checkpoint's num_snapshots " + std::to_string(kept) +
                               " is not between 0 and the file's " +
                               std::to_string(num_snapshots()) + " snapshots");
    h5::Handle series = h5::open_group(impl_->id(), "series");
    for (const std::string& name : impl_->series_names)
      h5::truncate(series.get(), name, static_cast<std::size_t>(rows));
    for (int k = num_snapshots() - 1; k >= static_cast<int>(kept); --k)
      H5Ldelete(impl_->id(), snapshot_name(k).c_str(), H5P_DEFAULT);
    impl_->flush();  // before anything reuses the space freed
    return 0;
  });
}

#define RUNFILE_STATE_TYPE(T)                                                                  \
  template void StateWriter::array<T>(const std::string&, const T*, std::size_t, std::size_t); \
  template std::vector<T> StateReader::array<T>(const std::string&) const;
RUNFILE_STATE_TYPE(double)
RUNFILE_STATE_TYPE(std::int32_t)
RUNFILE_STATE_TYPE(std::int64_t)
RUNFILE_STATE_TYPE(std::uint8_t)
#undef RUNFILE_STATE_TYPE

void RunFile::write_table(const std::string& name, const std::vector<std::string>& columns,
                          const std::vector<std::vector<double>>& rows) {
  impl_->guard("write table /analysis/" + name, [&] {
    impl_->reserve(rows.size() * columns.size() * sizeof(double));
    const std::string path = "analysis/" + name;
    h5::Handle group = h5::create_unlinked_group(impl_->id());
    std::string joined;
    for (std::size_t k = 0; k < columns.size(); ++k) {
      std::vector<double> column;
      for (const auto& row : rows) {
        if (row.size() != columns.size()) throw std::runtime_error("a row has the wrong length");
        column.push_back(row[k]);
      }
      h5::write_dataset(group.get(), columns[k], H5T_NATIVE_DOUBLE, column.data(), column.size());
      joined += (joined.empty() ? "" : ",") + columns[k];
    }
    h5::write_attribute(group.get(), "columns", joined);
    impl_->publish(group.get(), path);
    return 0;
  });
}

bool RunFile::has_table(const std::string& name) const {
  return h5::exists(impl_->id(), "analysis/" + name);
}

std::vector<std::pair<std::string, std::vector<double>>> RunFile::read_table(
    const std::string& name) const {
  return impl_->guard("read table /analysis/" + name, [&] {
    const std::string path = "analysis/" + name;
    if (!has_table(name))
      throw std::runtime_error("no such table (run `sffcal sff` on the file first?)");
    h5::Handle group = h5::open_group(impl_->id(), path);
    const std::string joined = h5::read_string_attribute(group.get(), "columns");
    std::vector<std::pair<std::string, std::vector<double>>> table;
    std::size_t begin = 0;
    while (begin <= joined.size() && !joined.empty()) {
      std::size_t end = joined.find(',', begin);
      if (end == std::string::npos) end = joined.size();
      const std::string column = joined.substr(begin, end - begin);
      table.emplace_back(column, h5::read_dataset<double>(group.get(), column, H5T_NATIVE_DOUBLE));
      begin = end + 1;
    }
    return table;
  });
}

void RunFile::flush() {
  if (impl_->writable) impl_->guard("flush", [&] { impl_->flush(); return 0; });
}

}  // namespace runfile
