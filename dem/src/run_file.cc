#include "dem/run_file.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "h5.h"

namespace dem {
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

// ---- flat views of the engine's arrays ----
void write_vec3(hid_t loc, const std::string& name, const std::vector<Eigen::Vector3d>& v) {
  static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "Vector3d must be packed");
  h5::write_dataset(loc, name, H5T_NATIVE_DOUBLE, v.data(), v.size(), 3);
}

std::vector<Eigen::Vector3d> read_vec3(hid_t loc, const std::string& name) {
  const std::vector<double> flat = h5::read_dataset<double>(loc, name, H5T_NATIVE_DOUBLE);
  std::vector<Eigen::Vector3d> v(flat.size() / 3);
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = {flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]};
  return v;
}

WallRecord wall_record(const Wall& wall, double normal_force) {
  WallRecord r;
  r.axis = wall.axis;
  r.upper = wall.upper;
  r.stress_controlled = wall.mode == WallMode::kStress;
  r.position = wall.position;
  r.velocity = wall.velocity;
  r.normal_force = normal_force;
  r.target_stress = wall.target_stress;
  return r;
}

template <typename T>
void write_vector(hid_t loc, const std::string& name, const std::vector<T>& v, hid_t type) {
  h5::write_dataset(loc, name, type, v.data(), v.size());
}

template <typename To, typename From>
std::vector<To> convert(const std::vector<From>& in) {
  return std::vector<To>(in.begin(), in.end());
}

}  // namespace

struct RunFile::Impl {
  std::string path;
  h5::Handle file;
  std::vector<std::string> series_names;
  bool writable = false;

  hid_t id() const { return file.get(); }
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
  if (impl_ && impl_->writable && impl_->file.valid()) H5Fflush(impl_->id(), H5F_SCOPE_GLOBAL);
}

RunFile RunFile::create(const std::string& path, const RunMetadata& metadata,
                        const std::vector<std::string>& series_names) {
  h5::silence_errors();
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->writable = true;
  impl->series_names = series_names;
  impl->guard("create", [&] {
    impl->file = h5::check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                           "create the file (is the folder there and writable?)");
    const hid_t root = impl->id();
    h5::write_attribute(root, "schema_version", kRunFileSchemaVersion);
    h5::write_attribute(root, "program", std::string("sffcal"));
    h5::write_attribute(root, "program_version", metadata.program_version);
    h5::write_attribute(root, "kind", metadata.kind);
    h5::write_attribute(root, "seed", static_cast<std::int64_t>(metadata.seed));
    h5::write_attribute(root, "config", metadata.config_text);
    h5::write_attribute(root, "units", std::string(kUnits));
    h5::write_attribute(root, "sign_convention", std::string(kSignConvention));
    h5::Handle series = h5::create_group(root, "series");
    std::string joined;
    for (const std::string& name : series_names) {
      h5::create_extendible(series.get(), name);
      joined += (joined.empty() ? "" : ",") + name;
    }
    h5::write_attribute(series.get(), "columns", joined);
    h5::create_group(root, "snapshots");
    return 0;
  });
  RunFile file(std::move(impl));
  file.flush();
  return file;
}

RunFile RunFile::open(const std::string& path, bool writable) {
  h5::silence_errors();
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->writable = writable;
  impl->guard("open", [&] {
    impl->file = h5::check(
        H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, H5P_DEFAULT),
        "open the file (missing, or not an HDF5 file?)");
    const std::int64_t version = h5::read_int_attribute(impl->id(), "schema_version");
    if (version != kRunFileSchemaVersion)
      throw std::runtime_error("schema version " + std::to_string(version) + ", expected " +
                               std::to_string(kRunFileSchemaVersion));
    h5::Handle series = h5::open_group(impl->id(), "series");
    std::stringstream columns(h5::read_string_attribute(series.get(), "columns"));
    std::string name;
    while (std::getline(columns, name, ',')) impl->series_names.push_back(name);
    return 0;
  });
  return RunFile(std::move(impl));
}

