# Inconsistent bodies and zero-area facets are reported at load and by
# check() (Evolver's WARNING 8745), and a correct surface gets no warning.
# Two stacked cubes sharing a face: its edges are triple junctions.
run() { "$TDS" -q "$@" 2>&1; echo "exit $?"; }
run -e 'dofile("twocubes.lua") print(check())'
# Face 6 listed with the wrong sign in body 2: its four edges.
run -e 'SIGNS = {1,1,1,1,1,1} dofile("twocubes.lua")'
# Any nonempty subset of body 2's faces reversed (a seeded choice of 12 of
# the 63, and all six) is reported: with all six, face 6 would have body 2
# on the side where body 1 is.
for mask in $(awk 'BEGIN { srand(7); for (k = 0; k < 12; k++) print 1 + int(rand() * 62) }') 63; do
  signs=$(awk -v m="$mask" 'BEGIN { s = ""; for (b = 0; b < 6; b++) { v = int(m / 2^b) % 2 ? -1 : 1; if (b == 5) v = -v; s = s (b ? "," : "") v } print s }')
  n=$("$TDS" -q -e "SIGNS = {$signs} dofile('twocubes.lua') local _, n = check() print(n)" 2>/dev/null)
  echo "reversed set $mask: $( [ "$n" -gt 0 ] && echo "$n warnings" || echo none)"
done
# A single cube turned inside out is consistent: no warning.
run -e "$(sed 's/{1,2,3,4,5,6, volume = 1}/{-1,-2,-3,-4,-5,-6}/' ../../scripts/cube.tds) print(check())"
# A facet whose corners coincide.
run -e 'vertices { {0,0,0}, {1,0,0}, {1,0,0} } edges { {1,2}, {2,3}, {3,1} } faces { {1,2,3} } print(check())'
