#!/usr/bin/env bash
# Builds the libFuzzer targets of the input readers (fuzz/README.md) with clang, AddressSanitizer
# and UBSan into BUILD, and runs each for SECONDS on a copy of its committed corpus (which replays
# the corpus first: a regression run). Reproducers of a crash, leak, time-out or out-of-memory are
# kept in BUILD/findings/<target>/, each target's log in BUILD/findings/<target>.log. Prints one
# line per target; exits 1 if any target found anything.
# Usage: [FUZZ_SEED=N] scripts/fuzz.sh [SECONDS_PER_TARGET=30] [BUILD=build-fuzz]
# FUZZ_SEED: libFuzzer's -seed (default 0: a random seed, printed in each target's log).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-30}
build=${2:-build-fuzz}
targets=(config csv_packing parameter_file umat run_file checkpoint import)

# Never a build folder of the normal (gcc) build: a fuzz build folder is one of its own.
if [ -f "$build/CMakeCache.txt" ] && ! grep -q '^SFFCAL_FUZZ:BOOL=ON' "$build/CMakeCache.txt"; then
  echo "fuzz.sh: $build is not a fuzz build folder (SFFCAL_FUZZ is not on): give another" >&2
  exit 2
fi

# -O1 -g with assertions on: readable stacks, Eigen's index checks, a cold build of a few minutes.
start=$SECONDS
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DSFFCAL_FUZZ=ON -DSFFCAL_BUILD_TESTS=OFF -DSFFCAL_BUILD_BENCH=OFF \
  -DSFFCAL_BUILD_CALIBRATION=OFF -DSFFCAL_BUILD_FE=OFF > /dev/null
cmake --build "$build" --target fuzz_targets
echo "fuzz.sh: built the fuzz targets in $((SECONDS - start)) s"

# halt_on_error: a UBSan finding stops the run as an ASan one does (libFuzzer keeps the input).
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:symbolize=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:symbolize=1"
export OMP_NUM_THREADS=1 HDF5_USE_FILE_LOCKING=FALSE
failed=()
for target in "${targets[@]}"; do
  work="$build/fuzz-corpus/$target" findings="$build/findings/$target"
  log="$build/findings/$target.log"
  rm -rf "$work" "$findings"
  mkdir -p "$work" "$findings"
  cp fuzz/corpus/"$target"/* "$work"/ 2> /dev/null || true
  options=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
           -seed="${FUZZ_SEED:-0}" -artifact_prefix="$findings/")
  [ -f "fuzz/dict/$target.dict" ] && options+=(-dict="fuzz/dict/$target.dict")
  # Every refused UMAT call prints its message on stderr, as FE codes want; libFuzzer's own
  # output and the sanitizers' reports still reach the log.
  [ "$target" = umat ] && options+=(-close_fd_mask=2)
  status=0
  timeout $((seconds + 300)) "$build/fuzz/fuzz_$target" "${options[@]}" "$work" > "$log" 2>&1 ||
    status=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  coverage=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$log" | tail -n 1)
  reproducers=$(find "$findings" -type f | wc -l)
  if [ "$status" -eq 0 ] && [ "$reproducers" -eq 0 ]; then
    result=ok
  else
    result="FOUND (exit status $status; reproducers in $findings/)"
    failed+=("$target")
  fi
  printf 'fuzz %-15s %9s runs in %s s, %s: %s\n' "$target" "${runs:-?}" "$seconds" \
    "${coverage:-cov: ?}" "$result"
done

for target in "${failed[@]}"; do
  echo "---- fuzz_$target: the end of $build/findings/$target.log ----"
  tail -n 40 "$build/findings/$target.log"
  echo "replay: $build/fuzz/fuzz_$target $build/findings/$target/<file> (fuzz/README.md)"
done
echo "fuzz.sh: $((SECONDS - start)) s in all"
[ ${#failed[@]} -eq 0 ]
