#!/usr/bin/python3
"""Writes one config of the servo and time-step sweep (issue 16) from the default configuration.

usage: make_config.py OUT.toml BODIES DENSITY RATE [SAFETY] [--sffcal PATH] [--max-strain E]
                      [--set KEY=VALUE ...]

DENSITY is "dense" (compaction friction 0.15) or "loose" (0.5); RATE the axial strain rate [1/s];
SAFETY the time-step safety factor (default: the engine's). p'0 = sigma_3 = 100 kPa, one thread,
sheared to 5 % axial strain with a series row every 0.05 %, no snapshots but the first and last;
--set changes any other key of the default config.
"""
import argparse
import functools
import subprocess

COMPACTION_FRICTION = {"dense": 0.15, "loose": 0.5}


@functools.lru_cache(maxsize=None)
def default_config(sffcal):
    """`sffcal config`, asked once per executable."""
    return subprocess.run([sffcal, "config"], check=True, capture_output=True, text=True).stdout


def config_text(sffcal, bodies, density, rate, safety=None, max_strain=0.05, extra=None):
    """The default config with the sweep's settings (and `extra` key -> value) written in."""
    text = default_config(sffcal)
    changes = {
        "threads": "1", "bodies": str(bodies),
        "compaction_friction": str(COMPACTION_FRICTION[density]),
        "strain_rate": str(rate), "max_axial_strain": str(max_strain),
        "output_strain_interval": "0.0005", "snapshot_strain_interval": "1.0",
        "checkpoint_strain_interval": "1.0",
    }
    if safety is not None:
        changes["time_step_safety"] = str(safety)
    changes.update(extra or {})
    lines = []
    for line in text.splitlines():
        key = line.split("=")[0].strip()
        if key in changes and "=" in line:
            line = f"{key} = {changes.pop(key)}"
        lines.append(line)
    if changes:
        raise SystemExit(f"keys not in the default config: {sorted(changes)}")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("bodies", type=int)
    ap.add_argument("density", choices=sorted(COMPACTION_FRICTION))
    ap.add_argument("rate", type=float)
    ap.add_argument("safety", type=float, nargs="?")
    ap.add_argument("--sffcal", default="build/sffcal")
    ap.add_argument("--max-strain", type=float, default=0.05)
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    a = ap.parse_args()
    extra = {}
    for item in a.set:
        key, sep, value = item.partition("=")
        if not sep:
            raise SystemExit(f"--set wants KEY=VALUE, got {item!r}")
        extra[key.strip()] = value.strip()
    with open(a.out, "w") as f:
        f.write(config_text(a.sffcal, a.bodies, a.density, a.rate, a.safety, a.max_strain, extra))


if __name__ == "__main__":
    main()
