# The command line: errors name the place and set a nonzero exit status.
run() { "$TDS" "$@" 2>&1; echo "exit $?"; }
run bad_edge.tds
run bad_face.tds
run bad_attr.tds
run no_such_file.tds | sed 's/: No such file.*/: no such file/'
run --bogus | head -n 1
run -e 'print(1 + 1)'
run -e 'help()' | head -n 1
run -e 'error("boom")'
run -e 'q(3)'
run ../../scripts/cube.tds -e 'print(vertex_count, edge_count, facet_count, body_count)'
"$TDS" --help | head -n 1
# An error object whose __tostring raises: an error message, not a PANIC.
run -e 'error(setmetatable({}, {__tostring = function() error("x") end}))'
run -e 'error(setmetatable({}, {__tostring = function() return "custom" end}))'
run -e 'error({})'
