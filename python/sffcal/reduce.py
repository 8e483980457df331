"""A reduced copy of a run file: what `sffcal calibrate`, `sffcal fe-check` and the reports read,
without the snapshots and the checkpoint (docs/reference-data.md)."""
import os

import h5py


def reduce(source, target, by):
    """Copies the root attributes (config, seed, program version, notes), /physics, /loading,
    /summary, the whole /series (compressed) and every /analysis table of `source` into `target`,
    and records the source in the root note `note:reduction` (`by`: the program that reduced it).
    `sffcal sff` cannot re-analyse the copy (no snapshots)."""
    with h5py.File(source, "r") as src, h5py.File(target, "w") as dst:
        for key, value in src.attrs.items():
            dst.attrs[key] = value
        for group in ("physics", "loading", "summary", "analysis"):
            if group in src:  # schema 1 has none of /physics, /loading, /summary
                src.copy(src[group], dst, group)
        # The series compressed: a run file's series chunks are not (they are appended to while
        # the run may be killed, docs/run-file.md); a reduced file is written once.
        series = dst.create_group("series")
        for key, value in src["series"].attrs.items():
            series.attrs[key] = value
        for name, column in src["series"].items():
            series.create_dataset(name, data=column[()], maxshape=(None,), chunks=True,
                                  shuffle=True, compression="gzip", compression_opts=4)
        snapshots = len(src["snapshots"]) if "snapshots" in src else 0
        dst.attrs["note:reduction"] = (f"reduced by {by} from {os.path.basename(source)}: /series and "
                                       f"/analysis kept; {snapshots} snapshots and the checkpoint left out")
