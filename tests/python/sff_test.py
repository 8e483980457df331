"""sffcal.sff (the compiled sffcal._core) against analytic answers, against what `sffcal sff`
stores for a fresh run's snapshots read by sffcal.runfile (the same code: the same numbers, bit for
bit), and the errors it names. Run by CTest as Python.Sff (PYTHONPATH=BUILD/python,
SFFCAL_BIN=the sffcal binary)."""
import os
import re
import subprocess

import h5py
import numpy as np
import pytest

from sffcal import runfile, sff


def fibonacci_sphere(n):
    """n nearly uniform unit vectors (a spiral on the sphere)."""
    k = np.arange(n) + 0.5
    z = 1 - 2 * k / n
    phi = np.pi * (1 + 5 ** 0.5) * k
    r = np.sqrt(1 - z * z)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)


def isotropic_contacts(n=4000, force=10.0, length=2e-3):
    normal = fibonacci_sphere(n)
    bodies = np.arange(2 * n).reshape(n, 2)
    return sff.contacts(normal=normal, normal_force=np.full(n, force),
                        tangential_force=np.zeros((n, 3)), branch=length * normal,
                        body_a=bodies[:, 0], body_b=bodies[:, 1]), 2 * n


def test_the_dtype_is_the_run_files_contact_record():
    assert sff.CONTACT_DTYPE.itemsize == 136
    assert sff.CONTACT_DTYPE.names == ("body_a", "body_b", "wall", "sliding", "point", "normal",
                                       "branch", "overlap", "normal_force", "tangential_force")


def test_isotropic_contacts_give_the_love_weber_stress_and_no_anisotropy():
    records, bodies = isotropic_contacts()
    volume = 1e-3
    out = sff.analyse(records, volume=volume, solid_volume=0.6 * volume, num_bodies=bodies,
                      youngs_modulus=1e8, friction=0.5)
    # sigma = (1/V) sum f l n n = (N f l / 3V) I for directions uniform on the sphere.
    expected = len(records) * 10.0 * 2e-3 / (3 * volume)
    assert out["p"] == pytest.approx(expected, rel=1e-9)
    assert abs(out["q"]) < 1e-3 * expected
    np.testing.assert_allclose(out["stress_tensor"], expected * np.eye(3), atol=1e-3 * expected)
    assert abs(out["a_c"]) < 1e-3 and abs(out["a_n"]) < 1e-3 and out["a_t"] == 0
    assert out["coordination"] == pytest.approx(2 * len(records) / bodies)
    assert out["void_ratio"] == pytest.approx(0.4 / 0.6)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """A fresh 150-clump run to 3 % with snapshots, analysed by `sffcal sff`."""
    work = tmp_path_factory.mktemp("run")
    binary = os.environ["SFFCAL_BIN"]
    config = subprocess.run([binary, "config"], check=True, capture_output=True, text=True).stdout
    config = re.sub(r"(?m)^bodies = .*", "bodies = 150", config)
    config = re.sub(r"(?m)^max_axial_strain = .*", "max_axial_strain = 0.03", config)
    config = re.sub(r"(?m)^snapshot_strain_interval = .*", "snapshot_strain_interval = 0.01", config)
    (work / "small.toml").write_text(config)
    subprocess.run([binary, "dem", "-c", str(work / "small.toml"), "-o", str(work / "run.h5")],
                   check=True, capture_output=True)
    subprocess.run([binary, "sff", str(work / "run.h5"), "--resamples", "0"], check=True,
                   capture_output=True)
    return work / "run.h5"


def test_each_snapshot_gives_what_sffcal_sff_stored_bit_for_bit(run):
    """sff.analyse on sffcal.runfile.snapshot_input: the numbers of `sffcal sff`, exactly."""
    with h5py.File(run, "r") as f:
        stored = {k: v[()] for k, v in f["analysis/sff"].items()}
    count = runfile.num_snapshots(str(run))
    assert count >= 3 and len(stored["p"]) == count
    for row in range(count):
        arguments = runfile.snapshot_input(str(run), row)
        assert arguments["contacts"].dtype == sff.CONTACT_DTYPE
        out = sff.analyse(**arguments)
        compared = 0
        for column, values in stored.items():
            if column in ("snapshot", "step", "axial_strain"):
                continue
            assert out[column] == values[row] or (np.isnan(out[column]) and np.isnan(values[row])), column
            compared += 1
        assert compared == len(stored) - 3 > 100  # every column of the table


