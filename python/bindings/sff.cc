// sffcal.sff (python/sffcal/sff.py re-exports it): the stress-force-fabric analysis of contacts
// given as numpy arrays (sff/analysis.h, sff-theory.md): one structured array of the run file's
// contact records (CONTACT_DTYPE, laid out as runfile::ContactRecord), read in place, without a
// copy. sff::analyse_snapshot checks them: a bad contact is a ValueError naming it.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "arrays.h"
#include "runfile/records.h"
#include "sff/analysis.h"
#include "sff/statistics.h"

namespace py = pybind11;

namespace sffcal_python {
namespace {

using Contacts = py::array_t<runfile::ContactRecord, py::array::c_style>;

// The analysis' input: the contacts in place; centroids (num_bodies, 3) where given.
struct Input {
  sff::SnapshotInput input;
  Contacts contacts;  // holds the array while the span points into it
};

Input make_input(const py::array& contacts, double volume, double solid_volume, int num_bodies,
                 double youngs_modulus, double friction, const py::object& wall_stress,
                 const py::object& centroids) {
  if (!Contacts::check_(contacts))
    throw std::invalid_argument(
        "contacts must be a C-ordered numpy array of sffcal.sff.CONTACT_DTYPE (the run file's "
        "contact records; sffcal.sff.contacts() builds one from separate arrays)");
  Input in;
  in.contacts = py::reinterpret_borrow<Contacts>(contacts);
  if (in.contacts.ndim() != 1) throw std::invalid_argument("contacts must be one-dimensional");
  in.input.contacts = sff::ContactSpan(in.contacts.data(), static_cast<std::size_t>(in.contacts.size()));
  in.input.volume = volume;
  in.input.solid_volume = solid_volume;
  in.input.num_bodies = num_bodies;
  in.input.youngs_modulus = youngs_modulus;
  in.input.friction = friction;
  if (!wall_stress.is_none()) {
    const auto w = py::cast<Array>(wall_stress);
    if (w.size() != 3) throw std::invalid_argument("wall_stress: the three principal stresses (x, y, z) [Pa]");
    in.input.wall_stress = Eigen::Vector3d(w.data()[0], w.data()[1], w.data()[2]);
  }
  if (!centroids.is_none()) {
    const auto c = py::cast<Array>(centroids);
    if (c.ndim() != 2 || c.shape(1) != 3)
      throw std::invalid_argument("centroids: an array (num_bodies, 3) [m]");
    for (py::ssize_t k = 0; k < c.shape(0); ++k)
      in.input.centroids.emplace_back(c.at(k, 0), c.at(k, 1), c.at(k, 2));
  }
  return in;
}

py::dict analyse(const py::array& contacts, double volume, double solid_volume, int num_bodies,
                 double youngs_modulus, double friction, const py::object& wall_stress,
                 const py::object& centroids) {
  const Input in = make_input(contacts, volume, solid_volume, num_bodies, youngs_modulus,
                              friction, wall_stress, centroids);
  sff::SnapshotAnalysis a;
  {
    py::gil_scoped_release release;
    a = sff::analyse_snapshot(in.input);
  }
  py::dict out;
  const std::vector<std::string>& names = sff::analysis_columns();
  const std::vector<double> row = sff::analysis_row(a);
  for (std::size_t i = 0; i < names.size(); ++i) out[py::str(names[i])] = row[i];
  out["stress_tensor"] = matrix_array(a.stress);
  out["fabric_tensor"] = matrix_array(a.fabric);
  out["normal_tensor"] = matrix_array(a.normal);
  out["tangential_tensor"] = matrix_array(a.tangential);
  out["mobilisation_tensor"] = matrix_array(a.mobilisation);
  out["weighted_mobilisation_tensor"] = matrix_array(a.weighted_mobilisation);
  return out;
}

py::dict check(const py::array& contacts, double volume, double solid_volume, int num_bodies,
               double youngs_modulus, double friction, int cells, int resamples,
               std::uint64_t seed) {
  const Input in = make_input(contacts, volume, solid_volume, num_bodies, youngs_modulus,
                              friction, py::none(), py::none());
  if (cells < 3 || cells % 2 == 0) throw std::invalid_argument("cells must be odd and >= 3");
  if (resamples < 0) throw std::invalid_argument("resamples must be >= 0");
  sff::SnapshotChecks c;
  {
    py::gil_scoped_release release;
    const sff::SnapshotAnalysis a = sff::analyse_snapshot(in.input);
    c = sff::check_snapshot(in.input, a, {cells, resamples, seed});
  }
  py::dict out;
  const std::vector<std::string>& names = sff::check_columns();
  const std::vector<double> row = sff::check_row(c);
  for (std::size_t i = 0; i < names.size(); ++i) out[py::str(names[i])] = row[i];
  return out;
}

}  // namespace

void bind_sff(py::module_& m) {
  PYBIND11_NUMPY_DTYPE(runfile::ContactRecord, body_a, body_b, wall, sliding, point, normal,
                       branch, overlap, normal_force, tangential_force);
  m.attr("CONTACT_DTYPE") = py::dtype::of<runfile::ContactRecord>();
  py::register_exception<sff::StatisticsError>(m, "StatisticsError", PyExc_ValueError);
  const char* doc_input =
      "contacts: a one-dimensional array of CONTACT_DTYPE (body_a, body_b, wall, sliding, point, "
      "normal from A to B, branch B - A [m], overlap [m], normal_force on B [N] > 0 in "
      "compression, tangential_force on B [N]), read in place; volume and solid_volume [m^3]; "
      "num_bodies; youngs_modulus [Pa] (the force scale); friction, the grains' mu.";
  m.def("analyse", &analyse, py::arg("contacts"), py::arg("volume"), py::arg("solid_volume"),
        py::arg("num_bodies"), py::arg("youngs_modulus"), py::arg("friction"),
        py::arg("wall_stress") = py::none(), py::arg("centroids") = py::none(),
        (std::string("The SFF analysis of one snapshot (sff-theory.md; the columns of "
                     "/analysis/sff, docs/sff.md): a dict of every scalar of the table and the "
                     "tensors stress_tensor, fabric_tensor (A), normal_tensor (F), "
                     "tangential_tensor (F^t), mobilisation_tensor (M), "
                     "weighted_mobilisation_tensor (T_m). ") +
         doc_input +
         " wall_stress: the walls' principal stresses (x, y, z) [Pa]; centroids (num_bodies, 3) "
         "[m] for the particle form with the wall contacts.")
            .c_str());
  m.def("check", &check, py::arg("contacts"), py::arg("volume"), py::arg("solid_volume"),
        py::arg("num_bodies"), py::arg("youngs_modulus"), py::arg("friction"),
        py::arg("cells") = 41, py::arg("resamples") = 200, py::arg("seed") = 1,
        (std::string("The statistical checks of the SFF assumptions (sff-theory.md §6; the "
                     "columns of /analysis/sff_checks) and the bootstrap intervals (resamples, "
                     "seeded: the same seed gives the same intervals). ") +
         doc_input)
            .c_str());
}

}  // namespace sffcal_python
