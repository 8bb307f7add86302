#!/bin/sh
# run.sh: run the tests of tds and print "N passed, N failed".
# Usage: tests/run.sh TDS_BINARY BUILD_DIR [RUNNER...]
#
# A runner prints lines "PASS name" or "FAIL name: why". The runners:
#   unit/NAME      BUILD_DIR/test_NAME (C unit tests, fuzz corpus replays)
#   script/NAME    tests/scripts/NAME.tds, self-checking (error() fails)
#   golden/NAME    tests/golden/NAME.sh, whose output must be NAME.out
#   doc            every ```lua block of README.md and doc/*.md
#   export         export round trips (tests/export)
#   web/NAME       the live view in headless Chromium (tests/web)
#   pictures/NAME  pictures and the progress line (tests/pictures)
#   repro          the fuzzing reproducers (tests/repro.sh)
#   module/NAME    tests/module/NAME.lua in the stock lua5.4 with build/tds.so
#   evolver/NAME   the same input through Surface Evolver and tds
#
# With no RUNNER, all run, in two lanes at once (Evolver's comparisons in
# one), and the names they print must be exactly those in tests/plan.txt:
# a test that silently stops running, or a new one not in the plan, fails
# (`make plan` rewrites the plan from a run). With RUNNERs (make test
# T='script/declare evolver'), only those run, by name or name prefix, and
# the plan is not checked.
TDS=$1
BUILD=$2
shift 2
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

runners() {
  for t in "$BUILD"/test_*; do [ -x "$t" ] && echo "unit/${t##*/test_}"; done
  for s in tests/scripts/*.tds; do s=${s##*/}; echo "script/${s%.tds}"; done
  for g in tests/golden/*.sh; do g=${g##*/}; echo "golden/${g%.sh}"; done
  echo doc
  echo export
  for w in tests/web/*.sh; do w=${w##*/}; echo "web/${w%.sh}"; done
  for p in tests/pictures/*.py; do p=${p##*/}; echo "pictures/${p%.py}"; done
  echo repro
  for m in tests/module/*.lua; do m=${m##*/}; echo "module/${m%.lua}"; done
  for e in tests/evolver/*.sh; do e=${e##*/}; echo "evolver/${e%.sh}"; done
}

run_one() {
  name=${1#*/}
  case $1 in
    unit/*) "$BUILD/test_$name" || echo "FAIL $1: exit status $?" ;;
    script/*)
      if (cd tests/scripts && "$TDS" -q "$name.tds") > "$out/$name.log" 2>&1; then
        echo "PASS $1"
      else
        echo "FAIL $1: $(tail -n 3 "$out/$name.log" | tr '\n' ' ')"
      fi ;;
    golden/*)
      (cd tests/golden && sh "$name.sh") > "$out/$name.got" 2>&1
      if cmp -s "$out/$name.got" "tests/golden/$name.out"; then
        echo "PASS $1"
      else
        echo "FAIL $1: output differs:"
        diff "tests/golden/$name.out" "$out/$name.got" | head -n 20 | sed 's/^/    /'
      fi ;;
    doc) sh tests/docs.sh ;;
    export) sh tests/export/run.sh ;;
    web/*) sh "tests/web/$name.sh" || echo "FAIL $1: exit status $?" ;;
    pictures/*) /usr/bin/python3 "tests/pictures/$name.py" "$TDS" "$BUILD" ||
                  echo "FAIL $1: exit status $?" ;;
    repro) sh tests/repro.sh ;;
    module/*) sh tests/module/run.sh "$BUILD" "$name" ;;
    evolver/*) sh "tests/evolver/$name.sh" || echo "FAIL $1: exit status $?" ;;
  esac
}

# The runners chosen by the arguments (all if none).
chosen() {
  runners | while read -r r; do
    [ $# -eq 0 ] && { echo "$r"; continue; }
    for want in "$@"; do
      case $r in "$want" | "$want"/*) echo "$r"; break ;; esac
    done
  done
}

chosen "$@" > "$out/runners"
[ -s "$out/runners" ] || { echo "run.sh: no test named $*"; echo "0 passed, 1 failed"; exit 1; }
grep '^evolver/' "$out/runners" > "$out/laneB"
grep -v '^evolver/' "$out/runners" > "$out/laneA"
(while read -r r; do run_one "$r"; done < "$out/laneB") > "$out/B.log" 2>&1 &
lane=$!
while read -r r; do run_one "$r"; done < "$out/laneA" | tee "$out/A.log"
wait $lane
cat "$out/B.log"
cat "$out/A.log" "$out/B.log" > "$out/all.log"

# The plan: exactly the names it lists, each once.
names() { sed -n 's/^\(PASS\|FAIL\) \([^ :]*\).*/\2/p' "$1" | LC_ALL=C sort; }
if [ $# -eq 0 ] && [ -n "$PLAN_WRITE" ]; then
  names "$out/all.log" | uniq > tests/plan.txt
  echo "run.sh: wrote tests/plan.txt ($(wc -l < tests/plan.txt) names)"
elif [ $# -eq 0 ]; then
  names "$out/all.log" > "$out/names"
  {
    uniq -d "$out/names" | sed 's/^/FAIL plan: reported twice: /'
    LC_ALL=C sort -u tests/plan.txt | LC_ALL=C comm -23 - "$out/names" | sed 's/^/FAIL plan: did not run: /'
    uniq "$out/names" | LC_ALL=C comm -13 tests/plan.txt - | sed 's|^|FAIL plan: not in tests/plan.txt (make plan): |'
  } | tee -a "$out/all.log"
fi

pass=$(grep -c '^PASS ' "$out/all.log")
fail=$(grep -c '^FAIL ' "$out/all.log")
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
