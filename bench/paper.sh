#!/bin/sh
# paper.sh: the paper's experiments in tds (pg) and in Surface Evolver from
# the same input, with the same metric code (doc/paper-results.md).
# Usage: sh bench/paper.sh [TDS_BINARY] [EXPERIMENT ...]
# Env: EVOLVER (default evolver-nox-d); PAPER_G_ITERS (g; u; V rounds, 1000);
# PAPER_REPEAT (default 1): run each tds row that many times and show the
# fastest run (the runs are identical but for their timings); PAPER_CACHE
# (below).
# Generated inputs (scripts/paper/generate.lua): an experiment named
# FAMILY/CASE runs scripts/paper/gen.tds with PAPER_GEN=FAMILY/CASE; by
# default every case of every family follows the paper's experiments
# (PAPER_GEN_FAMILIES, PAPER_GEN_CASES choose; PAPER_GEN_CASES=none skips
# them), without the plain tds row (PAPER_GEN_PLAIN=1 adds it), and a
# summary per family ends the output with its worst input.
# PAPER_POLISH_EXPS: the paper's experiments that also get a row
# "tds pg+polish" (pg() then pg_polish{}, doc/method.md); default: those
# with a nonzero curvature ("none": no such rows).
TDS=${1:-./tds}
[ $# -gt 0 ] && shift
case $TDS in /*) ;; *) TDS=$(pwd)/$TDS ;; esac
EVOLVER=${EVOLVER:-evolver-nox-d}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
# Evolver's outputs (it is deterministic) are kept by a hash of the input
# and the commands in PAPER_CACHE (default build/evolver-cache; "none":
# always run), with their run times: a second run only runs tds.
CACHE=${PAPER_CACHE:-$ROOT/build/evolver-cache}
[ "$CACHE" = none ] && CACHE=
[ -n "$CACHE" ] && { mkdir -p "$CACHE" 2>/dev/null || CACHE=; }
GEN_CASES=${PAPER_GEN_CASES:-"1 2 3 4 5 6 7 8 9 10"}
[ "$GEN_CASES" = none ] && GEN_CASES=
GEN=
for fam in ${PAPER_GEN_FAMILIES:-hemisphere catenoid schwarz_p cmc drop}; do
  for c in $GEN_CASES; do GEN="$GEN $fam/$c"; done
done
EXPS=${*:-"hemisphere random_hemisphere catenoid schwarz_p cmc_1 cmc_2 cmc_3 pendant pendant_random sessile $GEN"}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
have_evolver=1
command -v "$EVOLVER" >/dev/null 2>&1 || have_evolver=0

now() { date +%s.%N; }

field() { # field NAME LINE
  echo "$2" | tr ' ' '\n' | sed -n "s/^$1=//p"
}

row() { # row LABEL RESULT-LINE
  l=$2
  c=$(field cpvi "$l")
  case $c in ""|-) c=- ;; *) c=$(printf %.2e "$c") ;; esac
  printf '%-16s %6s %6s %6s %9s %9s %9s %9s %9s %7s %8s %9s %10s\n' "$1" \
    "$(printf %.2f "$(field mean "$l")")" "$(printf %.2f "$(field min "$l")")" \
    "$(printf %.1f "$(field above50 "$l")")" \
    "$(printf %.2e "$(field crms "$l")")" "$(printf %.2e "$(field cmax "$l")")" \
    "$(printf %.2e "$(field nrms "$l")")" \
    "$(printf %.1e "$(field verr "$l")")" "$(printf %.1e "$(field rrel "$l")")" \
    "$(field iters "$l")" "$(printf %.3f "$(field secs "$l")")" \
    "$(printf %.2e "$(field spvi "$l")")" "$c"
}

tds_best() { # tds_best OUT ENV...: run tds PAPER_REPEAT times, keep the fastest
  out=$1; shift
  n=${PAPER_REPEAT:-1}; best=
  while [ "$n" -gt 0 ]; do
    (cd "$d" && env "$@" "$TDS" -q "$script") > "$out.try" 2>&1
    s=$(field secs "$(grep '^RESULT' "$out.try")")
    if [ -z "$best" ] || [ "$(echo "${s:-1e9} < $best" | bc -l)" = 1 ]; then
      best=${s:-1e9}; mv "$out.try" "$out"
    fi
    n=$((n - 1))
  done
  rm -f "$out.try"
}

summary=$work/summary
: > "$summary"
for exp in $EXPS; do
  d=$work/$exp
  mkdir -p "$d"
  case $exp in
    */*) script=$ROOT/scripts/paper/gen.tds; PAPER_GEN=$exp; gen=1 ;;
    *) script=$ROOT/scripts/paper/$exp.tds; PAPER_GEN=; gen=0 ;;
  esac
  export PAPER_GEN
  tds_best "$d/tds.out" PAPER_FE=$d/in.fe PAPER_EVOLVER=$d
  tline=$(grep '^RESULT' "$d/tds.out")
  pline=
  if [ $gen = 0 ] || [ -n "$PAPER_GEN_PLAIN" ]; then
    tds_best "$d/plain.out" PAPER_PLAIN=1
    pline=$(grep '^RESULT' "$d/plain.out")
  fi
  [ $gen = 1 ] && [ -n "$tline" ] && echo "$exp tds $tline" >> "$summary"
  echo
  echo "== $exp"
  printf '%-16s %6s %6s %6s %9s %9s %9s %9s %9s %7s %8s %9s %10s\n' run mean min ">50%" \
    "|K|.rms" "|K|.max" "K.n.rms" "vol.err" "r/edge" iters seconds "s/(v*it)" "cpu/(v*it)"
  if [ -z "$tline" ]; then
    echo "tds failed:"; tail -n 5 "$d/tds.out"; continue
  fi
  row "tds pg" "$tline"
  [ -n "$pline" ] && row "tds pg plain" "$pline"
  poline=
  case " ${PAPER_POLISH_EXPS:-hemisphere random_hemisphere cmc_1 cmc_2 cmc_3 pendant pendant_random sessile} " in
    *" $exp "*)
      tds_best "$d/polish.out" PAPER_POLISH=1
      poline=$(grep '^RESULT' "$d/polish.out")
      [ -n "$poline" ] && row "tds pg+polish" "$poline" ;;
  esac
  if [ $have_evolver = 1 ]; then
    if [ -n "$PAPER_G_ITERS" ]; then
      sed -i "s/inx < [0-9]*/inx < $PAPER_G_ITERS/; s/ITERS [0-9]*/ITERS $PAPER_G_ITERS/" "$d/gloop.cmd"
    fi
    for mode in gloop relax; do
      key=
      if [ -n "$CACHE" ]; then
        # (not the header line naming the input's temporary path)
        key=$CACHE/paper-$( (grep -v '^// .*written by tds' "$d/in.fe"; cat "$d/$mode.cmd"
                             echo "$EVOLVER") | md5sum | cut -d' ' -f1)
      fi
      if [ -n "$key" ] && [ -f "$key" ] && [ -f "$key.secs" ]; then
        cp "$key" "$d/$mode.out"
        secs=$(cat "$key.secs")
      else
        t0=$(now)
        (cd "$d" && "$EVOLVER" -f "$mode.cmd" in.fe < /dev/null) > "$d/$mode.out" 2>&1
        t1=$(now)
        secs=$(echo "$t1 - $t0" | bc -l)
        if [ -n "$key" ]; then
          cp "$d/$mode.out" "$key.tmp" && mv "$key.tmp" "$key" && echo "$secs" > "$key.secs"
        fi
      fi
      (cd "$d" && PAPER_DUMP=$d/$mode.out PAPER_LABEL=evolver-$mode PAPER_SECONDS=$secs \
        "$TDS" -q "$script") > "$d/$mode.m" 2>&1
      eline=$(grep '^RESULT' "$d/$mode.m")
      if [ -n "$eline" ]; then
        case $mode in gloop) lab="evolver g;u;V" ;; *) lab="evolver hessian" ;; esac
        row "$lab" "$eline"
        [ $gen = 1 ] && echo "$exp $mode $eline" >> "$summary"
      else
        echo "evolver $mode: no result"; tail -n 3 "$d/$mode.m"
      fi
    done
  fi
  reached=$(field reached "$tline"); preached=$(field reached "$pline")
  [ -n "$reached" ] && echo "r < 1e-13 x mean edge at iteration: pg $reached, plain ${preached:--}"
  [ -n "$poline" ] && echo "pg_polish: $(field polish_iters "$poline") s = 0 iterations after pg's, $(printf %.3f "$(field polish_cpu "$poline")") processor seconds"
  st=$(field status "$tline")
  [ -n "$st" ] && [ "$st" != converged ] && echo "tds pg: $st"
done
[ -s "$summary" ] && awk -f "$ROOT/bench/paper_summary.awk" "$summary"
exit 0
