-- safe.lua: a safe surface (tds.new{ safe = true, outdir = ... }) in one
-- Lua state with an ordinary one. What the safe surface runs (its
-- datafile's read section, Evolver commands, scripts given to its dofile,
-- code reaching its library) cannot spawn processes, load native code or
-- bytecode, or write outside its folder; the host's own code is not
-- restricted. Run with the stock lua5.4.
local tds = require "tds"

local dir = os.tmpname()
os.remove(dir)
assert(os.execute("mkdir " .. dir .. " " .. dir .. "/out"))
local function exists(p) local f = io.open(p) if f then f:close() end return f ~= nil end
local function cleanup() os.execute("rm -rf " .. dir) end

local function fails(want, f, ...)
  local ok, err = pcall(f, ...)
  if ok then cleanup() end
  assert(not ok, "expected an error: " .. want)
  assert(tostring(err):find(want, 1, true), ("got %q, want %q"):format(tostring(err), want))
end

-- Option checks.
fails("tds.new: unknown key 'sfe' (known: outdir, quiet, safe)", tds.new, { sfe = true })
fails("tds.new: safe must be a boolean, not a number", tds.new, { safe = 1 })
fails("outdir is the output folder of a safe surface; give safe = true too",
      tds.new, { outdir = dir })
fails("output folder '" .. dir .. "/none'", tds.new, { safe = true, outdir = dir .. "/none" })

local s = tds.new{ safe = true, outdir = dir .. "/out", quiet = true }
local free = tds.new{ quiet = true }

-- A datafile whose read section runs a shell command: refused at its line,
-- nothing spawned. The cube of Evolver's examples is the datafile.
local src = assert(io.open("/usr/share/doc/evolver/examples/cube.fe")):read("a")
local function write(path, text) local f = assert(io.open(path, "w")) f:write(text) f:close() end
write(dir .. "/evil.fe", src .. '\nsystem "touch ' .. dir .. '/spawned"\n')
fails("evil.fe:", s.load_datafile, dir .. "/evil.fe")
fails("safe mode: os.execute is not allowed", s.evolver, 'system "touch ' .. dir .. '/spawned"')
assert(not exists(dir .. "/spawned"), "a safe surface spawned a process")
-- As in Evolver, the datafile itself stays loaded; its read section failed.
assert(s.facet_count == 24)
-- The ordinary surface loads the same file and runs its read section.
free.load_datafile(dir .. "/evil.fe")
assert(exists(dir .. "/spawned"), "the ordinary surface's read section did not run")
assert(free.facet_count == 24 and free.vertex_count == 14) -- quads get centres

-- Its library is a sandboxed copy; the host's is untouched.
fails("safe mode: os.execute is not allowed", s.os.execute, "true")
fails("safe mode: io.popen is not allowed", s.io.popen, "ls")
fails("safe mode: writing '/tmp/x-tds-safe' is refused", s.io.open, "/tmp/x-tds-safe", "w")
assert(s.debug == nil and s.package == nil, "debug and package reach the safe surface")
assert(s.require("os") == s.os and s.os ~= os, "require gives the sandboxed os")
fails("safe mode: require 'tds' is not allowed", s.require, "tds")
assert(s.load(string.dump(function() end)) == nil, "bytecode loaded")
assert(s.load("return os")() == s.os, "load's default environment is the surface")
assert(os.execute("true"), "the host's os.execute was changed")

-- The raw primitives cannot load a script into the host's globals either:
-- tds.load_chunk (the program's loader) runs it in the surface.
write(dir .. "/evil.lua", 'os.execute("touch ' .. dir .. '/spawned2") escaped = true')
fails("safe mode: os.execute is not allowed", s.tds.load_chunk(dir .. "/evil.lua"))
assert(not exists(dir .. "/spawned2") and escaped == nil, "load_chunk escaped the sandbox")

-- Files: inside the folder they are written, outside they are refused.
fails("safe mode: writing '" .. dir .. "/cube.dmp' is refused", s.dump, dir .. "/cube.dmp")
fails("safe mode: writing '" .. dir .. "/cube.ply' is refused", s.export, dir .. "/cube.ply")
fails("safe mode: writing '" .. dir .. "/c.png' is refused", s.snapshot, dir .. "/c.png")
fails("safe mode: writing", s.write_fe, dir .. "/c.fe")
assert(not exists(dir .. "/cube.dmp") and not exists(dir .. "/cube.ply"))

-- A script run in a safe surface declares into it, and is refused the same.
s = tds.new{ safe = true, outdir = dir .. "/out", quiet = true }
write(dir .. "/script.tds", [[
vertices{ {0,0,0}, {1,0,0}, {0,1,0} }
edges{ {1,2}, {2,3}, {3,1} }
faces{ {1,2,3} }
assert(total_area == 0.5)
dump("]] .. dir .. [[/out/tri.dmp")
local ok, err = pcall(os.execute, "true")
assert(not ok and err:find("safe mode"), err)
return vertex_count
]])
assert(s.dofile(dir .. "/script.tds") == 3)
assert(s.vertex_count == 3 and free.vertex_count == 14)
assert(exists(dir .. "/out/tri.dmp"), "the dump inside the folder was not written")
-- The dump is a datafile of the same triangle: an ordinary surface reads
-- it back with the same area (0.5 exactly: a right triangle of legs 1).
local back = tds.new{ quiet = true }
back.load_datafile(dir .. "/out/tri.dmp")
assert(back.total_area == 0.5 and back.facet_count == 1)
cleanup()
print("module/safe: ok")
