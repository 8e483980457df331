#!/usr/bin/python3
"""Run time against error (issue 8): shears the same small specimens with one knob changed at a
time and records each run's wall-clock time and its measures, for summarise.py to compare with
a converged reference.

usage: run_sweep.py OUT [--jobs J] [--sffcal PATH] [--only SUBSTRING[,SUBSTRING...]] [--list]

Specimens: SEEDS dense specimens (compaction friction 0.15, p'0 = 100 kPa) of BODIES two-sphere
clumps (300, or the environment's SWEEP_BODIES, read by summarise.py too), prepared once per seed
(and once per seed for the clump-number cases). Each case shears every seed's specimen to 30 % axial strain with `sffcal triaxial` on one thread and analyses it
with `sffcal sff` (no bootstrap). A case is one dictionary of config keys over BASE; REFERENCE is
the converged setting (fine step, slow loading). Runs are claimed with an exclusive lock file,
so several copies of this script (on one machine or sharing a folder) split the work, and a
finished run is never redone: the sweep can be interrupted and restarted (with --reclaim, once
no copy is running, to free the claims of the runs that were cut off).
"""
import argparse
import os
import subprocess
import sys
import time
from multiprocessing import Pool

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
SEEDS = (1, 2, 3)
BODIES = int(os.environ.get("SWEEP_BODIES", "300"))  # the specimens' size (summarise.py reads it too)
MAX_STRAIN = 0.30

# The base case: the settings examples/quick_triaxial.toml had in issue 8 (then the engine defaults; rate
# 50 /s where the config default is the paper's 20 /s, case rate_20; a snapshot every 1 % of axial
# strain instead of 5 %, so that a_c at the peak is resolved), written out in full.
BASE = {
    "engine.time_step_safety": 0.2,
    "engine.density_scaling": 1.0,
    "engine.local_damping": 0.0,
    "engine.skin_ratio": 0.1,
    "triaxial.strain_rate": 50.0,
    "triaxial.output_strain_interval": 0.002,
    "triaxial.snapshot_strain_interval": 0.01,
    "bodies": BODIES,
}
# The converged setting. Since issue 50 the critical step is leapfrog's limit 2/omega_max, about 1.9
# times the per-body estimate of issues 8 and 16, whose reference was 0.1 of it: 0.05 is that step.
REFERENCE = {"engine.time_step_safety": 0.05, "triaxial.strain_rate": 20.0,
             "triaxial.output_strain_interval": 0.001, "triaxial.snapshot_strain_interval": 0.005}

# name -> keys changed from BASE. One knob at a time, then the candidate presets.
CASES = {
    "reference": REFERENCE,
    "base": {},
    "safety_0.1": {"engine.time_step_safety": 0.1},
    "safety_0.35": {"engine.time_step_safety": 0.35},
    "safety_0.5": {"engine.time_step_safety": 0.5},
    "safety_0.7": {"engine.time_step_safety": 0.7},
    "rate_20": {"triaxial.strain_rate": 20.0},
    "rate_100": {"triaxial.strain_rate": 100.0},
    "rate_200": {"triaxial.strain_rate": 200.0},
    "rate_400": {"triaxial.strain_rate": 400.0},
    "scaling_10": {"engine.density_scaling": 10.0},
    "scaling_100": {"engine.density_scaling": 100.0},
    "damping_0.1": {"engine.local_damping": 0.1},
    "damping_0.3": {"engine.local_damping": 0.3},
    "damping_0.7": {"engine.local_damping": 0.7},
    "skin_0.05": {"engine.skin_ratio": 0.05},
    "skin_0.3": {"engine.skin_ratio": 0.3},
    "output_fine": {"triaxial.output_strain_interval": 0.0005, "triaxial.snapshot_strain_interval": 0.0025},
    "output_coarse": {"triaxial.output_strain_interval": 0.01, "triaxial.snapshot_strain_interval": 0.05},
    "bodies_150": {"bodies": 150},
    "bodies_600": {"bodies": 600},
    # Combinations, chosen after the one-knob cases (bench/RESULTS.md "Run time against error").
    "combo_rate100_safety0.35": {"triaxial.strain_rate": 100.0, "engine.time_step_safety": 0.35},
    "combo_rate200_safety0.5": {"triaxial.strain_rate": 200.0, "engine.time_step_safety": 0.5},
    "combo_rate400_safety0.7": {"triaxial.strain_rate": 400.0, "engine.time_step_safety": 0.7},
    # Issue 16: the stiffness-based critical step and the PI servo; the default's rate (100 /s)
    # at the safety factors the new estimate allows.
    "safety_1.0": {"engine.time_step_safety": 1.0},
    "combo_rate100_safety0.5": {"triaxial.strain_rate": 100.0, "engine.time_step_safety": 0.5},
    "combo_rate100_safety0.7": {"triaxial.strain_rate": 100.0, "engine.time_step_safety": 0.7},
    "combo_rate100_safety1.0": {"triaxial.strain_rate": 100.0, "engine.time_step_safety": 1.0},
    "combo_rate200_safety1.0": {"triaxial.strain_rate": 200.0, "engine.time_step_safety": 1.0},
}
# Issue 50: safety of the stability limit 2/omega_max, at the paper's rate and the default's.
CASES.update({f"i50_rate{rate}_safety{safety}": {"triaxial.strain_rate": float(rate),
                                                 "engine.time_step_safety": safety}
              for rate in (20, 100) for safety in (0.5, 0.7, 0.85, 1.0)})


