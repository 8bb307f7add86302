# hessian's line in the string model says "length", with the total edge
# length (as g's and Evolver's: "  1. length: ... energy: ..."); it said
# "area: 0.00000000000000", a soap film's word and the string model's
# (unused) facet area. The numbers are left out (they are compared with
# Evolver elsewhere), the words kept.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/sq.fe" <<'FE'
STRING
SPACE_DIMENSION 2
vertices
1 0 0
2 1 0
3 1 1
4 0 1
edges
1 1 2
2 2 3
3 3 4
4 4 1
faces
1 1 2 3 4
bodies
1 1 volume 1
FE
"$TDS" -q "$tmp/sq.fe" -e 'tds.quiet(true) r() r() g(100) tds.quiet(false)
hessian()
print(("%.6f"):format(total_energy))' 2>&1 | sed 's/  *[0-9.e+-]\{6,\}//g'
echo "exit $?"
