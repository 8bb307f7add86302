-- hesscmp.lua: compare what Evolver and tds print for the same Hessian
-- commands (tests/evolver/string_hessian.sh). Records, in order:
--   K<tag> v1 v2 ...   printf lines: reals to tolE relative (absolute below 1)
--   Eigencounts        the three counts, exactly
--   ritz values        the block of "  k.  value" lines after a count line,
--                      compared as sets to tolV (Evolver lists them in its
--                      own order), all but the one farthest from the
--                      shift -0.01 (Evolver's subspace iteration stops
--                      before that one has converged: 3.5e-5 measured)
-- hesscmp(name, evolver_out, tds_out, tolE, tolV) prints PASS/FAIL name and
-- a comment line with the largest differences seen.
local function records(path)
  local R, cur = {}, nil
  for l in io.lines(path) do
    local tag, rest = l:match("^K(%S*) (.+)$")
    if tag then
      local v = {}
      for w in rest:gmatch("%S+") do v[#v + 1] = tonumber(w) end
      R[#R + 1] = {k = "K" .. tag, v = v}
      cur = nil
    elseif l:match("^Eigencounts:") then
      local a, b, c = l:match("(%-?%d+) <,%s+(%-?%d+) ==,%s+(%-?%d+) >")
      R[#R + 1] = {k = "C", v = a .. " " .. b .. " " .. c}
      cur = nil
    elseif l:match("^ERROR") or l:match("^[^ ]+:%d+: ") then
      R[#R + 1] = {k = "E", v = l}
      cur = nil
    else
      local x = l:match("^%s+%d+%.%s+(%S+)%s*$")
      if x and tonumber(x) then
        if not cur then
          cur = {k = "R", v = {}}
          R[#R + 1] = cur
        end
        cur.v[#cur.v + 1] = tonumber(x)
      end
    end
  end
  return R
end

local function dev(a, b) return math.abs(a - b) / math.max(1, math.abs(a)) end

function hesscmp(name, evpath, tdpath, tolE, tolV)
  local ev, td = records(evpath), records(tdpath)
  local bad
  local worstE, worstV = 0, 0
  if #ev ~= #td then bad = ("%d records from Evolver, %d from tds"):format(#ev, #td) end
  for i = 1, math.min(#ev, #td) do
    local a, b = ev[i], td[i]
    if a.k ~= b.k then
      bad = bad or ("record %d: Evolver %s (%s), tds %s (%s)"):format(i, a.k, tostring(a.v), b.k,
                                                                     tostring(b.v))
      break
    elseif a.k == "C" or a.k == "E" then
      if a.v ~= b.v then bad = bad or ("record %d: Evolver '%s', tds '%s'"):format(i, a.v, b.v) end
    elseif a.k == "R" then
      local function near(x, y) return math.abs(x + 0.01) < math.abs(y + 0.01) end
      table.sort(a.v, near)
      table.sort(b.v, near)
      if #a.v >= 3 then a.v[#a.v] = nil end
      if #b.v >= 3 then b.v[#b.v] = nil end
      if #a.v ~= #b.v then bad = bad or ("record %d: %d eigenvalues vs %d"):format(i, #a.v, #b.v) end
      for j = 1, math.min(#a.v, #b.v) do
        local d = dev(a.v[j], b.v[j])
        worstV = math.max(worstV, d)
        if not (d <= tolV) then
          bad = bad or ("record %d: eigenvalue %.15g vs %.15g (tolerance %g)"):format(i, a.v[j], b.v[j], tolV)
        end
      end
    else
      if #a.v ~= #b.v then bad = bad or ("record %d (%s): %d values vs %d"):format(i, a.k, #a.v, #b.v) end
      for j = 1, math.min(#a.v, #b.v) do
        local d = dev(a.v[j], b.v[j])
        worstE = math.max(worstE, d)
        if not (d <= tolE) then
          bad = bad or ("record %d (%s): %.17g vs %.17g (tolerance %g)"):format(i, a.k, a.v[j], b.v[j], tolE)
        end
      end
    end
  end
  if bad then print("FAIL " .. name .. ": " .. bad) else print("PASS " .. name) end
  print(("# %s: %d records, worst value %.1e, worst eigenvalue %.1e"):format(name, #ev, worstE, worstV))
end
