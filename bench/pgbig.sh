#!/bin/sh
# pgbig.sh: pg() on large generated inputs (issue 13: "pg on a 100k-vertex
# surface converging in under a minute"). Each input is a case of
# scripts/paper/generate.lua built with PAPER_SIZE interior points (the
# border scaled with it, seeded), run by scripts/paper/gen.tds (accelerated
# pg() until converged, then the paper's metrics). Reported per input:
# vertices, iterations, the first iteration with r < 1e-13 x mean edge,
# how the run ended, pg's wall seconds, wall and processor seconds per
# vertex-iteration, the whole process's wall seconds (input built, pg,
# metrics) and its peak memory, and the mean smallest angle.
# With Evolver (evolver-nox-d) on PATH, it also times Evolver's `g` on the
# same input (the .fe twin): PGBIG_G steps (default 100; Evolver's `g`
# does not converge to pg's 1e-13 in any reasonable time at this size,
# so its speed per vertex-iteration is what is compared), processor
# seconds from its `clock`.
# The goal is a minute per 100k input; today a 100k input takes an hour or
# more (doc/paper-results.md, Large inputs): PGBIG_SIZES="1000 4000" or a
# PGBIG_MAX cap for a quick look.
# Usage: sh bench/pgbig.sh [TDS_BINARY]
# Env: PGBIG_SIZES (default "100000"), PGBIG_CASES (default
# "hemisphere/3 catenoid/1 drop/1": a jittered lattice on the hemisphere,
# random points on the catenoid, random points on the pendant drop),
# PGBIG_MAX (pg's iteration cap, default 100000), PGBIG_EVOLVER=0 (no
# Evolver), PGBIG_G.
TDS=${1:-./tds}
case $TDS in /*) ;; *) TDS=$(pwd)/$TDS ;; esac
ROOT=$(cd "$(dirname "$0")/.." && pwd)
EVOLVER=${EVOLVER:-evolver-nox-d}
SIZES=${PGBIG_SIZES:-100000}
CASES=${PGBIG_CASES:-"hemisphere/3 catenoid/1 drop/1"}
GSTEPS=${PGBIG_G:-100}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
have_evolver=0
[ "${PGBIG_EVOLVER:-1}" != 0 ] && command -v "$EVOLVER" >/dev/null 2>&1 && have_evolver=1
field() { echo "$2" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
echo "machine: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-30s %7s %6s %7s %-10s %8s %9s %9s %8s %7s %6s %10s\n' input vertices iters reached status pg.secs 's/(v*it)' 'cpu/(v*it)' total.s peak.MB mean 'ev.g s/(v*it)'
for n in $SIZES; do
  for c in $CASES; do
    d=$work/run
    rm -rf "$d"; mkdir -p "$d"
    fe=
    [ $have_evolver = 1 ] && fe=$d/in.fe
    t0=$(date +%s.%N)
    ( cd "$ROOT" && env PAPER_GEN=$c PAPER_SIZE=$n PAPER_MAX=${PGBIG_MAX:-100000} \
      ${fe:+PAPER_FE=$fe} /usr/bin/time -f "PEAK %M" "$TDS" -q scripts/paper/gen.tds ) > "$d/out" 2>&1
    t1=$(date +%s.%N)
    l=$(grep '^RESULT ' "$d/out")
    if [ -z "$l" ]; then echo "$c n=$n: no result"; tail -n 5 "$d/out"; continue; fi
    name=$(echo "$l" | cut -d' ' -f2)
    peak=$(awk '/^PEAK /{printf "%.0f", $2 / 1024}' "$d/out")
    ev=-
    if [ $have_evolver = 1 ] && [ -s "$fe" ]; then
      printf 'quiet on\nt0 := clock\ng %d\nt1 := clock\nprintf "EVG %%.6f %%d\\n", t1 - t0, vertex_count\nq\n' "$GSTEPS" > "$d/g.cmd"
      evl=$(cd "$d" && "$EVOLVER" -f g.cmd in.fe < /dev/null 2>&1 | grep '^EVG ')
      set -- $evl
      [ -n "$2" ] && ev=$(awk -v s="$2" -v v="$3" -v g="$GSTEPS" 'BEGIN { printf "%.2e", s / (v * g) }')
    fi
    nv=$(field nv "$l")
    printf '%-30s %7s %6s %7s %-10s %8.1f %9.2e %9s %8.1f %7s %6.2f %10s\n' "$name" "$nv" \
      "$(field iters "$l")" "$(field reached "$l")" "$(field status "$l")" "$(field secs "$l")" \
      "$(field spvi "$l")" "$(printf %.2e "$(field cpvi "$l")")" \
      "$(echo "$t1 - $t0" | bc)" "$peak" "$(field mean "$l")" "$ev"
  done
done
