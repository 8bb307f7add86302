# show() with open = true (the default) runs xdg-open on the page's
# address when xdg-open is on PATH, and only prints it when it is not.
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkdir "$dir/bin" "$dir/empty"
cat > "$dir/bin/xdg-open" <<EOS
#!/bin/sh
echo "\$@" > "$dir/opened"
EOS
chmod +x "$dir/bin/xdg-open"
PATH="$dir/bin:$PATH" "$TDS" -q ../../scripts/cube.tds -e 'show(); print((tds.live_port())); show(false)' > "$dir/out" 2>&1
port=$(sed -n 2p "$dir/out")
sed "s/$port/PORT/g" "$dir/out"
for i in 1 2 3 4 5 6 7 8 9 10; do [ -s "$dir/opened" ] && break; sleep 0.2; done
echo "xdg-open got: $(sed "s/$port/PORT/g" "$dir/opened")"
# No xdg-open: the address only. (sh must be found: call tds directly.)
PATH="$dir/empty" "$TDS" -q ../../scripts/cube.tds -e 'show{ port = 0 }; show{ stop = true }' 2>&1 |
  sed 's/127\.0\.0\.1:[0-9]*/127.0.0.1:PORT/'
