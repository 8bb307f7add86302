-- sector.lua: a sector of a disc-like film under SYMMETRY_GROUP "rotate"
-- (order N) with its centre on the axis as an axial_point (held on the
-- axis by two constraints): the centre, a middle ring of two vertices and
-- a fixed outer ring of two on the unit circle, from angle 0 clockwise
-- (Evolver's rotate turns clockwise) to the next copy. The facets at the
-- centre include one whose wraps multiply to the generator, not the
-- identity (Evolver's axial_point rule: the axial point at the tail of
-- its first edge). Interior vertices moved by a seeded pseudo-random
-- offset of size AMP; BODY: the facets as one body with that volume
-- target (nil: none). Set OUT, N, SEED, AMP, BODY, then dofile this.
math.randomseed(SEED)
local function rnd() return AMP * (2 * math.random() - 1) end
local a = -math.pi / N -- half the sector, clockwise
local L = {('// axial sector, order %d, seed %d'):format(N, SEED),
  ('parameter rotation_order = %d'):format(N), 'SYMMETRY_GROUP "rotate"',
  'constraint 1', 'formula: x = 0', 'constraint 2', 'formula: y = 0', 'vertices',
  ('1 0 0 %.17g axial_point constraints 1 2'):format(0.1 + rnd()),
  ('2 %.17g %.17g %.17g'):format(0.5 + rnd(), rnd(), 0.03 + rnd()),
  ('3 %.17g %.17g %.17g'):format(0.5 * math.cos(a) + rnd(), 0.5 * math.sin(a) + rnd(), 0.06 + rnd()),
  '4 1 0 0 fixed',
  ('5 %.17g %.17g 0 fixed'):format(math.cos(a), math.sin(a)),
  'edges', '1 1 2', '2 1 3', '3 2 3', '4 3 2 wrap 1', '5 4 5 fixed', '6 5 4 wrap 1 fixed',
  '7 2 4', '8 3 5', '9 2 5', '10 3 4 wrap 1',
  'faces', '1 1 3 -2', '2 2 4 -1', '3 -3 9 -8', '4 7 5 -9', '5 -4 10 -7', '6 8 6 -10'}
if BODY then L[#L + 1] = ('bodies\n1 1 2 3 4 5 6 volume %.17g'):format(BODY) end
local f = assert(io.open(OUT, 'w'))
f:write(table.concat(L, '\n'), '\n')
f:close()
