-- evorun.lua: the run-time side of Evolver command text (tds.E).
--
-- Code made by evolang.translate calls these functions. They give Evolver's
-- meaning to values (1/0 truth, reals), elements (vertex[3].x, sub-element
-- generators), commands (g 5, r, v, user commands with counts) and output
-- (print, printf, redirection). Variables are Lua globals, so Evolver text
-- and Lua scripts share them; parameters are the surface's.
--
--   E.run(text [, chunkname [, line0]])  translate and run command text
--   E.run_file(path)                     run a command file (tds -f, read)
--   E.run_read(path)                     run a loaded datafile's read section

local evolang = require("evolang")
local tds = tds
local E = {}
tds.E = E

local KINDNUM = { vertex = tds.vertex, edge = tds.edge, facet = tds.facet, body = tds.body }

local user = {}       -- functions defined by name := {...} (true) or procedure
-- Names defined by tds itself (the prelude and Lua's libraries): Evolver
-- text cannot redefine them as commands by accident (E.protect).
local protected = {}
local redefined = {}  -- single letters redefined with :::=
-- The runtime finds the user's line through the debug library, which safe
-- mode takes away from user code afterwards: keep a reference now.
local debug = debug

-- depth: how many top-level Evolver commands are running; an abort is
-- caught by the outermost one only (abort returns to the prompt).
local depth = 0

---------------------------------------------------------------- errors

-- Raise msg at the innermost line of Evolver or Lua user code.
local function where()
  for level = 2, 50 do
    local info = debug.getinfo(level, "Sl")
    if not info then break end
    if info.currentline and info.currentline > 0 and not info.source:match("^=%[tds ") then
      return info.short_src .. ":" .. info.currentline .. ": "
    end
  end
  return ""
end
local function fail(msg) error(where() .. msg, 0) end
E.fail = fail

---------------------------------------------------------------- values

local function num(v, what)
  if type(v) == "number" then return v end
  if type(v) == "boolean" then return v and 1 or 0 end
  if v == nil then return 0 end
  local n = tonumber(v)
  if n then return n end
  fail(("%s: expected a number, got %s"):format(what or "expression", type(v) == "string" and ("'" .. v .. "'") or type(v)))
end
E.num = num

function E.truth(v)
  if type(v) == "number" then return v ~= 0 end
  if type(v) == "boolean" then return v end
  if v == nil then return false end
  if type(v) == "string" then return v ~= "" end
  return true
end

-- Whole-array arithmetic: array +- array elementwise, array */ scalar,
-- scalar * array (syntax.htm#arrays).
local function arrayop(op, a, b)
  local ta, tb = type(a) == "table", type(b) == "table"
  local out = {}
  if ta and tb and op == "*" then
    -- vector . vector, matrix * vector, vector * matrix, matrix * matrix
    local ma, mb = type(a[1]) == "table", type(b[1]) == "table"
    local inner = mb and #b or #b
    if (ma and #a[1] or #a) ~= inner then
      fail(("array product: sizes %d and %d do not match"):format(ma and #a[1] or #a, inner))
    end
    local function row(r, j) -- sum_k r[k] * b[k][j] (or b[k] when b is a vector)
      local sum = 0.0
      for k = 1, #r do sum = sum + num(r[k]) * num(mb and b[k][j] or b[k]) end
      return sum
    end
    if not ma and not mb then return row(a) end
    if not ma then for j = 1, #b[1] do out[j] = row(a, j) end return out end
    for i = 1, #a do
      if mb then out[i] = {}; for j = 1, #b[1] do out[i][j] = row(a[i], j) end
      else out[i] = row(a[i]) end
    end
    return out
  elseif ta and tb then
    if op ~= "+" and op ~= "-" then fail("arrays can only be added, subtracted or multiplied") end
    if #a ~= #b then fail(("array sizes differ: %d and %d"):format(#a, #b)) end
    for i = 1, #a do out[i] = E.arith(op, a[i], b[i]) end
  elseif ta then
    if op ~= "*" and op ~= "/" then fail("an array can only be multiplied or divided by a number") end
    for i = 1, #a do out[i] = E.arith(op, a[i], b) end
  else
    if op ~= "*" then fail("a number can only multiply an array") end
    for i = 1, #b do out[i] = E.arith(op, a, b[i]) end
  end
  return out
end

function E.arith(op, a, b)
  if (type(a) == "table" and a.__quantity == nil) or (type(b) == "table" and b.__quantity == nil) then
    return arrayop(op, a, b)
  end
  if op == "+" then
    if type(a) == "string" and type(b) == "string" then return a .. b end
    return num(a) + num(b)
  elseif op == "-" then return num(a) - num(b)
  elseif op == "*" then return num(a) * num(b)
  elseif op == "/" then
    b = num(b)
    if b == 0 then fail("division by zero") end
    return num(a) / b
  elseif op == "%" or op == "mod" then
    a, b = num(a) + 0.0, num(b) + 0.0
    if b == 0 then fail("modulus by zero") end
    return a - math.floor(a / b) * b
  elseif op == "imod" then
    a, b = math.floor(num(a)), math.floor(num(b))
    if b == 0 then fail("imod by zero") end
    return (a - math.floor(a / b) * b) + 0.0
  elseif op == "idiv" then
    local x, y = num(a), num(b)
    x = x < 0 and math.ceil(x) or math.floor(x)
    y = y < 0 and math.ceil(y) or math.floor(y)
    if y == 0 then fail("idiv by zero") end
    local r = x / y
    return (r < 0 and math.ceil(r) or math.floor(r)) + 0.0
  end
  fail("unknown operator " .. tostring(op))
end

function E.pow(a, b)
  a, b = num(a), num(b)
  if a < 0 and b % 1 ~= 0 then fail(("negative number %g to a fractional power %g"):format(a, b)) end
  return a ^ b
end

local function checked(name, f, ok)
  return function(...)
    local args = { ... }
    for i = 1, select("#", ...) do args[i] = num(args[i], name) end
    if ok and not ok(table.unpack(args)) then
      fail(("%s(%s): argument out of range"):format(name, table.concat(args, ", ")))
    end
    return f(table.unpack(args)) + 0.0
  end
end

local function agm_ellipticK(m)
  if m >= 1 then fail("ellipticK(m) needs m < 1") end
  local a, b = 1.0, math.sqrt(1 - m)
  for _ = 1, 60 do a, b = (a + b) / 2, math.sqrt(a * b) end
  return math.pi / (2 * a)
end
local function ellipticE(m)
  if m > 1 then fail("ellipticE(m) needs m <= 1") end
  if m == 1 then return 1.0 end
  local a, b, c = 1.0, math.sqrt(1 - m), math.sqrt(m)
  local sum, p = c * c / 2, 0.5
  for _ = 1, 60 do
    a, b, c = (a + b) / 2, math.sqrt(a * b), (a - b) / 2
    p = p * 2
    sum = sum + p * c * c
  end
  return math.pi / (2 * a) * (1 - sum)
end

-- Carlson's symmetric integrals RF and RD (duplication until the
-- arguments agree to 1e-10 relative, then the series to fifth order).
local function carlson_rf(x, y, z)
  for _ = 1, 100 do
    local lam = math.sqrt(x * y) + math.sqrt(y * z) + math.sqrt(z * x)
    x, y, z = (x + lam) / 4, (y + lam) / 4, (z + lam) / 4
    local mu = (x + y + z) / 3
    if math.max(math.abs(x - mu), math.abs(y - mu), math.abs(z - mu)) < 1e-10 * mu then break end
  end
  local mu = (x + y + z) / 3
  local dx, dy, dz = 1 - x / mu, 1 - y / mu, 1 - z / mu
  local e2, e3 = dx * dy - dz * dz, dx * dy * dz
  return (1 - e2 / 10 + e3 / 14 + e2 * e2 / 24 - 3 * e2 * e3 / 44) / math.sqrt(mu)
end
local function carlson_rd(x, y, z)
  local sum, fac = 0.0, 1.0
  for _ = 1, 100 do
    local lam = math.sqrt(x * y) + math.sqrt(y * z) + math.sqrt(z * x)
    sum = sum + fac / (math.sqrt(z) * (z + lam))
    fac = fac / 4
    x, y, z = (x + lam) / 4, (y + lam) / 4, (z + lam) / 4
    local mu = (x + y + 3 * z) / 5
    if math.max(math.abs(x - mu), math.abs(y - mu), math.abs(z - mu)) < 1e-10 * mu then break end
  end
  local mu = (x + y + 3 * z) / 5
  local dx, dy, dz = (mu - x) / mu, (mu - y) / mu, (mu - z) / mu
  local ea, eb = dx * dy, dz * dz
  local ec, ed, ee = ea - eb, ea - 6 * eb, ea - 6 * eb + 2 * (ea - eb)
  return 3 * sum + fac * (1 + ed * (-3 / 14 + 9 / 88 * ed - 9 / 52 * dz * ee)
    + dz * (ee / 6 + dz * (-9 / 22 * ec + dz * 3 / 26 * ea))) / (mu * math.sqrt(mu))
end
-- Incomplete elliptic integrals F(phi|m), E(phi|m) (Mathematica's
-- convention, as Evolver), by symmetry and periodicity in phi.
local function incomplete(phi, m, second)
  local function part(p) -- |p| <= pi/2
    local s, c = math.sin(p), math.cos(p)
    local q = 1 - m * s * s
    if q <= 0 then fail("incompleteElliptic: m*sin(phi)^2 must be below 1") end
    local v = s * carlson_rf(c * c, q, 1)
    if second then v = v - m / 3 * s * s * s * carlson_rd(c * c, q, 1) end
    return v
  end
  local k = math.floor(phi / math.pi + 0.5)
  local rest = phi - k * math.pi
  if k == 0 then return part(rest) end
  return 2 * k * part(math.pi / 2) + part(rest)
end

E.fn = {
  abs = checked("abs", math.abs), sqr = checked("sqr", function(x) return x * x end),
  sqrt = checked("sqrt", math.sqrt, function(x) return x >= 0 end),
  sin = checked("sin", math.sin), cos = checked("cos", math.cos), tan = checked("tan", math.tan),
  asin = checked("asin", math.asin, function(x) return x >= -1 and x <= 1 end),
  acos = checked("acos", math.acos, function(x) return x >= -1 and x <= 1 end),
  atan = checked("atan", math.atan), atan2 = checked("atan2", function(y, x) return math.atan(y, x) end),
  log = checked("log", math.log, function(x) return x >= 0 end), exp = checked("exp", math.exp),
  sinh = checked("sinh", function(x) return (math.exp(x) - math.exp(-x)) / 2 end),
  cosh = checked("cosh", function(x) return (math.exp(x) + math.exp(-x)) / 2 end),
  tanh = checked("tanh", function(x) local a, b = math.exp(x), math.exp(-x); return (a - b) / (a + b) end),
  asinh = checked("asinh", function(x) return math.log(x + math.sqrt(x * x + 1)) end),
  acosh = checked("acosh", function(x) return math.log(x + math.sqrt(x * x - 1)) end, function(x) return x >= 1 end),
  atanh = checked("atanh", function(x) return 0.5 * math.log((1 + x) / (1 - x)) end, function(x) return x > -1 and x < 1 end),
  ceil = checked("ceil", math.ceil), floor = checked("floor", math.floor),
  pow = checked("pow", function(a, b) return a ^ b end),
  minimum = checked("minimum", math.min), maximum = checked("maximum", math.max),
  elliptick = checked("ellipticK", agm_ellipticK), elliptice = checked("ellipticE", ellipticE),
  incompleteelliptice = checked("incompleteEllipticE", function(p, m) return incomplete(p, m, true) end),
  incompleteellipticf = checked("incompleteEllipticF", function(p, m) return incomplete(p, m, false) end),
  is_defined = function(name)
    if type(name) ~= "string" then fail("is_defined(\"name\") needs a string") end
    local ok = pcall(E.getv, name)
    return (ok or E.B[name:lower()] or type(rawget(_G, name:lower())) == "function") and 1 or 0
  end,
  -- the surface's group (doc/torus.md); errors without the Lua position
  wrap_inverse = function(w)
    local ok, v = pcall(tds.wrap_inverse, w)
    if not ok then fail((tostring(v):gsub("^%[.-%]:%d+: ", ""))) end
    return v
  end,
  wrap_compose = function(a, b)
    local ok, v = pcall(tds.wrap_compose, a, b)
    if not ok then fail((tostring(v):gsub("^%[.-%]:%d+: ", ""))) end
    return v
  end,
  sizeof = function(v)
    if type(v) == "string" then return #v end
    if type(v) == "table" then return #v end
    fail("sizeof: expected an array or a string")
  end,
  -- Matrices (arrays of arrays): the result goes into an existing array of
  -- the right size, as Evolver requires; the operands may be the result.
  matrix_determinant = function(a)
    local m = E.matrix(a, "matrix_determinant")
    local _, det = E.lu_inverse(m)
    return det
  end,
  matrix_inverse = function(a, b)
    local m = E.matrix(a, "matrix_inverse")
    local inv = E.lu_inverse(m)
    E.matrix_into(b, inv, #m, #m, "matrix_inverse")
    return inv and 1 or 0
  end,
  matrix_multiply = function(a, b, c)
    local A, B = E.vecmat(a, "matrix_multiply"), E.vecmat(b, "matrix_multiply")
    if type(b[1]) ~= "table" then -- matrix * vector: the vector is a column
      B = {}
      for i = 1, #b do B[i] = { b[i] } end
    end
    local n, k, m = #A, #A[1], #B[1]
    if #B ~= k then fail(("matrix_multiply: sizes %dx%d and %dx%d do not fit"):format(n, k, #B, m)) end
    local P = {}
    for i = 1, n do
      P[i] = {}
      for j = 1, m do
        local sum = 0.0
        for l = 1, k do sum = sum + A[i][l] * B[l][j] end
        P[i][j] = sum
      end
    end
    if type(a[1]) ~= "table" then P = P[1]; n = 0 end -- vector * matrix
    if type(b[1]) ~= "table" then -- matrix * vector: a column
      local v = {}
      for i = 1, #P do v[i] = P[i][1] end
      P = v; m = 0
    end
    E.matrix_into(c, P, n, m, "matrix_multiply")
    return 0.0
  end,
  valid_constraint = function(n) return tds.declared("constraint", math.floor(num(n))) and 1 or 0 end,
  valid_boundary = function(n) return tds.declared("boundary", math.floor(num(n))) and 1 or 0 end,
}

-- A square matrix argument (an array of equal-length number arrays).
function E.matrix(a, what)
  local ok = type(a) == "table" and #a > 0
  for i = 1, ok and #a or 0 do ok = ok and type(a[i]) == "table" and #a[i] == #a end
  if not ok then fail(what .. ": expected a square matrix (a two-dimensional array)") end
  return a
end
-- A vector (a row) or matrix argument as a matrix.
function E.vecmat(a, what)
  if type(a) ~= "table" or #a == 0 then fail(what .. ": expected an array") end
  if type(a[1]) ~= "table" then
    return { a }
  end
  return a
end
-- Inverse (nil if singular) and determinant by Gaussian elimination with
-- partial pivoting.
function E.lu_inverse(m)
  local n = #m
  local a, inv, det = {}, {}, 1.0
  for i = 1, n do
    a[i], inv[i] = {}, {}
    for j = 1, n do a[i][j] = num(m[i][j]); inv[i][j] = i == j and 1.0 or 0.0 end
  end
  for c = 1, n do
    local p = c
    for r = c + 1, n do if math.abs(a[r][c]) > math.abs(a[p][c]) then p = r end end
    if a[p][c] == 0 then return nil, 0.0 end
    if p ~= c then a[p], a[c] = a[c], a[p]; inv[p], inv[c] = inv[c], inv[p]; det = -det end
    local d = a[c][c]
    det = det * d
    for j = 1, n do a[c][j] = a[c][j] / d; inv[c][j] = inv[c][j] / d end
    for r = 1, n do
      if r ~= c and a[r][c] ~= 0 then
        local f = a[r][c]
        for j = 1, n do a[r][j] = a[r][j] - f * a[c][j]; inv[r][j] = inv[r][j] - f * inv[c][j] end
      end
    end
  end
  return inv, det
end
-- Copy rows x cols values into the existing array dst (cols 0: a vector
-- of rows entries; rows 0: a vector of cols entries). A nil src (singular)
-- leaves dst alone.
function E.matrix_into(dst, src, rows, cols, what)
  if src == nil then return end
  local ok = type(dst) == "table"
  if ok and rows > 0 and cols > 0 then
    ok = #dst == rows
    for i = 1, ok and rows or 0 do ok = ok and type(dst[i]) == "table" and #dst[i] == cols end
  elseif ok then
    ok = #dst == (rows > 0 and rows or cols) and type(dst[1]) ~= "table"
  end
  if not ok then fail(what .. ": the result array must be defined with the result's size") end
  if rows > 0 and cols > 0 then
    for i = 1, rows do for j = 1, cols do dst[i][j] = src[i][j] end end
  else
    for i = 1, #src do dst[i] = src[i] end
  end
end

-- Elements, generators and attributes (lua/evoelem.lua).
require("evoelem")

---------------------------------------------------------------- variables

-- Internal read-only variables (syntax.htm#internal-variables).
local INTERNAL = {
  total_energy = function() return (tds.totals()) end,
  total_area = function() local _, a = tds.totals(); return a end,
  vertex_count = function() return tds.count(tds.vertex) + 0.0 end,
  edge_count = function() return tds.count(tds.edge) + 0.0 end,
  facet_count = function() return tds.count(tds.facet) + 0.0 end,
  body_count = function() return tds.count(tds.body) + 0.0 end,
  facetedge_count = function() return 3.0 * tds.count(tds.facet) end,
  scale = function() return (tds.scale()) end,
  scale_limit = function() return tds.setting("scale_limit") end,
  autochop_length = function() return tds.setting("autochop_length") end,
  iteration_counter = function() return tds.setting("iterations") + 0.0 end,
  gravity_constant = function() return (tds.gravity()) end,
  G = function() local g, on = tds.gravity(); return on and g or 0.0 end,
  space_dimension = function() local _, d = tds.dimensions(); return d + 0.0 end,
  surface_dimension = function() local d = tds.dimensions(); return d + 0.0 end,
  torus = function() return tds.torus() ~= 0 and 1.0 or 0.0 end,
  torus_filled = function() return tds.torus() == 2 and 1.0 or 0.0 end,
  symmetry_group = function() return 0.0 end,
  simplex_representation = function() return 0.0 end,
  lagrange_order = function() return 1.0 end,
  linear = function() return E.lagrange1 and 0.0 or 1.0 end,
  lagrange = function() return E.lagrange1 and 1.0 or 0.0 end,
  quadratic = function() return 0.0 end,
  clock = function() return os.clock() end,
  cpu_counter = function() return os.clock() end,
  random = function() return math.random() end,
  constraint_tolerance = function() return tds.setting("constraint_tolerance") end,
  datafilename = function() return tds.datafile_name and tds.datafile_name() or "" end,
  random_seed = function() return (E.random_seed or 1) + 0.0 end, -- Evolver starts at 1
  date_and_time = function() return os.date("%a %b %d %H:%M:%S %Y") end,
  conj_grad = function() return tds.setting("conj_grad") and 1.0 or 0.0 end,
  quiet = function() return tds.quiet() and 1.0 or 0.0 end,
  transforms = function() return E.toggle_get("transforms") and 1.0 or 0.0 end,
  gravity = function() local _, on = tds.gravity(); return on and 1.0 or 0.0 end,
  hessian_normal = function() return tds.hessian_setting("hessian_normal") and 1.0 or 0.0 end,
  linear_metric = function() return tds.hessian_setting("linear_metric") and 1.0 or 0.0 end,
  hessian_normal_one = function() return tds.hessian_setting("hessian_normal_one") and 1.0 or 0.0 end,
  hessian_normal_perp = function() return tds.hessian_setting("hessian_normal_perp") and 1.0 or 0.0 end,
  linear_metric_mix = function() return tds.hessian_setting("linear_metric_mix") end,
  last_eigenvalue = function() return tds.hessian_setting("last_eigenvalue") end,
  last_hessian_scale = function() return tds.hessian_setting("last_hessian_scale") end,
  eigenneg = function() return tds.hessian_setting("eigenneg") end,
  eigenzero = function() return tds.hessian_setting("eigenzero") end,
  eigenpos = function() return tds.hessian_setting("eigenpos") end,
  hessian_epsilon = function() return tds.hessian_setting("hessian_epsilon") end,
  total_length = function()
    local s = 0.0
    for _, e in ipairs(E.all("edge")) do s = s + e.length end
    return s
  end,
}
E.INTERNAL = INTERNAL
-- Evolver's read-write variables of the knot and Hooke methods: surface
-- parameters (the method rows read them there), with Evolver's defaults.
local METHOD_VARS = { knot_power = 2, hooke_length = 0, hooke_power = 2, hooke2_power = 2,
                      curvature_power = 2 }
for name, dflt in pairs(METHOD_VARS) do
  INTERNAL[name] = function() local p = tds.param(name); if p == nil then return dflt end return p end
end
-- Colour names are integers (syntax.htm#colors).
for i, c in ipairs { "black", "blue", "green", "cyan", "red", "magenta", "brown", "lightgray",
                     "darkgray", "lightblue", "lightgreen", "lightcyan", "lightred",
                     "lightmagenta", "yellow", "white" } do
  local v = i - 1.0
  INTERNAL[c] = function() return v end
end
INTERNAL.clear = function() return -1.0 end
INTERNAL.rgb_colors = function() return 0.0 end -- the toggle: off (colour numbers)
INTERNAL.transparent = INTERNAL.clear

-- Variables that may be assigned with their effect.
local SETTABLE = {
  knot_power = function(v) tds.param("knot_power", num(v)) end,
  hooke_length = function(v) tds.param("hooke_length", num(v)) end,
  hooke_power = function(v) tds.param("hooke_power", num(v)) end,
  hooke2_power = function(v) tds.param("hooke2_power", num(v)) end,
  curvature_power = function(v) tds.param("curvature_power", num(v)) end,
  scale = function(v) tds.scale(num(v)) end,
  gravity_constant = function(v) local _, on = tds.gravity(); tds.gravity(num(v), on) end,
  constraint_tolerance = function(v) tds.setting("constraint_tolerance", num(v)) end,
  scale_limit = function(v) tds.setting("scale_limit", num(v)) end,
  autochop_length = function(v) tds.setting("autochop_length", num(v)) end,
  random_seed = function(v) E.random_seed = math.floor(num(v)); math.randomseed(E.random_seed) end,
  linear_metric_mix = function(v) tds.hessian_setting("linear_metric_mix", num(v)) end,
  hessian_epsilon = function(v) tds.hessian_setting("hessian_epsilon", num(v)) end,
}

-- Evolver's internal variables tds does not have (syntax.htm): reading
-- one is an error naming it, not an undefined variable.
local EVOLVER_VARS = {}
for w in ([[ambient_pressure_value background breakflag body_dissolve_count brightness
  check_count delete_count detorus_epsilon dissolve_count edge_delete_count
  edge_dissolve_count edge_refine_count edge_pop_count edgeswap_count
  eigenvalues equi_count estimated_change facet_delete_count
  facet_dissolve_count fix_count graphics_title hessian_slant_cutoff
  high_boundary high_constraint inverse_periods integral_order integral_order_1d
  integral_order_2d jiggle_temperature last_error memory_arena
  memory_used notch_count pickvnum pickenum pickfnum pop_count pop_edge_to_tri_count
  pop_quad_to_quad_count pop_tri_to_edge_count quadratic_metric_mix refine_count
  rotation_order scale_scale scrollbuffersize self_sim_coeff string_curve_tolerance
  t1_edgeswap_count target_tolerance temperature thickness torus_periods total_time
  unfix_count vertex_dissolve_count vertex_pop_count view_transforms_unique_point
  where_count window_aspect_ratio console_title usr1 usr2 usr3 usr4 usr5
  usr6 usr7 usr8 usr9 x4 x5 x6 x7 x8 x9]]):gmatch("%S+") do
  EVOLVER_VARS[w] = true
end
E.EVOLVER_VARS = EVOLVER_VARS

function E.getv(name, cur)
  local f = INTERNAL[name] or INTERNAL[name:lower()]
  if f then return f() end
  local p = tds.param(name) -- parameters first: one named like a Lua function stays readable
  if p ~= nil then return p end
  local v = _G[name]
  local low = name:lower()
  if v == nil and low ~= name then v = _G[low] end
  if v == nil and cur and E.has_extra(cur, low) then return E.attr(cur, low) end
  if v == nil and tds.quantity_info(low) ~= nil then return { __quantity = low } end
  if v == nil then v = tds.constraint_named(low) end -- a named constraint is its number
  if v == nil and EVOLVER_VARS[low] then fail(("%s: not supported yet"):format(name)) end
  if v == nil then fail(("undefined variable '%s'"):format(name)) end
  if type(v) == "function" then
    if name == "new_body" then E.touch(); return v() end -- Evolver writes it without ()
    fail(("'%s' is a command, not a value"):format(name))
  end
  if type(v) == "boolean" then return v and 1.0 or 0.0 end
  return v
end

function E.setv(name, v)
  if SETTABLE[name] then return SETTABLE[name](v) end
  if INTERNAL[name] then fail(("%s is read-only"):format(name)) end
  if tds.param(name) ~= nil then
    tds.param(name, num(v, name))
    return
  end
  if E.B[name] then fail(("'%s' is a command and cannot be assigned"):format(name)) end
  if protected[name] then fail(("'%s' is a tds name and cannot be assigned"):format(name)) end
  local old = rawget(_G, name)
  if type(old) == "function" then fail(("'%s' is a command and cannot be assigned"):format(name)) end
  if tds.param(name) ~= nil then
    tds.param(name, num(v, name))
    return
  end
  rawset(_G, name, E.assign(old, v))
end

function E.index(a, i)
  if type(a) ~= "table" then fail("indexing a value that is not an array") end
  local k = num(i)
  local v = a[math.floor(k)]
  if v == nil then fail(("array index %d out of range 1..%d"):format(math.floor(k), #a)) end
  return v
end

function E.setindex(a, i, v)
  if type(a) ~= "table" then fail("indexing a value that is not an array") end
  local k = math.floor(num(i))
  if k < 1 or k > #a then fail(("array index %d out of range 1..%d"):format(k, #a)) end
  local ok, err = pcall(function() a[k] = v end)
  if not ok then -- a facetedge attribute's column (lua/evoelem.lua) named as the user knows it
    fail((tostring(err):gsub("^.-:%d+: ", ""):gsub("^facet (%d+): fe__", "facet %1: facetedge attribute ")))
  end
end

local function newarray(dims, d, ty, init)
  local n = math.floor(num(dims[d]))
  local a = {}
  for i = 1, n do
    local iv = type(init) == "table" and init[i] or nil
    if d < #dims then a[i] = newarray(dims, d + 1, ty, iv)
    else a[i] = iv ~= nil and iv or (ty == "string" and "" or 0.0) end
  end
  return a
end

-- name := {{...}, ...}: fill an array from an initializer of its shape.
function E.setarray(name, init)
  local a = rawget(_G, name)
  if a == nil and not protected[name] and not E.B[name] and tds.param(name) == nil then
    rawset(_G, name, init) -- a new array variable
    return
  end
  if type(a) ~= "table" then fail(("'%s' is not an array"):format(name)) end
  local function fill(dst, src, path)
    for i = 1, #src do
      if i > #dst then fail(("%s: too many initializers at %s[%d]"):format(name, path, i)) end
      if type(src[i]) == "table" then
        if type(dst[i]) ~= "table" then fail(("%s: too many braces at %s[%d]"):format(name, path, i)) end
        fill(dst[i], src[i], path .. "[" .. i .. "]")
      else
        dst[i] = src[i]
      end
    end
  end
  fill(a, init, name)
end

function E.newvalue(ty, dims, init)
  if #dims > 0 then return newarray(dims, 1, ty, init) end
  if init ~= nil then return init end
  return ty == "string" and "" or 0.0
end

function E.define(name, ty, dims, init)
  if tds.param(name) ~= nil or INTERNAL[name] or E.B[name] or protected[name] then
    fail(("define: '%s' is already a parameter, variable or command"):format(name))
  end
  rawset(_G, name, E.newvalue(ty, dims, init))
end

-- define constraint|boundary|quantity TEXT: a datafile declaration added
-- to the surface (messages at the command's file and line).
function E.defmodel(text, line)
  local file = where():match("^(.*):%d+: $")
  tds.define_text(text, file or "(define)", line)
end

-- Assignment of v to a variable holding old: a number assigned to an
-- array sets every element (Evolver's whole-array assignment).
local function copy(a)
  local t = {}
  for i = 1, #a do t[i] = type(a[i]) == "table" and copy(a[i]) or a[i] end
  return t
end
function E.assign(old, v)
  if type(old) == "table" and old.__quantity == nil and type(v) ~= "table" then
    local function fill(a) for i = 1, #a do if type(a[i]) == "table" then fill(a[i]) else a[i] = v end end end
    fill(old)
    return old
  end
  if type(v) == "table" and v.__quantity == nil then return copy(v) end -- arrays are values
  return v
end

function E.count(n)
  n = num(n, "repetition count")
  if n % 1 ~= 0 then fail(("repetition count %g is not a whole number"):format(n)) end
  return math.floor(n)
end

---------------------------------------------------------------- quantities

function E.qattr(q, name)
  local value, target, pressure, _, modulus, volconst = tds.quantity_info(q.__quantity)
  local v = ({ value = value, target = target, pressure = pressure, modulus = modulus,
               volconst = volconst })[name]
  if v == nil then fail(("quantity %s: attribute '%s' not supported yet"):format(q.__quantity, name)) end
  return v
end
function E.setqattr(q, name, v)
  local ok, msg = tds.quantity_set(q.__quantity, name, num(v, name))
  if not ok then fail(msg) end
end

---------------------------------------------------------------- output

E.out = function(s) io.write(s) end

local function fmtnum(v)
  if math.type(v) == "integer" then return tostring(v) end
  return ("%.15g"):format(v)
end
E.fmtnum = fmtnum

function E.print(v)
  if type(v) == "number" then E.out(("%20s\n"):format(fmtnum(v)))
  elseif type(v) == "string" then E.out(v .. "\n")
  elseif type(v) == "table" then
    -- Evolver's layout: {{ 0,1e-07},\n { 0, 0}}, numbers as %2.15g
    local function show(a, depth)
      local p = {}
      for i = 1, #a do
        local x = a[i]
        if type(x) == "table" then p[i] = show(x, depth + 1)
        elseif type(x) == "number" then p[i] = ("%2.15g"):format(x)
        else p[i] = tostring(x) end
      end
      local sep = type(a[1]) == "table" and (",\n" .. (" "):rep(depth + 1)) or ","
      return "{" .. table.concat(p, sep) .. "}"
    end
    E.out(show(v, 0) .. "\n")
  elseif E.isel(v) then E.out(tostring(v) .. "\n")
  else E.out(tostring(v) .. "\n") end
end

-- C-style formatting with Evolver's conversions: %d of a real truncates.
function E.sprintf(fmt, ...)
  if type(fmt) ~= "string" then fail("printf: the format must be a string") end
  local args, n, ai = { ... }, select("#", ...), 0
  local out = fmt:gsub("%%([-+ #0]*%d*%.?%d*)([hlLqjzt]*)([%a%%])", function(flags, _, conv)
    if conv == "%" then return "%" end -- length modifiers (%ld) are accepted and ignored
    ai = ai + 1
    if ai > n then fail(("printf: too few arguments for the format \"%s\""):format(fmt)) end
    local a = args[ai]
    if conv == "d" or conv == "i" or conv == "x" or conv == "X" or conv == "o" or conv == "c" or conv == "u" then
      local x = num(a, "printf %" .. conv)
      x = x < 0 and math.ceil(x) or math.floor(x)
      if conv == "u" or conv == "i" then conv = "d" end
      return ("%" .. flags .. conv):format(math.tointeger(x) or 0)
    elseif conv == "s" then
      if type(a) == "number" then a = fmtnum(a) end
      return ("%" .. flags .. "s"):format(tostring(a))
    elseif ("eEfgGaA"):find(conv, 1, true) then
      return ("%" .. flags .. conv):format(num(a, "printf %" .. conv))
    end
    fail(("printf: unknown conversion %%%s"):format(conv))
  end)
  return out
end

function E.printf(fmt, ...) E.out(E.sprintf(fmt, ...)) end
function E.errprintf(fmt, ...) io.stdout:flush(); io.stderr:write(E.sprintf(fmt, ...)) end
function E.eprint(v)
  local o = E.out
  E.out = function(s) io.stdout:flush(); io.stderr:write(s) end
  local ok, err = pcall(E.print, v)
  E.out = o
  if not ok then error(err, 0) end
end

-- cmd >> "file", >>> "file", | "command": what the command prints (its
-- own output and the core's progress lines) goes there. Nested
-- redirections restore the outer target.
local current_target
function E.redirect(mode, target, fn)
  if type(target) ~= "string" then fail("redirection needs a file name or command string") end
  io.stdout:flush()
  local t, err = tds.output_open(target, mode == "|" and "|" or mode == ">>" and "a" or "w")
  if not t then fail(err) end
  local o, outer = E.out, current_target
  current_target = t
  E.out = function(s) tds.output_write(t, s) end
  tds.output_set(t)
  local ok, e = pcall(fn)
  E.out, current_target = o, outer
  tds.output_set(outer)
  tds.output_close(t)
  if not ok then error(e, 0) end
end

---------------------------------------------------------------- commands

local function counts_line()
  local nf = tds.count(tds.facet)
  return ("Vertices: %d  Edges: %d  Facets: %d  Bodies: %d  Facetedges: %d\n"):format(
    tds.count(tds.vertex), tds.count(tds.edge), nf, tds.count(tds.body), 3 * nf)
end

local function times(n, what)
  if n == nil then return 1 end
  n = num(n, what)
  if n % 1 ~= 0 or n < 0 then fail(("%s: count %g must be a whole number >= 0"):format(what, n)) end
  return math.floor(n)
end

local function flush() io.stdout:flush() end

local TOGGLE_MSG = {
  conj_grad = "Conjugate gradient now %s. (was %s)",
  quiet = "Quiet %s. (was %s)",
  gravity = "Gravity %s. (was %s)",
  check_increase = "Increase check %s. (was %s)",
  autopop = "Autopopping %s.\n (was %s)",
  immediate_autopop = "Immediate autopop mode %s.\n (was %s)",
  autochop = "Autochopping %s. (was %s)",
  area_normalization = "Area normalization %s. (was %s)",
  pop_to_edge = "pop_to_edge %s. (was %s)",
  pop_to_face = "pop_to_face %s. (was %s)",
  pop_enjoin = "pop_enjoin %s. (was %s)",
  little_endian = "little_endian %s. (was %s)",
  big_endian = "big_endian %s. (was %s)",
  hessian_normal = "hessian_normal %3s. (was %s)",
  linear_metric = "Linear interpolation metric with Hessian %s.(was %s)",
  hessian_diff = "hessian_diff %s. (was %s)",
  hessian_special_normal = "hessian_special_normal %3s. (was %s)",
  hessian_normal_one = "hessian_normal_one %3s. (was %s)",
  hessian_normal_perp = "hessian_normal_perp %3s. (was %s)",
  transforms = "Transform showing %s. (was %s)", -- display only: no graphics in tds
}
local show_transforms = true

-- Byte order of binary_printf: "<" little endian (Evolver's default on
-- this machine), ">" big endian.
local endian = "<"

local function toggle_get(name)
  if name == "conj_grad" then return tds.setting("conj_grad") end
  if name == "quiet" then return tds.quiet() end
  if name == "gravity" then local _, on = tds.gravity(); return on end
  if name == "check_increase" then return tds.setting("check_increase") end
  if name == "autopop" or name == "immediate_autopop" or name == "autochop"
      or name == "area_normalization" or name == "pop_to_edge" or name == "pop_to_face" or name == "pop_enjoin" then
    return tds.setting(name)
  end
  if name == "little_endian" then return endian == "<" end
  if name == "big_endian" then return endian == ">" end
  if name == "transforms" then return show_transforms end
  if name == "hessian_normal" or name == "linear_metric" or name == "hessian_diff"
      or name == "hessian_special_normal" or name == "hessian_normal_one"
      or name == "hessian_normal_perp" then
    return tds.hessian_setting(name)
  end
end
E.toggle_get = toggle_get
local function toggle_set(name, on)
  if name == "conj_grad" then tds.setting("conj_grad", on)
  elseif name == "quiet" then tds.quiet(on)
  elseif name == "gravity" then local g = tds.gravity(); tds.gravity(g, on)
  elseif name == "check_increase" then tds.setting("check_increase", on)
  elseif name == "autopop" or name == "immediate_autopop" or name == "autochop"
      or name == "area_normalization" or name == "pop_to_edge" or name == "pop_to_face" or name == "pop_enjoin" then
    tds.setting(name, on)
  elseif name == "little_endian" then endian = on and "<" or ">"
  elseif name == "big_endian" then endian = on and ">" or "<"
  elseif name == "transforms" then show_transforms = on
  elseif name == "hessian_normal" or name == "linear_metric" or name == "hessian_diff"
      or name == "hessian_special_normal" or name == "hessian_normal_one"
      or name == "hessian_normal_perp" then
    tds.hessian_setting(name, on)
  end
end

-- binary_printf: Evolver's binary formats (%c one byte, %d two-byte and
-- %ld four-byte integers, %f float, %lf double, %s a string without its
-- NUL) in the byte order of the endian toggles; other characters are
-- copied as bytes.
function E.binary_printf(fmt, ...)
  if type(fmt) ~= "string" then fail("binary_printf needs a format string") end
  local args, k, out = table.pack(...), 0, {}
  local function arg(conv)
    k = k + 1
    if k > args.n then fail(("binary_printf: no value for %%%s"):format(conv)) end
    return args[k]
  end
  local i = 1
  while i <= #fmt do
    local c = fmt:sub(i, i)
    if c ~= "%" then
      out[#out + 1] = c
      i = i + 1
    else
      local conv = fmt:match("^%%(l?[cdfs%%])", i)
      if not conv then fail(("binary_printf: unknown conversion %s"):format(fmt:sub(i, i + 2))) end
      i = i + 1 + #conv
      if conv == "%" then out[#out + 1] = "%"
      elseif conv == "s" or conv == "ls" then out[#out + 1] = tostring(arg(conv))
      else
        local x = num(arg(conv), "binary_printf %" .. conv)
        if conv == "f" or conv == "lf" then
          out[#out + 1] = string.pack(endian .. (conv == "f" and "f" or "d"), x)
        else
          local bytes = conv == "c" and 1 or conv == "d" and 2 or 4
          x = x < 0 and math.ceil(x) or math.floor(x)
          local lim = 1 << (8 * bytes)
          x = math.tointeger(x) % lim -- two's complement, as C's conversion
          out[#out + 1] = string.pack(endian .. "I" .. bytes, x)
        end
      end
    end
  end
  if k < args.n then fail(("binary_printf: %d values for %d conversions"):format(args.n, k)) end
  E.out(table.concat(out))
end

-- Toggles tds has no switch for, accepted in the state tds always is in
-- (Evolver writes them into every dump's read section): name -> the
-- accepted state (true/false), or "any" for display-only toggles, which
-- have no effect without graphics.
local FIXED_TOGGLE = {
  metric_conversion = false, autorecalc = true, gv_binary = "any", autodisplay = "any",
  show_inner = "any", show_outer = "any", thicken = "any", pscolorflag = "any",
  ps_colorflag = "any", gridflag = "any", crossingflag = "any", labelflag = "any",
  show_all_edges = "any", rgb_colors = false,
  smooth_graph = "any", view_transforms_use_unique_point = "any", visibility_test = "any",
  -- tds always puts the volume and quantity gradients in a bordered
  -- (augmented) sparse system, and prints nothing while it factors
  augmented_hessian = true, sparse_constraints = true, hessian_quiet = true,
  -- Evolver's choice of factoring code: tds has one (CHOLMOD), whose
  -- results these would not change; E.toggle says so
  ysmp = "solver", bunch_kaufman = "solver", metis_factor = "solver",
}
E.FIXED_TOGGLE = FIXED_TOGGLE

-- Evolver's three-way display mode of the torus model: how pictures,
-- exports and detorus draw the surface (doc/torus.md). `clipped off`
-- goes back to raw cells.
local DRAW = {raw_cells = "raw", clipped = "clipped", clipped_cells = "clipped",
              connected = "connected", connected_cells = "connected"}

function E.toggle(name, on)
  if DRAW[name] then
    tds.torus_display(on == false and "raw" or DRAW[name])
    return
  end
  local fixed = FIXED_TOGGLE[name]
  if fixed ~= nil then
    if on == nil then on = true end
    if fixed == "solver" then
      E.out(("%s: no effect in tds (every Hessian is factored by CHOLMOD)\n"):format(name))
      return
    end
    if fixed == "any" or fixed == on then return end
    fail(("%s %s: not supported yet (tds always has %s %s)"):format(name, on and "on" or "off",
         name, fixed and "on" or "off"))
  end
  if not TOGGLE_MSG[name] then
    if name == "jiggle" then fail("jiggle on/off (jiggling at every iteration): not supported yet") end
    if E.B[name] or rawget(_G, name) then fail(("%s takes no on/off"):format(name)) end
    fail(("%s: not supported yet"):format(name))
  end
  local was = toggle_get(name)
  if on == nil then on = true end
  toggle_set(name, on)
  if name == "quiet" and on then return end
  E.out((TOGGLE_MSG[name] .. "\n"):format(on and "ON" or "OFF", was and "on" or "off"))
end

function E.setting(name, v)
  if TOGGLE_MSG[name] then return E.toggle(name, v == nil or E.truth(v)) end
  if v == nil then fail(("set %s needs a value"):format(name)) end
  E.setv(name, v)
end

local B = {}
E.B = B

B.g = function(n)
  n = times(n, "g")
  if tds.count(tds.vertex) == 0 then fail("g: there is no surface (load a datafile first)") end
  flush()
  tds.iterate(n)
end
B.iterate, B.go = B.g, B.g
B.r = function(n) for _ = 1, times(n, "r") do flush(); tds.refine(nil) end end
B.refine = B.r
B.u = function(n) for _ = 1, times(n, "u") do flush(); tds.equiangulate(nil) end end
B.equiangulate = B.u
-- Mesh maintenance: t w l K n take their cutoff on the line (Evolver would
-- prompt for it; a command file cannot answer).
local function cutcmd(name, what, fn)
  return function(v)
    if v == nil then fail(("%s needs a %s (%s value)"):format(name, what, name)) end
    flush()
    fn(num(v, name))
  end
end
B.t = cutcmd("t", "cutoff edge length", tds.edgeweed)
B.edgeweed = cutcmd("edgeweed", "cutoff edge length", tds.edgeweed)
B.w = cutcmd("w", "cutoff facet area", tds.areaweed)
B.areaweed = cutcmd("areaweed", "cutoff facet area", tds.areaweed)
B.l = cutcmd("l", "cutoff edge length", tds.edge_divide)
B.edge_divide = cutcmd("edge_divide", "cutoff edge length", tds.edge_divide)
B.K = cutcmd("K", "cutoff angle", tds.skinny)
B.n = cutcmd("n", "cutoff angle", tds.notch)
B.notch = cutcmd("notch", "cutoff angle", tds.notch)
B.o = function()
  flush()
  if tds.dimensions() == 1 then tds.string_pop(); return end -- the string model's o
  local ok, err = pcall(tds.pop, nil)
  if not ok then
    -- the message without its location and command (fail adds both)
    err = tostring(err):gsub("^[^\n]-:%d+: ", ""):gsub("^o: ", "")
    fail("o: " .. (err:match("not supported.*") or err))
  end
end
B.renumber_all = function() flush(); tds.renumber_all() end
B.rebody = function() flush(); tds.rebody() end
-- O: pops edges; in the string model the same as o (Evolver pops vertices there).
B.O = function()
  flush()
  if tds.dimensions() == 1 then tds.string_pop() else tds.pop_edges(nil) end
end
B.j = function(t) flush(); tds.jiggle(t ~= nil and num(t, "j") or nil) end
B.V = function(n) for _ = 1, times(n, "V") do flush(); tds.vertex_average(nil) end end
B.vertex_average = B.V
B.rawv = function() flush(); tds.vertex_average(nil, "raw") end
B.rawestv = function() flush(); tds.vertex_average(nil, "rawest") end
B.raw_vertex_average = B.rawv
B.rawest_vertex_average = B.rawestv
B.v = function()
  tds.totals()
  E.out("\nBody          target volume           actual volume          pressure\n")
  for _, b in ipairs(E.all("body")) do
    local target = b.target and ("%.15g"):format(b.target) or "-"
    E.out(("%3d  %22s  %22.15g  %16.15g\n"):format(b.id, target, b.volume, b.pressure))
  end
end
B.show_vol = B.v
B.U = function(n)
  local on = tds.setting("conj_grad")
  if n ~= nil and num(n) == 2 then
    tds.setting("conj_grad", true)
    E.out("Conjugate gradient history reset.\n")
    return
  end
  tds.setting("conj_grad", not on)
  E.out(("Conjugate gradient now %s. (was %s)\n"):format(on and "OFF" or "ON", on and "on" or "off"))
end
B.m = function(s)
  if s == nil then
    tds.optimize()
    E.out("Scale optimizing.\n")
  else
    s = num(s, "m")
    if s < 0 then fail("m: the scale must not be negative") end
    tds.scale(s)
    E.out(("Scale fixed at %g.\n"):format(s))
  end
end
B.optimize = function(lim) tds.optimize(lim and num(lim)) end
B.optimise = B.optimize
B.G = function(v)
  local g, on = tds.gravity()
  if v == nil then
    tds.gravity(g, not on)
    E.out(("Gravity is now %s.\n"):format(on and "OFF" or "ON"))
  else
    tds.gravity(num(v, "G"), true)
  end
end
B.q = function(code) error({ tds_quit = code and math.floor(num(code)) or 0 }, 0) end
B.x, B.quit, B.bye, B.exit = B.q, B.q, B.q, B.q
B.C = function() tds.check(); E.out("Checks completed.\n") end
B.check = B.C
B.c = function() E.out(counts_line()) end
B.counts = B.c
B.i = function()
  local en, ar = tds.totals()
  E.out(("Total energy: %28.15g\nTotal area: %30.15g\n"):format(en, ar))
  E.out(counts_line())
  local sc, fixed = tds.scale()
  E.out(("Motion scale factor %s at %g\n"):format(fixed and "fixed" or "optimizing", sc))
end
B.recalc = function() tds.totals(); if tds.pressures then tds.pressures() end end
B.dump = function(path)
  local ok, err = tds.dump(path)
  if not ok then fail(err) end
end
B.d = B.dump
B.system = function(cmd)
  if type(cmd) ~= "string" then fail("system needs a command string") end
  flush()
  os.execute(cmd)
end
B.matrix_multiply = function(...) E.fn.matrix_multiply(...) end
B.matrix_inverse = function(...) E.fn.matrix_inverse(...) end
B.chdir = function(path)
  if type(path) ~= "string" then fail("chdir needs a folder name string") end
  local ok, msg = tds.chdir(path)
  if not ok then fail(msg) end
end
B.shell = function() flush(); os.execute(os.getenv("SHELL") or "/bin/sh") end
B.help = function() help() end
B.N = function()
  for _, b in ipairs(E.all("body")) do if b.target then b.target = b.volume end end
end
B.list = function() fail("list needs a generator: list vertex, list edge where ...") end
B.read = function(path) E.readfile(path) end
-- load "file": a new surface in the same session; variables and commands
-- (Evolver's and Lua's) are kept, as with Evolver's permload.
B.load = function(path)
  if type(path) ~= "string" then fail("load needs a datafile name: load \"file.fe\"") end
  flush()
  E.touch()
  local ok, err = pcall(tds.load_replace, path)
  if not ok then
    err = tostring(err)
    if err:find("^" .. path:gsub("%p", "%%%0") .. ":%d") then error(err, 0) end -- has its place
    fail(err)
  end
  E.lagrange1 = false -- a new surface: the linear model
end
B.permload = B.load
-- addload "file": its elements added to the surface (renumbered after the
-- existing ones), its top section's declarations replacing those of the
-- same name; its read section is not run. replace_load: the elements go
-- first. Both are all or nothing.
local function addload(fn, what, path)
  if type(path) ~= "string" then fail(what .. " needs a datafile name: " .. what .. " \"file.fe\"") end
  flush()
  E.touch()
  local ok, err = pcall(fn, path)
  if not ok then
    err = tostring(err)
    if err:find("^" .. path:gsub("%p", "%%%0") .. ":%d") then error(err, 0) end
    fail(err)
  end
end
B.addload = function(path) addload(tds.addload, "addload", path) end
B.replace_load = function(path) addload(tds.replace_load, "replace_load", path) end
B.exec = function(text) E.exec(text) end

-- The element model. tds has linear elements only: `linear`, `M 1` and
-- `lagrange 1` (the same geometry in Evolver, stored another way) are
-- accepted and report what Evolver reports; `quadratic`, `M 2` and
-- `lagrange n` (n >= 2) are not supported yet. E.lagrange1: `lagrange 1`
-- was given (Evolver's LAGRANGE model) since the last `linear`.
local converted = false -- Evolver converts to named quantities once
local NO_HIGHER = " (tds has linear elements only; linear and lagrange 1 are accepted)"
B.linear = function()
  if E.lagrange1 then E.out("Changing to LINEAR model. (was LAGRANGE)\n") end
  E.lagrange1 = false
end
B.quadratic = function() fail("quadratic: not supported yet" .. NO_HIGHER) end
B.lagrange = function(n)
  if n == nil then fail("Syntax: LAGRANGE order") end
  n = num(n, "lagrange")
  if n % 1 ~= 0 then fail(("lagrange: order %g must be a whole number"):format(n)) end
  if n < 1 then fail("Lagrange order must be at least 1.") end
  if n > 1 then fail(("lagrange: not supported yet for order %d%s"):format(n, NO_HIGHER)) end
  if E.lagrange1 then
    E.out("Changing to LAGRANGE 1 model. (was LAGRANGE 1)\n")
  else
    E.out("Changing to LAGRANGE model. (was LINEAR)\n")
    if not converted then E.out("Converting to all named quantities...Done.\n") end
    converted = true
  end
  E.lagrange1 = true
end
B.M = function(n)
  if n == nil then fail("M: give the model: M 1 (linear) or M 2 (quadratic)") end
  n = num(n, "M")
  if n == 2 then fail("M: not supported yet for M 2, the quadratic model" .. NO_HIGHER) end
  if n ~= 1 then fail(("M %g: the model is 1 (linear) or 2 (quadratic)"):format(n)) end
  if not E.lagrange1 then E.out("Model already LINEAR.\n") end
  B.linear()
end

-- A toggle's name alone turns it on, as in Evolver (conj_grad; quiet).
-- Anything else after it is an error (Evolver's syntax error), not ignored.
local function toggle_on(name)
  return function(...)
    if select("#", ...) > 0 then
      local v = ...
      fail(("%s takes on or off, not %s"):format(name, type(v) == "number" and ("%g"):format(v) or tostring(v)))
    end
    E.toggle(name, true)
  end
end
for name in pairs(TOGGLE_MSG) do B[name] = toggle_on(name) end

for name in pairs(FIXED_TOGGLE) do B[name] = toggle_on(name) end
for name in pairs(DRAW) do B[name] = toggle_on(name) end
-- Energies are computed one way in tds: nothing to convert.
B.convert_to_quantities = function() end

-- Newton steps and eigenvalues (src/lua_newton.c, doc/newton.md).
local function need_surface(what)
  if tds.count(tds.vertex) == 0 then fail(what .. ": there is no surface (load a datafile first)") end
  flush()
end
B.hessian = function() need_surface("hessian"); tds.hessian() end
B.hessian_seek = function(s) need_surface("hessian_seek"); tds.hessian_seek(s ~= nil and num(s, "hessian_seek") or nil) end
B.saddle = function(s) need_surface("saddle"); tds.saddle(s ~= nil and num(s, "saddle") or nil) end
B.eigenprobe = function(c, iters)
  need_surface("eigenprobe")
  if iters ~= nil then iters = times(iters, "eigenprobe") end
  tds.eigenprobe(c ~= nil and num(c, "eigenprobe") or 0, iters)
end
B.ritz = function(c, n)
  need_surface("ritz")
  if n ~= nil then n = times(n, "ritz") end
  tds.ritz(c ~= nil and num(c, "ritz") or 0, n or 5)
end
B.lanczos = function(c, n) return B.ritz(c, n or 15) end

-- The torus model (src/lua_torus.c, doc/torus.md).
B.wrap_vertex = function(v, w)
  if v == nil or w == nil then fail("wrap_vertex needs a vertex and a wrap: wrap_vertex(1, 4096)") end
  tds.wrap_vertex(num(v, "wrap_vertex"), num(w, "wrap_vertex"))
end
B.detorus = function() need_surface("detorus"); tds.detorus() end
B.move = function(t)
  if t == nil then fail("move needs a step: move 0.1") end
  tds.move(num(t, "move"))
end

-- Evolver commands tds does not have: named in the error.
local UNSUPPORTED = {}
for w in ([[J e A a b f k p Q W y Z z s P D F H h X
  hessian_menu
  dirichlet dirichlet_seek sobolev sobolev_seek
  t1_edgeswap raw_vertex_average
  rawest_vertex_average rawv rawestv
  edge_merge facet_merge facet_crosscut zoom
  logfile keylogfile history pause subcommand breakpoint whereami flush_counts
  reset_counts metis kmetis body_metis ometis
  exprint show show_expr showq close_show
  display_text delete_text postscript binary_off_file off_file geomview
  homothety ribiere
  quietgo quietload verbose approximate_curvature runge_kutta
  post_project volgrads_every effective_area normal_motion
  kusner conf_edge normal_curvature boundary_curvature
  show_all_quantities interp_bdry_param break_after_warning break_on_warning
  itdebug memdebug debug estimate extrapolate set_body_target quantity]]):gmatch("%S+") do UNSUPPORTED[w] = true end
for w in ([[deturck diffusion hessian_special_normal
  hessian_double_normal sobolev_mode dirichlet_mode pop_disjoin
  septum_flag force_deletion star_finagling
  force_edgeswap k_altitude_mode assume_oriented calculate_in_3d self_similar
  immediate_autopop autopop_quartic longj simplex_to_fe ooglfile geompipe reorder_storage
  free_discards dump_memlist]]):gmatch("%S+") do
  UNSUPPORTED[w] = true
end
E.UNSUPPORTED = UNSUPPORTED
-- The translator takes what follows such a command as its arguments.
evolang.UNSUPPORTED = setmetatable({}, { __index = function(_, k)
  if UNSUPPORTED[k] and not B[k] then return true end
end })
-- jiggle is Evolver's toggle (jiggling at every iteration); tds's Lua
-- jiggle(t) is one jiggle, as Evolver's j
B.jiggle = function(t)
  if t == nil then fail("jiggle (jiggling at every iteration): not supported yet; j [temperature] jiggles once") end
  return B.j(t) -- tds's alias of j (doc/commands.md)
end



-- Whether E.cmd would find `name` now (a command, variable or function).
local function known(name)
  local low = name:lower()
  if redefined[name] or B[name] or B[low] or rawget(_G, name) ~= nil then return true end
  if #name > 1 and (rawget(_G, low) ~= nil or UNSUPPORTED[low] or EVOLVER_VARS[low]) then return true end
  if #name == 1 and UNSUPPORTED[name] then return true end
  return tds.param(name) ~= nil or INTERNAL[low] ~= nil
end

-- A definition names commands (words, from the translator) that nothing in
-- its text defines: each must exist when the definition runs, as Evolver
-- checks them when it reads the definition.
local function check_words(words)
  for _, w in ipairs(words or {}) do
    if not known(w) then fail(("'%s' is not a command, variable or function"):format(w)) end
  end
end

function E.defcmd(name, fn, words)
  check_words(words)
  if B[name] then fail(("'%s' is a built-in command and cannot be redefined (use a new name)"):format(name)) end
  if protected[name] and not user[rawget(_G, name)] then
    fail(("'%s' is a tds function and cannot be redefined (use a new name)"):format(name))
  end
  if INTERNAL[name] then fail(("'%s' is an internal variable"):format(name)) end
  if tds.param(name) ~= nil then fail(("'%s' is a parameter, not a command"):format(name)) end
  -- Called from Lua (or the prompt) the command is a top-level one.
  local cmd = function() if depth == 0 then return E.top(fn) end return fn() end
  user[cmd] = true
  rawset(_G, name, cmd)
end

function E.defproc(name, fn, words)
  check_words(words)
  if B[name] or INTERNAL[name] or protected[name] and not user[rawget(_G, name)] then
    fail(("'%s' is a built-in name"):format(name))
  end
  local proc = function(...) if depth == 0 then return E.top(fn, ...) end return fn(...) end
  user[proc] = "proc"
  rawset(_G, name, proc)
end

function E.redefine(letter, fn, words)
  check_words(words)
  redefined[letter] = fn
end

-- Run command `name` with arguments (counts repeat user commands).
function E.cmd(name, ...)
  local nargs = select("#", ...)
  local r = redefined[name]
  if r then
    for _ = 1, times(nargs > 0 and ... or nil, name) do r() end
    return
  end
  local b = B[name]
  if not b and #name > 1 then b = B[name:lower()] end
  if b then E.touch(); return b(...) end
  local f = rawget(_G, name)
  -- single letters are case-sensitive (W is not w)
  if f == nil and #name > 1 then f = rawget(_G, name:lower()) end
  if type(f) == "function" then
    if user[f] == true then
      if nargs > 1 then fail(("%s takes at most a repetition count"):format(name)) end
      for _ = 1, times(nargs > 0 and ... or nil, name) do f() end
      return
    end
    E.touch()
    local r = table.pack(f(...))
    E.touch() -- a Lua function may have changed the mesh
    return table.unpack(r, 1, r.n)
  end
  local low = name:lower()
  if #name == 1 and UNSUPPORTED[name] or #name > 1 and UNSUPPORTED[low] then
    fail(("%s: not supported yet"):format(name))
  end
  if f ~= nil or tds.param(name) ~= nil or INTERNAL[low] then
    if nargs == 0 then return E.print(E.getv(name)) end
    fail(("'%s' is a variable, not a command"):format(name))
  end
  fail(("'%s' is not a command, variable or function"):format(name))
end

function E.cmdvalue(v) E.print(v) end
function E.unsupported(what) fail(what .. ": not supported yet") end

-- 'r': the built-in single-letter command, bypassing :::= redefinitions.
function E.orig(letter, ...)
  local b = B[letter]
  if not b then fail(("'%s': not supported yet"):format(letter)) end
  return b(...)
end

function E.protect()
  for k, v in pairs(_G) do if type(v) == "function" or type(v) == "table" then protected[k] = true end end
end

-- A function called in an expression: user functions, procedures, Lua.
function E.callf(name, ...)
  E.touch()
  local f = rawget(_G, name)
  if f == nil then f = rawget(_G, name:lower()) end
  if type(f) ~= "function" then
    if UNSUPPORTED[name:lower()] then fail(name .. ": not supported yet") end
    fail(("'%s' is not a function"):format(name))
  end
  local v = f(...)
  E.touch()
  if type(v) == "boolean" then v = v and 1.0 or 0.0 end
  return v
end

-- Act on a collected element list (refine edges where ...).
function E.oncollection(name, kind, list)
  flush()
  E.touch()
  for i, x in ipairs(list) do list[i] = E.unwrap(x) end
  if name == "refine" then
    if kind ~= "edge" then fail("refine " .. kind .. ": not supported yet (refine edges)") end
    tds.edge_divide(list) -- each edge splits its facets in two, as Evolver's
  elseif name == "equiangulate" then
    if kind ~= "edge" then fail("equiangulate needs edges") end
    tds.equiangulate(list)
  elseif name == "vertex_average" or name == "raw_vertex_average" or name == "rawest_vertex_average" then
    if kind ~= "vertex" then fail(name .. " needs vertices") end
    -- one vertex after another, as Evolver's vertex_average
    tds.vertex_average(list, name == "vertex_average" and "V" or name:match("^(%a+)_"), true)
  elseif name == "delete" then
    if kind ~= "edge" and kind ~= "facet" then fail("delete needs edges or facets") end
    if #list > 0 then tds.delete(list) end
  elseif name == "pop_edge_to_tri" then
    if kind ~= "edge" then fail("pop_edge_to_tri needs edges") end
    tds.pop_edge_to_tri(list)
  elseif name == "pop_tri_to_edge" then
    if kind ~= "facet" then fail("pop_tri_to_edge needs facets") end
    tds.pop_tri_to_edge(list)
  elseif name == "pop_quad_to_quad" then
    if kind ~= "facet" then fail("pop_quad_to_quad needs facets") end
    tds.pop_quad_to_quad(list)
  elseif name == "dissolve" then
    if #list > 0 then tds.dissolve(list) end
  elseif name == "reverse_orientation" then
    if kind ~= "edge" and kind ~= "facet" then fail("reverse_orientation needs edges or facets") end
    if #list > 0 then tds.reverse_orientation(list) end
  elseif name == "pop" and tds.dimensions() == 1 then -- the string model: Evolver's o on them
    if kind ~= "vertex" then fail("pop " .. kind .. ": the string model pops vertices only (as Evolver)") end
    if #list > 0 then tds.string_pop(list, true) end
  elseif name == "pop" then
    if kind ~= "vertex" and kind ~= "edge" then fail("pop works on vertices and edges, not " .. kind) end
    tds.pop(list)
  elseif name == "edgeswap" then
    if kind ~= "edge" then fail("edgeswap needs edges") end
    tds.edgeswap(list)
  elseif name == "t1_edgeswap" then -- the string model (doc/string.md)
    if kind ~= "edge" then fail("t1_edgeswap needs edges") end
    tds.string_t1(list)
  else
    fail(name .. ": not supported yet")
  end
end

function E.abort() error({ evolver_abort = true }, 0) end

-- One top-level command: abort ends it quietly and returns to the caller.
function E.top(fn, ...)
  E.touch()
  depth = depth + 1
  local r = table.pack(pcall(fn, ...))
  depth = depth - 1
  E.touch()
  if r[1] then return table.unpack(r, 2, r.n) end
  local err = r[2]
  if type(err) == "table" and err.evolver_abort and depth == 0 then return end
  if type(err) == "string" and err:match("^%[tds evo%a+%]:%d+: interrupted$") then err = "interrupted" end
  error(err, 0)
end

---------------------------------------------------------------- running text

local function load_src(src, chunk)
  local fn, lerr = load(src, "@" .. (chunk or "evolver"), "t", _ENV) -- the surface's names
  if not fn then error("evolver translation failed: " .. lerr, 0) end
  return fn
end

-- Run text. A syntax error is raised after the command lines before it
-- have run, as Evolver reads and runs a file line by line.
function E.run(text, chunk, line0)
  if type(text) ~= "string" then fail("evolver: expected command text") end
  local src, err, partial = evolang.translate(text, line0)
  if src then return load_src(src, chunk)(E) end
  if partial then load_src(partial, chunk)(E) end
  error((chunk or "evolver") .. ":" .. err, 0)
end

function E.run_file(path)
  local f, err = io.open(path, "r")
  if not f then error("cannot read command file " .. err, 0) end
  local text = f:read("a")
  f:close()
  return E.run(text, path, 1)
end

function E.readfile(path)
  if type(path) ~= "string" then fail("read needs a file name string") end
  local f = io.open(path, "r")
  if not f then fail(("read: cannot open '%s'"):format(path)) end
  f:close()
  E.run_file(path)
end

function E.exec(text)
  if type(text) ~= "string" then fail("exec needs a string") end
  E.run(text, "exec", 1)
end

-- The read section a dump writes (src/lua_datafile.c, tds.dump): the
-- loaded one's definitions, and its variables with their values now
-- (evolang.dump_read).
function E.dump_read(text)
  return evolang.dump_read(text, function(name)
    local ok, v = pcall(E.getv, name)
    if ok then return v end
  end)
end

-- The read section of the datafile just loaded from `path`, run with its
-- own line numbers.
function E.run_read(path)
  local text = tds.read_text and tds.read_text()
  if not text then return end
  local line0 = 1
  local f = io.open(path, "r")
  if f then
    local all = f:read("a")
    f:close()
    if #all >= #text and all:sub(-#text) == text then
      local _, n = all:sub(1, #all - #text):gsub("\n", "")
      line0 = n + 1
    end
  end
  E.run(text, path, line0)
end

require("evoview")

-- evolver [[ text ]]: run Evolver command text from Lua. Errors read
-- "script.tds:CALLLINE: evolver:LINE: message" (LINE within the text).
function evolver(text)
  if type(text) ~= "string" then error("evolver(text): expected a string of Evolver commands", 2) end
  local info = debug.getinfo(2, "Sl")
  local name = "evolver"
  if info and info.currentline and info.currentline > 0 then
    name = ("%s:%d: evolver"):format(info.short_src, info.currentline)
  end
  return E.run(text, name, 1)
end

return E
