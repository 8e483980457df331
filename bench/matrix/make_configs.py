#!/usr/bin/python3
"""Writes the TOML configs of the reference test matrix (issue 7) into a folder: the specimens of
sffcal.matrix (python/sffcal/matrix.py, which describes them).

usage: make_configs.py OUT_FOLDER [--bodies N] [--seed S] [--only NAME_SUBSTRING]
"""
import argparse
import os
import sys

from sffcal.matrix import TEMPLATE, matrix, specimen_config


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("folder")
    parser.add_argument("--bodies", type=int, default=500)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--only", default="")
    args = parser.parse_args()
    os.makedirs(args.folder, exist_ok=True)
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    with open(os.path.join(root, TEMPLATE)) as f:
        template = f.read()
    for name, keys in matrix():
        if args.only not in name:
            continue
        try:
            text = specimen_config(template, name, keys, bodies=args.bodies, seed=args.seed)
        except KeyError as e:
            sys.exit(f"make_configs.py: {e.args[0]}")
        with open(os.path.join(args.folder, f"{name}.toml"), "w") as f:
            f.write(text)
        print(name)


if __name__ == "__main__":
    main()
