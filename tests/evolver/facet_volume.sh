#!/bin/sh
# facet_volume.sh: Evolver's facet_volume method (the integral of z dx dy
# over the facets) in named quantities: cube.fe with its volume held by a
# fixed quantity `method facet_volume` instead of the body, and an
# info_only one. Evolver and tds print the same counts, energy, values
# and the fixed quantity's pressure after loading, after g 10 (tds with
# Evolver's line search: measured 1.5e-12 apart) and after r, so 1e-10.
# (Later steps are not compared: after a refinement the two programs'
# restoring steps for fixed quantities differ by 3e-7, with
# facet_vector_integral as well.)
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sed -e 's/^1 *1 2 3 4 5 6 *volume 1/1 1 2 3 4 5 6/' \
    -e 's/^vertices/quantity vq fixed = 1 method facet_volume global\nquantity vi info_only method facet_volume global\nvertices/' \
    "$EXAMPLES/cube.fe" > "$tmp/cfv.fe"
cmd='pk := {printf "K %d %d %.15g %.15g %.15g %.15g\n", vertex_count, facet_count, total_energy, vq.value, vi.value, vq.pressure}
pk; g 10; pk; r; pk'
evolver_run "$tmp/cfv.fe" "$cmd" | grep '^K ' > "$tmp/ev.k"
printf '%s\n' "$cmd" > "$tmp/c.cmd"
"$TDS" -q "$tmp/cfv.fe" -e "tds.setting('evolver_line_search', true)" -f "$tmp/c.cmd" 2>&1 |
  grep '^K ' > "$tmp/tds.k"
"$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('facet_volume/cube', lines_of('$tmp/ev.k', '^K'), lines_of('$tmp/tds.k', '^K'), 1e-10)"
