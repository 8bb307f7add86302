-- hessgen.lua: seeded string-model datafiles for the Hessian comparisons
-- (tests/evolver/string_hessian.sh); the same text for Evolver and tds.
--   polygon_fe(n, seed): one 2-D bubble, an n-gon with its radii moved
--     by up to 20% at random, its area held 5% above the start's.
--   flower_fe(n, seed): a central n-gon cell whose corners are triple
--     junctions, joined by spokes to a fixed outer n-gon of radius 2; the
--     central cell and all petals but the first hold their areas (the
--     first is free: the fixed outline decides it). The inner corners
--     are moved at random.
--   string3_fe(n, seed): an open string in 3-D space from (0,0,0) to
--     (n,0,0) (both ends fixed) through n - 1 random vertices, with a
--     branch from the middle one to a free end: one junction.
--   drop_fe(seed): a 2-D drop on the line y = 0.1 x (constraint with
--     content), its two ends on the line, its area held.
local M = {}

-- x' = (a x + c) mod 2^31, as floats in [0, 1): exact in doubles.
local function lcg(seed)
  local x = seed % 2147483648
  return function()
    x = (1103515245 * x + 12345) % 2147483648
    return x / 2147483648
  end
end

local function f17(x) return ("%.17g"):format(x) end

function M.polygon_fe(n, seed)
  local rnd = lcg(seed)
  local L = {"STRING", "SPACE_DIMENSION 2", "vertices"}
  local area, P = 0, {}
  for i = 1, n do
    local a = 2 * math.pi * (i - 1 + 0.3 * (rnd() - 0.5)) / n
    local r = 1 + 0.4 * (rnd() - 0.5)
    P[i] = {r * math.cos(a), r * math.sin(a)}
    L[#L + 1] = ("%d %s %s"):format(i, f17(P[i][1]), f17(P[i][2]))
  end
  for i = 1, n do
    local p, q = P[i], P[i % n + 1]
    area = area + (p[1] * q[2] - q[1] * p[2]) / 2
  end
  L[#L + 1] = "edges"
  for i = 1, n do L[#L + 1] = ("%d %d %d"):format(i, i, i % n + 1) end
  local ids = {}
  for i = 1, n do ids[i] = i end
  L[#L + 1] = "faces"
  L[#L + 1] = "1 " .. table.concat(ids, " ")
  L[#L + 1] = "bodies"
  L[#L + 1] = "1 1 volume " .. f17(1.05 * area)
  return table.concat(L, "\n") .. "\n"
end

function M.flower_fe(n, seed)
  local rnd = lcg(seed)
  local L = {"STRING", "SPACE_DIMENSION 2", "vertices"}
  local inner = {}
  for i = 1, n do
    local a = 2 * math.pi * (i - 1 + 0.3 * (rnd() - 0.5)) / n
    local r = 0.5 * (1 + 0.3 * (rnd() - 0.5))
    inner[i] = {r * math.cos(a), r * math.sin(a)}
    L[#L + 1] = ("%d %s %s"):format(i, f17(inner[i][1]), f17(inner[i][2]))
  end
  for i = 1, n do
    local a = 2 * math.pi * (i - 1) / n
    L[#L + 1] = ("%d %s %s fixed"):format(n + i, f17(2 * math.cos(a)), f17(2 * math.sin(a)))
  end
  L[#L + 1] = "edges"
  for i = 1, n do L[#L + 1] = ("%d %d %d"):format(i, i, i % n + 1) end
  for i = 1, n do L[#L + 1] = ("%d %d %d"):format(n + i, i, n + i) end
  for i = 1, n do L[#L + 1] = ("%d %d %d fixed"):format(2 * n + i, n + i, n + i % n + 1) end
  L[#L + 1] = "faces"
  local ids = {}
  for i = 1, n do ids[i] = i end
  L[#L + 1] = "1 " .. table.concat(ids, " ")
  for i = 1, n do
    L[#L + 1] = ("%d %d %d %d %d"):format(i + 1, n + i, 2 * n + i, -(n + i % n + 1), -i)
  end
  -- the areas at the start: the centre's and each petal's
  local function area(P)
    local a = 0
    for i = 1, #P do
      local p, q = P[i], P[i % #P + 1]
      a = a + (p[1] * q[2] - q[1] * p[2]) / 2
    end
    return a
  end
  L[#L + 1] = "bodies"
  L[#L + 1] = "1 1 volume " .. f17(area(inner))
  for i = 1, n do
    local a0, a1 = 2 * math.pi * (i - 1) / n, 2 * math.pi * i / n
    local petal = {inner[i], {2 * math.cos(a0), 2 * math.sin(a0)}, {2 * math.cos(a1), 2 * math.sin(a1)},
                   inner[i % n + 1]}
    if i == 1 then L[#L + 1] = ("%d %d"):format(i + 1, i + 1)
    else L[#L + 1] = ("%d %d volume %s"):format(i + 1, i + 1, f17(area(petal))) end
  end
  return table.concat(L, "\n") .. "\n"
end

function M.string3_fe(n, seed)
  local rnd = lcg(seed)
  local L = {"STRING", "vertices", "1 0 0 0 fixed"}
  for i = 1, n - 1 do
    L[#L + 1] = ("%d %s %s %s"):format(i + 1, f17(i + 0.3 * (rnd() - 0.5)), f17(0.6 * (rnd() - 0.5)),
                                     f17(0.6 * (rnd() - 0.5)))
  end
  L[#L + 1] = ("%d %d 0 0 fixed"):format(n + 1, n)
  local mid = n // 2 + 1
  L[#L + 1] = ("%d %s %s %s"):format(n + 2, f17(mid - 1 + 0.5 * rnd()), f17(1 + rnd()), f17(0.5 * rnd()))
  L[#L + 1] = "edges"
  for i = 1, n do
    if rnd() < 0.5 then L[#L + 1] = ("%d %d %d"):format(i, i, i + 1) -- random orientations
    else L[#L + 1] = ("%d %d %d"):format(i, i + 1, i) end
  end
  L[#L + 1] = ("%d %d %d"):format(n + 1, mid, n + 2)
  return table.concat(L, "\n") .. "\n"
end

function M.drop_fe(seed)
  local rnd = lcg(seed)
  local L = {"STRING", "SPACE_DIMENSION 2", "constraint 1", "formula: y = 0.1*x", "content:",
             "c1: 0.05*x^2", "", "vertices", "1 1 0.1 constraint 1"}
  local k = 4
  for i = 1, k - 1 do
    local a = math.pi * i / k
    local r = 1 + 0.2 * (rnd() - 0.5)
    L[#L + 1] = ("%d %s %s"):format(i + 1, f17(r * math.cos(a)), f17(0.1 * r * math.cos(a) + r * math.sin(a)))
  end
  L[#L + 1] = ("%d -1 -0.1 constraint 1"):format(k + 1)
  L[#L + 1] = "edges"
  for i = 1, k do L[#L + 1] = ("%d %d %d"):format(i, i, i + 1) end
  L[#L + 1] = "faces"
  L[#L + 1] = "1 1 2 3 4"
  L[#L + 1] = "bodies"
  L[#L + 1] = "1 1 volume " .. f17(1.5 + 0.2 * rnd())
  return table.concat(L, "\n") .. "\n"
end

return M
