#!/usr/bin/python3
"""The lateral servo and the time step (issue 16): shears specimens of several sizes and
densities at several strain rates, time-step safety factors and servo laws, and tabulates the
worst lateral stress error |sigma_wall - sigma_3| / sigma_3 after the first 0.5 % of axial strain.

usage: run_servo_sweep.py OUT [--sizes 1000,4000] [--densities dense,loose] [--rates 20,100]
                          [--safeties 0.3,0.5,0.7,1.0] [--integral-times 10,0]
                          [--max-strain 0.03] [--jobs 2] [--sffcal build/sffcal]

Specimens (OUT/spec/DENSITY_SIZE.h5, 100 kPa, dense: compaction friction 0.15, loose: 0.5) are
prepared when missing; each run shears one on one thread with `sffcal triaxial` (series row every
0.05 %). An integral time of 0 is the purely proportional servo of the earlier versions, at the
same time step. A finished run is not redone. The table goes to stdout and OUT/table.md.
"""
import argparse
import os
import subprocess
import sys
import time
from multiprocessing import Pool

from make_config import config_text
from sffcal.runfile import read_csv_table

AFTER_STRAIN = 0.005  # the target holds after the first 0.5 % of axial strain


def run(job):
    """Shears one specimen (prepared before the pool starts) unless the run exists; returns its
    name."""
    out, sffcal, name, spec, text = job
    series = os.path.join(out, "runs", name + ".h5.series.csv")
    if os.path.exists(series):
        return name
    cfg = os.path.join(out, "runs", name + ".toml")
    with open(cfg, "w") as f:
        f.write(text)
    start = time.time()
    with open(os.path.join(out, "runs", name + ".log"), "w") as log:
        rc = subprocess.run([sffcal, "triaxial", "-c", cfg, "-s", spec, "-o",
                             os.path.join(out, "runs", name + ".h5"), "--force"],
                            stdout=log, stderr=subprocess.STDOUT).returncode
    with open(os.path.join(out, "runs", name + ".seconds"), "w") as f:
        f.write(f"{time.time() - start:.2f} {rc}\n")
    return name


def measures(out, name):
    path = os.path.join(out, "runs", name + ".h5.series.csv")
    if not os.path.exists(path):
        return None
    series = read_csv_table(path)
    errors = series["lateral_stress_error"][series["axial_strain"] > AFTER_STRAIN]
    steps = series["step"][-1] - series["step"][0]
    t = series["time"][-1] - series["time"][0]
    with open(os.path.join(out, "runs", name + ".seconds")) as f:
        seconds = f.read().split()[0]
    return {
        "worst": float(errors.max()), "mean": float(errors.mean()),
        "peak": float(series["eta"].max()), "steps": int(steps),
        "dt": t / steps if steps else 0.0, "seconds": float(seconds),
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--sizes", default="1000,4000")
    ap.add_argument("--densities", default="dense,loose")
    ap.add_argument("--rates", default="20,100")
    ap.add_argument("--safeties", default="0.3,0.5,0.7,1.0")
    ap.add_argument("--integral-times", default="10,0")
    ap.add_argument("--max-strain", type=float, default=0.03)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--sffcal", default="build/sffcal")
    a = ap.parse_args()
    os.makedirs(os.path.join(a.out, "spec"), exist_ok=True)
    os.makedirs(os.path.join(a.out, "runs"), exist_ok=True)
    sizes = [int(s) for s in a.sizes.split(",")]
    densities = a.densities.split(",")
    for n in sizes:
        for d in densities:
            spec = os.path.join(a.out, "spec", f"{d}_{n}.h5")
            if not os.path.exists(spec):
                cfg = spec[:-3] + ".toml"
                with open(cfg, "w") as f:
                    f.write(config_text(a.sffcal, n, d, 100.0))
                print(f"preparing {spec}", flush=True)
                subprocess.run([a.sffcal, "prepare", "-c", cfg, "-o", spec], check=True,
                               stdout=subprocess.DEVNULL)
    jobs, names = [], []
    for n in sizes:
        for d in densities:
            spec = os.path.join(a.out, "spec", f"{d}_{n}.h5")
            for rate in [float(r) for r in a.rates.split(",")]:
                for safety in [float(s) for s in a.safeties.split(",")]:
                    for it in [float(t) for t in a.integral_times.split(",")]:
                        name = f"{d}_{n}_rate{rate:g}_safety{safety:g}_it{it:g}"
                        text = config_text(a.sffcal, n, d, rate, safety, a.max_strain,
                                           {"servo_integral_time": str(it)})
                        jobs.append((a.out, a.sffcal, name, spec, text))
                        names.append((name, n, d, rate, safety, it))
    # Largest first, so the pool ends together.
    order = sorted(range(len(jobs)), key=lambda k: -names[k][1] / names[k][3] / names[k][4])
    with Pool(a.jobs) as pool:
        for done in pool.imap_unordered(run, [jobs[k] for k in order]):
            print("done", done, flush=True)
    lines = ["| clumps | specimen | rate [1/s] | safety | servo | time step [s] | steps | "
             "wall s | peak q/p | worst lateral error after 0.5 % [%] | mean [%] |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, n, d, rate, safety, it in names:
        m = measures(a.out, name)
        servo = f"PI, T_i = {it:g} dt_c" if it > 0 else "P only (T_i = 0)"
        if m is None:
            lines.append(f"| {n} | {d} | {rate:g} | {safety:g} | {servo} | failed | | | | | |")
            continue
        lines.append(f"| {n} | {d} | {rate:g} | {safety:g} | {servo} | {m['dt']:.3g} | "
                     f"{m['steps']} | {m['seconds']:.0f} | {m['peak']:.3f} | "
                     f"{100 * m['worst']:.2f} | {100 * m['mean']:.2f} |")
    table = "\n".join(lines) + "\n"
    with open(os.path.join(a.out, "table.md"), "w") as f:
        f.write(table)
    sys.stdout.write(table)


if __name__ == "__main__":
    main()
