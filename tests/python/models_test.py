"""sffcal.models (the compiled sffcal._core) against closed forms, against the C++ driver as
`sffcal point` writes it (bit for bit), a batch against its points one by one, and the errors it
names. Run by CTest as Python.Models (PYTHONPATH=BUILD/python, SFFCAL_BIN=the sffcal binary)."""
import csv
import os
import re
import subprocess

import numpy as np
import pytest

from sffcal import models

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
ACST = os.path.join(ROOT, "examples", "acst_toyoura.json")
NETWORK = os.path.join(ROOT, "bench", "reference", "network_paper_params.json")
RUNS = os.path.join(ROOT, "tests", "data", "reference", "matrix")
E, NU = 2.4e8, 0.2


def elastic():
    return models.Model("linear_elastic", parameters={"youngs_modulus": E, "poissons_ratio": NU})


def sffcal_point(tmp_path, *args):
    """The CSV of `sffcal point ARGS` as float columns."""
    out = tmp_path / "point.csv"
    subprocess.run([os.environ["SFFCAL_BIN"], "point", *args, "-o", str(out)], check=True,
                   capture_output=True)
    with open(out) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return {k: np.array([float(r[k]) for r in rows]) for k in ("axial_strain", "volumetric_strain",
                                                                 "sigma_xx", "sigma_zz")}


def test_the_registered_models_are_listed():
    assert {"acst", "contact_network", "linear_elastic"} <= set(models.model_names())


def test_linear_elasticity_follows_hookes_law_with_its_tangent():
    model = elastic()
    stress, state = model.initial_state(150e3)
    assert np.array_equal(stress, 150e3 * np.eye(3))
    increment = np.array([[1e-4, 2e-5, 0.0], [2e-5, -3e-4, 1e-5], [0.0, 1e-5, 2e-4]])
    out = model.update(stress, state, increment, tangent=True)
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    expected = stress + lam * np.trace(increment) * np.eye(3) + 2 * mu * increment
    assert out["status"] == "ok" and out["message"] == ""
    np.testing.assert_allclose(out["stress"], expected, rtol=0, atol=1e-9 * E * 3e-4)
    # d sigma_ij / d eps_kl at row 3 i + j, column 3 k + l, symmetric in (k, l).
    tangent = np.zeros((3, 3, 3, 3))
    for i, j, k, l in np.ndindex(3, 3, 3, 3):
        tangent[i, j, k, l] = (lam * (i == j) * (k == l)
                               + mu * ((i == k) * (j == l) + (i == l) * (j == k)))
    np.testing.assert_allclose(out["tangent"], tangent.reshape(9, 9), rtol=1e-12, atol=1e-6)


def test_a_batch_gives_its_points_one_by_one_bit_for_bit():
    model = models.Model.from_file(ACST)
    rng = np.random.default_rng(7)  # seeded: the same increments every run
    n = 200
    stress0, state0 = model.initial_state(100e3, {"void_ratio": 0.8})
    increments = rng.normal(scale=3e-4, size=(n, 3, 3))
    increments = 0.5 * (increments + increments.transpose(0, 2, 1))
    increments[:, 2, 2] += 1e-3
    batch = model.update(np.repeat(stress0[None], n, 0), np.repeat(state0[None], n, 0), increments,
                         tangent=True)
    assert batch["stress"].shape == (n, 3, 3) and batch["state"].shape == (n, model.state_size)
    for k in range(n):
        one = model.update(stress0, state0, increments[k], tangent=True)
        assert np.array_equal(one["stress"], batch["stress"][k])
        assert np.array_equal(one["state"], batch["state"][k])
        assert np.array_equal(one["tangent"], batch["tangent"][k])
        assert one["status"] == models.STATUS_NAMES[batch["status"][k]]


def test_a_point_that_cannot_be_integrated_says_so():
    model = models.Model.from_file(ACST)
    stress, state = model.initial_state(100e3, {"void_ratio": 0.8})
    huge = np.diag([-0.2, -0.2, 0.4])  # 40 % axial strain in one increment
    out = model.update(stress, state, huge)
    assert out["status"] != "ok" and out["message"] and out["step_ratio"] < 1
    batch = model.update(np.stack([stress, stress]), np.stack([state, state]),
                         np.stack([huge, 1e-6 * huge]))
    assert batch["status"][0] != 0 and batch["status"][1] == 0
    assert list(batch["messages"]) == [0]


@pytest.mark.parametrize("drainage,end", [("drained", 0.05), ("drained", -0.05),
                                          ("undrained", 0.05), ("undrained", -0.05)])
def test_acst_triaxial_equals_sffcal_point(tmp_path, drainage, end):
    model = models.Model.from_file(ACST)
    path = model.triaxial(150e3, end, steps=40, drainage=drainage, inputs={"void_ratio": 0.75})
    assert path["completed"], path["message"]
    cli = sffcal_point(tmp_path, "--parameters", ACST, "--pressure", "150e3", "--void-ratio",
                       "0.75", "--drainage", drainage, "--max-strain", repr(end), "--steps", "40")
    # The CSV's 17 digits read back every double exactly: the same code, the same numbers.
    assert np.array_equal(path["strain"][:, 2, 2], cli["axial_strain"])
    assert np.array_equal(path["stress"][:, 0, 0], cli["sigma_xx"])
    assert np.array_equal(path["stress"][:, 2, 2], cli["sigma_zz"])
    q = path["stress"][-1, 2, 2] - path["stress"][-1, 0, 0]
    assert abs(q) > 50e3 and (q > 0) == (end > 0)  # loaded, in the direction asked


