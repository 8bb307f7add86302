#!/bin/sh
# seek.sh: hessian_seek's line search (and saddle's) against Evolver 2.70.
# The same command file runs in both programs on the same start (a
# datafile, or Evolver's dump where the programs' g steps part); after
# each hessian_seek both print the energy (KE) and last_hessian_scale
# (KS). Energies must agree to 1e-10 relative (measured 1.1e-15): the
# line search is the same rule (trials from 0.01 of the largest scale,
# doubling, the parabola through the last three) on the same Newton
# direction and restoring, so only rounding differs. Scales to 1e-6
# (measured 1.8e-8, catbody): near a minimum the parabola's vertex is a
# ratio of energy differences of 1e-7 whose last digits are rounding.
# Cases: the tutorial cube (default scale, 0.5 and 1.5 which cap the
# trials, 300 and 1000 whose first trials rise and are divided by 10; the
# pressure after a seek is the whole Newton step's, which the second seek
# shows), mound.fe, catman.fe at its triangulation saddle with
# hessian_normal on and off (index 15), cat.fe far from equilibrium (the
# search reaches the default largest scale 10) and off its unstable
# catenoid (index 1: the Newton direction goes uphill, both programs seek
# backwards), catbody.fe (a body; from Evolver's dump), and seeded
# inputs: perturbed polygonal bubbles and drops on a tilted line
# (tests/evolver/string/hessgen.lua) and a cube whose refined vertices
# are moved at random (seeds 7 and 19; volume held; g 2 first).
# saddle: the same search along the eigenvector of the lowest
# eigenvalue at Evolver's length (below).
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
[ -n "$KEEP" ] && echo "# kept $tmp" || trap 'rm -rf "$tmp"' EXIT
GEN=$ROOT/tests/evolver/string/hessgen.lua
K='printf "KE %.17g\n", total_energy
printf "KS %.17g\n", last_hessian_scale'

# run NAME FE CMDS: CMDS (with $K after each seek) in both programs;
# energies to 1e-10, scales to 1e-6.
run() {
  evolver_run "$2" "$3" > "$tmp/$1.ev"
  printf '%s\n' "$3" > "$tmp/$1.cmd"
  [ "$2" = "$tmp/$1.fe" ] || cp "$2" "$tmp/$1.fe"
  (cd "$tmp" && "$TDS" -q "$1.fe" -f "$1.cmd") > "$tmp/$1.td" 2>&1
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('seek/$1/energy', lines_of('$tmp/$1.ev', '^KE'), lines_of('$tmp/$1.td', '^KE'), 1e-10)
numcmp('seek/$1/scale', lines_of('$tmp/$1.ev', '^KS'), lines_of('$tmp/$1.td', '^KS'), 1e-6)"
}

E=$EXAMPLES
run cube "$E/cube.fe" "g; r
hessian_seek
$K
hessian_seek
$K
hessian_seek 0.5
$K
hessian_seek 300
$K
g 2
hessian_seek 1.5
$K
hessian_seek 1000
$K"

run mound "$E/mound.fe" "g 5; r; g 5
hessian_seek
$K
hessian_seek 0.3
$K
hessian_seek
$K"

run catman "$E/catman.fe" "g; u; r; g 50
hessian_seek
$K
hessian_normal off
hessian_seek
$K"

evolver_dump seek cat20 "$E/cat.fe" "r; u; g 20"
run cat20 "$tmp/cat20.dmp" "hessian_seek
$K
hessian_seek 1
$K"
evolver_dump seek catup "$E/cat.fe" "r; u; g 20; hessian; hessian; hessian; g 2"
run catup "$tmp/catup.dmp" "hessian_seek
$K
hessian_seek 1
$K"
evolver_dump seek catbody "$E/catbody.fe" "r; g 10"
run catbody "$tmp/catbody.dmp" "hessian_seek
$K
hessian_seek 3
$K"

gen() { "$TDS" -q -e "io.write((dofile('$GEN').$2))" > "$tmp/$1.fe"; }
for c in "12 5" "20 31"; do
  set -- $c
  gen poly$1_$2 "polygon_fe($1, $2)"
  run poly$1_$2 "$tmp/poly$1_$2.fe" "g 2
hessian_seek
$K
hessian_seek 0.2
$K
hessian_seek
$K"
done
for seed in 1 3; do
  gen drop$seed "drop_fe($seed)"
  run drop$seed "$tmp/drop$seed.fe" "r
