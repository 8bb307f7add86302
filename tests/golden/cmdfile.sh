# Evolver command files: tds FILE -f CMDS and tds -f CMDS FILE, mixed with
# -e in the given order; an error names CMDS:LINE, abandons the rest of
# that file (what follows still runs) and gives exit status 1 at the end;
# quit N exits with N.
run() { "$TDS" "$@" 2>&1; echo "exit $?"; }
run -q ../../scripts/cube.tds -f cmdfiles/ok.cmd
run -q -f cmdfiles/ok.cmd ../../scripts/cube.tds -e 'print(gogo ~= nil)'
run -q ../../scripts/cube.tds -f cmdfiles/bad.cmd -e 'print("runs after the error; exit 1 at the end")'
run -q ../../scripts/cube.tds -f cmdfiles/quit.cmd
run -q ../../scripts/cube.tds -f cmdfiles/missing.cmd
run -q ../../scripts/cube.tds -f 2>&1 | head -n 1
# A Lua script piped in runs as one chunk with its line numbers.
printf 'local n = 2\nprint(n + 1)\nerror("line three")\n' | "$TDS" 2>&1; echo "exit $?"
printf 'print("dash")\n' | "$TDS" - 2>&1; echo "exit $?"
