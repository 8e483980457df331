#!/usr/bin/env bash
# `sffcal calibrate --model NAME` for a model with no fit of its own (the third registered model,
# linear elasticity), as a user calls it: the fit over the model's description writes its parameter
# file, a curve per run and the summary; `sffcal fe-check` takes that file; an option the fit does
# not read, an unknown model and an undrained run are refused by name.
# Usage: calibrate_any_model_test.sh SFFCAL_BINARY PYTHON (with h5py).
set -u
sffcal=$1
python=$2
runs=$(cd "$(dirname "$0")/../data/reference/matrix" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0

check() {  # check DESCRIPTION COMMAND...: the command succeeds
  local what=$1
  shift
  if "$@" > /dev/null 2>&1; then echo "ok   $what"; else echo "FAIL $what"; failures=$((failures + 1)); fi
}
refused() {  # refused DESCRIPTION EXPECTED_TEXT COMMAND...: fails, saying EXPECTED_TEXT
  local what=$1 expected=$2 out
  shift 2
  out=$("$@" 2>&1)
  if [ $? -ne 0 ] && [[ $out == *"$expected"* ]]; then echo "ok   $what"
  else echo "FAIL $what: $out"; failures=$((failures + 1)); fi
}

if ! "$sffcal" calibrate --model linear_elastic "$runs/iso_dense_100kPa.h5" \
    --hold-out "$runs/iso_loose_100kPa.h5" -o fit > fit.log 2>&1; then
  echo "FAIL calibrate --model linear_elastic exits 0:"; cat fit.log; exit 1
fi
echo "ok   calibrate --model linear_elastic exits 0"
check "summary.md lists both parameters and the held-out run" \
  bash -c "grep -q '| youngs_modulus | Pa |' fit/summary.md && grep -q '| iso_loose_100kPa | held out |' fit/summary.md"
for name in iso_dense_100kPa iso_loose_100kPa; do
  check "$name: curves with their header" \
    grep -q "^axial_strain,eta_dem,eta_model,volumetric_strain_dem,volumetric_strain_model" "fit/${name}_curves.csv"
done
check "parameters.json: the model's parameter file with the fit's record" \
  "$python" - fit/parameters.json <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert d["model"] == "linear_elastic"
assert set(d["parameters"]) == {"youngs_modulus", "poissons_ratio"}
assert d["parameters"]["youngs_modulus"]["value"] > 0
assert [i["fitted"] for i in d["provenance"]["inputs"]] == [True, False]
assert d["fit"]["usable"] is True
PY
"$sffcal" fe-check --parameters fit/parameters.json --dem "$runs/iso_dense_100kPa.h5" \
  --pressures 100e3 --no-mesh --steps 10 --max-strain 0.05 -o check > check.log 2>&1
check "fe-check reads the fitted file: element vs driver passes in q and eps_v" \
  bash -c "[ \$(grep -Ec 'element vs driver .* pass' check.log) -eq 4 ]"

refused "an option the fit does not read is refused by name" "--starts does not apply" \
  "$sffcal" calibrate --model linear_elastic "$runs/iso_dense_100kPa.h5" --starts 2 -o refused
refused "an unknown model is refused, listing the registered ones" "registered: acst" \
  "$sffcal" calibrate --model no_such_model "$runs/iso_dense_100kPa.h5" -o refused
refused "an undrained run is refused, naming it" "undrained_compression" \
  "$sffcal" calibrate --model linear_elastic "$runs/../matrix_paths/und_dense_100kPa.h5" -o refused

echo "$failures failure(s)"
[ $failures -eq 0 ]
