#!/usr/bin/env bash
# Makes the seed run file of the structure-aware fuzz targets, fuzz/corpus/tiny_run.h5 (fuzz/README.md):
# a triaxial run of 20 clumps (fuzz/corpus/config/tiny_run.toml over the default config) to 0.6 %
# of axial strain, with two snapshots, a checkpoint, a summary and an SFF table, copied into a
# file of the same layout small enough to commit: datasets contiguous instead of chunked and
# deflated (the series stay extendible, in chunks of 8), and of /analysis only the /analysis/sff
# columns the continuum stages read.
# Usage: fuzz/make_seed_run.sh SFFCAL_BINARY [OUT=fuzz/corpus/tiny_run.h5] (needs python3-h5py)
set -euo pipefail
sffcal=$(realpath "$1")
here=$(cd "$(dirname "$0")" && pwd)
out=$(realpath -m "${2:-$here/corpus/tiny_run.h5}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

"$sffcal" config -o base.toml > /dev/null
# The default config with the seed scene's keys replaced (tiny_run.toml sets a subset of them).
/usr/bin/python3 - "$here/corpus/config/tiny_run.toml" <<'EOF'
import re, sys
wanted = {}
section = ""
for line in open(sys.argv[1]):
    m = re.match(r"^\[(\w+)\]", line)
    if m: section = m.group(1)
    m = re.match(r"^(\w+)\s*=\s*(.*)$", line)
    if m: wanted[(section, m.group(1))] = m.group(2)
section = ""
with open("tiny.toml", "w") as out:
    for line in open("base.toml"):
        m = re.match(r"^\[(\w+)\]", line)
        if m: section = m.group(1)
        m = re.match(r"^(\w+)\s*=", line)
        if m and (section, m.group(1)) in wanted:
            line = "%s = %s\n" % (m.group(1), wanted[(section, m.group(1))])
        out.write(line)
EOF
"$sffcal" prepare -c tiny.toml -o specimen.h5 > /dev/null
"$sffcal" triaxial -c tiny.toml -s specimen.h5 -o run.h5 > /dev/null
"$sffcal" sff run.h5 -o sff > /dev/null

/usr/bin/python3 - run.h5 "$out" <<'EOF'
import sys, h5py
src, dst = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "w")
def attrs(s, d):
    for k in s.attrs:
        d.attrs.create(k, s.attrs[k], dtype=s.attrs.get_id(k).dtype)
def copy_group(s, d):
    attrs(s, d)
    for name, obj in s.items():
        if isinstance(obj, h5py.Group):
            copy_group(obj, d.create_group(name))
        else:
            attrs(obj, d.create_dataset(name, data=obj[...], dtype=obj.dtype))
attrs(src, dst)
for g in ["physics", "loading", "summary", "snapshots", "checkpoint"]:
    copy_group(src[g], dst.create_group(g))
series = dst.create_group("series")
attrs(src["series"], series)
for name in src["series"].attrs["columns"].split(","):
    series.create_dataset(name, data=src["series"][name][...], maxshape=(None,), chunks=(8,))
columns = ["axial_strain", "p", "q", "eta", "void_ratio", "a_c", "a_n", "m", "coordination",
           "lambda", "a_t"]
sff = dst.create_group("analysis/sff")
sff.attrs.create("columns", ",".join(columns), dtype=src["analysis/sff"].attrs.get_id("columns").dtype)
for c in columns:
    sff.create_dataset(c, data=src["analysis/sff"][c][...])
dst.close()
EOF
echo "wrote $out ($(stat -c %s "$out") bytes)"