const std::string& RunFile::path() const { return impl_->path; }

RunMetadata RunFile::metadata() const {
  return impl_->guard("read metadata", [&] {
    RunMetadata m;
    m.kind = h5::read_string_attribute(impl_->id(), "kind");
    m.config_text = h5::read_string_attribute(impl_->id(), "config");
    m.seed = static_cast<std::uint64_t>(h5::read_int_attribute(impl_->id(), "seed"));
    m.program_version = h5::read_string_attribute(impl_->id(), "program_version");
    return m;
  });
}

void RunFile::write_note(const std::string& key, const std::string& text) {
  impl_->guard("write note " + key, [&] {
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
    h5::Handle group = h5::create_group(impl_->id(), snapshot_name(index));
    const hid_t g = group.get();
    h5::write_attribute(g, "step", s.step);
    h5::write_attribute(g, "time", s.time);
    h5::write_attribute(g, "axial_strain", s.axial_strain);
    h5::write_dataset(g, "particles", h5::particle_record_type().get(), s.particles.data(),
                      s.particles.size());
    h5::write_dataset(g, "spheres", H5T_NATIVE_DOUBLE, s.spheres.data(), s.spheres.size(), 4);
    write_vector(g, "sphere_body", s.sphere_body, H5T_NATIVE_INT64);
    h5::write_dataset(g, "contacts", h5::contact_record_type().get(), s.contacts.data(),
                      s.contacts.size());
    h5::write_dataset(g, "walls", h5::wall_record_type().get(), s.walls.data(), s.walls.size());
    return 0;
  });
}

int RunFile::num_snapshots() const {
  return impl_->guard("count snapshots", [&] {
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
    return s;
  });
}

