#!/bin/sh
# drawmodes.sh: the torus model's display modes (raw_cells, connected,
# clipped) against Surface Evolver, through detorus, which in both programs
# makes the surface as drawn. Inputs: twointor.fe, phelanc.fe (read section
# cut off), tests/evolver/torus/kelvin.fe (skew periods) and twointor.fe
# with a DISPLAY_ORIGIN, each moved by three seeded random shifts (so
# facets cross the cell's faces anywhere).
# * raw_cells: vertex, edge and facet counts exactly, total area (1e-12
#   relative: the same sums in another order);
# * connected: the same, and every body's volume (1e-12): each body's
#   facets joined into its closed cell, facets both sides of which land in
#   the same place kept once, as in Evolver;
# * clipped: the area (1e-12) and the Euler characteristic V - E + F
#   exactly; every tds vertex is an Evolver vertex (1e-9: Evolver's
#   printed coordinates), and every Evolver vertex that tds does not have
#   lies on a face of the clip box. (Evolver cuts its triangles plane by
#   plane, so its earlier cuts' diagonals meet the later planes in extra
#   points; tds cuts each facet as a polygon and fans the piece: the same
#   surface, fewer triangles.)
# Evolver's detorus also splits bodies into connected pieces and numbers
# them anew (rebody); tds keeps the bodies, so body volumes are compared
# for connected only, as sorted lists.
. "$(dirname "$0")/lib.sh"

# As kcompare (lib.sh), with the volumes of the K3 lines sorted.
vcompare() {
  evolver_run "$2" "$4" | grep '^K' | awk '$1 == "K3" { print "K3", $3; next } { print }' |
    sort -k1,1 -k2,2g > "$tmp/ev.k"
  printf '%s\n' "$4" > "$tmp/c.cmd"
  cp "$2" "$tmp/run.fe"
  (cd "$tmp" && "$TDS" -q run.fe -f c.cmd) 2>&1 | grep '^K' |
    awk '$1 == "K3" { print "K3", $3; next } { print }' | sort -k1,1 -k2,2g > "$tmp/tds.k"
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('$1', lines_of('$tmp/ev.k', '^K'), lines_of('$tmp/tds.k', '^K'), $3)"
}

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sed '/^read/,$d' "$EXAMPLES/phelanc.fe" > "$tmp/phelanc.fe"
cp "$EXAMPLES/twointor.fe" "$tmp/twointor.fe"
cp "$ROOT/tests/evolver/torus/kelvin.fe" "$tmp/kelvin.fe"
# the clip box moved: DISPLAY_ORIGIN is its lower corner in Evolver 2.70
# (its manual says centre)
sed 's/^TORUS_FILLED/TORUS_FILLED\nDISPLAY_ORIGIN 0.3 -0.2 0.45/' "$EXAMPLES/twointor.fe" > "$tmp/origin.fe"

COUNTS='printf "K1 %d %d %d\n", vertex_count, edge_count, facet_count; printf "K2 %.15g\n", total_area;'
VOLS='foreach body bb do printf "K3 %d %.15g\n", bb.id, bb.volume;'
CLIP='printf "K1 %d\n", vertex_count - edge_count + facet_count; printf "K2 %.15g\n", total_area;'
VERTS='foreach vertex vv do printf "V %.12f %.12f %.12f\n", vv.x, vv.y, vv.z;'

seed=0
for f in twointor phelanc kelvin origin; do
  for s in 1 2 3; do
    seed=$((seed + 1))
    # a shift in [0.05, 0.95) of a unit along each axis, from a seeded LCG
    shift=$(awk -v s=$seed 'BEGIN { srand(7919 * s); printf "set vertex x x+%.4f; set vertex y y+%.4f; set vertex z z+%.4f;", 0.05 + 0.9 * rand(), 0.05 + 0.9 * rand(), 0.05 + 0.9 * rand() }')
    kcompare "drawmodes/$f/$s/raw" "$tmp/$f.fe" 1e-12 "$shift raw_cells; detorus; $COUNTS"
    vcompare "drawmodes/$f/$s/connected" "$tmp/$f.fe" 1e-12 "$shift connected; detorus; $COUNTS $VOLS"
    kcompare "drawmodes/$f/$s/clipped" "$tmp/$f.fe" 1e-12 "$shift clipped; detorus; $CLIP"
    # the clipped vertices: tds's among Evolver's, Evolver's others on the box
    evolver_run "$tmp/$f.fe" "$shift clipped; detorus; $VERTS" | grep '^V ' > "$tmp/ev.v"
    printf '%s\n' "$shift clipped; detorus; $VERTS" > "$tmp/v.cmd"
    (cd "$tmp" && "$TDS" -q "$f.fe" -f v.cmd) | grep '^V ' > "$tmp/tds.v"
    "$TDS" -q -e "
