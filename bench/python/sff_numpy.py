#!/usr/bin/env python3
"""The SFF analysis of contacts from numpy (sffcal.sff.analyse) against the C++ call alone
(build/bench/sff_numpy on the same records, written raw), alternated in one run: the Python call's
overhead as a ratio of medians. The contacts: seeded random, n of them among n / 2.4 bodies, unit
normals, exponential normal forces, tangential forces of 0.3 of them across the normals.

  PYTHONPATH=build/python /usr/bin/python3 bench/python/sff_numpy.py \\
      --bench build/bench/sff_numpy -n 60000 --rounds 9 -o out/bench_sff_numpy
"""
import argparse
import os
import statistics
import subprocess
import time

import numpy as np

from sffcal import sff


def random_contacts(n, seed):
    rng = np.random.default_rng(seed)
    bodies = int(n / 2.4)
    normal = rng.normal(size=(n, 3))
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    across = np.cross(normal, rng.normal(size=(n, 3)))
    across /= np.linalg.norm(across, axis=1)[:, None]
    fn = rng.exponential(10.0, size=n)
    a = rng.integers(0, bodies, size=n)
    b = (a + rng.integers(1, bodies, size=n)) % bodies
    records = sff.contacts(normal=normal, normal_force=fn, tangential_force=0.3 * fn[:, None] * across,
                           branch=2e-3 * rng.uniform(0.9, 1.1, size=n)[:, None] * normal,
                           body_a=a, body_b=b, sliding=(rng.uniform(size=n) < 0.05).astype(int))
    return records, bodies


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bench", required=True, help="build/bench/sff_numpy")
    parser.add_argument("-n", type=int, default=60000, help="contacts")
    parser.add_argument("--rounds", type=int, default=9, help="alternations of the two")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("-o", "--output", required=True, help="folder for the raw contacts")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)
    records, bodies = random_contacts(args.n, args.seed)
    path = os.path.join(args.output, "contacts.bin")
    records.tofile(path)
    volume, solid, young, mu = 1e-3, 6e-4, 1.5e8, 0.5

    python, cpp = [], []
    for _ in range(args.rounds):
        t0 = time.perf_counter()
        out = sff.analyse(records, volume=volume, solid_volume=solid, num_bodies=bodies,
                          youngs_modulus=young, friction=mu)
        python.append(time.perf_counter() - t0)
        lines = subprocess.run([args.bench, path, str(bodies), repr(volume), repr(solid),
                                repr(young), repr(mu), "1"], check=True, capture_output=True,
                               text=True).stdout.split("\n")
        cpp.append(float(lines[0]))
        if float(lines[1].split()[1]) != out["eta_sff"]:
            raise SystemExit(f"sff_numpy: the two analyses differ ({lines[1]} against "
                             f"{out['eta_sff']!r})")
    threads = os.environ.get("OMP_NUM_THREADS", "the default")
    print(f"{args.n} contacts, {bodies} bodies, seed {args.seed}, OpenMP threads: {threads}; "
          f"{args.rounds} rounds alternated; eta_sff equal bit for bit")
    print(f"{'':8} {'min [s]':>10} {'median [s]':>11} {'max [s]':>10}")
    for name, times in (("C++", cpp), ("Python", python)):
        print(f"{name:8} {min(times):10.4f} {statistics.median(times):11.4f} {max(times):10.4f}")
    print(f"Python / C++ (medians): {statistics.median(python) / statistics.median(cpp):.3f}")


if __name__ == "__main__":
    main()
