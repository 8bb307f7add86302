-- evoview.lua: Evolver's view transforms in command text, part of the
-- runtime tds.E (lua/evorun.lua): transform_expr "abc" and transform_depth
-- n make the view transforms from the datafile's VIEW_TRANSFORM_GENERATORS
-- (commands.htm#transform_expr), view_transforms[i][j][k] reads them and
-- transform_count counts them. The matrices are kept by the surface
-- (src/lua_view.c) for scripts and dumps; tds draws no graphics.
--
-- transform_expr's grammar (spaces ignored; letters name generators in
-- datafile order, either case):
--   expr := seq { '|' seq }          union
--   seq  := item { item }            all ordered products, left to right
--   item := digits item              n-fold products (n < 1 counts as 1)
--         | '!' item                 the item's set without the identity
--         | letter                   { identity, generator }
--         | '(' expr ')'
-- Duplicates (equal matrices to 1e-9) are dropped, the first kept.

local tds = tds
local E = tds.E
local fail, num, B, INTERNAL = E.fail, E.num, E.B, E.INTERNAL

-- Matrices are flat lists of 16 (row-major), with [17] the SWAP_COLORS
-- flag (0/1; a product's is the parity of its factors'); duplicates are
-- judged by the matrix alone.
local ID = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0 }
local floor, fmt = math.floor, string.format
local KEYFMT = ("%.9f,"):rep(16)
local function r9(v) return floor(v * 1e9 + 0.5) / 1e9 + 0.0 end
local function key(m)
  return fmt(KEYFMT, r9(m[1]), r9(m[2]), r9(m[3]), r9(m[4]), r9(m[5]), r9(m[6]), r9(m[7]),
    r9(m[8]), r9(m[9]), r9(m[10]), r9(m[11]), r9(m[12]), r9(m[13]), r9(m[14]), r9(m[15]), r9(m[16]))
end
local function mul(a, b)
  local c = {}
  for i = 0, 3 do
    for j = 1, 4 do
      local s = 0.0
      for k = 1, 4 do s = s + a[4 * i + k] * b[4 * (k - 1) + j] end
      c[4 * i + j] = s
    end
  end
  c[17] = (a[17] + b[17]) % 2
  return c
end
local MAXN = 100000
-- A set: a list of matrices (flat, 16) and their keys.
local function newset() return { keys = {} } end
local function add(s, m)
  local k = key(m)
  if s.keys[k] then return end
  if #s >= MAXN then fail(("transform_expr: more than %d transforms"):format(MAXN)) end
  s.keys[k] = true
  s[#s + 1] = m
end
local work -- products left to form in this transform_expr (a bound on its time)
local function product(a, b)
  work = work - #a * #b
  if work < 0 then fail("transform_expr: more than 200000 matrix products; use a smaller expression") end
  local c = newset()
  for _, x in ipairs(a) do for _, y in ipairs(b) do add(c, mul(x, y)) end end
  return c
end

function E.transform_expr(text)
  if type(text) ~= "string" then fail("transform_expr needs a string: transform_expr \"abc\"") end
  local gens, gswap = tds.view_generators()
  work = 2e5
  local src = text:gsub("%s", "")
  local pos = 1
  local function bad() fail("Illegal transform expression syntax: " .. text) end
  local function peek() return src:sub(pos, pos) end
  local expr
  local function item()
    local c = peek()
    local digits = src:match("^%d+", pos)
    if digits then
      pos = pos + #digits
      local n = math.max(1, math.tointeger(tonumber(digits)) or 1)
      if n > MAXN then fail(("transform_expr: count %s too large"):format(digits)) end
      local s = item()
      local r = s
      for _ = 2, n do r = product(r, s) end
      return r
    elseif c == "!" then
      pos = pos + 1
      local s, r = item(), newset()
      for _, m in ipairs(s) do if key(m) ~= key(ID) then add(r, m) end end
      return r
    elseif c == "(" then
      pos = pos + 1
      local s = expr()
      if peek() ~= ")" then bad() end
      pos = pos + 1
      return s
    elseif c:match("^%a$") then
      pos = pos + 1
      local g = gens[c:lower():byte() - 96]
      if not g then fail(("No generator '%s'."):format(c)) end
      local m = {}
      for i = 1, 4 do for j = 1, 4 do m[4 * (i - 1) + j] = g[i][j] end end
      m[17] = gswap[c:lower():byte() - 96] and 1 or 0
      local s = newset()
      add(s, ID)
      add(s, m)
      return s
    end
    bad()
  end
  local function seq()
    local s = item()
    while pos <= #src and peek() ~= "|" and peek() ~= ")" do s = product(s, item()) end
    return s
  end
  function expr()
    local s = seq()
    while peek() == "|" do
      pos = pos + 1
      local t = seq()
      for _, m in ipairs(t) do add(s, m) end
    end
    return s
  end
  local result
  if src == "" then
    result = newset()
    add(result, ID)
  else
    result = expr()
    if pos <= #src then
      if peek() == ")" then fail("Transform expression has unmatched parentheses.") end
      bad()
    end
  end
  local list, swaps = {}, {}
  for i, m in ipairs(result) do
    list[i] = { { m[1], m[2], m[3], m[4] }, { m[5], m[6], m[7], m[8] },
                { m[9], m[10], m[11], m[12] }, { m[13], m[14], m[15], m[16] } }
    swaps[i] = m[17] == 1
  end
  tds.view_transforms(list, swaps)
end

B.transform_expr = function(text) E.transform_expr(text) end
-- transform_depth n: every product of at most n generators
B.transform_depth = function(n)
  if n == nil then fail("transform_depth needs a depth: transform_depth 2") end
  n = num(n, "transform_depth")
  if n % 1 ~= 0 or n < 1 then fail(("transform_depth: %g must be a whole number >= 1"):format(n)) end
  local k = #tds.view_generators()
  if k == 0 then fail("transform_depth: the datafile has no VIEW_TRANSFORM_GENERATORS") end
  local letters = {}
  for i = 1, k do letters[i] = string.char(96 + i) end
  E.transform_expr(("%d(%s)"):format(n, table.concat(letters, "|")))
end
-- show_trans "string": graphics commands for the display; no effect here
B.show_trans = function(s)
  if type(s) ~= "string" then fail("show_trans needs a string") end
end
-- list topinfo: the top section of the datafile dump would write (what
-- comes before its vertices), as multiplicate.cmd uses it.
function E.listtop()
  local tmp = os.tmpname()
  local ok, err = tds.dump(tmp)
  if not ok then os.remove(tmp); fail(err) end
  local out = {}
  for line in io.lines(tmp) do
    if line:lower():match("^%s*vertices%s*$") then break end
    out[#out + 1] = line
  end
  os.remove(tmp)
  E.out(table.concat(out, "\n") .. "\n")
end

INTERNAL.view_transforms = function() return (tds.view_transforms()) end
INTERNAL.view_transform_swap_colors = function()
  local _, sw = tds.view_transforms()
  for i, b in ipairs(sw) do sw[i] = b and 1.0 or 0.0 end
  return sw
end
INTERNAL.transform_count = function() return #tds.view_transforms() + 0.0 end

return true
