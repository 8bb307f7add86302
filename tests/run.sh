#!/bin/sh
# run.sh: run every test of tds and print "N passed, N failed".
# Usage: tests/run.sh TDS_BINARY BUILD_DIR
# Each test prints lines "PASS name" or "FAIL name: why"; this counts them.
TDS=$1
BUILD=$2
export TDS
# The check mode (lua/check.lua): every command of every test run of tds is
# verified: nothing non-finite after it, nothing changed if it failed.
TDS_CHECK=1
export TDS_CHECK
cd "$(dirname "$0")/.." || exit 1
# Evolver's outputs are cached across runs of the suite (see lib.sh).
TDS_EVOLVER_CACHE=${TDS_EVOLVER_CACHE:-$(pwd)/build/evolver-cache}
export TDS_EVOLVER_CACHE
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

{
  for t in "$BUILD"/test_*; do
    [ -x "$t" ] || continue
    "$t" || echo "FAIL $(basename "$t"): exit status $?"
  done
  for s in tests/scripts/*.tds; do
    name=$(basename "$s" .tds)
    if (cd tests/scripts && "$TDS" -q "$name.tds") > "$out/$name.log" 2>&1; then
      echo "PASS script/$name"
    else
      echo "FAIL script/$name: $(tail -n 3 "$out/$name.log" | tr '\n' ' ')"
    fi
  done
  for g in tests/golden/*.sh; do
    name=$(basename "$g" .sh)
    (cd tests/golden && sh "$name.sh") > "$out/$name.got" 2>&1
    if cmp -s "$out/$name.got" "tests/golden/$name.out"; then
      echo "PASS golden/$name"
    else
      echo "FAIL golden/$name: output differs:"
      diff "tests/golden/$name.out" "$out/$name.got" | head -n 20 | sed 's/^/    /'
    fi
  done
  sh tests/docs.sh
  sh tests/repro.sh
  for e in tests/evolver/*.sh; do
    [ -f "$e" ] || continue
    sh "$e" || echo "FAIL evolver/$(basename "$e" .sh): exit status $?"
  done
} | tee "$out/all.log"

pass=$(grep -c '^PASS ' "$out/all.log")
fail=$(grep -c '^FAIL ' "$out/all.log")
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
