#include "dem/run_file_io.h"

#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace dem {
namespace {

// The largest step or list-build count a checkpoint may hold (2^62: a run of 10^9 steps a second
// for a century stays far below it, and counting on from it never wraps).
constexpr std::int64_t kMaxCount = std::int64_t{1} << 62;

// ---- flat views of the engine's arrays ----
void write_vec3(runfile::StateWriter& out, const std::string& name,
                const std::vector<Eigen::Vector3d>& v) {
  static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "Vector3d must be packed");
  out.array(name, v.empty() ? nullptr : v.front().data(), v.size(), 3);
}

std::vector<Eigen::Vector3d> read_vec3(const runfile::StateReader& in, const std::string& name) {
  const std::vector<double> flat = in.array<double>(name);
  std::vector<Eigen::Vector3d> v(flat.size() / 3);
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = {flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]};
  return v;
}

template <typename T>
void write_vector(runfile::StateWriter& out, const std::string& name, const std::vector<T>& v) {
  out.array(name, v.data(), v.size());
}

template <typename To, typename From>
std::vector<To> convert(const std::vector<From>& in) {
  return std::vector<To>(in.begin(), in.end());
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

}  // namespace

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

void write_checkpoint(RunFile& file, const SimulationState& state, const CheckpointExtras& extras) {
  runfile::StateWriter out = file.begin_checkpoint();
  const Particles& p = state.particles;
  const ContactList& c = state.contacts;
  out.attribute("time", state.time);
  out.attribute("step_count", state.step_count);
  out.attribute("rebuild_due", static_cast<std::int64_t>(state.rebuild_due));
  out.attribute("max_sphere_move", state.max_sphere_move);
  out.attribute("skin", c.skin());
  out.attribute("num_builds", c.num_builds());
  out.extras(extras);

  write_vector(out, "id", p.id);
  write_vec3(out, "position", p.position);
  write_vec3(out, "velocity", p.velocity);
  std::vector<double> quaternions;
  for (const auto& q : p.orientation)
    quaternions.insert(quaternions.end(), q.coeffs().data(), q.coeffs().data() + 4);
  out.array("orientation_xyzw", quaternions.data(), p.orientation.size(), 4);
  write_vec3(out, "angular_momentum", p.angular_momentum);
  write_vec3(out, "angular_velocity", p.angular_velocity);
  write_vector(out, "mass", p.mass);
  write_vector(out, "inertia_axial", p.inertia_axial);
  write_vector(out, "inertia_transverse", p.inertia_transverse);
  write_vector(out, "volume", p.volume);
  write_vector(out, "first_sphere", p.first_sphere);
  write_vector(out, "num_body_spheres", convert<std::int32_t>(p.num_body_spheres));
  write_vec3(out, "sphere_position", p.sphere_position);
  write_vector(out, "sphere_radius", p.sphere_radius);
  write_vector(out, "sphere_offset", p.sphere_offset);
  write_vector(out, "sphere_body", p.sphere_body);

  write_vector(out, "pair_i", c.pair_i);
  write_vector(out, "pair_j", c.pair_j);
  write_vec3(out, "pair_tangential", c.pair_tangential);
  write_vec3(out, "pair_normal", c.pair_normal);
  write_vector(out, "pair_touching", c.pair_touching);
  write_vector(out, "wall_sphere", c.wall_sphere);
  write_vector(out, "wall_index", c.wall_index);
  write_vec3(out, "wall_tangential", c.wall_tangential);
  write_vector(out, "wall_touching", c.wall_touching);
  write_vec3(out, "build_position", c.build_position);
  write_vector(out, "build_wall_position", c.build_wall_position);

  std::vector<WallRecord> walls;
  for (const Wall& w : state.walls) walls.push_back(wall_record(w, 0.0));
  out.walls(walls);
  std::vector<double> last_move, integral;
  for (const ServoState& servo : state.servo) {
    last_move.push_back(servo.last_move);
    integral.push_back(servo.integral);
  }
  write_vector(out, "wall_last_move", last_move);
  write_vector(out, "wall_servo_integral", integral);
  out.commit();
}

