#!/bin/sh
# xattr.sh: element attributes in integrands and constraint formulas
# (Evolver's `define edge attribute angle real` used as `angle` in a
# constraint's energy), the same files and commands run by Surface Evolver
# and tds. The lines starting with K must agree: counts and attribute
# values exactly, energies and quantity values to 1e-10 relative (tds
# takes Evolver's steps with evolver_line_search; measured 4e-15 apart,
# the same sums in another order).
# * addload_example.fe (Evolver's example): its read section addloads
#   itself 8 times and gives each drop its own contact angle, an edge
#   attribute read by the table's energy integrand; then its gogo (refines,
#   g, two hessian steps), with Evolver's search to 1e-10 and with tds's
#   own to 2e-3 (commands.sh's bound for gogos).
# * xattr/gen.lua's drops, seeds 1-3: a random contact angle per edge
#   (constraint energy), a random table curvature per vertex (the
#   constraint's formula), random weights per facet and per edge and the
#   built-in tension and original (named quantities); load, g, r (new
#   vertices have 0 for vertex attributes, split edges and facets keep
#   theirs), attributes changed at run time.
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

K='printf "K %d %d %d %d %.15g\n", vertex_count, edge_count, facet_count, body_count, total_energy'
for run in "load|$K|" "gogo-evolver-search|gogo; $K|tds.setting('evolver_line_search', true)|1e-10" \
           "gogo|gogo; $K||2e-3"; do
  name=${run%%|*} rest=${run#*|}
  cmd=${rest%%|*} rest=${rest#*|}
  lua=${rest%%|*} tol=${rest#*|}
  evolver_run "$EXAMPLES/addload_example.fe" "$cmd" | grep '^K ' > "$tmp/ev.k"
  cp "$EXAMPLES/addload_example.fe" "$tmp/"
  printf '%s\n' "$cmd" > "$tmp/c.cmd"
  (cd "$tmp" && "$TDS" -q addload_example.fe -e "$lua" -f c.cmd) 2>&1 | grep '^K ' > "$tmp/tds.k"
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('xattr/addload_example/$name', lines_of('$tmp/ev.k', '^K'), lines_of('$tmp/tds.k', '^K'), ${tol:-1e-10})"
done

cmds=$(cat "$ROOT/tests/evolver/xattr/drop.cmd")
for seed in 1 2 3; do
  "$TDS" -q -e "dofile('$ROOT/tests/evolver/xattr/gen.lua'); xdrop($seed, '$tmp/xdrop$seed.fe')"
  evolver_run "$tmp/xdrop$seed.fe" "$cmds" | grep '^K ' > "$tmp/ev.k"
  "$TDS" -q "$tmp/xdrop$seed.fe" -e "tds.setting('evolver_line_search', true)" \
    -f "$ROOT/tests/evolver/xattr/drop.cmd" 2>&1 | grep '^K ' > "$tmp/tds.k"
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('xattr/drop$seed', lines_of('$tmp/ev.k', '^K'), lines_of('$tmp/tds.k', '^K'), 1e-10)"
done
