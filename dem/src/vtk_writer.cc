#include "dem/vtk_writer.h"

#include <filesystem>
#include <map>
#include <string>
#include <stdexcept>

#include "sffcal/output_file.h"
#include "sffcal/pvd.h"

namespace dem {
namespace {

using BodyIndex = std::map<std::int64_t, const ParticleRecord*>;

BodyIndex index_by_id(const Snapshot& s) {
  BodyIndex by_id;
  for (const ParticleRecord& p : s.particles) by_id[p.id] = &p;
  return by_id;
}

// The body `id` that a sphere or a contact of the snapshot refers to; an edited or damaged file
// can refer to one it does not hold.
const ParticleRecord& body(const BodyIndex& by_id, std::int64_t id, const char* referrer) {
  const auto it = by_id.find(id);
  if (it == by_id.end())
    throw std::runtime_error(std::string("snapshot: a ") + referrer + " refers to body " +
                             std::to_string(id) + ", which the snapshot does not hold");
  return *it->second;
}

}  // namespace

void write_snapshot_vtu(const Snapshot& s, const std::string& stem) {
  {
    sffcal::OutputFile file(stem + "_spheres.vtu");
    std::ostream& out = file.stream();
    out.precision(10);
    const std::size_t n = s.spheres.size();
    const BodyIndex by_id = index_by_id(s);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n"
        << "<UnstructuredGrid><Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n"
        << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const auto& x : s.spheres) out << x[0] << ' ' << x[1] << ' ' << x[2] << '\n';
    out << "</DataArray></Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (std::size_t k = 0; k < n; ++k) out << k << '\n';
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t k = 0; k < n; ++k) out << k + 1 << '\n';
    out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t k = 0; k < n; ++k) out << "1\n";  // VTK_VERTEX
    out << "</DataArray>\n</Cells>\n<PointData Scalars=\"radius\">\n"
        << "<DataArray type=\"Float64\" Name=\"radius\" format=\"ascii\">\n";
    for (const auto& x : s.spheres) out << x[3] << '\n';
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"body_id\" format=\"ascii\">\n";
    for (std::int64_t b : s.sphere_body) out << b << '\n';
    out << "</DataArray>\n<DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (std::int64_t b : s.sphere_body) {
      const auto& v = body(by_id, b, "sphere").velocity;
      out << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
    }
    out << "</DataArray>\n</PointData>\n</Piece></UnstructuredGrid>\n</VTKFile>\n";
    file.commit();
  }
  {
    // Body-body contacts as lines between the two centroids (branch vectors).
    std::vector<const ContactRecord*> contacts;
    for (const ContactRecord& c : s.contacts)
      if (c.wall < 0) contacts.push_back(&c);
    const BodyIndex by_id = index_by_id(s);
    sffcal::OutputFile file(stem + "_contacts.vtu");
    std::ostream& out = file.stream();
    out.precision(10);
    const std::size_t n = contacts.size();
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n"
        << "<UnstructuredGrid><Piece NumberOfPoints=\"" << 2 * n << "\" NumberOfCells=\"" << n << "\">\n"
        << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const ContactRecord* c : contacts) {
      const auto& a = body(by_id, c->body_a, "contact").position;
      const auto& b = body(by_id, c->body_b, "contact").position;
      out << a[0] << ' ' << a[1] << ' ' << a[2] << '\n' << b[0] << ' ' << b[1] << ' ' << b[2] << '\n';
    }
    out << "</DataArray></Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (std::size_t k = 0; k < 2 * n; ++k) out << k << '\n';
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t k = 0; k < n; ++k) out << 2 * (k + 1) << '\n';
    out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t k = 0; k < n; ++k) out << "3\n";  // VTK_LINE
    out << "</DataArray>\n</Cells>\n<CellData Scalars=\"normal_force\">\n"
        << "<DataArray type=\"Float64\" Name=\"normal_force\" format=\"ascii\">\n";
    for (const ContactRecord* c : contacts) out << c->normal_force << '\n';
    out << "</DataArray>\n<DataArray type=\"Int32\" Name=\"sliding\" format=\"ascii\">\n";
    for (const ContactRecord* c : contacts) out << c->sliding << '\n';
    out << "</DataArray>\n</CellData>\n</Piece></UnstructuredGrid>\n</VTKFile>\n";
    file.commit();
  }
}

int export_run_to_vtk(const RunFile& run, const std::string& folder) {
  std::filesystem::create_directories(folder);
  std::vector<std::string> spheres, contacts;
  std::vector<double> times;
  const int n = run.num_snapshots();
  for (int k = 0; k < n; ++k) {
    const Snapshot s = run.read_snapshot(k);
    const std::string name = "snapshot_" + std::to_string(k);
    write_snapshot_vtu(s, folder + "/" + name);
    spheres.push_back(name + "_spheres.vtu");
    contacts.push_back(name + "_contacts.vtu");
    times.push_back(s.time);
  }
  sffcal::write_pvd(folder + "/spheres.pvd", spheres, times, "simulated time [s]");
  sffcal::write_pvd(folder + "/contacts.pvd", contacts, times, "simulated time [s]");
  return n;
}

}  // namespace dem
