-- net.lua: a seeded random string network under SYMMETRY_GROUP "genus2"
-- (tests/evolver/genus2.sh). Globals: OUT (path), SEED, NV (vertices),
-- NE (edges), KLEIN (true: KLEIN_METRIC), LONG (true: wraps may be runs
-- of 2 and 3 generators; else single generators and 0), FIXED (every
-- k-th vertex fixed, 0: none). Vertices uniform in the disk of radius
-- 0.7 (inside the octagon, whose inradius is tanh 1.53 = 0.91); edges
-- join distinct random vertices, tension 1 or a random one.
math.randomseed(SEED)
local lines = {"STRING", "SPACE_DIMENSION 2"}
if KLEIN then lines[#lines + 1] = "KLEIN_METRIC" end
lines[#lines + 1] = 'SYMMETRY_GROUP "genus2"'
lines[#lines + 1] = "vertices"
for i = 1, NV do
  local r, t = 0.7 * math.sqrt(math.random()), 2 * math.pi * math.random()
  lines[#lines + 1] = ("%d %.17g %.17g%s"):format(i, r * math.cos(t), r * math.sin(t),
    (FIXED or 0) > 0 and i % FIXED == 0 and " fixed" or "")
end
lines[#lines + 1] = "edges"
for i = 1, NE do
  local a = math.random(NV)
  local b = math.random(NV - 1)
  if b >= a then b = b + 1 end
  local code = 0
  if math.random() < 0.8 then
    local s = math.random(0, 7)
    local len = LONG and math.random(1, 3) or 1
    code = s + 16 * ((s + len) % 8)
  end
  local ten = math.random() < 0.3 and (" tension %.17g"):format(0.5 + math.random()) or ""
  lines[#lines + 1] = ("%d %d %d wrap %d%s"):format(i, a, b, code, ten)
end
local f = assert(io.open(OUT, "w"))
f:write(table.concat(lines, "\n"), "\n")
f:close()