def case_keys(name):
    keys = dict(BASE)
    keys.update(CASES[name])
    return keys


def toml_value(value):
    return repr(value) if isinstance(value, (int, float)) else f'"{value}"'


def write_config(path, seed, keys):
    """A complete-enough config: everything not named keeps the project's default."""
    sections = {"": [f"seed = {seed}", "threads = 1", f"bodies = {keys['bodies']}"],
                "preparation": ["pressure = 1.0e5", "compaction_friction = 0.15"],
                "triaxial": [f"max_axial_strain = {MAX_STRAIN}", "checkpoint_strain_interval = 1.0",
                             "critical_min_strain = 1.0"],
                "engine": []}
    for key, value in keys.items():
        if "." in key:
            section, name = key.split(".")
            sections[section].append(f"{name} = {toml_value(value)}")
    with open(path, "w") as f:
        for section, lines in sections.items():
            if section:
                f.write(f"[{section}]\n")
            f.write("\n".join(lines) + "\n")


def run(command, log):
    with open(log, "a") as f:
        f.write("$ " + " ".join(command) + "\n")
        f.flush()
        return subprocess.run(command, stdout=f, stderr=subprocess.STDOUT).returncode


def claim(path):
    try:
        os.close(os.open(path, os.O_CREAT | os.O_EXCL | os.O_WRONLY))
        return True
    except FileExistsError:
        return False


def specimen(out, sffcal, seed, bodies):
    """Prepared once; a concurrent claimant waits for the file."""
    path = os.path.join(out, "specimens", f"n{bodies}_seed{seed}.h5")
    if claim(path + ".claim"):
        config = path.replace(".h5", ".toml")
        write_config(config, seed, dict(BASE, bodies=bodies))
        if run([sffcal, "prepare", "-c", config, "-o", path + ".part", "--force"], path + ".log") != 0:
            sys.exit(f"preparing {path} failed: see {path}.log")
        os.replace(path + ".part", path)
    while not os.path.exists(path):
        time.sleep(5)
    return path


def shear(task):
    out, sffcal, name, seed = task
    stem = os.path.join(out, "runs", f"{name}_seed{seed}")
    if os.path.exists(stem + ".time") or not claim(stem + ".claim"):
        return f"{name} seed {seed}: done or taken"
    keys = case_keys(name)
    spec = specimen(out, sffcal, seed, keys["bodies"])
    write_config(stem + ".toml", seed, keys)
    for leftover in (stem + ".h5", stem + ".log"):
        if os.path.exists(leftover):
            os.remove(leftover)
    start = time.time()
    code = run([sffcal, "triaxial", "-c", stem + ".toml", "-s", spec, "-o", stem + ".h5"], stem + ".log")
    seconds = time.time() - start
    if code == 0:
        code = run([sffcal, "sff", stem + ".h5", "--resamples", "0"], stem + ".log")
    with open(stem + ".time", "w") as f:
        f.write(f"{seconds:.2f} {code}\n")
    return f"{name} seed {seed}: {'ok' if code == 0 else 'FAILED'} in {seconds:.0f} s"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out")
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--sffcal", default=os.path.join(ROOT, "build", "sffcal"))
    parser.add_argument("--only", default="")
    parser.add_argument("--seeds", default=",".join(map(str, SEEDS)),
                        help="comma-separated seeds (default: %(default)s); more seeds for some cases tighten "
                             "their errors (summarise.py pairs every case with the reference seed by seed)")
    parser.add_argument("--list", action="store_true")
    parser.add_argument("--reclaim", action="store_true", help="drop the claims of unfinished runs first")
    args = parser.parse_args()
    names = [n for n in CASES if any(part in n for part in args.only.split(","))]
    if args.list:
        print("\n".join(names))
        return
    for folder in ("specimens", "runs"):
        os.makedirs(os.path.join(args.out, folder), exist_ok=True)
    if args.reclaim:
        for folder in ("specimens", "runs"):
            path = os.path.join(args.out, folder)
            for f in os.listdir(path):
                # a run's claim is STEM.claim, done at STEM.time; a specimen's is FILE.h5.claim
                done = f[:-len(".claim")] + (".time" if folder == "runs" else "")
                if f.endswith(".claim") and not os.path.exists(os.path.join(path, done)):
                    os.remove(os.path.join(path, f))
    seeds = [int(s) for s in args.seeds.split(",")]
    tasks = [(args.out, os.path.abspath(args.sffcal), name, seed) for name in names for seed in seeds]
    print(f"{len(tasks)} runs ({len(names)} cases x seeds {seeds}), {args.jobs} at a time", flush=True)
    with Pool(args.jobs) as pool:
        for line in pool.imap_unordered(shear, tasks):
            print(time.strftime("%H:%M:%S"), line, flush=True)


if __name__ == "__main__":
    main()
