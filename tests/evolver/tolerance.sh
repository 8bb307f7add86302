#!/bin/sh
# tolerance.sh: when Evolver's restoring moves stop (src/iterate.c,
# evolver_off), measured on evolver-nox-d 2.70 with cube.fe scaled by
# 0.01, 0.1 and 100 (volumes 1e-6, 1e-3, 1e6) and with its volume as a
# fixed named quantity instead of a body. Evolver's manual: the moves go
# on until "the sum of all ratios of quantity discrepancies to
# tolerances is less than 1", the tolerance target_tolerance (1e-4). What
# Evolver does: a body's tolerance is absolute (the cube of volume 1e6
# stops 9.5e-5 off after a step, the one of 1e-6 1.3e-9 off after one
# move), a named quantity's is relative to its target (1e6: 49 off, 4.9e-5
# of it). tds does the same: energy and the distance to the target after
# fixed-scale steps, to 1e-10 relative (absolute below 1) for the energy
# and volume, and the distance to the target to 1e-3 of itself (at 1e6 it
# is the difference of two numbers near 1e6: measured 3e-5 of itself,
# 6e-16 of the volume; another stopping rule would change it by orders of
# magnitude: one move more squares it).
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for s in 0.01 0.1 100; do
  awk -v s=$s '/^vertices/ { v = 1; print; next } /^edges/ { v = 0 }
    v && NF >= 4 { printf "%s %.17g %.17g %.17g\n", $1, $2 * s, $3 * s, $4 * s; next }
    /volume 1$/ { sub(/volume 1$/, sprintf("volume %.17g", s * s * s)) }
    /^read/ { exit } { print }' "$EXAMPLES/cube.fe" > "$tmp/cube$s.fe"
  { echo "quantity qv fixed = $(awk -v s=$s 'BEGIN { printf "%.17g", s * s * s }') method facet_vector_integral global"
    printf 'vector_integrand:\nq1: 0\nq2: 0\nq3: z\n'
    sed '/^bodies/,$d' "$tmp/cube$s.fe"; } > "$tmp/q$s.fe"
  B='printf "K1 %.15g %.15g\n", total_energy, body[1].volume; printf "K2 %.15g\n", body[1].volume - body[1].target;'
  Q='printf "K1 %.15g %.15g\n", total_energy, qv.value; printf "K2 %.15g\n", qv.value - qv.target;'
  for c in "m 0.1; g 1" "m 0.1; g 3" "r; m 0.05; g 3"; do
    n=$(echo "$c" | tr -d ' ;.')
    for kind in body q; do
      f=$tmp/cube$s.fe P=$B
      [ $kind = q ] && f=$tmp/q$s.fe P=$Q
      evolver_run "$f" "$c; $P" | grep '^K' > "$tmp/ev.k"
      printf '%s\n' "$c; $P" > "$tmp/c.cmd"
      cp "$f" "$tmp/run.fe"
      (cd "$tmp" && "$TDS" -q run.fe -f c.cmd) 2>&1 | grep '^K' > "$tmp/tds.k"
      "$TDS" -q -e "dofile('$ROOT/tests/evolver/numcmp.lua')
local ev, td = lines_of('$tmp/ev.k', '^K1'), lines_of('$tmp/tds.k', '^K1')
local ev2, td2 = lines_of('$tmp/ev.k', '^K2'), lines_of('$tmp/tds.k', '^K2')
numcmp('tolerance/$kind-$s/$n', ev, td, 1e-10)
-- the distance to the target, relative to itself
local a, b = tonumber((ev2[1] or ''):match('K2 (%S+)')), tonumber((td2[1] or ''):match('K2 (%S+)'))
local ok = a and b and math.abs(a - b) <= 1e-3 * math.abs(a)
print((ok and 'PASS' or 'FAIL') .. ' tolerance/$kind-$s/$n-off' .. (ok and '' or (': Evolver %s, tds %s'):format(a, b)))"
    done
  done
done
