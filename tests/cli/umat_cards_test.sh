#!/usr/bin/env bash
# `sffcal umat-cards` as a user calls it: the PROPS of both fitted models, eight a line, CalculiX's
# temperature after the last constant (a line of its own where the constants fill their last line),
# none for Abaqus; *DEPVAR from the state layout; the initial stress per integration point; bad
# element lists and a network without a DEM run refused by name.
# Usage: umat_cards_test.sh SFFCAL_BINARY
set -u
sffcal=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
runs=$root/tests/data/reference/matrix
failures=0
ok() { echo "ok   $1"; }
fail() { echo "FAIL $1"; failures=$((failures + 1)); }

net=$("$sffcal" umat-cards --parameters "$root/bench/reference/network_paper_params.json" \
  --dem "$runs/iso_dense_100kPa.h5" --elements 1-2 --points 8 2>&1)
if [ $? -eq 0 ] && [[ $net == *"*MATERIAL, NAME=ABAQUSCONTACT_NETWORK"* ]] &&
   [[ $net == *"*USER MATERIAL, CONSTANTS=48"* ]] && [[ $net == *"48 n_ra"* ]]; then
  ok "network: ABAQUSCONTACT_NETWORK, 48 PROPS, each named"
else fail "network cards: $net"; fi
# 48 constants: six full lines, then CalculiX's temperature on a seventh.
data=$(printf '%s\n' "$net" | sed -n '/^\*USER MATERIAL/,/^\*DEPVAR/p' | sed '1d;$d')
if [ "$(printf '%s\n' "$data" | wc -l)" -eq 7 ] && [ "$(printf '%s\n' "$data" | tail -1)" = "0" ] &&
   [ "$(printf '%s\n' "$data" | head -1 | tr ',' '\n' | wc -l)" -eq 8 ]; then
  ok "network: eight a line and the temperature line"
else fail "network PROPS lines: $data"; fi
if [[ $(printf '%s\n' "$net" | grep -A1 '^\*DEPVAR' | tail -1) == "29" ]] &&
   [ "$(printf '%s\n' "$net" | grep -c '^[12], [1-8], -')" -eq 16 ]; then
  ok "network: *DEPVAR 29 and 2 x 8 initial stresses"
else fail "network DEPVAR/initial conditions"; fi
acst=$("$sffcal" umat-cards --parameters "$root/examples/acst_toyoura.json" --client abaqus \
  --pressure 2e5 --void-ratio 0.7 2>&1)
data=$(printf '%s\n' "$acst" | sed -n '/^\*USER MATERIAL/,/^\*DEPVAR/p' | sed '1d;$d')
if [[ $acst == *"*MATERIAL, NAME=ACST"* ]] && [[ $acst == *"CONSTANTS=25"* ]] &&
   [ "$(printf '%s\n' "$data" | wc -l)" -eq 4 ] && [ "$(printf '%s\n' "$data" | tail -1)" = "0" ] &&
   [[ $(printf '%s\n' "$data" | head -1) == 0.69999999999999996,* ]] &&
   [[ $acst != *"INITIAL CONDITIONS"* ]]; then
  ok "ACST for Abaqus: NAME=ACST, 25 PROPS from e_0, no temperature, no initial stress card"
else fail "ACST cards: $acst"; fi
abaqus=$("$sffcal" umat-cards --parameters "$root/examples/acst_toyoura.json" --client abaqus \
  --pressure 2e5 --elements 3-4 2>&1)
stresses=$(printf '%s\n' "$abaqus" | sed -n '/^\*INITIAL CONDITIONS/,$p' | sed '1d')
if [ "$(printf '%s\n' "$stresses" | wc -l)" -eq 2 ] &&
   [ "$(printf '%s\n' "$stresses" | head -1)" = "3, -200000, -200000, -200000, 0, 0, 0" ]; then
  ok "Abaqus' initial stress: one line per element, no integration point"
else fail "Abaqus initial stress: $stresses"; fi
out=$("$sffcal" umat-cards --parameters "$root/examples/acst_toyoura.json" --void-ratio 5 2>&1)
if [ $? -ne 0 ] && [[ $out == *"void ratio"* ]]; then ok "a start the model cannot carry is refused"
else fail "--void-ratio 5: $out"; fi
for bad in "0" "2-1" "1-x" "1-2147483647"; do
  out=$("$sffcal" umat-cards --parameters "$root/examples/acst_toyoura.json" --elements "$bad" 2>&1)
  if [ $? -ne 0 ] && [[ $out == *"--elements"* ]]; then ok "--elements $bad refused by name"
  else fail "--elements $bad: $out"; fi
done
out=$("$sffcal" umat-cards --parameters "$root/bench/reference/network_paper_params.json" 2>&1)
if [ $? -ne 0 ] && [[ $out == *"--dem"* ]]; then ok "a network without a DEM run refused, naming --dem"
else fail "network without --dem: $out"; fi
echo "$failures failure(s)"
[ $failures -eq 0 ]