void RunFile::write_checkpoint(const SimulationState& state, const CheckpointExtras& extras) {
  impl_->guard("write checkpoint", [&] {
    const hid_t root = impl_->id();
    // Write the new checkpoint beside the old one and swap at the end: a run killed while
    // writing still has the previous checkpoint.
    if (h5::exists(root, "checkpoint_new")) H5Ldelete(root, "checkpoint_new", H5P_DEFAULT);
    h5::Handle group = h5::create_group(root, "checkpoint_new");
    const hid_t g = group.get();
    const Particles& p = state.particles;
    const ContactList& c = state.contacts;
    h5::write_attribute(g, "time", state.time);
    h5::write_attribute(g, "step_count", state.step_count);
    h5::write_attribute(g, "rebuild_due", static_cast<std::int64_t>(state.rebuild_due));
    h5::write_attribute(g, "max_sphere_move", state.max_sphere_move);
    h5::write_attribute(g, "skin", c.skin());
    h5::write_attribute(g, "num_builds", c.num_builds());
    h5::write_attribute(g, "series_length", static_cast<std::int64_t>(series_length()));
    h5::write_attribute(g, "num_snapshots", static_cast<std::int64_t>(num_snapshots()));
    h5::Handle extra = h5::create_group(g, "extras");
    for (const auto& [key, value] : extras) h5::write_attribute(extra.get(), key, value);

    write_vector(g, "id", p.id, H5T_NATIVE_INT64);
    write_vec3(g, "position", p.position);
    write_vec3(g, "velocity", p.velocity);
    std::vector<double> quaternions;
    for (const auto& q : p.orientation) quaternions.insert(quaternions.end(), q.coeffs().data(), q.coeffs().data() + 4);
    h5::write_dataset(g, "orientation_xyzw", H5T_NATIVE_DOUBLE, quaternions.data(), p.orientation.size(), 4);
    write_vec3(g, "angular_momentum", p.angular_momentum);
    write_vec3(g, "angular_velocity", p.angular_velocity);
    write_vector(g, "mass", p.mass, H5T_NATIVE_DOUBLE);
    write_vector(g, "inertia_axial", p.inertia_axial, H5T_NATIVE_DOUBLE);
    write_vector(g, "inertia_transverse", p.inertia_transverse, H5T_NATIVE_DOUBLE);
    write_vector(g, "volume", p.volume, H5T_NATIVE_DOUBLE);
    write_vector(g, "first_sphere", p.first_sphere, H5T_NATIVE_INT32);
    write_vector(g, "num_body_spheres", convert<std::int32_t>(p.num_body_spheres), H5T_NATIVE_INT32);
    write_vec3(g, "sphere_position", p.sphere_position);
    write_vector(g, "sphere_radius", p.sphere_radius, H5T_NATIVE_DOUBLE);
    write_vector(g, "sphere_offset", p.sphere_offset, H5T_NATIVE_DOUBLE);
    write_vector(g, "sphere_body", p.sphere_body, H5T_NATIVE_INT32);

    write_vector(g, "pair_i", c.pair_i, H5T_NATIVE_INT32);
    write_vector(g, "pair_j", c.pair_j, H5T_NATIVE_INT32);
    write_vec3(g, "pair_tangential", c.pair_tangential);
    write_vec3(g, "pair_normal", c.pair_normal);
    write_vector(g, "pair_touching", c.pair_touching, H5T_NATIVE_UINT8);
    write_vector(g, "wall_sphere", c.wall_sphere, H5T_NATIVE_INT32);
    write_vector(g, "wall_index", c.wall_index, H5T_NATIVE_INT32);
    write_vec3(g, "wall_tangential", c.wall_tangential);
    write_vector(g, "wall_touching", c.wall_touching, H5T_NATIVE_UINT8);
    write_vec3(g, "build_position", c.build_position);
    write_vector(g, "build_wall_position", c.build_wall_position, H5T_NATIVE_DOUBLE);

    std::vector<WallRecord> walls;
    for (const Wall& w : state.walls) walls.push_back(wall_record(w, 0.0));
    h5::write_dataset(g, "walls", h5::wall_record_type().get(), walls.data(), walls.size());
    std::vector<double> last_move, integral;
    for (const ServoState& servo : state.servo) {
      last_move.push_back(servo.last_move);
      integral.push_back(servo.integral);
    }
    write_vector(g, "wall_last_move", last_move, H5T_NATIVE_DOUBLE);
    write_vector(g, "wall_servo_integral", integral, H5T_NATIVE_DOUBLE);
    group.reset();
    if (h5::exists(root, "checkpoint")) H5Ldelete(root, "checkpoint", H5P_DEFAULT);
    h5::check_status(H5Lmove(root, "checkpoint_new", root, "checkpoint", H5P_DEFAULT, H5P_DEFAULT),
                     "rename the new checkpoint");
    return 0;
  });
  flush();
}

bool RunFile::has_checkpoint() const { return h5::exists(impl_->id(), "checkpoint"); }

