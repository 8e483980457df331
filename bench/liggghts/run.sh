#!/usr/bin/env bash
# Reproduces the LIGGGHTS reference throughput figures of README.md.
#
#   bench/liggghts/run.sh                 # N = 2000 and 10000, 1 and 2 MPI ranks, 5 repeats each
#   SIZES="2000" REPEATS=1 bench/liggghts/run.sh
#
# Environment knobs: SIZES, NP_LIST, REPEATS, NSTEPS (timed steps), NWARM, OUT (output folder),
# MAX_FOREIGN (cores of foreign CPU load tolerated during a timed run, default 0.10), RETRIES, IDLE_WAIT,
# FORCE_COMPACT=1 (rebuild the packings even if OUT already holds them).
# Requires the Debian 12 package 'liggghts' (LIGGGHTS-PUBLIC 3.8.0) and, for the 2-rank runs,
# mpirun (pulled in by liggghts via mpi-default-bin), plus python3 for the summary table.
set -euo pipefail
cd "$(dirname "$0")"

if ! command -v liggghts >/dev/null 2>&1; then
  echo "run.sh: 'liggghts' is not installed. Install it from the Debian archive:" >&2
  echo "        apt-get update && apt-get install -y liggghts" >&2
  exit 1
fi

SIZES=${SIZES:-"2000 10000"}
NP_LIST=${NP_LIST:-"1 2"}
REPEATS=${REPEATS:-5}
NSTEPS=${NSTEPS:-5000}
NWARM=${NWARM:-1000}
OUT=${OUT:-results}
mkdir -p "$OUT"

MPIRUN=()
if command -v mpirun >/dev/null 2>&1; then
  MPIRUN=(mpirun -np)
  [ "$(id -u)" -eq 0 ] && MPIRUN=(mpirun --allow-run-as-root -np)
fi

echo "run.sh: $(liggghts -log none -h 2>/dev/null | head -1)"
echo "run.sh: host $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"

