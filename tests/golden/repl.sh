# A scripted session at the prompt: Lua first, Evolver habits second.
printf '%s\n' \
  'vertex_count' \
  'g 2' \
  'r; print(facet_count)' \
  'x = 3' \
  'x * 2' \
  'for i = 1, 2 do' \
  '  print("line", i)' \
  'end' \
  'angle := 1' \
  'print total_area > 0' \
  'body[1].target = 1.5' \
  'this is not lua' \
  'vertex[999]' \
  'v' \
  'q' \
  'print("not reached")' | "$TDS" -q -i ../../scripts/cube.tds 2>&1
echo "exit $?"
