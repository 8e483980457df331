#!/usr/bin/env bash
# Numerical stability stress suite (issue 8): the wall servo at sigma_3 = 10 kPa, 100 kPa and 1 MPa
# on dense and loose specimens, through the command line (sffcal prepare + sffcal triaxial).
#
# For each run the table gives the compaction outcome, the initial void ratio, the worst lateral
# stress deviation |sigma_wall - sigma_3| / sigma_3 over the output rows of the shearing (the
# summary's figure), the largest lateral wall speed against the servo cap, the peak q/p and the
# largest inertial number. The wall speed is the wall's displacement between two series rows over
# their time interval (a mean over OUTPUT_INTERVAL of axial strain, about 400 steps), so it bounds
# the per-step speed from below; the per-step cap itself is asserted in
# tests/dem/stability_test.cc (Servo.*). A run that stops with an error gets the error's first
# line in the table instead of numbers.
#
# Usage: bench/stress/run_stress_suite.sh [out_folder]      (default out/stress)
# Environment: SFFCAL (the executable, default build/sffcal), BODIES (200), THREADS (1),
#              MAX_STRAIN (0.10), RATE (50 /s), OUTPUT_INTERVAL (5e-4).
# Run it niced on a shared machine:  nice -n 10 bench/stress/run_stress_suite.sh
set -uo pipefail
cd "$(dirname "$0")/../.."
SFFCAL=${SFFCAL:-build/sffcal}
OUT=${1:-out/stress}
BODIES=${BODIES:-200}
THREADS=${THREADS:-1}
MAX_STRAIN=${MAX_STRAIN:-0.10}
RATE=${RATE:-50.0}
OUTPUT_INTERVAL=${OUTPUT_INTERVAL:-5e-4}
CAP=0.5  # triaxial.servo_max_speed [m/s]
mkdir -p "$OUT"
[ -x "$SFFCAL" ] || { echo "no executable $SFFCAL (build first, or set SFFCAL)" >&2; exit 1; }

# write_config file pressure compaction_friction
write_config() {
  cat > "$1" <<TOML
seed = 1
threads = $THREADS
bodies = $BODIES
[preparation]
pressure = $2
compaction_friction = $3
[triaxial]
strain_rate = $RATE
servo_max_speed = $CAP
max_axial_strain = $MAX_STRAIN
output_strain_interval = $OUTPUT_INTERVAL
snapshot_strain_interval = 1.0
checkpoint_strain_interval = 1.0
critical_min_strain = 1.0
TOML
}

# summarise name density pressure seconds prepare_log triaxial_log series_csv
summarise() {
  python3 - "$@" "$CAP" <<'PY'
import csv, re, sys
name, density, pressure, seconds, prep_log, tri_log, series, cap = sys.argv[1:9]
prep = open(prep_log).read()
compaction = re.search(r"(accepted|NOT accepted) after (\d+) steps", prep)
void = re.search(r"void ratio ([0-9.]+)", prep)
def error_line(log):
    for line in open(log):
        if line.startswith("error") or "error:" in line:
            return line.strip().replace("|", "/")
    return None
failed = error_line(prep_log) or (error_line(tri_log) if tri_log != "-" else None)
if failed or series == "-":
    steps = compaction.group(2) if compaction else "-"
    e0 = void.group(1) if void else "-"
    print(f"| {name} | {density} | {float(pressure)/1e3:g} | {steps} | {e0} | - | - | - | - | {seconds} | {failed or 'no run'} |")
    sys.exit()
rows = list(csv.DictReader(open(series)))
col = lambda k: [float(r[k]) for r in rows]
t = col("time")
speed = 0.0
for wall in ("wall_x_lower", "wall_x_upper", "wall_y_lower", "wall_y_upper"):
    x = col(wall)
    for k in range(1, len(rows)):
        speed = max(speed, abs(x[k] - x[k - 1]) / (t[k] - t[k - 1]))
print(f"| {name} | {density} | {float(pressure)/1e3:g} | {compaction.group(2)} | {void.group(1)} "
      f"| {100 * max(col('lateral_stress_error')):.2f} | {speed:.3g} / {cap} | {max(col('eta')):.3f} "
      f"| {max(col('inertial_number')):.1e} | {seconds} | ok |")
PY
}

{
echo "stress suite: $BODIES clumps, $THREADS thread(s), strain rate $RATE /s to $MAX_STRAIN axial strain, $(git rev-parse --short HEAD 2>/dev/null)"
echo
echo "| run | specimen | sigma_3 [kPa] | compaction steps | e0 | worst lateral deviation [%] | max lateral wall speed / cap [m/s] | peak q/p | max I | wall-clock [s] | outcome |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
} | tee "$OUT/table.md"
for density in dense loose; do
  friction=$([ "$density" = dense ] && echo 0.0 || echo 0.5)
  for pressure in 1.0e4 1.0e5 1.0e6; do
    name="${density}_$(python3 -c "print(f'{float($pressure)/1e3:g}kPa')")"
    config="$OUT/$name.toml"
    write_config "$config" "$pressure" "$friction"
    start=$(date +%s)
    series="-"; tri_log="-"
    if "$SFFCAL" prepare -c "$config" -o "$OUT/$name.specimen.h5" > "$OUT/$name.prepare.log" 2>&1; then
      tri_log="$OUT/$name.triaxial.log"
      if "$SFFCAL" triaxial -c "$config" -s "$OUT/$name.specimen.h5" -o "$OUT/$name.h5" > "$tri_log" 2>&1; then
        series="$OUT/$name.h5.series.csv"
      fi
    fi
    summarise "$name" "$density (compaction friction $friction)" "$pressure" "$(( $(date +%s) - start ))" \
      "$OUT/$name.prepare.log" "$tri_log" "$series" | tee -a "$OUT/table.md"
  done
done
