"""sffcal.seeds on run files whose series are known: the mean of two seeds and the DEM's noise
between them (RMS(a - b)/sqrt(2)), on rows and strains that differ, in compression and extension;
runs of another specimen refused by name. Run by CTest with pytest (PYTHONPATH=BUILD/python)."""
import os

import h5py
import numpy as np
import pytest

from sffcal import seeds


CONFIG = 'seed = {seed}\nthreads = {threads}\nbodies = 400\n[preparation]\ncompaction_friction = {friction}\n'


def write_run(path, seed, strain, eta, eps_v, p, snapshot_strain, a_c, sign=1.0, friction=0.15):
    with h5py.File(path, "w") as f:
        f.attrs["seed"] = seed
        # the stored config: the same specimen but for the seed (and the thread count)
        f.attrs["config"] = CONFIG.format(seed=seed, threads=seed, friction=friction)
        s = f.create_group("series")
        for name, values in (("axial_strain", sign * strain), ("eta", eta), ("volumetric_strain", eps_v),
                             ("p", p), ("step", np.arange(len(strain)) * 10)):
            s.create_dataset(name, data=values, maxshape=(None,), chunks=True)
        sff = f.create_group("analysis/sff")
        sff.create_dataset("axial_strain", data=sign * snapshot_strain)
        sff.create_dataset("a_c", data=a_c)
        sff.create_dataset("snapshot", data=np.arange(len(snapshot_strain)))


@pytest.mark.parametrize("sign", [1.0, -1.0])  # compression; extension: eps_a < 0
def test_mean_and_noise_of_two_seeds(tmp_path, sign):
    folder = str(tmp_path)
    # Seed A on 101 rows to 0.25, seed B on 81 rows to 0.20 (it ended earlier): linear curves, so
    # interpolation is exact and the mean and noise are known in closed form on A's rows <= 0.20.
    a_strain, b_strain = np.linspace(0, 0.25, 101), np.linspace(0, 0.20, 81)
    a = os.path.join(folder, f"a{sign:+.0f}.h5")
    b = os.path.join(folder, f"b{sign:+.0f}.h5")
    write_run(a, 1, a_strain, 1.0 + 2.0 * a_strain, 0.1 * a_strain, 1e5 * (1 + a_strain),
              np.array([0.0, 0.1, 0.2]), np.array([0.1, 0.5, 0.8]), sign)
    write_run(b, 2, b_strain, 1.0 + 2.0 * b_strain + 0.04, -0.1 * b_strain, 2e5 * (1 + 3 * b_strain),
              np.array([0.0, 0.1]), np.array([0.3, 0.7]), sign)
    noise = seeds.noise([a, b])
    rows = a_strain <= 0.20 + 1e-12
    x = a_strain[rows]
    assert abs(noise["eta"] - 0.04 / np.sqrt(2)) < 1e-12, f"sign {sign}: q/p noise {noise['eta']}"
    expected_v = np.sqrt(np.mean((0.2 * x) ** 2)) / np.sqrt(2)
    assert abs(noise["volumetric_strain"] - expected_v) < 1e-12, \
        f"sign {sign}: eps_v noise {noise['volumetric_strain']} against {expected_v}"
    expected_p = np.sqrt(np.mean((2 * x) ** 2)) / np.sqrt(2)  # p/p0: 1 + x against 1 + 3x
    assert abs(noise["p_ratio"] - expected_p) < 1e-12, f"sign {sign}: p/p0 noise {noise['p_ratio']}"
    # a_c over the sheared snapshots both runs have (B's one, at 0.1): 0.5 against 0.7.
    assert abs(noise["a_c"] - 0.2 / np.sqrt(2)) < 1e-12, f"sign {sign}: a_c noise {noise['a_c']}"
    target = os.path.join(folder, f"mean{sign:+.0f}.h5")
    seeds.mean_run_file([a, b], target, "seeds_test.py")
    for left in (".part", ".compact"):
        assert not os.path.exists(target + left), f"sign {sign}: the {left} file is left"
    with h5py.File(target, "r") as f:
        s = f["series"]
        assert len(s["axial_strain"]) == rows.sum(), f"sign {sign}: {len(s['axial_strain'])} rows"
        assert np.allclose(s["eta"][()], 1.02 + 2.0 * x, atol=1e-12), f"sign {sign}: mean q/p"
        assert np.allclose(s["volumetric_strain"][()], 0.0, atol=1e-15), f"sign {sign}: mean eps_v"
        assert np.array_equal(s["step"][()], np.arange(rows.sum()) * 10), f"sign {sign}: integer column"
        sff = f["analysis/sff"]
        assert np.allclose(sff["a_c"][()], [0.2, 0.6]), f"sign {sign}: mean a_c {sff['a_c'][()]}"
        assert "seeds 1, 2" in f.attrs["note:mean_of"], f"sign {sign}: note {f.attrs['note:mean_of']}"
    with pytest.raises(ValueError):
        seeds.noise([a])
    # Another specimen (compaction friction 0.5) is refused by name, before anything is written.
    other = os.path.join(folder, f"other{sign:+.0f}.h5")
    write_run(other, 3, b_strain, 1.0 + b_strain, 0 * b_strain, 1e5 * (1 + b_strain),
              np.array([0.0, 0.1]), np.array([0.3, 0.7]), sign, friction=0.5)
    for call in (lambda: seeds.noise([a, other]),
                 lambda: seeds.mean_run_file([a, other], os.path.join(folder, "refused.h5"), "t")):
        with pytest.raises(ValueError, match="preparation.compaction_friction"):
            call()
    assert not os.path.exists(os.path.join(folder, "refused.h5")), f"sign {sign}: refused file written"

