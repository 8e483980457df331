"""sffcal.calibration (the compiled sffcal._fit): the fit from Python writes what `sffcal
calibrate` writes for the same runs and settings (the same parameters, bit for bit), and refuses by
name a setting the model's fit does not read, an unknown one and an output folder in use. Run by
CTest as Python.Calibration (PYTHONPATH=BUILD/python, SFFCAL_BIN=the sffcal binary)."""
import json
import os
import subprocess

import h5py
import numpy as np
import pytest

import sffcal
from sffcal import calibration

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
RUNS = [os.path.join(ROOT, "tests", "data", "reference", "matrix", name + ".h5")
        for name in ("iso_dense_100kPa", "iso_dense_200kPa")]


def parameters(folder):
    with open(os.path.join(folder, "parameters.json")) as f:
        return json.load(f)["parameters"]


def test_the_fit_from_python_equals_sffcal_calibrate(tmp_path):
    lines = []
    fit = calibration.calibrate(RUNS, str(tmp_path / "python"), model="linear_elastic",
                                progress=lines.append, points=20)
    subprocess.run([os.environ["SFFCAL_BIN"], "calibrate", *RUNS, "-o", str(tmp_path / "cli"),
                    "--model", "linear_elastic", "--points", "20"],
                   check=True, capture_output=True)
    assert fit["usable"] and fit["summary"]
    mine, theirs = parameters(tmp_path / "python"), parameters(tmp_path / "cli")
    assert set(mine) == set(theirs) == {"youngs_modulus", "poissons_ratio"}
    for name in mine:
        assert mine[name]["value"] == theirs[name]["value"], name
    assert fit["parameters"]["youngs_modulus"] == mine["youngs_modulus"]["value"]
    assert sum(line.startswith("read ") for line in lines) == 2
    assert sffcal.calibrate is calibration.calibrate


def curves(path):
    """A run file's test as data: its series and SFF columns, named as the file names them."""
    with h5py.File(path, "r") as f:
        series = {k: f["series"][k][()] for k in ("axial_strain", "eta", "volumetric_strain",
                                                    "void_ratio", "p")}
        table = {k: f["analysis/sff"][k][()] for k in ("axial_strain", "a_c", "a_n", "m", "eta")}
    return {"name": os.path.basename(path)[:-3], "series": series, "sff": table,
            "friction": float(np.tan(np.radians(30)))}


def test_curves_given_as_data_fit_as_their_run_files(tmp_path):
    """The schema-1 reference runs shear at tan 30 deg, which their stored config gives."""
    from_files = calibration.calibrate(RUNS, str(tmp_path / "files"), model="acst", stages="csl")
    from_data = calibration.calibrate([curves(r) for r in RUNS], str(tmp_path / "data"),
                                      model="acst", stages="csl")
    assert from_data["parameters"] == from_files["parameters"]
    broken = curves(RUNS[0])
    del broken["series"]["eta"]
    with pytest.raises(RuntimeError, match="missing column 'eta'"):
        calibration.calibrate([broken], str(tmp_path / "broken"), model="acst", stages="csl")
    with pytest.raises(RuntimeError, match="friction must be a number"):
        calibration.calibrate([{**curves(RUNS[0]), "friction": float("nan")}],
                              str(tmp_path / "nan"), model="acst", stages="csl")
    with pytest.raises(ValueError, match="needs 'friction'"):
        calibration.calibrate([{k: v for k, v in curves(RUNS[0]).items() if k != "friction"}],
                              str(tmp_path / "nofriction"), model="acst", stages="csl")


@pytest.mark.parametrize("settings,words", [
    ({"stages": "csl"}, "stages does not apply to model linear_elastic (its fit reads output, held_out"),
    ({"iterations": 3}, "no setting 'iterations'"),
    ({"threads": 0}, "threads must be in 1..1024"),
    ({"points": 0}, "points must be in 3..100000"),
    ({"max_strain_step": float("nan")}, "max-strain-step must be in [0, 0.1]"),
])
def test_a_setting_is_refused_by_name(tmp_path, settings, words):
    with pytest.raises(ValueError) as caught:
        calibration.calibrate(RUNS, str(tmp_path / "fit"), model="linear_elastic", **settings)
    assert words in str(caught.value)


def test_a_setting_of_the_wrong_type_is_a_type_error_naming_it(tmp_path):
    with pytest.raises(TypeError, match="setting 'starts' must be an int"):
        calibration.calibrate(RUNS, str(tmp_path / "fit"), model="acst", starts=2.5)


def test_an_output_folder_in_use_is_refused(tmp_path):
    (tmp_path / "kept.txt").write_text("mine")
    with pytest.raises(ValueError, match="not an empty folder"):
        calibration.calibrate(RUNS, str(tmp_path), model="linear_elastic")
    assert (tmp_path / "kept.txt").read_text() == "mine"
    with pytest.raises(ValueError, match="unknown model"):
        calibration.calibrate(RUNS, str(tmp_path / "new"), model="sand")
