#!/usr/bin/env bash
# `sffcal point` as a user calls it: linear elasticity against its closed forms (undrained: eps_v
# = 0, p = sigma_3, q = 3 G eps_a; drained extension: q = E eps_a < 0), ACST and the
# contact-network model undrained from a DEM run's start, the CSV's layout, an existing output kept
# without --force, and bad options refused by name.
# Usage: point_test.sh SFFCAL_BINARY
set -u
sffcal=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
runs=$root/tests/data/reference/matrix
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
ok() { echo "ok   $1"; }
fail() { echo "FAIL $1"; failures=$((failures + 1)); }
# The value of COLUMN in the CSV's last row (the first line is a comment, the second the header).
last() {
  awk -F, -v c="$2" 'NR == 2 { for (i = 1; i <= NF; ++i) if ($i == c) k = i } NR > 2 { v = $k }
                     END { print v }' "$1"
}
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'; }

cat > "$work/elastic.json" <<'JSON'
{"model": "linear_elastic", "parameters": {"youngs_modulus": {"value": 2.4e8, "unit": "Pa"},
 "poissons_ratio": {"value": 0.2, "unit": "1"}}}
JSON
# G = E / (2 (1 + nu)) = 1e8 Pa: q = 3 G eps_a = 3e6 Pa at eps_a = 0.01.
if "$sffcal" point --parameters "$work/elastic.json" --pressure 1e5 --drainage undrained \
     --max-strain 0.01 --steps 4 -o "$work/u.csv" > "$work/u.log" 2>&1 &&
   [ "$(wc -l < "$work/u.csv")" -eq 7 ] && near "$(last "$work/u.csv" q)" 3e6 1e-3 &&
   near "$(last "$work/u.csv" p)" 1e5 1e-6 && near "$(last "$work/u.csv" volumetric_strain)" 0 1e-17 &&
   [ "$(last "$work/u.csv" status)" = ok ]; then
  ok "linear elasticity undrained: q = 3 G eps_a, p = sigma_3, eps_v = 0, 4 steps + the start"
else fail "linear elasticity undrained: $(cat "$work/u.log" "$work/u.csv" 2>/dev/null)"; fi
# Drained extension: q = E eps_a = -2.4e6 Pa, eps_v = (1 - 2 nu) eps_a = -0.006.
if "$sffcal" point --parameters "$work/elastic.json" --pressure 1e5 --max-strain -0.01 \
     -o "$work/e.csv" > "$work/e.log" 2>&1 &&
   near "$(last "$work/e.csv" q)" -2.4e6 1e-3 && near "$(last "$work/e.csv" volumetric_strain)" -0.006 1e-12; then
  ok "linear elasticity in drained extension: q = E eps_a, eps_v = (1 - 2 nu) eps_a"
else fail "linear elasticity drained extension: $(cat "$work/e.log")"; fi
# ACST and the network model undrained from a deposit: complete, volume kept, loaded.
for model in "$root/examples/acst_toyoura.json $runs/dep_dense_a90.h5" \
             "$root/bench/reference/network_paper_params.json $runs/dep_dense_a45.h5"; do
  set -- $model
  name=$(basename "$1" .json)
  if "$sffcal" point --parameters "$1" --dem "$2" --drainage undrained --max-strain 0.05 \
       --steps 100 -o "$work/$name.csv" > "$work/$name.log" 2>&1 &&
     [ "$(wc -l < "$work/$name.csv")" -eq 103 ] &&
     [ -z "$(awk -F, 'NR > 2 && $3 != 0' "$work/$name.csv")" ] &&
     awk -v q="$(last "$work/$name.csv" q)" 'BEGIN { exit !(q > 1e5) }' &&
     grep -q "undrained to axial strain 0.05 in 100 steps" "$work/$name.csv"; then
    ok "$name undrained from a deposit: 100 steps, eps_v = 0 in every row, q > 100 kPa"
  else fail "$name undrained: $(cat "$work/$name.log")"; fi
done

before=$(cat "$work/u.csv")
out=$("$sffcal" point --parameters "$work/elastic.json" -o "$work/u.csv" 2>&1)
if [ $? -ne 0 ] && [[ $out == *"--force"* ]] && [ "$(cat "$work/u.csv")" = "$before" ]; then
  ok "an existing CSV is kept without --force"
else fail "existing output: $out"; fi
if "$sffcal" point --parameters "$work/elastic.json" --max-strain 0.002 -o "$work/u.csv" --force \
     > /dev/null 2>&1 && near "$(last "$work/u.csv" axial_strain)" 0.002 1e-15; then
  ok "--force replaces it"
else fail "--force"; fi
refused() {  # refused EXPECTED-WORD DESCRIPTION ARGS...
  local word=$1 what=$2
  shift 2
  out=$("$sffcal" point "$@" -o "$work/refused.csv" 2>&1)
  if [ $? -ne 0 ] && [[ $out == *"$word"* ]] && [ ! -e "$work/refused.csv" ]; then ok "$what refused"
  else fail "$what: $out"; fi
}
refused "--max-strain" "--max-strain 0" --parameters "$work/elastic.json" --max-strain 0
refused "--max-strain" "--max-strain 0.8" --parameters "$work/elastic.json" --max-strain 0.8
refused "--drainage" "--drainage partly" --parameters "$work/elastic.json" --drainage partly
refused "--pressure" "--pressure -1" --parameters "$work/elastic.json" --pressure -1
refused "--dem" "the network without a DEM run" \
  --parameters "$root/bench/reference/network_paper_params.json"
refused "excludes" "--pressure with --dem (it would be ignored)" \
  --parameters "$root/examples/acst_toyoura.json" --dem "$runs/dep_dense_a90.h5" --pressure 5e5
refused "requires --dem" "--a-cs without --dem (it would be ignored)" \
  --parameters "$root/examples/acst_toyoura.json" --a-cs 0.8
refused "void ratio" "a void ratio ACST cannot carry" \
  --parameters "$root/examples/acst_toyoura.json" --void-ratio 5
out=$("$sffcal" point --parameters "$work/elastic.json" -o "$work/elastic.json" --force 2>&1)
if [ $? -ne 0 ] && grep -q linear_elastic "$work/elastic.json"; then
  ok "the parameter file as the output refused, even with --force"
else fail "output = input: $out"; fi
echo "$failures failure(s)"
[ $failures -eq 0 ]