def test_network_triaxial_from_a_deposit_equals_sffcal_point(tmp_path):
    """The network's initial inputs of a DEM run (Z, Lambda, A, F, F^t) as `sffcal umat-cards`
    lays them out: the first input_size PROPS."""
    model = models.Model.from_file(NETWORK)
    run = os.path.join(RUNS, "dep_dense_a45.h5")
    cards = subprocess.run([os.environ["SFFCAL_BIN"], "umat-cards", "--parameters", NETWORK,
                            "--dem", run, "--elements", "1"], check=True, capture_output=True,
                           text=True).stdout
    props = re.search(r"\*USER MATERIAL, CONSTANTS=\d+\n(.*?)\n\*DEPVAR", cards, re.S).group(1)
    inputs = np.array([float(x) for x in props.replace("\n", ",").split(",")][:model.input_size])
    sigma_3 = -float(re.search(r"\n1, 1, (\S+),", cards).group(1))
    path = model.triaxial(sigma_3, 0.08, steps=40, drainage="undrained", inputs=inputs)
    assert path["completed"], path["message"]
    cli = sffcal_point(tmp_path, "--parameters", NETWORK, "--dem", run, "--drainage", "undrained",
                       "--max-strain", "0.08", "--steps", "40")
    assert np.array_equal(path["stress"][:, 2, 2], cli["sigma_zz"])
    assert np.all(np.abs(np.trace(path["strain"], axis1=1, axis2=2)) < 1e-17)


def test_numpy_scalars_are_numbers():
    model = elastic()
    for value in (np.float32(1e5), np.int64(100000), 1e5):
        stress, _ = model.initial_state(value)
        assert np.array_equal(stress, 1e5 * np.eye(3))


def test_inputs_by_name_equal_inputs_by_position():
    model = models.Model.from_file(ACST)
    fabric = np.diag([-0.1, -0.1, 0.2])
    by_name = model.initial_state(100e3, {"void_ratio": 0.7, "fabric": fabric})
    by_position = model.initial_state(100e3, np.array([0.7, -0.1, -0.1, 0.2, 0, 0, 0]))
    assert np.array_equal(by_name[1], by_position[1])
    assert [s["name"] for s in model.input_layout] == ["void_ratio", "fabric"]
    assert sum(s["size"] for s in model.state_layout) == model.state_size


@pytest.mark.parametrize("call,kind,words", [
    (lambda: models.Model("sand"), ValueError, "unknown model 'sand'"),
    (lambda: models.Model("linear_elastic", parameters={"youngs": 1e8}), ValueError,
     "no parameter 'youngs'"),
    (lambda: models.Model("linear_elastic", parameters={"youngs_modulus": 1e8}), ValueError,
     "needs the parameter 'poissons_ratio'"),
    (lambda: models.Model("linear_elastic", parameters={"youngs_modulus": -1.0,
                                                        "poissons_ratio": 0.2}), ValueError,
     "youngs_modulus"),
    (lambda: models.Model.from_file("/no/such/file.json"), RuntimeError, "/no/such/file.json"),
    (lambda: elastic().update(np.eye(3), np.zeros(5), np.eye(3)), ValueError, "state (0,)"),
    (lambda: elastic().triaxial(1e5, 0.01, drainage="partly"), ValueError, "drainage 'partly'"),
    (lambda: elastic().triaxial(-1.0, 0.01), ValueError, "lateral stress"),
    (lambda: models.Model.from_file(ACST).initial_state(1e5, {"void_ratio": 0.0}), ValueError,
     "void"),
    (lambda: models.Model.from_file(ACST).initial_state(1e5, {"porosity": 0.4}), ValueError,
     "no input 'porosity'"),
    (lambda: elastic().initial_state(float("nan")), ValueError, "stress is not finite"),
    (lambda: elastic().initial_state(np.array([[1e5, 1.0, 0], [0, 1e5, 0], [0, 0, 1e5]])),
     ValueError, "finite and symmetric"),
    (lambda: elastic().update(1e5 * np.eye(3), np.zeros(0),
                              np.array([[0, 1e-3, 0], [0, 0, 0], [0, 0, 0]])),
     ValueError, "strain increment is not finite and symmetric"),
    (lambda: elastic().update(np.repeat(1e5 * np.eye(3)[None], 2, 0), np.zeros((2, 0)),
                              np.stack([np.zeros((3, 3)), np.full((3, 3), np.nan)])),
     ValueError, "strain increment of point 1"),
    (lambda: elastic().triaxial(1e5, 0.0), ValueError, "non-zero"),
    (lambda: elastic().triaxial(1e5, 0.8), ValueError, "at most 0.6"),
    (lambda: models.Model("linear_elastic", parameters={"youngs_modulus": "stiff",
                                                        "poissons_ratio": 0.2}),
     TypeError, "'youngs_modulus' must be a number"),
])
def test_errors_name_what_is_wrong(call, kind, words):
    with pytest.raises(kind) as caught:
        call()
    assert words in str(caught.value)
