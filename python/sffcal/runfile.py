"""Reading a run file (docs/run-file.md) with the names of the C++ runfile library: the series,
the test summary (/summary), the run's physics (/physics), the loading path (/loading) and the
analysis tables (/analysis/<name>); and the CSV tables the commands write. The snapshots
(num_snapshots, read_snapshot, snapshot_input) are read by the C++ reader itself, through the
compiled sffcal._core (docs/python.md)."""
import csv
import os
import tomllib

import h5py
import numpy as np

# The friction of a schema-1 run file without a [contact] table: that schema's default, tan 30 deg
# (as runfile/src/stored_physics.cc).
SCHEMA1_FRICTION = 0.5773502691896257


class RunFileError(Exception):
    """A run file lacks what was asked of it; the message names the file and the dataset."""


def _text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def name_of(path):
    """The run's name: its file name without .h5 (or .sff.csv / .csv)."""
    base = os.path.basename(path)
    for suffix in (".sff.csv", ".h5", ".csv"):
        if base.endswith(suffix):
            return base[: -len(suffix)]
    return base


def config_text(f):
    """The TOML config the run was made from (the root attribute `config`)."""
    return _text(f.attrs.get("config", ""))


def loading_path(f):
    """The loading path's name (/loading's `path`; drained compression in files without it)."""
    return _text(f["loading"].attrs["path"]) if "loading" in f else "drained_compression"


def summary(f):
    """/summary's attributes (TestSummary: ended, peak and critical q/p, ...) as a dict; empty for
    a schema-1 file, whose summary is a prose note."""
    return {k: (_text(v) if isinstance(v, (bytes, str)) else v)
            for k, v in f["summary"].attrs.items()} if "summary" in f else {}


def ended(f):
    """How the test ended, in words (schema 2: /summary's `ended`; schema 1: the note's first
    clause)."""
    if "summary" in f:
        return {"critical_state": "critical state reached",
                "max_axial_strain": "maximum axial strain reached"}.get(
                    _text(f["summary"].attrs["ended"]), _text(f["summary"].attrs["ended"]))
    return _text(f.attrs.get("note:summary", "")).split(";")[0]


def friction(f):
    """The grains' friction while shearing: /physics of a schema-2 run file; a schema-1 file's
    stored config with that schema's default."""
    if "physics" in f:
        return float(f["physics"].attrs["friction"])
    return float(tomllib.loads(config_text(f)).get("contact", {}).get("friction", SCHEMA1_FRICTION))


def series(f, names=None):
    """The columns of /series (all, or those named) as numpy arrays."""
    if "series" not in f:
        raise RunFileError(f"{f.filename}: no /series")
    group = f["series"]
    missing = [n for n in (names or []) if n not in group]
    if missing:
        raise RunFileError(f"{f.filename}: /series has no {', '.join(missing)}")
    return {k: group[k][()] for k in (names or group)}


def table(f, name, columns=None):
    """/analysis/<name> (e.g. sff, sff_rose) as a dict of numpy arrays."""
    if f"analysis/{name}" not in f:
        raise RunFileError(f"{f.filename}: no /analysis/{name}; run `sffcal sff {f.filename}` first")
    group = f[f"analysis/{name}"]
    return {k: group[k][()] for k in (columns or group)}


def read_csv_rows(path):
    """The rows of a CSV file written by the commands (lines starting with # are comments), the
    header first, as lists of strings."""
    with open(path, newline="") as f:
        return list(csv.reader(line for line in f if not line.startswith("#")))


def _column(values):
    """Floats (empty cells NaN), or the strings as they are where a cell is not a number."""
    try:
        return np.array([float(v) if v != "" else np.nan for v in values])
    except ValueError:
        return list(values)


def read_csv_table(path):
    """A CSV table written by the commands or the scripts (lines starting with # are comments) as
    a dict of columns: float arrays (empty cells and "nan" NaN), or lists of strings for text
    columns (e.g. a status)."""
    rows = read_csv_rows(path)
    if len(rows) < 2:
        return {}
    header, body = rows[0], rows[1:]
    return {name: _column([r[k] for r in body]) for k, name in enumerate(header)}


def open_run(path):
    """A run file opened for reading (an h5py.File, to use in `with`); RunFileError naming the
    file where it cannot be opened as HDF5."""
    try:
        return h5py.File(path, "r")
    except OSError as e:
        raise RunFileError(f"{path}: cannot be read as a run file ({e})") from None


def read_sff(path):
    """The SFF table of a run: /analysis/sff of a run file, or the <run>.sff.csv of `sffcal sff`."""
    if path.endswith(".csv"):
        return read_csv_table(path)
    with open_run(path) as f:
        return table(f, "sff")


def _core():
    """The compiled module, imported only where a snapshot is read: the scripts that use the rest
    run from the source tree, which has none."""
    try:
        from sffcal import _core
    except ImportError as error:
        raise ImportError("reading snapshots needs the compiled module sffcal._core: put "
                          f"BUILD/python on PYTHONPATH or install the package (docs/python.md); "
                          f"{error}") from error
    return _core


def num_snapshots(path):
    """The number of snapshots of a run file."""
    return _core().num_snapshots(path)


def read_snapshot(path, index):
    """Snapshot `index` (0 first) of a run file, checked as every reader of the project checks it:
    a dict of step, time, axial_strain and the structured arrays contacts (sffcal.sff's
    CONTACT_DTYPE), particles, walls, and spheres (n, 4: x, y, z, radius [m]), sphere_body.
    IndexError for a snapshot the file does not hold; RuntimeError naming what is wrong with one."""
    return _core().read_snapshot(path, index)


def snapshot_input(path, index):
    """The arguments of sffcal.sff.analyse for snapshot `index`, as `sffcal sff` builds them (the
    box and wall stress from the walls, the solid volume from the clumps' spheres, E and mu from
    /physics, the centroids): sff.analyse(**snapshot_input(path, k)) gives what `sffcal sff`
    stores for that snapshot."""
    return _core().snapshot_input(path, index)


def end_window(axial_strain, width=0.05):
    """The rows over the last `width` of axial strain (the end of a test: its critical-state
    estimate in the reports), as a boolean mask; |axial strain|, so extension alike. The rule of
    the C++ side's sffcal::final_window_start (common/include/sffcal/final_window.h)."""
    strain = np.abs(axial_strain)
    return strain[-1] - strain <= width
