-- edges.lua: do two string-model torus dumps (A, B) have the same edges,
-- each from the same tail to the same head? Vertices are matched by
-- position modulo the unit lattice (a program may keep a vertex in
-- another copy of the cell; ids differ: Evolver reuses freed ids, tds
-- does not), to TOL digits. Prints PASS/FAIL NAME.
local function read(path)
  local V, E, sec = {}, {}, nil
  for l in io.lines(path) do
    local w = l:match('^(%a+)')
    w = w and w:lower()
    if w == 'vertices' or w == 'edges' or w == 'faces' or w == 'bodies' then sec = w
    elseif w == 'read' then sec = nil
    else
      local id, rest = l:match('^%s*(%d+)%s+(.*)')
      if id and sec == 'vertices' then
        local x, y = rest:match('^(%S+)%s+(%S+)')
        V[tonumber(id)] = {tonumber(x), tonumber(y)}
      elseif id and sec == 'edges' then
        local a, b = rest:match('^(%d+)%s+(%d+)')
        E[#E + 1] = {tonumber(a), tonumber(b)}
      end
    end
  end
  return V, E
end
local function key(p) -- position modulo the lattice, rounded
  local function m(x) local r = x % 1; if r > 1 - 0.5 * 10 ^ -DIGITS then r = 0 end return r end
  return ('%.' .. DIGITS .. 'f,%.' .. DIGITS .. 'f'):format(m(p[1]), m(p[2]))
end
local sets, n = {}, {}
for i, path in ipairs {A, B} do
  local V, E = read(path)
  local s = {}
  for _, e in ipairs(E) do s[key(V[e[1]]) .. '>' .. key(V[e[2]])] = true end
  sets[i], n[i] = s, #E
end
local bad
if n[1] ~= n[2] or n[1] == 0 then bad = ('%d edges against %d'):format(n[1], n[2]) end
for k in pairs(sets[1]) do
  if not bad and not sets[2][k] then
    local t, h = k:match('(.*)>(.*)')
    bad = (sets[2][h .. '>' .. t] and 'reversed: ' or 'only in Evolver\'s: ') .. k
  end
end
print(bad and ('FAIL ' .. NAME .. ': ' .. bad) or ('PASS ' .. NAME))
