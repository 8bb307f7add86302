# Ctrl-C (SIGINT) during a long g: the step in progress finishes, the
# command stops with a message, the surface stays consistent, and at the
# prompt the session goes on with the next line.
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
# A script: the interruption ends it with status 1.
"$TDS" -q ../../scripts/cube.tds -e 'g(100000000)' > "$dir/out" 2>&1 &
pid=$!
sleep 1
kill -INT $pid
wait $pid
echo "script exit $?"
sed 's/[0-9][0-9]* of 100000000/N of 100000000/' "$dir/out"
# The prompt: the next line runs on the unchanged, consistent surface.
mkfifo "$dir/in"
"$TDS" -q -i ../../scripts/cube.tds < "$dir/in" > "$dir/out2" 2>&1 &
pid=$!
exec 3> "$dir/in"
echo 'g 100000000' >&3
sleep 1
kill -INT $pid
sleep 0.5
echo 'print(check(), vertex_count, body[1].volume > 0.999)' >&3
echo 'q' >&3
exec 3>&-
wait $pid
echo "prompt exit $?"
sed 's/[0-9][0-9]* of 100000000/N of 100000000/' "$dir/out2"