SimulationState RunFile::read_checkpoint(CheckpointExtras* extras) {
  return impl_->guard("read checkpoint", [&] {
    if (!has_checkpoint()) throw std::runtime_error("the file has no checkpoint");
    h5::Handle group = h5::open_group(impl_->id(), "checkpoint");
    const hid_t g = group.get();
    SimulationState s;
    s.time = h5::read_double_attribute(g, "time");
    s.step_count = h5::read_int_attribute(g, "step_count");
    s.rebuild_due = h5::read_int_attribute(g, "rebuild_due") != 0;
    s.max_sphere_move = h5::read_double_attribute(g, "max_sphere_move");
    if (extras) {
      extras->clear();
      h5::Handle extra = h5::open_group(g, "extras");
      H5O_info_t info;
      H5Oget_info2(extra.get(), &info, H5O_INFO_NUM_ATTRS);
      for (hsize_t k = 0; k < info.num_attrs; ++k) {
        char name[256];
        H5Aget_name_by_idx(extra.get(), ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof(name), H5P_DEFAULT);
        (*extras)[name] = h5::read_double_attribute(extra.get(), name);
      }
    }
    Particles& p = s.particles;
    p.id = h5::read_dataset<std::int64_t>(g, "id", H5T_NATIVE_INT64);
    p.position = read_vec3(g, "position");
    p.velocity = read_vec3(g, "velocity");
    const auto q = h5::read_dataset<double>(g, "orientation_xyzw", H5T_NATIVE_DOUBLE);
    for (std::size_t k = 0; k + 3 < q.size(); k += 4)
      p.orientation.emplace_back(q[k + 3], q[k], q[k + 1], q[k + 2]);
    p.angular_momentum = read_vec3(g, "angular_momentum");
    p.angular_velocity = read_vec3(g, "angular_velocity");
    p.force.assign(p.position.size(), Eigen::Vector3d::Zero());
    p.torque.assign(p.position.size(), Eigen::Vector3d::Zero());
    p.mass = h5::read_dataset<double>(g, "mass", H5T_NATIVE_DOUBLE);
    p.inertia_axial = h5::read_dataset<double>(g, "inertia_axial", H5T_NATIVE_DOUBLE);
    p.inertia_transverse = h5::read_dataset<double>(g, "inertia_transverse", H5T_NATIVE_DOUBLE);
    p.volume = h5::read_dataset<double>(g, "volume", H5T_NATIVE_DOUBLE);
    p.first_sphere = h5::read_dataset<std::int32_t>(g, "first_sphere", H5T_NATIVE_INT32);
    p.num_body_spheres = convert<std::int8_t>(h5::read_dataset<std::int32_t>(g, "num_body_spheres", H5T_NATIVE_INT32));
    p.sphere_position = read_vec3(g, "sphere_position");
    p.sphere_radius = h5::read_dataset<double>(g, "sphere_radius", H5T_NATIVE_DOUBLE);
    p.sphere_offset = h5::read_dataset<double>(g, "sphere_offset", H5T_NATIVE_DOUBLE);
    p.sphere_body = h5::read_dataset<std::int32_t>(g, "sphere_body", H5T_NATIVE_INT32);

    ContactList& c = s.contacts;
    c.pair_i = h5::read_dataset<std::int32_t>(g, "pair_i", H5T_NATIVE_INT32);
    c.pair_j = h5::read_dataset<std::int32_t>(g, "pair_j", H5T_NATIVE_INT32);
    c.pair_tangential = read_vec3(g, "pair_tangential");
    c.pair_normal = read_vec3(g, "pair_normal");
    c.pair_touching = h5::read_dataset<std::uint8_t>(g, "pair_touching", H5T_NATIVE_UINT8);
    c.wall_sphere = h5::read_dataset<std::int32_t>(g, "wall_sphere", H5T_NATIVE_INT32);
    c.wall_index = h5::read_dataset<std::int32_t>(g, "wall_index", H5T_NATIVE_INT32);
    c.wall_tangential = read_vec3(g, "wall_tangential");
    c.wall_touching = h5::read_dataset<std::uint8_t>(g, "wall_touching", H5T_NATIVE_UINT8);
    c.build_position = read_vec3(g, "build_position");
    c.build_wall_position = h5::read_dataset<double>(g, "build_wall_position", H5T_NATIVE_DOUBLE);
    const std::string particles_error = p.check();
    if (!particles_error.empty()) throw std::runtime_error("the checkpoint's bodies: " + particles_error);

    for (const WallRecord& r : h5::read_dataset<WallRecord>(g, "walls", h5::wall_record_type().get())) {
      Wall w;
      w.axis = r.axis;
      w.upper = r.upper != 0;
      w.mode = r.stress_controlled ? WallMode::kStress : WallMode::kVelocity;
      w.position = r.position;
      w.velocity = r.velocity;
      w.target_stress = r.target_stress;
      s.walls.push_back(w);
    }
    // Checkpoints of the purely proportional servo (before issue 16) have no integral: it starts
    // from zero, so such a file continues with the new servo law, not bit for bit.
    const auto last_move = h5::read_dataset<double>(g, "wall_last_move", H5T_NATIVE_DOUBLE);
    const auto integral =
        h5::exists(g, "wall_servo_integral")
            ? h5::read_dataset<double>(g, "wall_servo_integral", H5T_NATIVE_DOUBLE)
            : std::vector<double>(s.walls.size(), 0.0);
    if (last_move.size() != s.walls.size() || integral.size() != s.walls.size())
      throw std::runtime_error("the checkpoint's servo state does not have one entry per wall");
    for (std::size_t w = 0; w < s.walls.size(); ++w) s.servo.push_back({last_move[w], integral[w]});
    const std::string contacts_error = c.check(p.num_spheres(), static_cast<int>(s.walls.size()));
    if (!contacts_error.empty())
      throw std::runtime_error("the checkpoint's contact list: " + contacts_error);
    const double skin = h5::read_double_attribute(g, "skin");
    const std::int64_t num_builds = h5::read_int_attribute(g, "num_builds");
    if (!(std::isfinite(skin) && skin >= 0.0) || num_builds < 0)
      throw std::runtime_error("the checkpoint's skin or num_builds is out of range");
    c.restore(skin, num_builds, p.num_spheres());

    // Drop what was written after the checkpoint.
    if (impl_->writable) {
      const auto rows = static_cast<std::size_t>(h5::read_int_attribute(g, "series_length"));
      h5::Handle series = h5::open_group(impl_->id(), "series");
      for (const std::string& name : impl_->series_names) h5::truncate(series.get(), name, rows);
      const auto kept = static_cast<int>(h5::read_int_attribute(g, "num_snapshots"));
      for (int k = num_snapshots() - 1; k >= kept; --k)
        H5Ldelete(impl_->id(), snapshot_name(k).c_str(), H5P_DEFAULT);
    }
    return s;
  });
}

