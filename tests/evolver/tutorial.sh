#!/bin/sh
# tutorial.sh: the manual's tutorial command files (copies of
# ../shared/reference/cmds/*.cmd in tutorial/) run unchanged in tds and in
# Surface Evolver on the shipped datafiles; the lines they print are
# compared with numcmp.lua.
# * Counts (r's "Vertices: ..." lines) exactly.
# * Volumes and pressures (v's lines) to 1e-6: the volume is held at its
#   target to the projection tolerance and the pressure is a multiplier.
# * Energies and areas after many steps to 1e-3 relative: `g` takes the
#   same steps with a line search that differs in detail, so unconverged
#   values differ by the line search only (converge.sh checks the minima
#   to 1e-8).
# Command files that reach a command tds does not have must stop with an
# error naming it (and tds exits 1, as for any error in a command file).
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
T=$ROOT/tests/evolver/tutorial

# run NAME FE CMD PATTERN TOL
run() {
  name=$1 fe=$EXAMPLES/$2 cmd=$T/$3 pat=$4 tol=$5
  evolver_run "$fe" "$(grep -v '^q$' "$cmd")" > "$tmp/ev.out"
  cp "$fe" "$tmp/in.fe"
  cp "$cmd" "$tmp/c.cmd"
  if ! (cd "$tmp" && "$TDS" in.fe -f c.cmd) > "$tmp/tds.out" 2> "$tmp/tds.err"; then
    echo "FAIL tutorial/$name: tds failed: $(head -n 2 "$tmp/tds.err" | tr '\n' ' ')"
    return
  fi
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('tutorial/$name', lines_of('$tmp/ev.out', '$pat'), lines_of('$tmp/tds.out', '$pat'), $tol)"
}

# stops NAME FE CMD COMMAND: tds must stop at COMMAND, naming it.
stops() {
  cp "$EXAMPLES/$2" "$tmp/in.fe"
  cp "$T/$3" "$tmp/c.cmd"
  (cd "$tmp" && "$TDS" -q in.fe -f c.cmd) > "$tmp/tds.out" 2>&1
  rc=$?
  if [ $rc -eq 1 ] && grep -q ": $4: not supported yet" "$tmp/tds.out"; then
    echo "PASS tutorial/$1 (stops at unsupported '$4')"
  else
    echo "FAIL tutorial/$1: expected an error naming $4 and exit 1, got exit $rc: $(tail -n 1 "$tmp/tds.out")"
  fi
}

run cube-counts cube.fe cube_tutorial.cmd '^Vertices:' 0
run cube-volume cube.fe cube_tutorial.cmd '^  1  ' 1e-6
run catman-saddle catman.fe catman_saddle.cmd '^after' 1e-3
run catman-cg catman.fe catman_cg.cmd '^area' 1e-3
# With Newton steps: after hessian the energies converge faster than the
# g paths they start from agree (1e-4 and below here), and the step
# restricted to the normals keeps the tangential positions g left, so
# these compare to 1e-3 as the g runs do.
run cube-gogo cube.fe cube_gogo.cmd '^total_area' 1e-3
run mound mound.fe mound_tutorial.cmd '^G=' 1e-3
run column column.fe column_tutorial.cmd '^energy' 1e-3
stops cat cat.fe cat_tutorial.cmd t
