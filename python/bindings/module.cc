// sffcal._core: the compiled part of the Python package (python/sffcal). One binding file per
// library it opens: models.cc (sffcal.models), sff.cc (sffcal.sff), runfile.cc (the snapshots of
// sffcal.runfile). sff.cc registers the contact record's dtype, which runfile.cc uses: it binds
// first.
#include <pybind11/pybind11.h>

namespace sffcal_python {
void bind_models(pybind11::module_& m);
void bind_sff(pybind11::module_& m);
void bind_runfile(pybind11::module_& m);
}

PYBIND11_MODULE(_core, m) {
  m.doc() = "sffcal's compiled core: the constitutive models (sffcal.models), the SFF analysis "
            "(sffcal.sff) and the run files' snapshots (sffcal.runfile)";
  m.attr("__version__") = SFFCAL_VERSION;
  sffcal_python::bind_models(m);
  sffcal_python::bind_sff(m);
  sffcal_python::bind_runfile(m);
}
