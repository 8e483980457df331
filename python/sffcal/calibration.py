"""The fit of a constitutive model to DEM run files from Python: what `sffcal calibrate` does
(docs/calibration.md), in process (compiled: sffcal._fit, which links Ceres; docs/python.md).

    from sffcal import calibration
    fit = calibration.calibrate(["a.h5", "b.h5"], "out/fit", model="acst", starts=2)
    fit["parameters"]                  # {name: value}, from out/fit/parameters.json
    fit["summary"]                     # summary.md's text

The settings are the command line's flags with underscores (stages, loss, starts, seed, points,
max_strain_step, range, hold, predicted_only, start, threads, verbose); one the model's fit does
not read is refused by name (ValueError), as on the command line.
"""
import os

try:
    from sffcal._fit import calibrate as _calibrate
except ImportError as error:
    raise ImportError("sffcal.calibration needs the compiled module sffcal._fit, which CMake builds "
                      "into BUILD/python/sffcal: put BUILD/python on PYTHONPATH (docs/python.md); "
                      f"{error}") from error

from sffcal import models

__all__ = ["calibrate"]


def calibrate(runs, output, model="acst", held_out=(), progress=None, **settings):
    """Fits `model` to the tests `runs`, predicts the `held_out` ones, writes the outputs into the
    folder `output` (which must be new or empty: nothing is overwritten) and returns a dict:
    summary, report (the solver's record), usable (the solver's verdict), seconds, plot_hint,
    parameters_file and parameters ({name: value}). `progress` receives a line per run read and
    per stage.

    A test is a run file's path (with /analysis/sff: `sffcal sff` first) or its curves as a dict:
    {"name": str, "series": {axial_strain, eta, volumetric_strain, void_ratio, p},
     "sff": {axial_strain, a_c, a_n, m, eta (and coordination, lambda, a_t for the network
     model)}, "friction": mu, "path": "drained_compression" (the default), "drained_extension",
     "constant_p_compression", "undrained_compression" or "undrained_extension"}, each column a
    sequence of numbers named as the run file's (compression positive, stresses in Pa)."""
    if os.path.exists(output) and (not os.path.isdir(output) or os.listdir(output)):
        raise ValueError(f"calibrate: {output} exists and is not an empty folder; give a new one")
    os.makedirs(output, exist_ok=True)
    result = _calibrate([r if isinstance(r, dict) else str(r) for r in runs], output, model,
                        [r if isinstance(r, dict) else str(r) for r in held_out], progress, **settings)
    result["parameters_file"] = os.path.join(output, "parameters.json")
    result["parameters"] = models.Model.from_file(result["parameters_file"]).parameters
    return result
