#!/usr/bin/env python3
"""Generated bad input (issue 17, point 6): malformed TOML configs, CSV packings, JSON parameter
files and run files, each given to the sffcal command that reads it.

Every case must end in one of two ways, within the time limit:
  - refused: exit status 1 and a last line "sffcal: error: ..." (or CLI11's usage error) that is
    not a bare library exception (map::at, bad_alloc, std::..., stod, vector, basic_string);
  - accepted: exit status 0, and what was written holds no NaN or inf (`sffcal info` on it).
Never a signal (crash, abort, sanitizer), never a time-out, and the inputs are left as they were
(except the run file a command is asked to update: `sff`, `--resume`).
A mutation that leaves a valid config asking for the defaults' long run (1000 clumps, 45 % of
strain) is not bad input and is drawn again. The mutations are drawn with a seed that is printed; a failing case is kept in the work folder
with its command (rerun with --keep FOLDER).

Usage: fuzz_inputs.py SFFCAL [--cases N] [--seed S] [--timeout SECONDS] [--keep FOLDER]
"""
import argparse
import hashlib
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import tomllib

import h5py
import numpy as np

# Values put where a number, a string or a table was (TOML spellings).
TOML_VALUES = ["nan", "inf", "-inf", "-1", "0", "1e400", "-1e400", "1e-320", "-0.0",
               "9223372036854775807", "99999999999999999999", '"text"', '""', "true",
               "[1, 2]", "{}", "0x10", "1_0", "", "1e9", "2", "0.5", "'x'", "1979-05-27"]
JSON_VALUES = ["NaN", "Infinity", "1e400", "-1e400", "-1", "0", "1e-320", "1e308", '"text"',
               "null", "[]", "{}", "true", "", "-0.0", "2", "0.5", "9223372036854775807"]
CSV_CELLS = ["nan", "inf", "-1", "0", "1e400", "5e-05abc", "6e-05 7e-05", "", "x", "1e-320",
             "1e3", "-1e-3", "0x10", "+", "1e", "  ", "1,2"]
LIBRARY_MARKERS = ["map::at", "bad_alloc", "std::", "stod", "stoi", "vector::", "basic_string",
                   "what()", "terminate called", "Assertion", "Sanitizer", "runtime error:"]


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def garbage(rng):
    alphabet = [chr(c) for c in range(32, 127)] + ["\n", "\t", "\r", "\x00", "\x7f", "\xff",
                                                   "\u00e9", "\ufffd", "[", "]", "=", '"', "#"]
    return "".join(rng.choice(alphabet) for _ in range(rng.randint(1, 12)))


def mutate_text(rng, text, values, key_pattern):
    """One to three edits of a key-value text: a value replaced, a line deleted, duplicated or
    truncated, a key misspelt, garbage inserted."""
    lines = text.split("\n")
    for _ in range(rng.randint(1, 3)):
        op = rng.randrange(6)
        keyed = [i for i, line in enumerate(lines) if re.match(key_pattern, line)]
        if op == 0 and keyed:
            i = rng.choice(keyed)
            lines[i] = re.sub(key_pattern + r"(.*?)(\s*[,#].*)?$",
                              lambda m: m.group(1) + rng.choice(values) + (m.group(3) or ""),
                              lines[i], count=1)
        elif op == 1 and lines:
            del lines[rng.randrange(len(lines))]
        elif op == 2 and lines:
            i = rng.randrange(len(lines))
            lines.insert(i, lines[i])
        elif op == 3 and keyed:
            i = rng.choice(keyed)
            lines[i] = re.sub(r"(\w+)", lambda m: m.group(1) + "x", lines[i], count=1)
        elif op == 4:
            joined = "\n".join(lines)
            lines = joined[:rng.randrange(len(joined) + 1)].split("\n")
        else:
            i = rng.randrange(len(lines) + 1)
            lines.insert(i, garbage(rng))
    return "\n".join(lines)


