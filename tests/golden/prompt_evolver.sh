# The prompt with Evolver lines (issue 9): the first tutorial commands,
# the rule for lines that are both Lua and Evolver, the mode switches,
# multi-line Evolver input, and errors that leave the session running
# (a bare name that names nothing is Evolver's error, not Lua's nil).
printf '%s\n' \
  'gogo' \
  'print 2^3^2' \
  'print(2^3^2)' \
  'print sqrt(2)' \
  'G -5' \
  'print gravity_constant' \
  'G 0' \
  'set body[1] target 2' \
  'print body[1].target' \
  'foreach vertex vv where z > 0.9 and x < 0.1 do printf "%d\n", vv.id' \
  'mine := {' \
  '  printf "%d facets\n", facet_count }' \
  'mine' \
  'mine()' \
  'C' \
  'hessian_menu' \
  'r := 5' \
  '.evolver' \
  'print 1 < 2 < 3' \
  '.lua' \
  'print(1 < 2)' \
  '.auto' \
  '.evolver print 7 idiv 2' \
  '.lua print(7 // 2)' \
  'g 1 // comment' \
  'g2' \
  'print iteration_counter' \
  'x = 5' \
  'x' \
  'nosuchthing' \
  'print "still here"' | "$TDS" -q -i ../../scripts/cube.tds 2>&1
echo "exit $?"
# The tutorial's first commands on the datafiles themselves.
printf '%s\n' 're' 'g 5' 'printf "%d %d %d\n", vertex_count, edge_count, facet_count' 'gogo' |
  "$TDS" -q -i /usr/share/doc/evolver/examples/mound.fe 2>&1
echo "exit $?"
printf '%s\n' 'gogo' 'print vertex_count' | "$TDS" -q -i /usr/share/doc/evolver/examples/cube.fe 2>&1
echo "exit $?"
