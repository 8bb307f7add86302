-- perturb.lua: a variant of an Evolver SYMMETRY_GROUP "torus" datafile
-- (symtest.fe) that nobody designed: the unit cell mapped onto a skew
-- cell (PERIODS P, each vertex x -> x P, so the wraps still fit), every
-- vertex then moved by a seeded pseudo-random offset of size AMP, and
-- optionally volume targets on the bodies (VOLS, fractions of the cell
-- volume). Set IN, OUT, SEED, AMP, P ({{...},{...},{...}}) and VOLS (or
-- nil), then dofile this.
math.randomseed(SEED)
local det = P[1][1] * (P[2][2] * P[3][3] - P[2][3] * P[3][2])
  - P[1][2] * (P[2][1] * P[3][3] - P[2][3] * P[3][1])
  + P[1][3] * (P[2][1] * P[3][2] - P[2][2] * P[3][1])
local out, section = {}, nil
for line in io.lines(IN) do
  local w = line:match('^(%a+)')
  if w then section = w:lower() end
  if line:match('^SYMMETRY_GROUP') then
    out[#out + 1] = line
    out[#out + 1] = 'PERIODS'
    for i = 1, 3 do out[#out + 1] = ('%.17g %.17g %.17g'):format(P[i][1], P[i][2], P[i][3]) end
  elseif section == 'vertices' and line:match('^%s*%d+%s+%S+%s+%S+%s+%S+%s*$') then
    local id, a, b, c = line:match('^%s*(%d+)%s+(%S+)%s+(%S+)%s+(%S+)')
    local x = {tonumber(a), tonumber(b), tonumber(c)}
    local y = {}
    for j = 1, 3 do
      y[j] = x[1] * P[1][j] + x[2] * P[2][j] + x[3] * P[3][j] + AMP * (2 * math.random() - 1)
    end
    out[#out + 1] = ('%s %.17g %.17g %.17g'):format(id, y[1], y[2], y[3])
  elseif section == 'bodies' and VOLS and line:match('^%s*(%d+)%s') and VOLS[tonumber(line:match('^%s*(%d+)'))] then
    local id = tonumber(line:match('^%s*(%d+)'))
    local body = line:gsub('//.*$', '')
    out[#out + 1] = ('%s volume %.17g'):format(body, VOLS[id] * math.abs(det))
  else
    out[#out + 1] = line
  end
end
local f = assert(io.open(OUT, 'w'))
f:write(table.concat(out, '\n'), '\n')
f:close()
