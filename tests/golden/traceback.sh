# Errors point at the user's line, never at tds's own Lua ([tds prelude]);
# an error inside the user's functions also shows the chain of the user's
# calls (C and tds's embedded modules left out); at the top level the
# position alone.
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cat > "$dir/nested.tds" <<'LUA'
vertices{ {0,0,0}, {1,0,0}, {0,1,0} }
local function relax(n)
  g(n)
end
local function run(list)
  for _, n in ipairs(list) do relax(n) end
end
run{ 1, "many" }
LUA
cat > "$dir/decl.tds" <<'LUA'
local function build()
  edges{ {1, 2} }
end
build()
LUA
cat > "$dir/top.tds" <<'LUA'
vertices{ {0,0,0} }
print(vertex[1].colour)
LUA
cat > "$dir/cross.tds" <<'LUA'
local a, b = tds.new{ quiet = true }, tds.new{ quiet = true }
a.vertices{ {0,0,0} }
b.vertices{ {0,0,0} }
local function move(s, v) s.V(v) end
move(b, a.vertex[1])
LUA
cd "$dir" || exit 1
for f in nested decl top cross; do
  "$TDS" -q "$f.tds"
  echo "exit $?"
done 2>&1 | sed "s|$dir/||g"