for N in $SIZES; do
  tag="N$N"
  if [ "${FORCE_COMPACT:-0}" = 1 ] || [ ! -f "$OUT/packing_$tag.restart" ] || [ ! -f "$OUT/walls_$tag.in" ]; then
    echo "run.sh: compacting $tag (serial) ..."
    t0=$(date +%s)
    liggghts -in in.compact -var N "$N" -var tag "$tag" -var outdir "$OUT" \
             -log "$OUT/compact_$tag.log" > "$OUT/compact_$tag.screen" 2>&1
    echo "run.sh:   $(grep '^FINAL' "$OUT/compact_$tag.log")  [$(( $(date +%s) - t0 )) s]"
  fi
  for np in $NP_LIST; do
    if [ "$np" -gt 1 ] && [ ${#MPIRUN[@]} -eq 0 ]; then
      echo "run.sh: mpirun not found, skipping np=$np"; continue
    fi
    for r in $(seq 1 "$REPEATS"); do
      log="$OUT/bench_${tag}_np${np}_r$r.log"
      if [ "$np" -eq 1 ]; then
        cmd=(liggghts)
      else
        cmd=("${MPIRUN[@]}" "$np" liggghts)
      fi
      # cpuguard.py waits for an idle machine, runs, and reports CPU used by foreign processes
      # during the run; a run disturbed by > MAX_FOREIGN busy cores is repeated (up to RETRIES).
      for attempt in $(seq 0 "${RETRIES:-3}"); do
        python3 cpuguard.py --idle-wait "${IDLE_WAIT:-600}" -- "${cmd[@]}" -in in.bench -var tag "$tag" \
                -var outdir "$OUT" -var nsteps "$NSTEPS" -var nwarm "$NWARM" -log "$log" > "${log%.log}.screen" 2>&1
        foreign=$(sed -n 's/.*foreign_cores=\([0-9.]*\).*/\1/p' "${log%.log}.screen")
        awk -v f="$foreign" -v m="${MAX_FOREIGN:-0.10}" 'BEGIN{exit !(f <= m)}' && break
        echo "run.sh:   (foreign CPU load $foreign cores during the run, repeating)"
      done
      echo "run.sh:   $tag np=$np rep=$r: $(awk '/^TIMED_SEGMENT_BEGIN/{f=1} f&&/^Loop time/{print; exit}' "$log") [foreign load $foreign cores]"
    done
  done
done

python3 - "$OUT" <<'PY'
import glob, os, re, statistics, sys
out = sys.argv[1]
rows = {}
for log in sorted(glob.glob(os.path.join(out, "bench_*_np*_r*.log"))):
    txt = open(log).read()
    seg = txt.split("\nTIMED_SEGMENT_BEGIN\n", 1)[1].split("\nTIMED_SEGMENT_END\n", 1)[0]
    m = re.search(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms", seg)
    loop, np_, steps, atoms = float(m.group(1)), int(m.group(2)), int(m.group(3)), int(m.group(4))
    br = {k: float(v) for k, v in re.findall(r"^(Pair|Neigh|Comm|Outpt|Modify|Other)\s+time \(%\) = \S+ \(([0-9.eE+-]+)\)", seg, re.M)}
    nb = int(re.search(r"Neighbor list builds = (\d+)", seg).group(1))
    res = re.search(r"^RESULT tag (\S+) atoms (\d+) contacts (\S+) Z (\S+) phi (\S+) P (\S+) dt (\S+) skin (\S+)", txt, re.M)
    scr = open(log[:-4] + ".screen").read()
    fm = re.search(r"foreign_cores=([0-9.]+)", scr)
    key = (atoms, np_)
    rows.setdefault(key, []).append(dict(foreign=float(fm.group(1)) if fm else float("nan"), loop=loop, steps=steps, br=br, nb=nb,
        contacts=float(res.group(3)), Z=float(res.group(4)), phi=float(res.group(5)),
        P=float(res.group(6)), dt=res.group(7), skin=res.group(8)))
lines = ["| N | MPI ranks | steps | loop time s (median of n; min) | sphere-steps/s per core (median; best) | Pair % | Neigh % | Comm % | Other % | neigh. builds | contacts (sphere-sphere) | Z | phi | P (kPa) | dt (s) | skin (m) | max foreign load (cores) |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
csv = ["N,ranks,steps,repeats,loop_time_median_s,loop_times_s,sphere_steps_per_s_per_core,sphere_steps_per_s_per_core_best,max_foreign_cores,pair_pct,neigh_pct,comm_pct,other_pct,neigh_builds,contacts,Z,phi,P_Pa,dt_s,skin_m"]
for (N, np_), rs in sorted(rows.items()):
    loops = [r["loop"] for r in rs]
    med = statistics.median(loops)
    r = min(rs, key=lambda r: abs(r["loop"] - med))
    thr = N * r["steps"] / med / np_
    best = N * r["steps"] / min(loops) / np_
    fmax = max(x["foreign"] for x in rs)
    b = r["br"]
    lines.append("| %d | %d | %d | %.3f (n=%d); %.3f | %.3g; %.3g | %.1f | %.1f | %.1f | %.1f | %d | %d | %.2f | %.3f | %.1f | %s | %s | %.2f |" % (
        N, np_, r["steps"], med, len(rs), min(loops), thr, best, b.get("Pair", 0), b.get("Neigh", 0), b.get("Comm", 0), b.get("Other", 0),
        r["nb"], r["contacts"], r["Z"], r["phi"], r["P"] / 1e3, r["dt"], r["skin"], fmax))
    csv.append("%d,%d,%d,%d,%.6g,%s,%.6g,%.6g,%.3f,%.2f,%.2f,%.2f,%.2f,%d,%d,%.4f,%.5f,%.6g,%s,%s" % (
        N, np_, r["steps"], len(rs), med, ";".join("%.4f" % x for x in loops), thr, best, fmax, b.get("Pair", 0), b.get("Neigh", 0),
        b.get("Comm", 0), b.get("Other", 0), r["nb"], r["contacts"], r["Z"], r["phi"], r["P"], r["dt"], r["skin"]))
open(os.path.join(out, "results.md"), "w").write("\n".join(lines) + "\n")
open(os.path.join(out, "results.csv"), "w").write("\n".join(csv) + "\n")
print("\n".join(lines))
PY
