# User attributes in the Evolver command language: list writes them after
# each element as Evolver 2.70 does (" weight 2.5", integer arrays
# "{1,2,3}", real arrays "{1.5, 2}"), foreach/printf reads them, set ...
# where changes them, define ... attribute adds one at run time, and a
# wrong value is an error naming the element.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/t.fe" <<'FE'
define vertex attribute weight real
define edge attribute ew real[2]
define facet attribute flags integer[3]
define body attribute bw real
vertices
1 0 0 0 weight 2.5
2 1 0 0 weight -1
3 1 1 0
4 0 1 0
5 0 0 1
6 1 0 1
7 1 1 1
8 0 1 1
edges
1 1 2 ew {1.5, 2}
2 2 3
3 3 4
4 4 1
5 5 6
6 6 7
7 7 8
8 8 5
9 1 5
10 2 6
11 3 7
12 4 8
faces
1 1 10 -5 -9 flags {1,2,3} color red
2 2 11 -6 -10
3 3 12 -7 -11
4 4 9 -8 -12
5 5 6 7 8
6 -4 -3 -2 -1
bodies
1 1 2 3 4 5 6 volume 1 bw 7
FE
cat > "$tmp/c.cmd" <<'CMD'
list vertex where id <= 3
list edge where id <= 2
list facet where id <= 2
list body
set vertex weight z + 0.5 where z > 0
foreach vertex vv where id >= 4 and id <= 6 do printf "%d %g\n", vv.id, vv.weight
define vertex attribute tag integer[2]
set vertex tag[2] id * 10 where id < 3
print vertex[2].tag[2]
print facet[1].flags[3] + edge[1].ew[1]
set facet flags[1] 2.5 where id == 1
CMD
"$TDS" -q "$tmp/t.fe" -f "$tmp/c.cmd" > "$tmp/out" 2>&1
rc=$?
sed "s|$tmp/||" "$tmp/out"
echo "exit $rc"