SimulationState read_checkpoint(RunFile& file, CheckpointExtras* extras) {
  const runfile::StateReader in = file.read_checkpoint();
  auto fail = [&](const std::string& what) { throw std::runtime_error(in.where(what)); };
  SimulationState s;
  s.time = in.real("time");
  s.step_count = in.integer("step_count");
  s.rebuild_due = in.integer("rebuild_due") != 0;
  s.max_sphere_move = in.real("max_sphere_move");
  // The counters go on counting from here: far below where they would wrap.
  if (!(std::isfinite(s.time) && s.time >= 0.0) || s.step_count < 0 ||
      s.step_count > kMaxCount || !(std::isfinite(s.max_sphere_move) && s.max_sphere_move >= 0.0))
    fail("the checkpoint's time, step_count or max_sphere_move is out of range");
  if (extras) *extras = in.extras();

  Particles& p = s.particles;
  p.id = in.array<std::int64_t>("id");
  p.position = read_vec3(in, "position");
  p.velocity = read_vec3(in, "velocity");
  const auto q = in.array<double>("orientation_xyzw");
  for (std::size_t k = 0; k + 3 < q.size(); k += 4)
    p.orientation.emplace_back(q[k + 3], q[k], q[k + 1], q[k + 2]);
  p.angular_momentum = read_vec3(in, "angular_momentum");
  p.angular_velocity = read_vec3(in, "angular_velocity");
  p.force.assign(p.position.size(), Eigen::Vector3d::Zero());
  p.torque.assign(p.position.size(), Eigen::Vector3d::Zero());
  p.mass = in.array<double>("mass");
  p.inertia_axial = in.array<double>("inertia_axial");
  p.inertia_transverse = in.array<double>("inertia_transverse");
  p.volume = in.array<double>("volume");
  p.first_sphere = in.array<std::int32_t>("first_sphere");
  p.num_body_spheres = convert<std::int8_t>(in.array<std::int32_t>("num_body_spheres"));
  p.sphere_position = read_vec3(in, "sphere_position");
  p.sphere_radius = in.array<double>("sphere_radius");
  p.sphere_offset = in.array<double>("sphere_offset");
  p.sphere_body = in.array<std::int32_t>("sphere_body");

  ContactList& c = s.contacts;
  c.pair_i = in.array<std::int32_t>("pair_i");
  c.pair_j = in.array<std::int32_t>("pair_j");
  c.pair_tangential = read_vec3(in, "pair_tangential");
  c.pair_normal = read_vec3(in, "pair_normal");
  c.pair_touching = in.array<std::uint8_t>("pair_touching");
  c.wall_sphere = in.array<std::int32_t>("wall_sphere");
  c.wall_index = in.array<std::int32_t>("wall_index");
  c.wall_tangential = read_vec3(in, "wall_tangential");
  c.wall_touching = in.array<std::uint8_t>("wall_touching");
  c.build_position = read_vec3(in, "build_position");
  c.build_wall_position = in.array<double>("build_wall_position");
  const std::string particles_error = p.check();
  if (!particles_error.empty()) fail("the checkpoint's bodies: " + particles_error);
  // Particles::check follows the spheres of each body; a sphere of no body (its body id past the
  // bodies: body arrays shorter than the sphere arrays say) would be followed by the engine.
  std::size_t owned = 0;
  for (const std::int8_t count : p.num_body_spheres) owned += static_cast<std::size_t>(count);
  if (owned != p.sphere_radius.size())
    fail("the checkpoint's bodies own " + std::to_string(owned) + " spheres of " +
         std::to_string(p.sphere_radius.size()));

  for (const WallRecord& r : in.walls()) {
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
  const auto last_move = in.array<double>("wall_last_move");
  const auto integral = in.has("wall_servo_integral")
                            ? in.array<double>("wall_servo_integral")
                            : std::vector<double>(s.walls.size(), 0.0);
  if (last_move.size() != s.walls.size() || integral.size() != s.walls.size())
    fail("the checkpoint's servo state does not have one entry per wall");
  for (std::size_t w = 0; w < s.walls.size(); ++w) s.servo.push_back({last_move[w], integral[w]});
  const std::string contacts_error = c.check(p.num_spheres(), static_cast<int>(s.walls.size()));
  if (!contacts_error.empty()) fail("the checkpoint's contact list: " + contacts_error);
  // A list without its build positions (a state never stepped) must be built at the first step:
  // without a rebuild due, that step measures every move from the positions that are not there.
  if (!s.rebuild_due && (c.build_position.size() != p.sphere_radius.size() ||
                         c.build_wall_position.size() != s.walls.size()))
    fail("the checkpoint's contact list has no build positions, and no rebuild is due");
  const double skin = in.real("skin");
  const std::int64_t num_builds = in.integer("num_builds");
  if (!(std::isfinite(skin) && skin >= 0.0) || num_builds < 0 || num_builds > kMaxCount)
    fail("the checkpoint's skin or num_builds is out of range");
  c.restore(skin, num_builds, p.num_spheres());
  if (file.writable()) file.rewind_to_checkpoint();
  return s;
}

}  // namespace dem
