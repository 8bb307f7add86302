-- doublecone.lua: two cones of facets over fixed rims of n vertices at
-- z = +-0.8 meeting at one free vertex (a pinched neck), as an Evolver
-- datafile, for pop_enjoin (tests/evolver/enjoin.sh). return function(p)
-- -> the text; p.n, p.seed, p.jit (every coordinate moved by up to jit/2,
-- seeded), p.opts letters: f the second cone's facets turned round, g the
-- first cone's, i the edges at the vertex run into it, c the rims numbered
-- clockwise, u the lower cone listed first.
return function(p)
local n, seed, jit, o = p.n, p.seed or 0, p.jit or 0, p.opts or ""
local function has(c) return o:find(c, 1, true) ~= nil end
local s = seed * 7919 + 3
local function rnd() s = (s * 1103515245 + 12345) % 2147483648; return s / 2147483648 - 0.5 end
local out = {"vertices", ("1 %.15g %.15g %.15g"):format(jit * rnd(), jit * rnd(), jit * rnd())}
for c = 0, 1 do
  local zc = (c == 0) ~= has("u") and 0.8 or -0.8
  for k = 0, n - 1 do
    local t = 2 * math.pi * k / n * (has("c") and -1 or 1)
    out[#out + 1] = ("%d %.15g %.15g %.15g fixed"):format(2 + c * n + k, math.cos(t) + jit * rnd(), math.sin(t) + jit * rnd(), zc + jit * rnd())
  end
end
out[#out + 1] = "edges"
for c = 0, 1 do for k = 0, n - 1 do
  if has("i") then out[#out + 1] = ("%d %d 1"):format(1 + c * n + k, 2 + c * n + k)
  else out[#out + 1] = ("%d 1 %d"):format(1 + c * n + k, 2 + c * n + k) end
end end
for c = 0, 1 do for k = 0, n - 1 do out[#out + 1] = ("%d %d %d fixed"):format(1 + 2 * n + c * n + k, 2 + c * n + k, 2 + c * n + (k + 1) % n) end end
out[#out + 1] = "faces"
local sg = has("i") and -1 or 1
for c = 0, 1 do for k = 0, n - 1 do
  local s1, s2, r = sg * (1 + c * n + k), sg * (1 + c * n + (k + 1) % n), 1 + 2 * n + c * n + k
  if (has("f") and c == 1) or (has("g") and c == 0) then out[#out + 1] = ("%d %d %d %d"):format(1 + c * n + k, s2, -r, -s1)
  else out[#out + 1] = ("%d %d %d %d"):format(1 + c * n + k, s1, r, -s2) end
end end
return table.concat(out, "\n") .. "\n"
end
