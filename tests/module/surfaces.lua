-- surfaces.lua: two surfaces in one stock lua5.4 state (require "tds").
-- Run by tests/run.sh as module/surfaces with LUA_CPATH_5_4 at build/tds.so.
local tds = require "tds"

-- The module installs no globals.
assert(vertices == nil and g == nil and vertex == nil and total_area == nil,
       "require 'tds' installed globals")
assert(type(tds.new) == "function" and type(tds.globals) == "function")

-- The cube of scripts/cube.tds with side L, volume L^3.
local function cube(s, L)
  s.vertices{ {0,0,0}, {L,0,0}, {L,L,0}, {0,L,0}, {0,0,L}, {L,0,L}, {L,L,L}, {0,L,L} }
  s.edges{ {1,2}, {2,3}, {3,4}, {4,1}, {5,6}, {6,7}, {7,8}, {8,5},
           {1,5}, {2,6}, {3,7}, {4,8} }
  s.faces{ {1,10,-5,-9}, {2,11,-6,-10}, {3,12,-7,-11}, {4,9,-8,-12},
           {5,6,7,8}, {-4,-3,-2,-1} }
  s.bodies{ {1,2,3,4,5,6, volume = L^3} }
end
local function evolve(s)
  s.g(5); s.r(); s.g(5); s.r(); s.g(5)
end

local a, b = tds.new{quiet = true}, tds.new{quiet = true}
cube(a, 1)
assert(a.vertex_count == 14 and a.facet_count == 24 and b.vertex_count == 0 and b.facet_count == 0,
       "a declaration reached the other surface")
cube(b, 2)
-- Interleaved: every command on one surface between commands on the other.
a.g(5); b.g(5); a.r(); b.r(); a.g(5); b.g(5); a.r(); b.r(); a.g(5); b.g(5)
assert(a.vertex_count == 194 and a.edge_count == 576 and a.facet_count == 384)
assert(b.vertex_count == 194 and b.facet_count == 384)
a.U(); b.U()
for _ = 1, 200 do a.g(1); b.g(1) end

-- Independence: a surface evolved alone gets the same numbers, bit for bit
-- (the same operations on the same data; nothing is shared).
local c = tds.new{quiet = true}
cube(c, 1)
evolve(c); c.U()
for _ = 1, 200 do c.g(1) end
assert(a.total_area == c.total_area and a.body[1].pressure == c.body[1].pressure,
       ("a alone %.17g, a beside b %.17g"):format(c.total_area, a.total_area))

-- Known answers. The converged refined cube is a polyhedron of volume 1,
-- so its area is above the sphere's, (36 pi)^(1/3), by the discretisation
-- error of 384 facets (0.33%; bound 0.5%, as tests/scripts/cube_gogo.tds);
-- its pressure is Laplace's 2/R for the sphere of radius R, to 0.5% too.
local sphere = (36 * math.pi) ^ (1 / 3)
local excess = a.total_area / sphere - 1
assert(excess > 0 and excess < 0.005, ("area excess %g"):format(excess))
local R = (3 / (4 * math.pi)) ^ (1 / 3)
assert(math.abs(a.body[1].pressure / (2 / R) - 1) < 0.005, a.body[1].pressure)
assert(math.abs(a.body[1].volume - 1) < 1e-12, "volume held at its target")
-- b is a scaled by 2: a power of two scales every coordinate exactly in
-- binary floating point, and the iteration (gradients, the optimizing scale
-- search, the volume projection) commutes with it, so b's area is 4 times
-- a's and its volume 8 to rounding (1e-12 relative allows a few ulps of
-- difference should any step not be exactly scale-free).
assert(math.abs(b.total_area / a.total_area - 4) <= 4e-12,
       ("area ratio %.17g"):format(b.total_area / a.total_area))
assert(math.abs(b.body[1].volume - 8) <= 8e-12, b.body[1].volume)
assert(math.abs(b.body[1].pressure * 2 / a.body[1].pressure - 1) <= 1e-12)

-- Each surface has its own iteration history (pictures' history()).
local d = tds.new{ quiet = true }
cube(d, 1)
d.g(3)
assert(#d.history() == 3, #d.history())
assert(#a.history() == 215 and #b.history() == 215,
       #a.history())

-- Parameters and live values belong to their surface.
a.parameter{ SIDE = 3 }
assert(a.SIDE == 3 and b.SIDE == nil)
a.SIDE = 4
assert(a.SIDE == 4 and b.SIDE == nil)
-- A surface's names do not leak into the globals.
assert(SIDE == nil and rawget(_G, "vertices") == nil)
print("module/surfaces: areas", a.total_area, b.total_area)
