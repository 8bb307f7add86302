-- common.lua: the driver shared by the paper's experiments.
--
-- An experiment is a table:
--   name      short name
--   model()   declares parameters, constraints, gravity (optional)
--   input()   returns the input mesh as a trimesh{} table
--   target    curvature target: number, "lambda" or "pressure"
--   fe_header Evolver text declaring the same model (optional)
--   evolver_dump_extra  extra per-vertex printf fields (optional)
--
-- run(exp) builds the input and then, by the environment:
--   PAPER_FE=path        also write the Evolver twin of the input there
--   PAPER_EVOLVER=dir    also write the Evolver command files gloop.cmd and
--                        relax.cmd into dir (bench/paper.sh runs them)
--   PAPER_DUMP=file      instead of running pg, load the mesh Evolver
--                        printed into `file` and measure it
--   PAPER_PLAIN=1        run plain pg (no acceleration)
--   PAPER_S, PAPER_DEPTH pg's s and depth (defaults: pg's)
--   PAPER_MAX            pg's iteration cap (default: pg's, 100000)
--   PAPER_NEWTON=0       pg{ newton = false } (no Newton preconditioning)
--   PAPER_MOMENTUM=b     pg{ momentum = b } (the warm steps' momentum)
--   PAPER_MOMENTUM_SIZE=n pg{ momentum_size = n } (0: momentum as given)
--   PAPER_POLISH=1       pg_polish{} after pg (the curvature polish)
--   PAPER_POLISH_LOSS=b  its max_loss (degrees; default pg_polish's, 1)
--   PAPER_ANALYSE=1      also print where the curvature error sits
--                        (C.breakdown)
-- and prints the metrics and one machine-readable line starting RESULT.
require("pg")
local C = {}

local env = os.getenv

-- Read the V/F/B lines Evolver printed (see the command files below).
local function read_dump(path, exp)
  local V, F, B, idmap = {}, {}, {}, {}
  local extra = {}
  for line in io.lines(path) do
    local tag = line:match("^(%u+) ")
    if tag == "V" then
      local id, x, y, z, fixed, con = line:match("^V (%d+) (%S+) (%S+) (%S+) (%d+) ?(%d*)")
      V[#V + 1] = { tonumber(x), tonumber(y), tonumber(z), fixed = fixed == "1" or nil,
                    constraint = (con == "1") and 1 or nil }
      idmap[tonumber(id)] = #V
    elseif tag == "F" then
      local a, b, c, dens, fixed, fb, bb = line:match(
        "^F %d+ (%d+) (%d+) (%d+) (%S+) (%d+) (%d+) (%d+)")
      F[#F + 1] = { tonumber(a), tonumber(b), tonumber(c), tension = tonumber(dens),
                    fixed = fixed == "1" or nil,
                    body = tonumber(fb) > 0 and tonumber(fb) or nil,
                    backbody = tonumber(bb) > 0 and tonumber(bb) or nil }
    elseif tag == "B" then
      local id, target, vol, pres, dens = line:match("^B (%d+) (%S+) (%S+) (%S+) (%S+)")
      B[tonumber(id)] = { volume = tonumber(target), density = tonumber(dens),
                          actual = tonumber(vol), pressure = tonumber(pres) }
    elseif tag then
      extra[tag] = line:match("^%u+ (.*)")
    end
  end
  for _, f in ipairs(F) do
    for k = 1, 3 do f[k] = idmap[f[k]] end
  end
  return { vertices = V, facets = F, bodies = #B > 0 and B or nil }, extra
end

-- Evolver commands: print the mesh as V/F/B lines, and r.
local function dump_cmds(exp)
  local con = exp.has_constraint and ', (vv on_constraint 1)' or ''
  local fmt = exp.has_constraint and ' %d' or ''
  return table.concat({
    'foreach vertex vv do printf "V %d %.17g %.17g %.17g %d' .. fmt .. '\\n", vv.id, vv.x, vv.y, vv.z, vv.fixed' .. con .. ';',
    'foreach facet ff do printf "F %d %d %d %d %.17g %d %d %d\\n", ff.id, ff.vertex[1].id, ff.vertex[2].id, ff.vertex[3].id, ff.density, ff.fixed, ff.frontbody, ff.backbody;',
    'foreach body bb do printf "B %d %.17g %.17g %.17g %.17g\\n", bb.id, bb.target, bb.volume, bb.pressure, bb.density;',
  }, "\n")
end

local save = "set vertex ox x; set vertex oy y; set vertex oz z;"
local move = "max(vertex, sqrt((x-ox)^2+(y-oy)^2+(z-oz)^2))"

-- The paper's Evolver loop: g; u; V repeated.
local function gloop_cmds(exp, n)
  return table.concat({
    "define vertex attribute ox real", "define vertex attribute oy real",
    "define vertex attribute oz real", "quiet on",
    ("for ( inx := 1 ; inx < %d ; inx += 1 ) { g; u; V; }"):format(n),
    save, "g; u; V;",
    ('printf "R %%.17g\\n", %s;'):format(move),
    ('printf "ITERS %d\\n";'):format(n),
    dump_cmds(exp), "q", "" }, "\n")
end

-- Relaxed Evolver: a short g; u; V start, then u; V; hessian_seek until
-- hessian_seek moves no vertex by more than 1e-13 (at most 60 rounds).
local function relax_cmds(exp, n0)
  return table.concat({
    "define vertex attribute ox real", "define vertex attribute oy real",
    "define vertex attribute oz real", "quiet on",
    ("for ( inx := 1 ; inx <= %d ; inx += 1 ) { g; u; V; }"):format(n0),
    "cyc := 0", "mv := 1",
    "do { u; V; " .. save .. " hessian_seek; mv := " .. move ..
      "; cyc += 1; } while mv > 1e-13 && cyc < 60",
    'printf "R %.17g\\n", mv;',
    ('printf "ITERS %%d\\n", cyc + %d;'):format(n0),
    dump_cmds(exp), "q", "" }, "\n")
end

local function volume_error()
  local worst = 0
  for b in bodies() do
    if b.target then
      worst = math.max(worst, math.abs(b.volume - b.target) / math.abs(b.target))
    end
  end
  return worst
end

local function mean_edge()
  local s, n = 0, 0
  for e in edges() do s = s + e.length; n = n + 1 end
  return n > 0 and s / n or 0
end

local function fmt(x)
  if math.type(x) == "integer" then return tostring(x) end
  return ("%.6g"):format(x)
end

-- Where the curvature error c (curvature{}) sits: its RMS by the
-- vertices' valence and by their distance in edges from the border
-- (fixed vertices and vertices on constraints), with each group's share
-- of the sum of squares.
function C.breakdown(c)
  local nb, dist, queue = {}, {}, {}
  for e in edges() do
    local a, b = e.tail.id, e.head.id
    nb[a] = nb[a] or {}; nb[b] = nb[b] or {}
    nb[a][#nb[a] + 1] = b; nb[b][#nb[b] + 1] = a
  end
  for vv in vertices() do
    if vv.fixed or next(vv.constraints or {}) then
      dist[vv.id] = 0; queue[#queue + 1] = vv.id
    end
  end
  local head = 1
  while head <= #queue do
    local a = queue[head]; head = head + 1
    for _, b in ipairs(nb[a] or {}) do
      if not dist[b] then dist[b] = dist[a] + 1; queue[#queue + 1] = b end
    end
  end
  local groups, total = {}, 0
  local function add(key, e)
    local g = groups[key] or { n = 0, s = 0 }
    groups[key] = g
    g.n = g.n + 1; g.s = g.s + e * e
  end
  for vv in vertices() do
    local e = c.errors[vv.id]
    if e then
      local d = dist[vv.id] or 99
      add(("valence %d"):format(vv.valence), e)
      add(d <= 3 and ("ring %d"):format(d) or "ring 4+", e)
      total = total + e * e
    end
  end
  local keys = {}
  for k in pairs(groups) do keys[#keys + 1] = k end
  table.sort(keys)
  print("curvature error by group (ring: edges from the border):")
  for _, k in ipairs(keys) do
    local g = groups[k]
    print(("  %-10s %5d vertices  rms %.3e  share %5.1f%%"):format(k, g.n,
      math.sqrt(g.s / g.n), total > 0 and 100 * g.s / total or 0))
  end
end

function C.run(exp)
  if exp.model then exp.model() end
  local dump = env("PAPER_DUMP")
  local extra = {}
  local evres
  if dump then
    local t
    t, extra = read_dump(dump, exp)
    evres = t
    trimesh(t)
  else
    trimesh(exp.input())
  end
  local label = env("PAPER_LABEL") or (dump and "evolver" or "tds")
  if env("PAPER_FE") and not dump then
    write_fe(env("PAPER_FE"), { header = exp.fe_header })
  end
  local evdir = env("PAPER_EVOLVER")
  if evdir and not dump then
    local f = assert(io.open(evdir .. "/gloop.cmd", "w"))
    f:write(gloop_cmds(exp, exp.evolver_iterations or 1000)); f:close()
    f = assert(io.open(evdir .. "/relax.cmd", "w"))
    f:write(relax_cmds(exp, exp.evolver_start or 100)); f:close()
  end
  print(("== %s (%s): %d vertices, %d facets"):format(exp.name, label, vertex_count, facet_count))
  local res = { iterations = 0, r = 0, seconds = 0, vertices = 0 }
  if dump then
    res.iterations = tonumber(extra.ITERS) or 0
    res.r = tonumber(extra.R) or 0
    res.seconds = tonumber(env("PAPER_SECONDS") or 0)
    local n = 0
    for vv in vertices() do if not vv.fixed then n = n + 1 end end
    res.vertices = n
  else
    print("input:")
    quality()
    res = pg{ plain = env("PAPER_PLAIN") ~= nil, every = tonumber(env("PAPER_EVERY") or 500), depth = tonumber(env("PAPER_DEPTH") or ""), s = tonumber(env("PAPER_S") or ""), newton = env("PAPER_NEWTON") ~= "0", momentum = tonumber(env("PAPER_MOMENTUM") or ""), momentum_size = tonumber(env("PAPER_MOMENTUM_SIZE") or ""), max = tonumber(env("PAPER_MAX") or "") }
    if env("PAPER_POLISH") == "1" then
      -- the curvature polish (doc/method.md): r and the volumes are the
      -- polished mesh's; its plain s = 0 iterations are counted apart
      local p = pg_polish{ max_loss = tonumber(env("PAPER_POLISH_LOSS") or "") }
      res.polish_iterations = p.iterations
      res.polish_cpu = p.cpu_seconds
      res.r = p.r
    end
  end
  print("result:")
  local q = quality()
  local c = curvature{ target = exp.target }
  v()
  local h = mean_edge()
  local spvi = (res.iterations > 0 and res.vertices > 0)
               and res.seconds / (res.iterations * res.vertices) or 0
  local cpvi = (res.cpu_seconds and res.iterations > 0 and res.vertices > 0)
               and res.cpu_seconds / (res.iterations * res.vertices) or nil
  local out = {
    ("RESULT %s %s"):format(exp.name, label),
    "mean=" .. fmt(q.mean), "min=" .. fmt(q.min), "above50=" .. fmt(q.above50),
    "crms=" .. fmt(c.rms), "cmax=" .. fmt(c.max),
    "nrms=" .. fmt(c.normal.rms), "nmax=" .. fmt(c.normal.max), "verr=" .. fmt(volume_error()),
    "r=" .. fmt(res.r), "rrel=" .. fmt(h > 0 and res.r / h or 0),
    "iters=" .. fmt(res.iterations), "secs=" .. fmt(res.seconds),
    "spvi=" .. fmt(spvi), "nv=" .. fmt(res.vertices),
    "cpvi=" .. (cpvi and fmt(cpvi) or "-"),
    "energy=" .. fmt(total_energy),
  }
  if res.reached then out[#out + 1] = "reached=" .. fmt(res.reached) end
  if res.polish_iterations then
    out[#out + 1] = "polish_iters=" .. fmt(res.polish_iterations)
    out[#out + 1] = "polish_cpu=" .. fmt(res.polish_cpu)
  end
  if res.status then out[#out + 1] = "status=" .. res.status end
  if res.newton_builds then out[#out + 1] = "builds=" .. fmt(res.newton_builds) end
  print(table.concat(out, " "))
  if env("PAPER_ANALYSE") then C.breakdown(c) end
  return res, q, c
end

return C