local function read(path)
  local t = {}
  for l in io.lines(path) do
    local x, y, z = l:match('^V (%S+) (%S+) (%S+)')
    t[#t + 1] = {tonumber(x), tonumber(y), tonumber(z)}
  end
  return t
end
local ev, td = read('$tmp/ev.v'), read('$tmp/tds.v')
local function key(p) return ('%.7f %.7f %.7f'):format(p[1] + 0, p[2] + 0, p[3] + 0) end
local function near(p, set)
  for _, q in ipairs(set) do
    if math.abs(p[1] - q[1]) < 1e-9 and math.abs(p[2] - q[2]) < 1e-9 and math.abs(p[3] - q[3]) < 1e-9 then return true end
  end
end
-- lattice coordinates from the clip box's corner
tds.load_datafile('$tmp/$f.fe')
local per, org = tds.periods(), tds.display_origin() or {0, 0, 0}
local function lattice(p)
  -- solve p = sum c_i per[i] by Cramer's rule
  local a = per
  local function det(m) return m[1][1]*(m[2][2]*m[3][3]-m[2][3]*m[3][2]) - m[1][2]*(m[2][1]*m[3][3]-m[2][3]*m[3][1]) + m[1][3]*(m[2][1]*m[3][2]-m[2][2]*m[3][1]) end
  local M = {{a[1][1], a[2][1], a[3][1]}, {a[1][2], a[2][2], a[3][2]}, {a[1][3], a[2][3], a[3][3]}}
  local d, c = det(M), {}
  for i = 1, 3 do
    local N = {{M[1][1], M[1][2], M[1][3]}, {M[2][1], M[2][2], M[2][3]}, {M[3][1], M[3][2], M[3][3]}}
    for r = 1, 3 do N[r][i] = p[r] - org[r] end
    c[i] = det(N) / d
  end
  return c
end
local bad
if #td == 0 or #ev < #td then bad = ('%d tds vertices, %d Evolver vertices'):format(#td, #ev) end
for _, p in ipairs(td) do
  if not bad and not near(p, ev) then bad = 'tds vertex ' .. key(p) .. ' is not an Evolver vertex' end
end
local extra = 0
for _, p in ipairs(ev) do
  if not bad and not near(p, td) then
    extra = extra + 1
    local c, onface = lattice(p), false
    for i = 1, 3 do onface = onface or math.abs(c[i]) < 1e-9 or math.abs(c[i] - 1) < 1e-9 end
    if not onface then bad = 'Evolver vertex ' .. key(p) .. ' tds lacks is not on the clip box' end
  end
end
print(bad and ('FAIL drawmodes/$f/$s/clipped-vertices: ' .. bad) or 'PASS drawmodes/$f/$s/clipped-vertices')
"
  done
done

# The mode and the clip box survive a dump: tds dumps origin.fe in clipped
# mode; Evolver reads the dump (its read section sets the mode) and
# detoruses it to what tds makes of the original.
printf 'clipped\ndump "%s"\n' "$tmp/mode.dmp" > "$tmp/d.cmd"
(cd "$tmp" && "$TDS" -q origin.fe -f d.cmd) > /dev/null 2>&1
if [ -s "$tmp/mode.dmp" ]; then
  evolver_run "$tmp/mode.dmp" "detorus; $CLIP" | grep '^K' > "$tmp/ev.k"
  printf '%s\n' "clipped; detorus; $CLIP" > "$tmp/c2.cmd"
  (cd "$tmp" && "$TDS" -q origin.fe -f c2.cmd) 2>&1 | grep '^K' > "$tmp/tds.k"
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('drawmodes/dump-mode', lines_of('$tmp/ev.k', '^K'), lines_of('$tmp/tds.k', '^K'), 1e-12)"
else
  echo "FAIL drawmodes/dump-mode: tds did not dump"
fi

# The string model detoruses raw cells only: 100grain.fe's read section
# turns clipped on, so detorus warns and makes what Evolver's raw_cells;
# detorus makes (vertex and edge counts; Evolver also splits some cells).
ev=$(evolver_run "$EXAMPLES/100grain.fe" 'raw_cells; detorus; printf "K %d %d\n", vertex_count, edge_count;' | grep '^K ')
td=$("$TDS" -q "$EXAMPLES/100grain.fe" -e 'detorus() print(("K %d %d"):format(vertex_count, edge_count))' 2>&1)
case "$td" in
  *"detorus: clipped mode is not supported yet in the string model"*"$ev"*) echo "PASS drawmodes/string-raw" ;;
  *) echo "FAIL drawmodes/string-raw: Evolver '$ev', tds '$td'" ;;
esac

# The string model's clipped pictures and exports: 100grain.fe's edges cut
# into the cell, the points and segments of Evolver's clipped detorus.
ev=$(evolver_run "$EXAMPLES/100grain.fe" 'detorus; printf "K %d %d\n", vertex_count, edge_count;' | grep '^K ')
"$TDS" -q "$EXAMPLES/100grain.fe" -e "export('$tmp/g.obj')" > /dev/null 2>&1
td=$(awk '/^v / { n++; for (i = 2; i <= 3; i++) if ($i < -1e-12 || $i > 1 + 1e-12) out++ }
          /^l / { l++ } END { printf "K %d %d%s", n, l, out ? " outside" : "" }' "$tmp/g.obj")
if [ -n "$ev" ] && [ "$ev" = "$td" ]; then echo "PASS drawmodes/string-clipped-export"
else echo "FAIL drawmodes/string-clipped-export: Evolver '$ev', tds '$td'"; fi