def test_a_snapshot_reads_as_structured_arrays(run):
    snapshot = runfile.read_snapshot(str(run), 1)
    with h5py.File(run, "r") as f:
        group = f["snapshots/000001"]
        assert snapshot["step"] == group.attrs["step"]
        for name in ("contacts", "particles", "walls", "spheres", "sphere_body"):
            assert snapshot[name].tobytes() == group[name][()].tobytes(), name
    assert len(snapshot["walls"]) == 6 and snapshot["particles"]["id"].max() == 149
    with pytest.raises(IndexError, match="no snapshot 99"):
        runfile.read_snapshot(str(run), 99)


def test_the_checks_are_seeded_and_sffcal_sffs(run):
    arguments = runfile.snapshot_input(str(run), runfile.num_snapshots(str(run)) - 1)
    with h5py.File(run, "r") as f:
        stored = {k: v[-1] for k, v in f["analysis/sff_checks"].items()}
    del arguments["wall_stress"], arguments["centroids"]
    checks = sff.check(**arguments, resamples=0)
    for column, value in stored.items():
        if column in ("snapshot", "step", "axial_strain") or column.endswith(("_low", "_high")):
            continue
        assert checks[column] == value or (np.isnan(checks[column]) and np.isnan(value)), column
    a = sff.check(**arguments, resamples=30, seed=5)
    b = sff.check(**arguments, resamples=30, seed=5)
    assert a == b and a["a_c_low"] < a["a_c_high"]


@pytest.mark.parametrize("change,words", [
    (lambda r: r["normal"].__setitem__(3, [1.0, 1.0, 0.0]), "contact 3: the normal is not a unit"),
    (lambda r: r["normal_force"].__setitem__(7, np.nan), "contact 7: a number is not finite"),
    (lambda r: r["point"].__setitem__(5, [0.0, -np.inf, 0.0]), "contact 5: a number is not finite"),
    (lambda r: r["body_b"].__setitem__(2, 10 ** 9), "contact 2: body_b 1000000000"),
    (lambda r: r["body_a"].__setitem__(4, r["body_b"][4]), "contact 4: body_a"),
])
def test_a_bad_contact_is_named(change, words):
    records, bodies = isotropic_contacts(100)
    change(records)
    with pytest.raises(ValueError) as caught:
        sff.analyse(records, volume=1e-3, solid_volume=6e-4, num_bodies=bodies,
                    youngs_modulus=1e8, friction=0.5)
    assert words in str(caught.value)


def test_large_finite_numbers_are_no_error():
    # The check adds v * 0 over a record's numbers: finite values whose sum would overflow pass.
    records, bodies = isotropic_contacts(100)
    records["point"][9] = [1.7e308, 1.7e308, 1.7e308]
    out = sff.analyse(records, volume=1e-3, solid_volume=6e-4, num_bodies=bodies,
                      youngs_modulus=1e8, friction=0.5)
    assert np.isfinite(out["eta_sff"])


def test_bad_arguments_are_named():
    records, bodies = isotropic_contacts(100)
    good = dict(volume=1e-3, solid_volume=6e-4, num_bodies=bodies, youngs_modulus=1e8, friction=0.5)
    for key, value, words in [("volume", -1.0, "volume"), ("solid_volume", 2e-3, "solid volume"),
                              ("friction", 0.0, "friction"), ("youngs_modulus", np.inf, "Young")]:
        with pytest.raises(ValueError, match=words):
            sff.analyse(records, **{**good, key: value})
    with pytest.raises(ValueError, match="CONTACT_DTYPE"):
        sff.analyse(np.zeros((100, 3)), **good)
    with pytest.raises(ValueError, match="CONTACT_DTYPE"):
        sff.analyse(records[::2], **good)  # not C-ordered: no silent copy
    with pytest.raises(ValueError):  # no contact: the statistics are undefined
        sff.analyse(records[:0], **good)
    three = dict(normal=np.eye(3), normal_force=[1.0, 2.0, 3.0], tangential_force=np.zeros((3, 3)),
                 branch=np.eye(3), body_a=[0, 1, 2], body_b=[1, 2, 0])
    assert len(sff.contacts(**three)) == 3
    for change, words in [({"normal_force": [1.0, 2.0]}, "normal_force must be of shape (3,)"),
                          ({"normal": [0.0, 0.0, 1.0]}, "normal must be an array (n, 3)"),
                          ({"tangential_force": np.zeros(3)}, "tangential_force must be of shape (3, 3)"),
                          ({"body_a": [0.7, 1.9, 2.0]}, "body_a must hold integers")]:
        with pytest.raises(ValueError, match=re.escape(words)):
            sff.contacts(**{**three, **change})
