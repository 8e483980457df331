#!/usr/bin/env python3
"""A batch of model updates from Python (sffcal.models) against the same loop in C++
(build/bench/model_batch), alternated in one run: the Python call's overhead as a ratio of medians.
Both build the batch of bench/model_batch.cc and must agree on its checksum.

  PYTHONPATH=build/python /usr/bin/python3 bench/python/model_batch.py \\
      --bench build/bench/model_batch --parameters examples/acst_toyoura.json -n 10000 --rounds 9
"""
import argparse
import statistics
import subprocess
import time

import numpy as np

from sffcal import models


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bench", required=True, help="build/bench/model_batch")
    parser.add_argument("--parameters", required=True)
    parser.add_argument("-n", type=int, default=10000, help="points in the batch")
    parser.add_argument("--rounds", type=int, default=9, help="alternations of the two")
    args = parser.parse_args()

    model = models.Model.from_file(args.parameters)
    inputs = {"void_ratio": 0.8} if any(s["name"] == "void_ratio" for s in model.input_layout) else None
    stress0, state0 = model.initial_state(100e3, inputs)
    k = np.arange(args.n)
    a = 1e-4 * (1.0 + (k % 97) / 97.0)
    increments = np.zeros((args.n, 3, 3))
    increments[:, 0, 0] = increments[:, 1, 1] = -0.5 * a
    increments[:, 2, 2] = a
    stress = np.repeat(stress0[None], args.n, 0)
    state = np.repeat(state0[None], args.n, 0)

    python, cpp = [], []
    for _ in range(args.rounds):
        t0 = time.perf_counter()
        out = model.update(stress, state, increments)
        python.append(time.perf_counter() - t0)
        lines = subprocess.run([args.bench, args.parameters, str(args.n), "1"], check=True,
                               capture_output=True, text=True).stdout.split("\n")
        cpp.append(float(lines[0]))
        checksum = float(lines[1].split()[1])
    # Summed in the C++ order, one double after the other: the same batch gives the same bits.
    mine = 0.0
    for x in out["stress"].ravel().tolist():
        mine += x
    if checksum != mine:
        raise SystemExit(f"model_batch: the two batches differ (checksums {checksum} and {mine})")
    ok = int(np.sum(out["status"] == 0))
    print(f"{model.name}, {args.n} points ({ok} ok), {args.rounds} rounds alternated")
    print(f"{'':8} {'min [s]':>10} {'median [s]':>11} {'max [s]':>10} {'us/update':>10}")
    for name, times in (("C++", cpp), ("Python", python)):
        print(f"{name:8} {min(times):10.4f} {statistics.median(times):11.4f} {max(times):10.4f} "
              f"{1e6 * statistics.median(times) / args.n:10.2f}")
    print(f"Python / C++ (medians): {statistics.median(python) / statistics.median(cpp):.3f}")


if __name__ == "__main__":
    main()
