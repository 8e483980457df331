#include "frame_snapshot.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <unordered_map>
#include <vector>

namespace dem_import::internal {
namespace {

// The frame's column for `role`; required ones throw naming the dump and the column.
class Columns {
 public:
  Columns(const DumpFrame& frame, const std::map<std::string, std::string>& names,
          const std::string& where)
      : frame_(frame), names_(names), where_(where) {}
  std::size_t required(const std::string& role) const {
    const std::string& name = ImportDescription::column(names_, role);
    const std::size_t k = frame_.find(name);
    if (k == DumpFrame::npos)
      throw std::runtime_error(where_ + " has no column '" + name + "'" +
                               (name == role ? "" : " (the role " + role + ")") +
                               " (docs/import.md)");
    return k;
  }
  std::size_t optional(const std::string& role) const {
    return frame_.find(ImportDescription::column(names_, role));
  }
  /// All three of role x, y, z, or none: npos where none is there.
  std::size_t vector(const std::string& x, const std::string& y, const std::string& z) const {
    const std::size_t k = optional(x);
    if (k == DumpFrame::npos && optional(y) == DumpFrame::npos && optional(z) == DumpFrame::npos)
      return DumpFrame::npos;
    for (const std::string& role : {x, y, z}) required(role);
    if (required(y) != k + 1 || required(z) != k + 2)
      throw std::runtime_error(where_ + ": the columns of " + x + ", " + y + ", " + z +
                               " must follow each other");
    return k;
  }

