-- compare.lua: helpers for tds's side of the Evolver comparison tests.
-- Loaded with dofile() from the -e code of a tests/evolver/*.sh script.

-- "V E F B" counts, as the Evolver side prints them.
function counts()
  return ("%d %d %d %d"):format(vertex_count, edge_count, facet_count, body_count)
end

-- Print PASS/FAIL name, with both values on failure.
function report(name, ok, got, want)
  if ok then
    print("PASS " .. name)
  else
    print(("FAIL %s: tds %s, Evolver %s"):format(name, tostring(got), tostring(want)))
  end
end

-- Compare a number with a relative tolerance and report it.
function same(name, got, want, tol)
  report(name, near(got, want, tol), ("%.15g"):format(got), ("%.15g"):format(want))
end

-- Iterate g until one step changes the energy by at most rel (relative).
function converge(rel, maxit)
  rel, maxit = rel or 1e-13, maxit or 100000
  local e0 = total_energy
  for i = 1, maxit do
    g(1)
    local e = total_energy
    if math.abs(e - e0) <= rel * math.abs(e0) then return i end
    e0 = e
  end
  error("g did not converge in " .. maxit .. " iterations")
end

-- Numbers of an Evolver "KEY v1 v2 ..." line given as "v1 v2 ...".
function nums(s)
  local t = {}
  for w in s:gmatch("%S+") do t[#t + 1] = tonumber(w) end
  return table.unpack(t)
end
