# tds.new() surfaces in a tds --safe session are safe too, with the
# session's output folder: a script from someone else cannot escape the
# sandbox by making a surface of its own.
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkdir "$dir/out"
cat > "$dir/escape.tds" <<'LUA'
local s = tds.new{ quiet = true }
s.vertices{ {0,0,0}, {1,0,0}, {0,1,0} }
s.edges{ {1,2}, {2,3}, {3,1} }
s.faces{ {1,2,3} }
print("dump outside", pcall(s.dump, "../stolen.fe"))
print("export outside", pcall(s.export, "stolen.ply"))
print("execute", pcall(s.os.execute, "echo spawned"))
print("outdir", pcall(tds.new, { safe = true, outdir = "/tmp" }))
print("inside", s.dump("out/tri.dmp"))
LUA
cd "$dir" || exit 1
"$TDS" -q --safe --out out escape.tds 2>&1 | sed "s|$dir|DIR|g"
ls out
[ -e stolen.fe ] || [ -e ../stolen.fe ] || [ -e stolen.ply ] || echo "nothing written outside"
