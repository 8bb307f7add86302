-- lib.lua: for the export round-trip tests (run.sh). export_all(name)
-- writes the current surface in every format and variant into
-- $EXPORT_DIR, and name.json with the values tds itself reports (vertex
-- positions and curvatures through v.x, v.mean_curvature,
-- v.gauss_curvature; facet area, min_angle, tension, colour, bodies;
-- body volumes; the positions recorded at mark()) for check.py.
local dir = assert(os.getenv("EXPORT_DIR"), "EXPORT_DIR is not set")

local marked = {}
-- test_mark(): mark() and remember the positions as tds reports them.
function test_mark()
  mark()
  marked = {}
  for v in vertices() do marked[v.id] = { v.x, v.y, v.z } end
end

local function num(x)
  if x == nil or x ~= x then return "null" end
  return ("%.17g"):format(x)
end

local VF = { "position", "normal", "mean_curvature", "gauss_curvature", "displacement", "id" }
local FF = { "min_angle", "area", "tension", "color", "frontbody", "backbody", "id" }

local function reference(path, selected)
  local out = assert(io.open(path, "w"))
  local parts = {}
  for v in vertices() do
    local m = marked[v.id]
    parts[#parts + 1] = ("[%d,%s,%s,%s,%s,%s,%s,%s,%s,%d]"):format(v.id, num(v.x), num(v.y),
      num(v.z), num(v.mean_curvature), num(v.gauss_curvature), num(m and m[1]),
      num(m and m[2]), num(m and m[3]), v.fixed and 1 or 0)
  end
  out:write('{"vertices": [', table.concat(parts, ",\n"), "],\n")
  parts = {}
  for f in facets() do
    local vs = f.vertices
    parts[#parts + 1] = ("[%d,%d,%d,%d,%s,%s,%s,%d,%d,%d,%d]"):format(f.id, vs[1].id,
      vs[2].id, vs[3].id, num(f.area), num(f.min_angle), num(f.tension), f.color,
      f.frontbody and f.frontbody.id or 0, f.backbody and f.backbody.id or 0,
      (selected == nil or selected(f)) and 1 or 0)
  end
  out:write('"facets": [', table.concat(parts, ",\n"), "],\n")
  parts = {}
  for b in bodies() do parts[#parts + 1] = ("[%d,%s]"):format(b.id, num(b.volume)) end
  out:write('"bodies": [', table.concat(parts, ","), "]}\n")
  out:close()
end

-- export_all(name [, select]): select(f) chooses the facets of the
-- per-body files ("cut" shells closed by caps); the other files hold all.
function export_all(name, select)
  local p = dir .. "/" .. name
  tds.totals() -- current body volumes
  reference(p .. ".json", select)
  local all = { vertex_fields = VF, facet_fields = FF }
  local function with(t)
    local o = { vertex_fields = VF, facet_fields = FF }
    for k, v in pairs(t) do o[k] = v end
    return o
  end
  export(p .. ".obj")
  export(p .. ".off")
  export(p .. "_ascii.stl", { encoding = "ascii" })
  export(p .. "_binary.stl")
  export(p .. "_ascii.ply", with { encoding = "ascii" })
  export(p .. "_binary.ply", all)
  export(p .. "_vonly.ply", { vertex_fields = VF })
  export(p .. "_ascii.vtu", with { encoding = "ascii" })
  export(p .. "_base64.vtu", with { encoding = "base64" })
  export(p .. "_b64app.vtu", with { encoding = "base64", appended = true })
  export(p .. "_binary.vtu", all)
  -- ASCII legacy VTK cannot hold NaN: only fields defined everywhere
  export(p .. "_ascii.vtk", { encoding = "ascii", facet_fields = FF,
                              vertex_fields = { "position", "normal", "id" } })
  export(p .. "_binary.vtk", all)
  export(p .. "_22ascii.msh", { version = "2.2", encoding = "ascii" })
  export(p .. "_22binary.msh", { version = "2.2" })
  export(p .. "_41ascii.msh", { version = "4.1", encoding = "ascii" })
  export(p .. "_41binary.msh", { version = 4.1, encoding = "binary" })
  -- the format option overrides the extension
  export(p .. "_asply.dat", { format = "ply", encoding = "ascii" })
  if body_count > 0 then
    local o = { per_body = true, facets = select }
    local files = export(p .. "_pb.stl", o)
    assert(#files == body_count, "one file per body")
    export(p .. "_pba.stl", { per_body = true, facets = select, encoding = "ascii" })
    export(p .. "_pb.ply", { per_body = true, facets = select, encoding = "ascii",
                             facet_fields = FF })
  end
end
