#!/bin/sh
# pictures.sh: time of `snapshot` on the cube refined 6 times (98,304
# facets), 800 x 600, for each colouring and with edges. Prints processor
# seconds per picture (best of 3; the PNG encoding included).
# Usage: bench/pictures.sh [TDS_BINARY]
TDS=${1:-./tds}
here=$(cd "$(dirname "$0")/.." && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$TDS" -q "$here/scripts/cube.tds" -e "
for i = 1, 6 do r() end
local function best(o)
  local b = math.huge
  for _ = 1, 3 do
    local t0 = os.clock()
    snapshot('$dir/p.png', o)
    b = math.min(b, os.clock() - t0)
  end
  return b
end
print(('snapshot of %d facets, 800 x 600:'):format(facet_count))
for _, c in ipairs { 'none', 'mean_curvature', 'min_angle', 'body' } do
  print(('  color = %-16s %.3f s'):format(c, best { color = c }))
end
print(('  edges = true           %.3f s'):format(best { color = 'none', edges = true }))
print(('  smooth = true          %.3f s'):format(best { color = 'mean_curvature', smooth = true }))"
