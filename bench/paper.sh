#!/bin/sh
# paper.sh: the paper's experiments in tds (pg) and in Surface Evolver from
# the same input, with the same metric code (doc/paper-results.md).
# Usage: sh bench/paper.sh [TDS_BINARY] [EXPERIMENT ...]
# Env: EVOLVER (default evolver-nox-d); PAPER_G_ITERS (g; u; V rounds, 1000);
# PAPER_REPEAT (default 1): run each tds row that many times and show the
# fastest run (the runs are identical but for their timings).
TDS=${1:-./tds}
[ $# -gt 0 ] && shift
case $TDS in /*) ;; *) TDS=$(pwd)/$TDS ;; esac
EVOLVER=${EVOLVER:-evolver-nox-d}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
EXPS=${*:-"hemisphere random_hemisphere catenoid schwarz_p cmc_1 cmc_2 cmc_3 pendant pendant_random sessile"}
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

for exp in $EXPS; do
  d=$work/$exp
  mkdir -p "$d"
  script=$ROOT/scripts/paper/$exp.tds
  tds_best "$d/tds.out" PAPER_FE=$d/in.fe PAPER_EVOLVER=$d
  tline=$(grep '^RESULT' "$d/tds.out")
  tds_best "$d/plain.out" PAPER_PLAIN=1
  pline=$(grep '^RESULT' "$d/plain.out")
  echo
  echo "== $exp"
  printf '%-16s %6s %6s %6s %9s %9s %9s %9s %9s %7s %8s %9s %10s\n' run mean min ">50%" \
    "|K|.rms" "|K|.max" "K.n.rms" "vol.err" "r/edge" iters seconds "s/(v*it)" "cpu/(v*it)"
  if [ -z "$tline" ]; then
    echo "tds failed:"; tail -n 5 "$d/tds.out"; continue
  fi
  row "tds pg" "$tline"
  [ -n "$pline" ] && row "tds pg plain" "$pline"
  if [ $have_evolver = 1 ]; then
    if [ -n "$PAPER_G_ITERS" ]; then
      sed -i "s/inx < [0-9]*/inx < $PAPER_G_ITERS/; s/ITERS [0-9]*/ITERS $PAPER_G_ITERS/" "$d/gloop.cmd"
    fi
    for mode in gloop relax; do
      t0=$(now)
      (cd "$d" && "$EVOLVER" -f "$mode.cmd" in.fe < /dev/null) > "$d/$mode.out" 2>&1
      t1=$(now)
      secs=$(echo "$t1 - $t0" | bc -l)
      (cd "$d" && PAPER_DUMP=$d/$mode.out PAPER_LABEL=evolver-$mode PAPER_SECONDS=$secs \
        "$TDS" -q "$script") > "$d/$mode.m" 2>&1
      eline=$(grep '^RESULT' "$d/$mode.m")
      if [ -n "$eline" ]; then
        case $mode in gloop) lab="evolver g;u;V" ;; *) lab="evolver hessian" ;; esac
        row "$lab" "$eline"
      else
        echo "evolver $mode: no result"; tail -n 3 "$d/$mode.m"
      fi
    done
  fi
  reached=$(field reached "$tline"); preached=$(field reached "$pline")
  [ -n "$reached" ] && echo "r < 1e-13 x mean edge at iteration: pg $reached, plain $preached"
done
