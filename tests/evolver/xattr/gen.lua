-- gen.lua: xdrop(seed, path) writes a drop on a curved table (mound.fe's
-- drop) whose integrands read element attributes with seeded random
-- values: a contact angle per edge in the constraint's energy integrand,
-- the table's curvature per vertex in its formula, a weight per facet and
-- per edge (and the built-in tension and original) in named quantities.
-- Used by tests/evolver/xattr.sh, which runs the same file in Evolver.
function xdrop(seed, path)
  math.randomseed(seed)
  local function u(a, b) return a + (b - a) * math.random() end
  local t = {}
  local function w(fmt, ...) t[#t + 1] = fmt:format(...) end
  w("// xdrop seed %d: attributes in integrands", seed)
  w("define edge attribute ang real")
  w("define vertex attribute cv real")
  w("define facet attribute fw real")
  w("define edge attribute ew real")
  w("gravity_constant 0")
  w("constraint 1")
  w("formula: x3 = cv*(x^2 + y^2)")
  w("energy:")
  w("e1: cos(ang*pi/180)*y")
  w("e2: 0")
  w("e3: 0")
  w("quantity fq energy method facet_scalar_integral global")
  w("scalar_integrand: fw*tension*z^2")
  w("quantity eq energy method edge_scalar_integral global")
  w("scalar_integrand: ew*(x^2 + y^2 + z^2) + 0.001*original")
  w("quantity vq info_only method facet_vector_integral global")
  w("vector_integrand:")
  w("q1: 0")
  w("q2: fw*x")
  w("q3: fw*z")
  w("vertices")
  local P = {{0,0,0},{1,0,0},{1,1,0},{0,1,0},{0,0,1},{1,0,1},{1,1,1},{0,1,1}}
  for i, p in ipairs(P) do
    local x, y, z = p[1] + u(-0.1, 0.1), p[2] + u(-0.1, 0.1), p[3] + (i > 4 and u(-0.1, 0.1) or 0)
    if i <= 4 then
      w("%d %.6f %.6f %.6f constraint 1 cv %.6f", i, x, y, z, u(0, 0.2))
    else
      w("%d %.6f %.6f %.6f cv %.6f", i, x, y, z, u(-1, 1))
    end
  end
  w("edges")
  local E = {{1,2},{2,3},{3,4},{4,1},{5,6},{6,7},{7,8},{8,5},{1,5},{2,6},{3,7},{4,8}}
  for i, e in ipairs(E) do
    w("%d %d %d %s ang %.6f ew %.6f", i, e[1], e[2], i <= 4 and "constraint 1" or "",
      u(60, 120), u(0, 0.1))
  end
  w("faces")
  local F = {{1,10,-5,-9},{2,11,-6,-10},{3,12,-7,-11},{4,9,-8,-12},{5,6,7,8}}
  for i, f in ipairs(F) do
    w("%d %d %d %d %d density %.6f fw %.6f", i, f[1], f[2], f[3], f[4], u(0.9, 1.1), u(0, 0.2))
  end
  w("bodies")
  w("1 1 2 3 4 5 volume 1")
  local f = assert(io.open(path, "w"))
  f:write(table.concat(t, "\n"), "\n")
  f:close()
end