void RunFile::write_table(const std::string& name, const std::vector<std::string>& columns,
                          const std::vector<std::vector<double>>& rows) {
  impl_->guard("write table /analysis/" + name, [&] {
    const std::string path = "analysis/" + name;
    if (h5::exists(impl_->id(), path)) H5Ldelete(impl_->id(), path.c_str(), H5P_DEFAULT);
    h5::Handle group = h5::create_group(impl_->id(), path);
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
    return 0;
  });
  flush();
}

std::vector<std::pair<std::string, std::vector<double>>> RunFile::read_table(
    const std::string& name) const {
  return impl_->guard("read table /analysis/" + name, [&] {
    const std::string path = "analysis/" + name;
    if (!h5::exists(impl_->id(), "analysis") || !h5::exists(impl_->id(), path))
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
  if (impl_->writable) H5Fflush(impl_->id(), H5F_SCOPE_GLOBAL);
}

Snapshot take_snapshot(const Simulation& sim, double axial_strain) {
  const Particles& p = sim.particles();
  Snapshot s;
  s.step = sim.step_count();
  s.time = sim.time();
  s.axial_strain = axial_strain;
  for (int b = 0; b < p.num_bodies(); ++b) s.particles.push_back(p.record(b));
  for (int k = 0; k < p.num_spheres(); ++k) {
    const Eigen::Vector3d& x = p.sphere_position[k];
    s.spheres.push_back({x.x(), x.y(), x.z(), p.sphere_radius[k]});
    s.sphere_body.push_back(p.id[p.sphere_body[k]]);
  }
  s.contacts = sim.contact_records(true);
  for (std::size_t w = 0; w < sim.walls().size(); ++w)
    s.walls.push_back(wall_record(sim.walls()[w], sim.wall_forces()[w]));
  return s;
}

}  // namespace dem
