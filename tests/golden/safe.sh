# tds --safe: a script or datafile from someone else runs without process
# spawning, native libraries, bytecode or writes outside the output folder;
# each refusal is a clear error. Reading and writing inside --out work.
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkdir "$dir/out"
cp ../../scripts/cube.tds "$dir/cube.tds"
cat > "$dir/evil.tds" <<'LUA'
local function try(what, f, ...)
  local ok, err = pcall(f, ...)
  print(what, ok and "allowed" or err)
end
try("execute", os.execute, "echo spawned")
try("popen", io.popen, "ls")
try("loadlib", package.loadlib, "libc.so.6", "puts")
try("tmpname", os.tmpname)
try("open w", io.open, "../victim.txt", "w")
try("open a", io.open, "/tmp/tds-safe-victim.txt", "a")
try("open r+", io.open, "cube.tds", "r+")
try("output", io.output, "x.txt")
try("remove", os.remove, "cube.tds")
try("rename", os.rename, "cube.tds", "out/c.tds")
try("dump", dump, "stolen.fe")
try("write_fe", write_fe, "stolen.fe")
print("bytecode", load(string.dump(function() return 1 end)))
print("bytecode b", load(string.dump(function() return 1 end), "x", "b"))
local bc = assert(io.open("out/pre.luac", "wb"))
bc:write(string.dump(function() return 1 end))
bc:close()
print("loadfile b", loadfile("out/pre.luac", "b"))
print("loadfile env", loadfile("out/pre.luac", "bt", {}))
print("dofile", pcall(dofile, "out/pre.luac"))
print("C modules", package.cpath == "", #package.searchers)
bc = assert(io.open("out/bcmod.lua", "wb"))
bc:write(string.dump(function() return 1 end))
bc:close()
package.path = "out/?.lua"
print("require", pcall(require, "bcmod"))
print("debug", debug)
print("text load", load("return 6 * 7")())
print("read", io.open("cube.tds"):read("l"))
dofile("cube.tds")
local f = assert(io.open("out/note.txt", "w"))
f:write("inside the output folder\n")
f:close()
dump("out/cube.dmp")
write_fe("out/cube.fe")
print("written", vertex_count, io.open("out/note.txt"):read("l"))
LUA
cd "$dir" || exit 1
run() { "$TDS" -q "$@" > run.out 2>&1; rc=$?; sed "s|$dir|DIR|g" run.out; echo "exit $rc"; }
run --safe --out out evil.tds
ls out | grep -v run.out
[ -e "$dir/victim.txt" ] || [ -e /tmp/tds-safe-victim.txt ] || [ -e stolen.fe ] || echo "nothing written outside"
# A file named as a datafile, or not named .tds/.lua, is never run as Lua
# in safe mode, whatever its content.
printf 'os.execute("echo spawned")\n' > lua_inside
run --safe lua_inside
cp lua_inside lua_inside.fe
run lua_inside.fe
# a precompiled chunk named .tds is refused in safe mode and out of it
"$TDS" -q -e 'local f = io.open("pre.tds", "wb") f:write(string.dump(function() print("ran") end)) f:close()'
run --safe pre.tds
run pre.tds
# the output folder must exist; --out needs --safe
run --safe --out nowhere -e 'print(1)'
run --out out -e 'print(1)'
# Evolver's command language in a datafile's read section: system, a pipe
# and a redirection outside the output folder are refused.
cp /usr/share/doc/evolver/examples/cube.fe cube_system.fe
cp cube_system.fe cube_clean.fe
cp cube_system.fe cube_pipe.fe
cp cube_system.fe cube_redirect.fe
printf '\nsystem "touch spawned_system"\n' >> cube_system.fe
printf '\nprint 1 | "touch spawned_pipe"\n' >> cube_pipe.fe
printf '\nprint 2 >> "../victim_redirect"\n' >> cube_redirect.fe
run --safe --out out cube_system.fe
run --safe --out out cube_pipe.fe
run --safe --out out cube_redirect.fe
run --safe --out out cube_clean.fe -e 'evolver [[ print 3 >> "out/inside.txt" ]] print(io.open("out/inside.txt"):read("l"))'
[ -e spawned_system ] || [ -e spawned_pipe ] || [ -e "$dir/../victim_redirect" ] || echo "nothing spawned or written outside"
