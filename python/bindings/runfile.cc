// The compiled half of sffcal.runfile (python/sffcal/runfile.py calls it): a run file's snapshots
// read by the C++ reader (runfile/run_file.h), which checks each one (runfile/src/
// snapshot_check.h), as numpy structured arrays laid out as the run file's records; and a
// snapshot's SFF input as `sffcal sff` builds it (sff/run_snapshot.h), so that sffcal.sff.analyse
// on it gives the numbers `sffcal sff` stores, bit for bit. The records are moved into the arrays,
// not copied.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <utility>
#include <vector>

#include "runfile/records.h"
#include "runfile/run_file.h"
#include "sff/run_snapshot.h"

namespace py = pybind11;

namespace sffcal_python {
namespace {

// A numpy array over the elements of `values`, which it takes over (freed with the array).
// A numpy array of Element over the records of `values`, which it takes over (freed with the
// array): one record per row, `columns` elements each (1: a 1-D array of records).
template <typename Element, typename T>
py::array_t<Element> adopt(std::vector<T>&& values, py::ssize_t columns = 1) {
  static_assert(sizeof(T) % sizeof(Element) == 0, "a record is a whole number of elements");
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule free(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  const auto rows = static_cast<py::ssize_t>(owned->size());
  std::vector<py::ssize_t> shape = {rows};
  if (columns > 1) shape.push_back(columns);
  return py::array_t<Element>(shape, reinterpret_cast<Element*>(owned->data()), free);
}

template <typename T>
py::array_t<T> adopt(std::vector<T>&& values) {
  return adopt<T, T>(std::move(values));
}

// Snapshot `index` of an open run file; IndexError naming the count where it has none.
runfile::Snapshot read(const runfile::RunFile& file, const std::string& path, int index) {
  if (index < 0 || index >= file.num_snapshots())
    throw py::index_error(path + " has " + std::to_string(file.num_snapshots()) +
                          " snapshots: no snapshot " + std::to_string(index));
  return file.read_snapshot(index);
}

py::dict read_snapshot(const std::string& path, int index) {
  runfile::Snapshot s = read(runfile::RunFile::open(path), path, index);
  py::dict out;
  out["step"] = s.step;
  out["time"] = s.time;
  out["axial_strain"] = s.axial_strain;
  // x, y, z, radius of each sphere: a record of four doubles, a row of the array.
  static_assert(sizeof(s.spheres[0]) == 4 * sizeof(double), "a sphere record is four doubles");
  out["spheres"] = adopt<double>(std::move(s.spheres), 4);
  out["sphere_body"] = adopt(std::move(s.sphere_body));
  out["particles"] = adopt(std::move(s.particles));
  out["contacts"] = adopt(std::move(s.contacts));
  out["walls"] = adopt(std::move(s.walls));
  // A periodic snapshot's cell (an imported run): lower and upper corners; (0, 3) where walls are.
  static_assert(sizeof(s.periodic_cell[0]) == 3 * sizeof(double), "a corner is three doubles");
  out["periodic_cell"] = adopt<double>(std::move(s.periodic_cell), 3);
  return out;
}

py::dict snapshot_input(const std::string& path, int index) {
  const runfile::RunFile file = runfile::RunFile::open(path);
  runfile::Snapshot s = read(file, path, index);
  const sff::SnapshotInput in = sff::snapshot_input(s, file.metadata().physics);
  py::dict out;
  out["volume"] = in.volume;
  out["solid_volume"] = in.solid_volume;
  out["num_bodies"] = in.num_bodies;
  out["youngs_modulus"] = in.youngs_modulus;
  out["friction"] = in.friction;
  py::array_t<double> wall_stress(3);
  for (int a = 0; a < 3; ++a) wall_stress.mutable_data()[a] = in.wall_stress[a];
  out["wall_stress"] = wall_stress;
  py::array_t<double> centroids({static_cast<py::ssize_t>(in.centroids.size()), py::ssize_t{3}});
  for (std::size_t k = 0; k < in.centroids.size(); ++k)
    for (int a = 0; a < 3; ++a)
      centroids.mutable_data(static_cast<py::ssize_t>(k))[a] = in.centroids[k][a];
  out["centroids"] = centroids;
  out["contacts"] = adopt(std::move(s.contacts));  // the span of `in` pointed into these
  return out;
}

}  // namespace

void bind_runfile(py::module_& m) {
  PYBIND11_NUMPY_DTYPE(runfile::ParticleRecord, id, num_spheres, sphere_diameter, position,
                       orientation, velocity, angular_velocity);
  PYBIND11_NUMPY_DTYPE(runfile::WallRecord, axis, upper, stress_controlled, padding, position,
                       velocity, normal_force, target_stress);
  m.attr("PARTICLE_DTYPE") = py::dtype::of<runfile::ParticleRecord>();
  m.attr("WALL_DTYPE") = py::dtype::of<runfile::WallRecord>();
  m.def("num_snapshots",
        [](const std::string& path) { return runfile::RunFile::open(path).num_snapshots(); },
        py::arg("path"), "The number of snapshots of a run file.");
  m.def("read_snapshot", &read_snapshot, py::arg("path"), py::arg("index"),
        "Snapshot `index` of a run file, checked as every reader of the project checks it: a dict "
        "of step, time, axial_strain and the arrays contacts (CONTACT_DTYPE), particles "
        "(PARTICLE_DTYPE), walls (WALL_DTYPE), spheres (n, 4: x, y, z, radius [m]), "
        "sphere_body (the body of each sphere) and periodic_cell (the lower and upper corners "
        "[m] of an imported periodic run's cell, shape (2, 3); (0, 3) where walls bound it).");
  m.def("snapshot_input", &snapshot_input, py::arg("path"), py::arg("index"),
        "The arguments of sffcal.sff.analyse for snapshot `index`, as `sffcal sff` builds them: "
        "contacts, volume (the walls' box or the periodic cell), solid_volume (the clumps' spheres), num_bodies, "
        "youngs_modulus and friction (/physics), wall_stress, centroids.");
}

}  // namespace sffcal_python
