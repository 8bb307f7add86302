-- globals.lua: require("tds").globals() in the stock lua5.4 gives the tds
-- program's names, so a .tds script runs unchanged; surfaces made with
-- tds.new() live beside it.
local before = {}
for k in pairs(_G) do before[k] = true end
local tds = require "tds"
local a = tds.new{ quiet = true }
a.vertices{ {0,0,0}, {1,0,0}, {0,1,0} }
a.g(1)
-- Nothing global so far: requiring the module and using a surface
-- installs no name (the exact set of global names is unchanged).
for k in pairs(_G) do assert(before[k], "a global appeared: " .. tostring(k)) end
for k in pairs(before) do assert(rawget(_G, k) ~= nil, "a global vanished: " .. k) end

local G = tds.globals()
assert(G == _G and tds.globals() == _G, "globals() is the global table, once")
assert(type(vertices) == "function" and type(g) == "function" and vertex_count == 0)
-- The global `tds` is now the surface's primitives, as in the program.
assert(rawget(_G, "tds") ~= tds and _G.tds.new == tds.new)
_G.tds.quiet(true)
-- scripts/cube.tds as the program runs it (tests/scripts/cube_gogo.tds's
-- counts: two refinements of the cube give 194 vertices, 576 edges and
-- 384 facets; the volume is held at 1 to 1e-12).
dofile("../../scripts/cube.tds")
gogo()
assert(vertex_count == 194 and edge_count == 576 and facet_count == 384)
assert(math.abs(body[1].volume - 1) < 1e-12)
assert(check())
-- Evolver's command language works on the global surface.
evolver("r")
assert(facet_count == 4 * 384)
-- The global surface and a are independent.
assert(a.vertex_count == 3 and a.facet_count == 0)
-- The global table as a namespace: parameters and live values.
parameter{ SCALE = 2 }
assert(SCALE == 2 and a.SCALE == nil)
print("module/globals: ok", total_area)
