"""The constitutive models of sffcal from Python (compiled: sffcal._core; docs/python.md).

    from sffcal import models
    models.model_names()                     # ['acst', 'contact_network', 'linear_elastic']
    acst = models.Model.from_file("examples/acst_toyoura.json")
    stress, state = acst.initial_state(100e3, {"void_ratio": 0.8})
    out = acst.update(stress, state, strain_increment)        # one point, or a batch of n
    path = acst.triaxial(100e3, 0.05, steps=50, drainage="undrained", inputs={"void_ratio": 0.8})

Compression positive, stress in Pa, tensor shear components. Errors of the C++ code arrive as
ValueError (a bad argument or value) or RuntimeError (a file), with its message.
"""
try:
    from sffcal._core import Model, model_names, STATUS_NAMES  # noqa: F401
except ImportError as error:  # the source tree's copy of the package, without the build's module
    raise ImportError("sffcal.models needs the compiled module sffcal._core, which CMake builds "
                      "into BUILD/python/sffcal: put BUILD/python on PYTHONPATH (docs/python.md); "
                      f"{error}") from error

__all__ = ["Model", "model_names", "STATUS_NAMES"]