def asks_for_a_long_run(text):
    """A mutated config that is still valid TOML but (a line or a table cut away, a value
    raised) falls back to the defaults' 1000 clumps, 2e6 compaction steps or 45 % of strain, or
    asks for as much, is a user's long run, not bad input: such draws are redrawn. A value of the
    wrong type is bad input and stays."""
    try:
        config = tomllib.loads(text)
    except (tomllib.TOMLDecodeError, UnicodeError, ValueError):
        return False
    def long(table, key, limit, valid_below):
        value = config.get(table, {}).get(key) if table else config.get(key)
        if value is None:
            return True  # the default's
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            return False
        return limit < value < valid_below
    return (long(None, "bodies", 100, 1e7 + 1) or long("preparation", "max_steps", 1e5, 1e19)
            or long("triaxial", "max_axial_strain", 0.01, 0.9))


def mutate_csv(rng, text):
    lines = text.split("\n")
    for _ in range(rng.randint(1, 3)):
        op = rng.randrange(5)
        data = [i for i, line in enumerate(lines) if line and not line.startswith("#")
                and not line.startswith("x,")]
        if op == 0 and data:
            i = rng.choice(data)
            cells = lines[i].split(",")
            cells[rng.randrange(len(cells))] = rng.choice(CSV_CELLS)
            lines[i] = ",".join(cells)
        elif op == 1 and data:
            i = rng.choice(data)
            cells = lines[i].split(",")
            lines[i] = ",".join(cells[:rng.randrange(len(cells))] if rng.random() < 0.5
                                else cells + ["1"] * rng.randint(1, 3))
        elif op == 2:
            box = [i for i, line in enumerate(lines) if line.startswith("# box:")]
            if box:
                words = lines[box[0]].split()
                k = rng.randrange(2, len(words))
                words[k] = rng.choice(CSV_CELLS + ["-1e-3", "1e-9"])
                lines[box[0]] = " ".join(words)
        elif op == 3 and lines:
            del lines[rng.randrange(len(lines))]
        else:
            lines.insert(rng.randrange(len(lines) + 1), garbage(rng))
    return "\n".join(lines)


def mutate_run_file(rng, path):
    """Edits a copy of a run file as a tool or a hand could: a dataset deleted, shortened,
    re-typed or given a non-finite value; an attribute deleted or given another value."""
    with h5py.File(path, "r+") as f:
        datasets, groups = [], []
        f.visititems(lambda name, obj: (datasets if isinstance(obj, h5py.Dataset) else groups)
                     .append(name))
        for _ in range(rng.randint(1, 2)):
            op = rng.randrange(6)
            names = [d for d in datasets if d in f]
            if op == 0 and names:
                del f[rng.choice(names)]
            elif op == 1 and names:
                name = rng.choice(names)
                data = f[name][()]
                del f[name]
                f[name] = data[:rng.randrange(len(data))] if data.ndim and len(data) else data
            elif op == 2 and names:
                name = rng.choice(names)
                data = f[name][()]
                if data.dtype.kind == "f" and data.size:
                    flat = data.reshape(-1)
                    flat[rng.randrange(flat.size)] = rng.choice([np.nan, np.inf, -1e300, 0.0])
                    f[name][...] = flat.reshape(data.shape)
                elif data.dtype.names and data.size:
                    field = rng.choice(data.dtype.names)
                    values = data[field].reshape(len(data), -1)
                    bad = ([np.nan, -1.0, 1e9] if values.dtype.kind == "f"
                           else [-1, 10 ** 9, np.iinfo(values.dtype).max])
                    values[rng.randrange(len(data))] = rng.choice(bad)
                    data[field] = values.reshape(data[field].shape)
                    f[name][...] = data
            elif op == 3 and names:
                name = rng.choice(names)
                shape = f[name].shape
                del f[name]
                f[name] = (np.zeros(shape, dtype="int8") if rng.random() < 0.5
                           else np.array([b"text"] * max(1, shape[0] if shape else 1)))
            else:
                owners = [f] + [f[g] for g in groups if g in f] + [f[d] for d in names]
                owner = rng.choice(owners)
                if len(owner.attrs):
                    key = rng.choice(list(owner.attrs))
                    if op == 4:
                        del owner.attrs[key]
                    else:
                        owner.attrs[key] = rng.choice([np.nan, -1, 99, "text", np.int64(3),
                                                       "[broken\n", 1e300])


