#!/usr/bin/env python3
"""A triaxial run killed (SIGKILL) at random moments loses nothing it had written.

For each kill the run file must (docs/run-file.md, "A killed run"):
  - open in h5py with every dataset and attribute readable;
  - hold, in /series, the uninterrupted run's rows up to its last completed row, bit for bit;
  - be continued by `sffcal triaxial --resume` into the uninterrupted run, bit for bit in every
    dataset (series, snapshots, checkpoint).
Three scenes: fine output (a row every 1e-5 of axial strain, a checkpoint every 2.5e-4, a snapshot
every 5e-4: the file is written almost all the time), coarse output (the defaults' proportions)
and a true triaxial test (its lateral targets set step by step from the axial stress).
The moments are drawn with a seed that is printed; a kill before the file exists, or before its
first checkpoint, is counted separately (resume then refuses by name: nothing to continue).

Usage: kill_test.py SFFCAL [--kills N] [--seed S] [--keep FOLDER]. Exit status 0 when all pass.
"""
import argparse
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

SCENES = {
    "fine": {"max_axial_strain": "0.012", "output_strain_interval": "1e-5", "checkpoint_strain_interval": "2.5e-4",
             "snapshot_strain_interval": "5e-4"},
    "coarse": {"max_axial_strain": "0.04", "output_strain_interval": "1e-3", "checkpoint_strain_interval": "2e-3",
               "snapshot_strain_interval": "5e-3"},
    # a loading path whose lateral targets follow the axial stress step by step (docs/dem.md)
    "true_triaxial": {"path": '"true_triaxial"', "b": "0.5", "max_axial_strain": "0.02",
                      "output_strain_interval": "5e-4", "checkpoint_strain_interval": "2e-3",
                      "snapshot_strain_interval": "5e-3"},
}
COMMON = {"bodies": "150", "threads": "1"}


def write_config(sffcal, path, settings):
    subprocess.run([sffcal, "config", "-o", path], check=True, stdout=subprocess.DEVNULL)
    with open(path) as f:
        text = f.read()
    for key, value in settings.items():
        text, count = re.subn(rf"(?m)^{key} = \S+", f"{key} = {value}", text)
        if count != 1:
            sys.exit(f"kill_test: key {key} found {count} times in the default config")
    with open(path, "w") as f:
        f.write(text)


def read_everything(path):
    """Every dataset's values and every attribute, read through h5py (raises if any fails)."""
    data = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            for key in obj.attrs:
                obj.attrs[key]
            if isinstance(obj, h5py.Dataset):
                data[name] = obj[()]
        for key in f.attrs:
            f.attrs[key]
        f.visititems(visit)
    return data


def completed_rows(data):
    lengths = [len(v) for k, v in data.items() if k.startswith("series/")]
    return min(lengths) if lengths else 0


def run_until(command, moment):
    """Starts command, kills it with SIGKILL after `moment` seconds; True if it was killed."""
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        process.wait(timeout=moment)
        return False
    except subprocess.TimeoutExpired:
        process.send_signal(signal.SIGKILL)
        process.wait()
        return True


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sffcal")
    parser.add_argument("--kills", type=int, default=16, help="kills in all, shared by the scenes")
    parser.add_argument("--seed", type=int, default=17)
    parser.add_argument("--scene", choices=sorted(SCENES), help="only this scene")
    parser.add_argument("--keep", help="work in this folder and keep it")
    args = parser.parse_args()
    sffcal = os.path.abspath(args.sffcal)
    work = args.keep or tempfile.mkdtemp(prefix="sffcal-kill-")
    os.makedirs(work, exist_ok=True)
    os.chdir(work)
    rng = random.Random(args.seed)
    print(f"kill_test: seed {args.seed}, {args.kills} kills, in {work}")

    failures = 0
    tally = {"resumed bit for bit": 0, "before the file": 0, "before the first checkpoint": 0,
             "finished before the kill": 0}
    scenes = {args.scene: SCENES[args.scene]} if args.scene else SCENES
    for scene, settings in scenes.items():
        config = f"{scene}.toml"
        write_config(sffcal, config, {**COMMON, **settings})
        subprocess.run([sffcal, "prepare", "-c", config, "-o", f"{scene}_specimen.h5"],
                       check=True, stdout=subprocess.DEVNULL)
        command = [sffcal, "triaxial", "-c", config, "-s", f"{scene}_specimen.h5"]
        start = time.monotonic()
        subprocess.run(command + ["-o", f"{scene}_reference.h5"], check=True,
                       stdout=subprocess.DEVNULL)
        duration = time.monotonic() - start
        reference = read_everything(f"{scene}_reference.h5")
        print(f"{scene}: uninterrupted run {duration:.2f} s, "
              f"{completed_rows(reference)} rows, {len(reference)} datasets")

        for k in range(args.kills // len(scenes)):
            moment = rng.uniform(0.0, duration)
            run = f"{scene}_killed.h5"
            if os.path.exists(run):
                os.remove(run)
            label = f"{scene} kill {k} at {moment:.3f} s"
            if not run_until(command + ["-o", run], moment):
                tally["finished before the kill"] += 1
                print(f"ok   {label}: the run had finished")
                continue
            if not os.path.exists(run):
                tally["before the file"] += 1
                print(f"ok   {label}: before the run file was created")
                continue
            try:
                killed = read_everything(run)
            except Exception as error:  # noqa: BLE001 (any h5py failure is the finding)
                failures += 1
                print(f"FAIL {label}: h5py cannot read the file: {error}")
                shutil.copy(run, f"{scene}_unreadable_{k}.h5")
                continue
            rows = completed_rows(killed)
            bad = [name for name, values in killed.items() if name.startswith("series/")
                   and not np.array_equal(values[:rows], reference[name][:rows])]
            if bad:
                failures += 1
                print(f"FAIL {label}: the first {rows} rows differ from the reference in {bad}")
                continue
            resume = subprocess.run([sffcal, "triaxial", "-o", run, "--resume"],
                                    capture_output=True, text=True)
            has_checkpoint = any(name.startswith("checkpoint/") for name in killed)
            if not has_checkpoint:
                if resume.returncode != 0 and "no checkpoint" in resume.stderr:
                    tally["before the first checkpoint"] += 1
                    print(f"ok   {label}: {rows} rows, before the first checkpoint "
                          f"(resume refuses by name)")
                else:
                    failures += 1
                    print(f"FAIL {label}: no checkpoint, and resume said: {resume.stderr.strip()}")
                continue
            if resume.returncode != 0:
                failures += 1
                print(f"FAIL {label}: resume failed: {resume.stderr.strip()}")
                continue
            resumed = read_everything(run)
            bad = sorted(name for name in set(resumed) | set(reference)
                         if name not in resumed or name not in reference
                         or not np.array_equal(resumed[name], reference[name]))
            if bad:
                failures += 1
                print(f"FAIL {label}: resumed from {rows} rows, differs in {bad[:6]}")
                continue
            tally["resumed bit for bit"] += 1
            print(f"ok   {label}: {rows} rows readable, resumed bit for bit")

    print("kill_test: " + ", ".join(f"{name} {count}" for name, count in tally.items()) +
          f"; {failures} failed")
    if not args.keep:
        os.chdir("/")
        shutil.rmtree(work)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
