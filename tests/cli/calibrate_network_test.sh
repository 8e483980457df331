#!/usr/bin/env bash
# `sffcal calibrate --model network` as a user calls it (issue 19): two 500-clump runs fitted and a
# third held back (one start) write the contact-network parameter file with the fit's record and
# standard errors, a curve per test and the summary; `sffcal fe-check` takes that parameter file;
# a refit starts from it (--start); an ACST-only option and a run without the network's columns are
# refused by name.
# Usage: calibrate_network_test.sh SFFCAL_BINARY PYTHON (with h5py).
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

# w_psi held: free, this two-run, one-start fit ends at kappa's bound 10 with k_a 114, where the
# element and the driver, whose RK4 substeps differ, part by 7.7e-7 in eps_v (relative; 2e-6 when
# the fit read sff's a_n rather than the closing one), close to the element-vs-driver check's 1e-6.
if ! "$sffcal" calibrate --model network "$runs/iso_dense_100kPa.h5" "$runs/iso_loose_100kPa.h5" \
    --hold-out "$runs/iso_dense_200kPa.h5" --starts 1 --hold w_psi -o fit > fit.log 2>&1; then
  echo "FAIL calibrate --model network exits 0:"; cat fit.log; exit 1
fi
echo "ok   calibrate --model network exits 0"
check "progress lines per stage" grep -q "start 1 of 1, on the predicted paths" fit.log
check "summary.md with the held-back test" grep -q "iso_dense_200kPa | held back" fit/summary.md
for name in iso_dense_100kPa iso_loose_100kPa iso_dense_200kPa; do
  check "$name: predicted curve with its header" \
    grep -q "^axial_strain,volumetric_strain,void_ratio,p,q,eta,coordination" "fit/${name}_network.csv"
done
check "parameters.json: the contact-network model, standard errors, inputs and errors" \
  "$python" - fit/parameters.json <<'PY'
import json, math, sys
d = json.load(open(sys.argv[1]))
assert d["model"] == "contact_network"
assert len(d["parameters"]) == 27
errors = d["fit"]["standard_errors"]
assert sum(1 for v in errors.values() if v is not None and math.isfinite(v) and v > 0) >= 12
assert [i["fitted"] for i in d["provenance"]["inputs"]] == [True, True, False]
assert len(d["errors"]) == 3 and d["errors"][2]["role"] == "held back"
PY
# fe-check reads the fitted file: element against material point must pass. FE against DEM is not
# asserted (this two-run, one-start fit misses the 500-clump curves by about 0.15 in q/p).
"$sffcal" fe-check --parameters fit/parameters.json --dem "$runs/iso_dense_100kPa.h5" \
  --no-mesh --steps 40 --max-strain 0.1 -o check > check.log 2>&1
check "fe-check reads the fitted parameter file: element vs driver in q passes" \
  grep -Eq "element vs driver +q \(max rel.\) .* pass" check.log
check "fe-check: element vs driver in eps_v passes" grep -Eq "element vs driver +eps_v .* pass" check.log
check "fe-check: no element vs driver failure" bash -c "! grep -E 'element vs driver.*FAIL' check.log"

# --predicted-only: the second stage from the start directly, recorded in parameters.json.
if "$sffcal" calibrate --model network "$runs/iso_dense_100kPa.h5" --starts 1 --predicted-only \
    -o direct > direct.log 2>&1; then
  check "--predicted-only: no first stage, the second from the start" \
    bash -c "grep -q 'start 1 of 1, on the predicted paths' direct.log && \
             ! grep -q 'along the DEM strain paths' direct.log"
  check "--predicted-only is recorded in parameters.json" \
    "$python" -c "import json, sys
sys.exit(json.load(open('direct/parameters.json'))['fit']['first_stage'] is not False)"
else
  echo "FAIL calibrate --model network --predicted-only exits 0:"; cat direct.log
  failures=$((failures + 1))
fi

# --start: the first start from the fit's own parameter file; on the predicted paths directly
# the fit can only go down from there. w_psi held as in the fit (free, the refit leaves that
# optimum for stiff rates: 929 -> 812 in 63 iterations of 4 s each).
if "$sffcal" calibrate --model network "$runs/iso_dense_100kPa.h5" "$runs/iso_loose_100kPa.h5" \
    --start fit/parameters.json --predicted-only --starts 1 --hold w_psi -o again \
    > again.log 2>&1; then
  check "--start: said, and the refit ends at or below the first fit's cost" \
    "$python" -c "import json, sys
first = json.load(open('fit/parameters.json'))['fit']['final_cost']
again = json.load(open('again/parameters.json'))['fit']['final_cost']
print(first, again)
sys.exit(not (again <= first * (1 + 1e-9) and 'first start from fit/parameters.json' in open('again.log').read()))"
else
  echo "FAIL calibrate --model network --start exits 0:"; cat again.log
  failures=$((failures + 1))
fi

# Refusals, each naming the cause.
out=$("$sffcal" calibrate "$runs/iso_dense_100kPa.h5" --start fit/parameters.json -o refused 2>&1)
if [ $? -ne 0 ] && [[ $out == *"--start does not apply to --model acst"* ]]; then
  echo "ok   --start with the ACST fit is refused by name"
else
  echo "FAIL --start with ACST: $out"; failures=$((failures + 1))
fi
out=$("$sffcal" calibrate "$runs/iso_dense_100kPa.h5" --predicted-only -o refused 2>&1)
if [ $? -ne 0 ] && [[ $out == *"--predicted-only does not apply to --model acst"* ]]; then
  echo "ok   --predicted-only with the ACST fit is refused by name"
else
  echo "FAIL --predicted-only with ACST: $out"; failures=$((failures + 1))
fi
out=$("$sffcal" calibrate --model network "$runs/iso_dense_100kPa.h5" --stages joint -o refused 2>&1)
if [ $? -ne 0 ] && [[ $out == *"--stages does not apply to --model contact_network"* ]]; then
  echo "ok   --stages with --model network is refused by name"
else
  echo "FAIL --stages with --model network: $out"; failures=$((failures + 1))
fi
out=$("$sffcal" calibrate --model network "$runs/iso_dense_100kPa.h5" --hold xyz -o refused 2>&1)
if [ $? -ne 0 ] && [[ $out == *"no parameter 'xyz' to hold"* ]]; then
  echo "ok   --hold with an unknown parameter is refused by name"
else
  echo "FAIL --hold xyz: $out"; failures=$((failures + 1))
fi
mkdir -p a b && cp "$runs/iso_loose_100kPa.h5" a/run.h5 && cp "$runs/iso_dense_100kPa.h5" b/run.h5
out=$("$sffcal" calibrate --model network a/run.h5 --hold-out b/run.h5 -o refused 2>&1)
if [ $? -ne 0 ] && [[ $out == *"two tests are named 'run'"* ]] && [[ $out != *"start 1"* ]]; then
  echo "ok   two runs of one name are refused before the fit"
else
  echo "FAIL two runs of one name: $out"; failures=$((failures + 1))
fi
cp "$runs/iso_loose_100kPa.h5" no_z.h5
"$python" -c "import h5py; f = h5py.File('no_z.h5', 'r+'); del f['analysis/sff/coordination']"
out=$("$sffcal" calibrate --model network no_z.h5 -o refused 2>&1)
if [ $? -ne 0 ] && [[ $out == *"no_z"* ]] && [[ $out == *"coordination"* ]]; then
  echo "ok   a run without Z is refused, naming the run and the column"
else
  echo "FAIL a run without Z: $out"; failures=$((failures + 1))
fi

echo "$failures failure(s)"
[ $failures -eq 0 ]