class Fuzz:
    def __init__(self, sffcal, timeout):
        self.sffcal, self.timeout = sffcal, timeout
        self.failures, self.cases, self.refused, self.accepted = 0, 0, 0, 0

    def run(self, label, command, inputs, outputs, updated=()):
        """Runs one case and judges it (docstring at the top)."""
        self.cases += 1
        before = {p: digest(p) for p in inputs if os.path.isfile(p) and p not in updated}
        try:
            result = subprocess.run(command, capture_output=True, text=True, errors="replace",
                                    timeout=self.timeout)
        except subprocess.TimeoutExpired:
            return self.fail(label, command, f"no answer within {self.timeout} s")
        tail = (result.stderr.strip().splitlines() or [""])[-1]
        if result.returncode < 0 or result.returncode > 1:
            return self.fail(label, command, f"exit status {result.returncode}: {tail}")
        changed = [p for p, h in before.items() if digest(p) != h]
        if changed:
            return self.fail(label, command, f"an input was changed: {changed}")
        if result.returncode == 1:
            if not (tail.startswith("sffcal: error:") or "Run with --help" in result.stderr):
                return self.fail(label, command, f"refused without a message: {tail!r}")
            if any(marker in tail for marker in LIBRARY_MARKERS):
                return self.fail(label, command, f"a library's message, not ours: {tail}")
            self.refused += 1
            return
        for output in outputs:
            if os.path.isfile(output):
                info = subprocess.run([self.sffcal, "info", output], capture_output=True,
                                      text=True, errors="replace", timeout=self.timeout)
                if info.returncode != 0 or re.search(r"\b(-?nan|-?inf)\b", info.stdout):
                    return self.fail(label, command, f"accepted, but {output} reads as: "
                                     f"{(info.stdout + info.stderr).strip()[-300:]}")
        self.accepted += 1

    def fail(self, label, command, why):
        self.failures += 1
        print(f"FAIL {label}: {why}\n     command: {' '.join(command)}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sffcal")
    parser.add_argument("--cases", type=int, default=120, help="cases in all, a quarter per kind")
    parser.add_argument("--seed", type=int, default=11)
    parser.add_argument("--timeout", type=float, default=60.0, help="per command [s]")
    parser.add_argument("--keep", help="work in this folder and keep it")
    args = parser.parse_args()
    sffcal = os.path.abspath(args.sffcal)
    examples = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples")
    work = args.keep or tempfile.mkdtemp(prefix="sffcal-fuzz-")
    os.makedirs(work, exist_ok=True)
    os.chdir(work)
    rng = random.Random(args.seed)
    fuzz = Fuzz(sffcal, args.timeout)
    print(f"fuzz_inputs: seed {args.seed}, {args.cases} cases, in {work}")

    # The valid inputs the mutations start from: a small, short scene (any valid mutation ends
    # quickly: max_steps bounds the preparation, max_axial_strain the test).
    subprocess.run([sffcal, "config", "-o", "base.toml"], check=True, stdout=subprocess.DEVNULL)
    with open("base.toml") as f:
        config = f.read()
    for key, value in {"bodies": "40", "threads": "1", "max_steps": "20000",
                       "max_axial_strain": "0.006", "output_strain_interval": "0.001",
                       "checkpoint_strain_interval": "0.001",
                       "snapshot_strain_interval": "0.002"}.items():
        config = re.sub(rf"(?m)^{key} = \S+", f"{key} = {value}", config)
    with open("small.toml", "w") as f:
        f.write(config)
    subprocess.run([sffcal, "dem", "-c", "small.toml", "-o", "run.h5"], check=True,
                   stdout=subprocess.DEVNULL)
    subprocess.run([sffcal, "sff", "run.h5"], check=True, stdout=subprocess.DEVNULL)
    packing = ["# a valid packing: a loose lattice of clumps",
               "# box: 0 0 0 6e-4 6e-4 6e-4", "x,y,z,axis_x,axis_y,axis_z,diameter"]
    for i in range(3):
        for j in range(3):
            for k in range(3):
                packing.append(f"{1.2e-4 + 1.8e-4 * i:.6g},{1.2e-4 + 1.8e-4 * j:.6g},"
                               f"{1.2e-4 + 1.8e-4 * k:.6g},0,0.6,0.8,5e-05")
    packing = "\n".join(packing) + "\n"
    with open(os.path.join(examples, "acst_toyoura.json")) as f:
        parameters = f.read()

    kinds = ["toml", "csv", "json", "run"]
    for case in range(args.cases):
        kind = kinds[case % len(kinds)]
        folder = f"case{case:04d}_{kind}"
        os.makedirs(folder)
        label = f"case {case} ({kind})"
        if kind == "toml":
            path = os.path.join(folder, "config.toml")
            text = mutate_text(rng, config, TOML_VALUES, r"^(\s*\w+\s*=\s*)")
            while asks_for_a_long_run(text):
                text = mutate_text(rng, config, TOML_VALUES, r"^(\s*\w+\s*=\s*)")
            with open(path, "w", errors="surrogateescape") as f:
                f.write(text)
            out = os.path.join(folder, "run.h5")
            fuzz.run(label, [sffcal, "dem", "-c", path, "-o", out], [path],
                     [out, out + ".specimen.h5"])
        elif kind == "csv":
            csv_path = os.path.join(folder, "packing.csv")
            with open(csv_path, "w", errors="surrogateescape") as f:
                f.write(mutate_csv(rng, packing))
            path = os.path.join(folder, "config.toml")
            with open(path, "w") as f:
                f.write(re.sub(r'(?m)^method = "compaction"', 'method = "csv"',
                               re.sub(r'(?m)^csv = ""', f'csv = "{os.path.abspath(csv_path)}"',
                                      config)))
            out = os.path.join(folder, "specimen.h5")
            fuzz.run(label, [sffcal, "prepare", "-c", path, "-o", out], [path, csv_path], [out])
        elif kind == "json":
            path = os.path.join(folder, "parameters.json")
            with open(path, "w", errors="surrogateescape") as f:
                f.write(mutate_text(rng, parameters, JSON_VALUES, r'^(\s*"\w+"\s*:\s*)'))
            fuzz.run(label, [sffcal, "fe-check", "--parameters", path, "--no-mesh",
                             "--pressures", "100000", "--steps", "10", "--max-strain", "0.02",
                             "-o", os.path.join(folder, "fe")], [path], [])
        else:
            path = os.path.join(folder, "run.h5")
            shutil.copy("run.h5", path)
            mutate_run_file(rng, path)
            command = rng.choice(["info", "sff", "resume", "vtk", "calibrate"])
            if command == "info":
                argv = [sffcal, "info", path]
            elif command == "sff":
                argv = [sffcal, "sff", path]
            elif command == "resume":
                argv = [sffcal, "triaxial", "-o", path, "--resume"]
            elif command == "vtk":
                argv = [sffcal, "vtk", path, "-o", os.path.join(folder, "vtk")]
            else:
                argv = [sffcal, "calibrate", path, "--stages", "csl", "-o",
                        os.path.join(folder, "calibration")]
            fuzz.run(f"{label} {command}", argv, [path], [], updated=[path])
    print(f"fuzz_inputs: {fuzz.cases} cases: {fuzz.refused} refused by name, {fuzz.accepted} "
          f"accepted with finite output, {fuzz.failures} failed")
    if not args.keep:
        os.chdir("/")
        shutil.rmtree(work)
    return 1 if fuzz.failures else 0


if __name__ == "__main__":
    sys.exit(main())
