#!/usr/bin/python3
"""Markdown table of the SFF results of several runs, one row per test (sffcal.sff_table).

usage: sff_table.py RUN.h5|RUN.sff.csv [...]

Reads each run's SFF table (/analysis/sff of a run file, or the <run>.sff.csv that `sffcal sff`
writes) and prints: e0, the peak and last stress ratio with a_c, a_n, m, the last void ratio, the worst SFF stress
error, the worst |eta_SFF - eta| / |eta| (|eta| > 0.3) and the worst particle-form-vs-wall stress
difference (the peak: the largest |eta|, an extension test's most negative).
"""
import sys

from sffcal.runfile import RunFileError
from sffcal.sff_table import print_table

if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    try:
        print_table(sys.argv[1:])
    except RunFileError as e:
        sys.exit(str(e))
