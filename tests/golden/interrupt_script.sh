# Ctrl-C in script mode stops the running command and then the script, even
# when the script catches the error with pcall; with --on-interrupt dump the
# surface so far is saved first (also on SIGTERM), and it loads back whole.
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cat > "$dir/long.tds" <<'LUA'
dofile("../../scripts/cube.tds")
r()
print("pcall:", pcall(g, 100000000))
print("the script went on after the interruption")
LUA
stop() { # stop SIGNAL ARGS...: run tds, send SIGNAL after a second
  sig=$1
  shift
  "$TDS" -q "$@" > "$dir/out" 2>&1 &
  pid=$!
  sleep 2
  kill -"$sig" $pid
  wait $pid
  echo "exit $?"
  sed -e "s|$dir/||" -e 's/[0-9][0-9]* of 100000000/N of 100000000/' "$dir/out"
}
stop INT "$dir/long.tds"
stop INT --on-interrupt dump "$dir/long.tds"
"$TDS" -q "$dir/long.dmp" -e 'print(vertex_count, facet_count, check(), near(body[1].volume, 1, 1e-9), total_energy < 6)'
stop TERM --on-interrupt=dump="$dir/saved.fe" ../../scripts/cube.tds -e 'g(100000000)'
"$TDS" -q "$dir/saved.fe" -e 'print(vertex_count, facet_count, check(), near(body[1].volume, 1, 1e-9), total_energy < 6)'
