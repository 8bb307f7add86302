# A vertex that cannot be projected onto its constraint as the datafile
# declares it (x^2 + y^2 = -1 has no point) loads with a warning that
# names the file and the vertex's line; it named neither
# ("vertex 2: projection onto its constraints did not converge").
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/w.fe" <<'FE'
constraint 1
formula: x^2 + y^2 = -1
vertices
1 0 0 0
2 1 0 0 constraint 1
3 0 1 0
edges
1 1 2
2 2 3
3 3 1
FE
"$TDS" -q -e "tds.load_datafile('$tmp/w.fe') print(vertex_count)" > "$tmp/out" 2>&1
echo "exit $?"
sed "s|$tmp/||" "$tmp/out"