g 12
hessian_seek
$K
hessian_seek
$K"
done

# the cube refined once, its free vertices moved by up to 0.05 at random
# (x' = (a x + c) mod 2^31 from the seed), volume held; g 2 first (the
# pressure a datafile starts with is 0, from which the two programs'
# first Newton steps part: 6.0026 in Evolver, 5.6504 in tds; after g
# both take g's pressure)
evolver_dump seek cube_r "$E/cube.fe" "r"
for seed in 7 19; do
  "$TDS" -q -e "
local x = $seed
local function rnd() x = (1103515245 * x + 12345) % 2147483648; return x / 2147483648 end
local sect
for l in io.lines('$tmp/cube_r.dmp') do
  local w = l:match('^(%a+)')
  if w then sect = w:lower() end
  local id, a, b, c, rest = l:match('^%s*(%d+)%s+(%S+)%s+(%S+)%s+(%S+)(.*)$')
  if sect == 'vertices' and id and tonumber(a) and not rest:find('fixed') then
    a, b, c = tonumber(a) + 0.1 * (rnd() - 0.5), tonumber(b) + 0.1 * (rnd() - 0.5), tonumber(c) + 0.1 * (rnd() - 0.5)
    l = ('%s %.17g %.17g %.17g%s'):format(id, a, b, c, rest)
  end
  print(l)
end" > "$tmp/cubep$seed.fe"
  run cubep$seed "$tmp/cubep$seed.fe" "g 2
hessian_seek
$K
hessian_seek
$K
hessian_seek 2
$K"
done

# saddle (Evolver's line search along its eigenvector, scaled so that its
# largest unknown is 0.1 of the largest distance of a vertex from the
# origin): at catman's triangulation saddle (every coordinate free), with
# the default largest step and 0.01, and off cat.fe's unstable catenoid.
# The lowest eigenvalue to 1e-8; the energy after it to 1e-8 and the
# size of the step to 1e-6 (measured 6e-10 and 1e-7: Evolver's
# eigenvector is converged to about 6e-6 in direction, so its trials'
# energies are 1e-9 off tds's); the sign of the step is each program's
# own (Evolver's vector has its own sign; tds's goes downhill).
evolver_dump seek catman_off "$E/catman.fe" "g; u; r; g 50
hessian_normal off"
S='printf "KL %.17g\n", last_eigenvalue
printf "KE %.17g\n", total_energy
printf "KS %.17g\n", last_hessian_scale'
saddle_case() {
  ev=$(evolver_run "$tmp/$2.dmp" "$3")
  printf '%s\n' "$3" > "$tmp/$1.cmd"
  td=$(cd "$tmp" && "$TDS" -q "$2.dmp" -f "$1.cmd" 2>&1)
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/compare.lua')
local function col(text, key)
  local t = {}
  for v in text:gmatch(key .. ' (%S+)') do t[#t + 1] = tonumber(v) end
  return t
end
local ev, td = [[$ev]], [[$td]]
local el, tl = col(ev, 'KL'), col(td, 'KL')
local ee, te = col(ev, 'KE'), col(td, 'KE')
local es, ts = col(ev, 'KS'), col(td, 'KS')
local ok = #el > 0 and #el == #tl and #ee == #te and #es == #ts
for i = 1, ok and #el or 0 do ok = ok and near(el[i], tl[i], 1e-8) and el[i] < 0 end
report('seek/$1/lowest', ok, table.concat(tl, ' '), table.concat(el, ' '))
ok = #ee > 0 and #ee == #te
for i = 1, ok and #ee or 0 do ok = ok and near(ee[i], te[i], 1e-8) end
report('seek/$1/energy', ok, table.concat(te, ' '), table.concat(ee, ' '))
ok = #es > 0 and #es == #ts
for i = 1, ok and #es or 0 do ok = ok and near(math.abs(es[i]), math.abs(ts[i]), 1e-6) end
report('seek/$1/step', ok, table.concat(ts, ' '), table.concat(es, ' '))
"
}
saddle_case saddle-catman catman_off "hessian_normal off
saddle
$S"
saddle_case saddle-catman-limit catman_off "hessian_normal off
saddle 0.01
$S"
saddle_case saddle-cat catup "saddle
$S"
