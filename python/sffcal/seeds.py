"""Several seeds of one specimen (the same config but for the packing seed): their mean curves as
a reduced run file, and the DEM's own noise, the scatter between seeds (issue 19: the RMS
difference between two seeds of the same specimen divided by sqrt(2)). Used by the main job's
`mean` stage (sffcal.mean_of_seeds, its command line) and by bench/calibration/."""
import os
import tomllib

import h5py
import numpy as np

from sffcal.reduce import reduce
from sffcal.runfile import config_text

# The noise is measured on these: q/p, the volumetric strain and p/p0 (undrained tests) over the
# series rows, and the fabric anisotropy a_c over the snapshots.
NOISE_KEYS = ("eta", "volumetric_strain", "p_ratio", "a_c")


def _flat(table, prefix=""):
    """A TOML table as {"section.key": value}."""
    out = {}
    for key, value in table.items():
        if isinstance(value, dict):
            out.update(_flat(value, prefix + key + "."))
        else:
            out[prefix + key] = value
    return out


def check_same_specimen(runs):
    """Raises ValueError unless the runs' stored configs (the root attribute `config`) are the
    same but for the packing seed and the thread count (which changes nothing but the time): the
    mean and the noise are those of one specimen's seeds. Names the first run and the keys that
    differ."""
    configs = []
    for path in runs:
        with h5py.File(path, "r") as f:
            text = config_text(f)
        if not text:
            raise ValueError(f"{path}: no stored config (root attribute 'config'): cannot tell "
                             "which specimen it is")
        flat = _flat(tomllib.loads(text))
        for key in ("seed", "threads"):
            flat.pop(key, None)
        configs.append(flat)
    for path, config in zip(runs[1:], configs[1:]):
        differ = sorted(k for k in set(config) | set(configs[0]) if config.get(k) != configs[0].get(k))
        if differ:
            raise ValueError(f"{path} and {runs[0]} are not seeds of one specimen: their configs "
                             f"differ in {', '.join(differ)}")


def _common_rows(strains):
    """The first run's rows up to the smallest final |axial strain| of all runs (extension: ε_a < 0)."""
    top = min(abs(s[-1]) for s in strains)
    return np.abs(strains[0]) <= top + 1e-12


def _on_first_rows(strains, columns):
    """Each run's column interpolated linearly in |axial strain| onto the first run's common rows:
    an array (runs x rows)."""
    rows = _common_rows(strains)
    x = np.abs(strains[0][rows])
    return np.array([np.interp(x, np.abs(s), c) for s, c in zip(strains, columns)])


def noise(runs):
    """The DEM's noise over the seeds `runs` (run files, at least two), per quantity of NOISE_KEYS:
    the root mean square over the common rows of the sample standard deviation across the seeds.
    For two seeds that is RMS(a - b)/sqrt(2); for more, the same as the mean of (a - b)^2/2 over all
    pairs. The mean of K seeds scatters by noise/sqrt(K). a_c: the same over the snapshots after
    the first (the sheared ones; as many as the run with the fewest, as mean_run_file takes them),
    where the fit's RMS a_c errors are taken; None where no run has a sheared snapshot."""
    if len(runs) < 2:
        raise ValueError("the noise needs at least two seeds")
    check_same_specimen(runs)
    strains, columns, fabric = [], {k: [] for k in NOISE_KEYS if k != "a_c"}, []
    for path in runs:
        with h5py.File(path, "r") as f:
            s = f["series"]
            strains.append(s["axial_strain"][()])
            columns["eta"].append(s["eta"][()])
            columns["volumetric_strain"].append(s["volumetric_strain"][()])
            p = s["p"][()]
            columns["p_ratio"].append(p / p[0])
            fabric.append(f["analysis/sff/a_c"][()])
    noise = {k: float(np.sqrt(np.mean(np.var(_on_first_rows(strains, c), axis=0, ddof=1))))
             for k, c in columns.items()}
    n_snapshots = min(len(a) for a in fabric)
    sheared = np.array([a[1:n_snapshots] for a in fabric])
    noise["a_c"] = (float(np.sqrt(np.mean(np.var(sheared, axis=0, ddof=1))))
                    if n_snapshots > 1 else None)
    return noise


def mean_run_file(runs, target, by):
    """Writes `target`: the first run reduced (sffcal.reduce), then /series replaced by the mean
    over the runs, each interpolated linearly in |axial strain| onto the first run's rows up to the
    smallest final strain of all runs, and /analysis/sff by the mean over the runs snapshot by
    snapshot (the snapshots are at the same nominal strains; as many as the run with the fewest).
    Integer columns (steps, snapshot numbers) are the first run's. The root note `note:mean_of`
    names the runs and their seeds (`by`: the program). Built as `target`.part, copied compactly
    and renamed to `target`: an interrupted run leaves no partial target. `sffcal calibrate` and
    `sffcal fe-check` read the file as they read a run file. ValueError where the runs are not of
    one specimen (check_same_specimen)."""
    check_same_specimen(runs)
    part = target + ".part"
    reduce(runs[0], part, by)
    files = [h5py.File(r, "r") for r in runs]
    try:
        strains = [f["series/axial_strain"][()] for f in files]
        rows = _common_rows(strains)
        n_snapshots = min(len(f["analysis/sff/axial_strain"]) for f in files)
        with h5py.File(part, "r+") as out:
            for name, column in out["series"].items():
                first = files[0]["series"][name][()]
                column.resize((int(rows.sum()),))
                if np.issubdtype(first.dtype, np.floating):
                    column[...] = _on_first_rows(strains, [f["series"][name][()] for f in files]).mean(axis=0)
                else:
                    column[...] = first[rows]
            sff = out["analysis/sff"]
            for name in list(sff.keys()):
                first = files[0]["analysis/sff"][name][()]
                if first.ndim != 1:
                    del sff[name]  # a table of other shape (none today) is not averaged
                    continue
                if np.issubdtype(first.dtype, np.floating):
                    data = np.mean([f["analysis/sff"][name][()][:n_snapshots] for f in files], axis=0)
                else:
                    data = first[:n_snapshots]
                attrs = dict(sff[name].attrs)
                del sff[name]
                sff.create_dataset(name, data=data)
                for key, value in attrs.items():
                    sff[name].attrs[key] = value
            seeds = [int(f.attrs.get("seed", 0)) for f in files]
            out.attrs["note:mean_of"] = (f"mean of {len(runs)} runs (seeds {', '.join(map(str, seeds))}) "
                                         f"by {by}: " + ", ".join(os.path.basename(r) for r in runs))
    finally:
        for f in files:
            f.close()
    _copy_compact(part, target + ".compact")
    os.replace(target + ".compact", target)
    os.remove(part)


def _copy_compact(source, target):
    """Copies `source` into a new file `target`, root attributes and top-level objects: the columns
    resized and the tables rewritten above leave their old space unused in the file, which a fresh
    copy does not carry (the means take half the size)."""
    with h5py.File(source, "r") as src, h5py.File(target, "w") as dst:
        for key, value in src.attrs.items():
            dst.attrs[key] = value
        for name in src:
            src.copy(src[name], dst, name)
