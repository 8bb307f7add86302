# Ctrl-C (SIGINT) stops a long command on a tds.new() surface too, not only
# on the program's own surface (it used to run to its end).
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cat > "$dir/run.tds" <<'LUA'
local s = tds.new{ quiet = true }
s.dofile("../../scripts/cube.tds")
s.g(100000000)
LUA
"$TDS" -q "$dir/run.tds" > "$dir/out" 2>&1 &
pid=$!
sleep 1
kill -INT $pid
wait $pid
echo "script exit $?"
sed -e "s|$dir/||" -e 's/[0-9][0-9]* of 100000000/N of 100000000/' "$dir/out"