 private:
  const DumpFrame& frame_;
  const std::map<std::string, std::string>& names_;
  std::string where_;
};

struct Atom {
  std::size_t body = 0;  ///< the body's index in the snapshot
  Eigen::Vector3d position;
  double radius = 0.0;
};

// The id in a dump's column of doubles; `where` makes the row's name for a message.
template <class Where>
std::int64_t id_of(double value, const Where& where) {
  if (!(std::abs(value) < 9.0e15) || value != std::floor(value))
    throw std::runtime_error(where() + ": an id that is not an integer (" + std::to_string(value) + ")");
  return static_cast<std::int64_t>(value);
}

}  // namespace

void check_box_kind(const DumpFrame& atoms, const ImportDescription& d, const std::string& where) {
  for (int a = 0; a < 3; ++a) {
    const std::string axis(1, "xyz"[a]);
    const bool periodic = atoms.boundary[a].find('p') != std::string::npos;
    if (!d.walls && atoms.boundary[a] != "pp")
      throw std::runtime_error(where + ": the box is not periodic along " + axis + " ('" +
                               atoms.boundary[a] + "'); a box between walls needs boundary = "
                               "\"walls\" in import.toml's [test] (docs/import.md)");
    if (d.walls && periodic)
      throw std::runtime_error(where + ": the box is periodic along " + axis + " ('" +
                               atoms.boundary[a] + "'), but import.toml's [test] boundary is "
                               "\"walls\"; a box partly periodic is not imported");
  }
  if (atoms.triclinic)
    throw std::runtime_error(where + ": a sheared (triclinic) cell is not imported; the cell "
                             "must be an orthogonal box");
}

runfile::Snapshot snapshot_from_frames(const DumpFrame& atoms, const DumpFrame& contacts,
                                       const FrameBox& box, const ImportDescription& d,
                                       const std::string& atoms_name,
                                       const std::string& contacts_name) {
  const std::string at = " at timestep " + std::to_string(atoms.timestep);
  const std::string atoms_where = atoms_name + at, contacts_where = contacts_name + at;
  check_box_kind(atoms, d, atoms_where);
  const Eigen::Vector3d length(box.length.data());
  Eigen::Vector3d lower(box.lower.data());
  for (int a = 0; a < 3; ++a)
    if (!(length[a] > 0.0) || !std::isfinite(length[a]) || !std::isfinite(lower[a]))
      throw std::runtime_error(atoms_where + ": the series row of that step gives a " +
                               (d.walls ? "gap between the walls" : "cell length") + " along " +
                               std::string(1, "xyz"[a]) + " that is not positive and finite (" +
                               std::to_string(length[a]) + " m)");
  if (!d.walls) {
    lower = Eigen::Vector3d(atoms.lower.data());
    for (int a = 0; a < 3; ++a) {
      // The bounds as the dump wrote them, to 6 significant digits at least.
      const double written = atoms.upper[a] - atoms.lower[a];
      const double precision = 1e-5 * std::max({std::abs(atoms.lower[a]), std::abs(atoms.upper[a]),
                                                std::abs(length[a])});
      if (!(std::abs(written - length[a]) <= precision))
        throw std::runtime_error(atoms_where + ": the box is " + std::to_string(written) +
                                 " m long along " + std::string(1, "xyz"[a]) +
                                 ", the series row of that step says " + std::to_string(length[a]) +
                                 " m");
    }
  }
  const Eigen::Vector3d upper = lower + length;
  // Between walls, positions are as they are; in a periodic cell, a vector is taken to its
  // nearest image.
  const auto nearest_image = [&](Eigen::Vector3d v) {
    if (!d.walls)
      for (int a = 0; a < 3; ++a) v[a] -= length[a] * std::round(v[a] / length[a]);
    return v;
  };

  // The atoms, grouped into bodies numbered in the order of their source ids.
  const Columns ac(atoms, d.atoms_columns, atoms_where);
  const std::size_t c_id = ac.required("id"), c_body = ac.optional("mol");
  const std::size_t c_x = ac.vector("x", "y", "z"), c_radius = ac.required("radius");
  if (c_x == DumpFrame::npos) ac.required("x");
  std::array<std::size_t, 6> c_wall{};
  if (d.walls)
    for (int w = 0; w < 6; ++w) {
      const std::string name = kWallNames[w];
      c_wall[w] = ac.vector(name + "_fx", name + "_fy", name + "_fz");
      if (c_wall[w] == DumpFrame::npos) ac.required(name + "_fx");
    }
  struct WallForce {
    std::int64_t atom;
    int wall;
    Eigen::Vector3d force;  ///< of the wall on the sphere [N]
  };
  std::vector<WallForce> wall_forces;
  std::unordered_map<std::int64_t, Atom> atom;
  atom.reserve(atoms.rows());
  std::map<std::int64_t, std::vector<std::int64_t>> members;  // source body id -> atom ids
  for (std::size_t r = 0; r < atoms.rows(); ++r) {
    // Messages are made only for a row at fault (a frame holds tens of thousands).
    const auto row = [&] { return atoms_where + ", atom row " + std::to_string(r + 1); };
    const std::int64_t id = id_of(atoms.at(r, c_id), row);
    Atom a;
    a.position = {atoms.at(r, c_x), atoms.at(r, c_x + 1), atoms.at(r, c_x + 2)};
    a.radius = atoms.at(r, c_radius);
    if (!a.position.allFinite() || !(a.radius > 0.0) || !std::isfinite(a.radius))
      throw std::runtime_error(row() + ": a position that is not finite or a radius not positive");
    if (!atom.emplace(id, a).second)
      throw std::runtime_error(row() + ": atom " + std::to_string(id) + " is repeated");
    if (d.walls)
      for (int w = 0; w < 6; ++w) {
        const Eigen::Vector3d f(atoms.at(r, c_wall[w]), atoms.at(r, c_wall[w] + 1),
                                atoms.at(r, c_wall[w] + 2));
        if (!f.allFinite())
          throw std::runtime_error(row() + ": the force of wall " + kWallNames[w] +
                                   " is not finite");
        if (f != Eigen::Vector3d::Zero()) wall_forces.push_back({id, w, f});
      }
    const std::int64_t body = c_body == DumpFrame::npos ? id : id_of(atoms.at(r, c_body), row);
    members[body].push_back(id);
  }

  runfile::Snapshot s;
  if (!d.walls)
    s.periodic_cell = {{lower.x(), lower.y(), lower.z()}, {upper.x(), upper.y(), upper.z()}};
  std::vector<Eigen::Vector3d> centroid;
  for (const auto& [source_id, ids] : members) {
    const std::size_t body = s.particles.size();
    const auto name = [&, id = source_id] { return atoms_where + ": body " + std::to_string(id); };
    if (ids.size() > 2)
      throw std::runtime_error(name() + " has " + std::to_string(ids.size()) +
                               " spheres; a body is one sphere or a two-sphere clump");
    Atom& first = atom.at(ids.front());
    Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
    Eigen::Vector3d middle = first.position;
    if (ids.size() == 2) {
      Atom& second = atom.at(ids.back());
      if (std::abs(second.radius - first.radius) > 1e-9 * first.radius)
        throw std::runtime_error(name() + " joins spheres of unequal radii (" +
                                 std::to_string(first.radius) + ", " +
                                 std::to_string(second.radius) +
                                 " m); the run file's clumps are of equal spheres");
      // Join the second sphere to the first (across a periodic boundary).
      second.position = first.position + nearest_image(second.position - first.position);
      const Eigen::Vector3d between = second.position - first.position;
      if (!(between.norm() < 2.0 * first.radius))
        throw std::runtime_error(name() + ": its two spheres do not overlap (" +
                                 std::to_string(between.norm()) + " m apart), not one clump");
      middle = 0.5 * (first.position + second.position);
      if (between.norm() > 0.0) axis = between.normalized();
    }
    runfile::ParticleRecord p;
    p.id = static_cast<std::int64_t>(body);
    p.num_spheres = static_cast<std::int32_t>(ids.size());
    p.sphere_diameter = 2.0 * first.radius;
    p.position = {middle.x(), middle.y(), middle.z()};
    const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), axis);
    p.orientation = {q.w(), q.x(), q.y(), q.z()};  // velocities: unknown, left zero
    s.particles.push_back(p);
    centroid.push_back(middle);
    for (std::int64_t id : ids) {
      Atom& a = atom.at(id);
      a.body = body;
      s.spheres.push_back({a.position.x(), a.position.y(), a.position.z(), a.radius});
      s.sphere_body.push_back(static_cast<std::int64_t>(body));
    }
  }

  // The contacts.
  const Columns cc(contacts, d.contacts_columns, contacts_where);
  const std::size_t c_a = cc.required("atom1"), c_b = cc.required("atom2");
  const std::size_t c_f = cc.vector("fx", "fy", "fz");
  if (c_f == DumpFrame::npos) cc.required("fx");
  // A tangential part given apart (LAMMPS's compute pair/local: fx fy fz the normal force, p1 p2
  // p3 the tangential one) is added.
  const std::size_t c_ft = cc.vector("ftx", "fty", "ftz");
  const std::size_t c_n = cc.vector("nx", "ny", "nz"), c_p = cc.vector("px", "py", "pz");
  const std::size_t c_overlap = cc.optional("overlap");
  const double mu = d.physics.friction;
  s.contacts.reserve(contacts.rows());
  for (std::size_t r = 0; r < contacts.rows(); ++r) {
    const auto row = [&] { return contacts_where + ", contact row " + std::to_string(r + 1); };
    const auto find_atom = [&](std::size_t column) -> const Atom& {
      const std::int64_t id = id_of(contacts.at(r, column), row);
      const auto it = atom.find(id);
      if (it == atom.end())
        throw std::runtime_error(row() + " names atom " + std::to_string(id) +
                                 ", which the atoms frame of that timestep does not hold");
      return it->second;
    };
    const Atom &a = find_atom(c_a), &b = find_atom(c_b);
    if (a.body == b.body)
      throw std::runtime_error(row() + " joins two spheres of one body (exclude them in the "
                               "source, e.g. LAMMPS's neigh_modify exclude molecule/intra)");
    Eigen::Vector3d force(contacts.at(r, c_f), contacts.at(r, c_f + 1), contacts.at(r, c_f + 2));
    if (c_ft != DumpFrame::npos)
      force += Eigen::Vector3d(contacts.at(r, c_ft), contacts.at(r, c_ft + 1), contacts.at(r, c_ft + 2));
    if (d.force_on_atom1) force = -force;
    const Eigen::Vector3d centre_line = nearest_image(b.position - a.position);
    Eigen::Vector3d n = centre_line.normalized();
    if (c_n != DumpFrame::npos) {
      n = {contacts.at(r, c_n), contacts.at(r, c_n + 1), contacts.at(r, c_n + 2)};
      if (!(std::abs(n.norm() - 1.0) <= 1e-6))
        throw std::runtime_error(row() + ": the normal is not a unit vector");
    }
    const double overlap = c_overlap != DumpFrame::npos
                               ? contacts.at(r, c_overlap)
                               : a.radius + b.radius - centre_line.norm();
    Eigen::Vector3d point = a.position + (a.radius - 0.5 * overlap) * n;
    if (c_p != DumpFrame::npos)
      point = {contacts.at(r, c_p), contacts.at(r, c_p + 1), contacts.at(r, c_p + 2)};
    const Eigen::Vector3d branch = nearest_image(centroid[b.body] - centroid[a.body]);
    if (!force.allFinite() || !n.allFinite() || !point.allFinite() || !std::isfinite(overlap))
      throw std::runtime_error(row() + ": a value is not finite");
    runfile::ContactRecord c;
    c.body_a = static_cast<std::int64_t>(a.body);
    c.body_b = static_cast<std::int64_t>(b.body);
    c.normal_force = force.dot(n);
    const Eigen::Vector3d tangential = force - c.normal_force * n;
    c.sliding = c.normal_force > 0.0 && tangential.norm() >= mu * c.normal_force * (1.0 - 1e-9);
    c.overlap = overlap;
    for (int k = 0; k < 3; ++k) {
      c.point[k] = point[k];
      c.normal[k] = n[k];
      c.branch[k] = branch[k];
      c.tangential_force[k] = tangential[k];
    }
    s.contacts.push_back(c);
  }

  // The walls and their contacts, after the bodies' (the run file's order). A wall's force on a
  // sphere is a contact of the wall (A) with the sphere's body (B): the normal is the wall's
  // inward one, the overlap the radius less the centre's distance from the wall's plane.
  if (!d.walls) return s;
  for (int w = 0; w < 6; ++w) {
    runfile::WallRecord wall;
    wall.axis = w / 2;
    wall.upper = w % 2;
    wall.position = wall.upper ? upper[wall.axis] : lower[wall.axis];
    s.walls.push_back(wall);  // velocity and control: not imported (the test's axis_control says)
  }
  for (const WallForce& f : wall_forces) {
    const Atom& a = atom.at(f.atom);
    runfile::WallRecord& wall = s.walls[static_cast<std::size_t>(f.wall)];
    const Eigen::Vector3d n = (wall.upper ? -1.0 : 1.0) * Eigen::Vector3d::Unit(wall.axis);
    const double overlap = a.radius - n.dot(a.position - wall.position * Eigen::Vector3d::Unit(wall.axis));
    if (!(overlap > -1e-3 * a.radius))
      throw std::runtime_error(atoms_where + ": atom " + std::to_string(f.atom) + " has a force of wall " +
                               kWallNames[f.wall] + ", but its sphere is " +
                               std::to_string(-overlap) + " m from touching the wall at " +
                               std::to_string(wall.position) +
                               " m (the series' wall positions, or the dump's wall columns, are not "
                               "those of the run)");
    runfile::ContactRecord c;
    c.body_b = static_cast<std::int64_t>(a.body);
    c.wall = f.wall;
    c.normal_force = f.force.dot(n);
    const Eigen::Vector3d tangential = f.force - c.normal_force * n;
    c.sliding = c.normal_force > 0.0 &&
                tangential.norm() >= d.physics.wall_friction * c.normal_force * (1.0 - 1e-9);
    c.overlap = overlap;
    const Eigen::Vector3d point = a.position - (a.radius - 0.5 * overlap) * n;
    for (int k = 0; k < 3; ++k) {
      c.point[k] = point[k];
      c.normal[k] = n[k];
      c.tangential_force[k] = tangential[k];
    }
    wall.normal_force += c.normal_force;
    s.contacts.push_back(c);
  }
  return s;
}

}  // namespace dem_import::internal
