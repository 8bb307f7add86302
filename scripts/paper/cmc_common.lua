-- cmc_common.lua: a constant-mean-curvature surface between two fixed unit
-- circles at z = -0.5 and 0.5, closed by fixed tensionless end caps into a
-- body of prescribed volume (cmc_1/2/3.tds choose the volume). The input
-- is irregular, as the paper's: 384 random points on the cylinder between
-- the rings (M.random_cylinder), Delaunay-triangulated.
local dir = debug.getinfo(1, "S").source:match("^@(.*/)") or "./"
local M = dofile(dir .. "meshes.lua")
local C = dofile(dir .. "common.lua")
return function(name, volume)
  return C.run {
    name = name,
    target = "lambda",
    input = function()
      local t = M.random_cylinder(48, 384, -0.5, 0.5, { caps = true })
      for _, f in ipairs(t.facets) do f.body = 1 end
      t.bodies = { { volume = volume } }
      return t
    end,
  }
end
