#!/bin/sh
# docs.sh: every ```lua block in README.md and doc/*.md must run: each is
# saved to a file and run with $TDS from the project root, and the output
# it shows (`print(...)  --> value`) must be what it prints (the rules are
# in tests/doccheck.lua). Blocks that are not meant to run are fenced as
# ```text.
cd "$(dirname "$0")/.." || exit 1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for md in README.md doc/*.md; do
  awk -v dir="$dir" -v base="$(echo "$md" | tr '/.' '__')" '
    /^```lua[ \t]*$/ { n++; f = sprintf("%s/%s_%d.lua", dir, base, n); inb = 1; next }
    /^```/ { inb = 0; next }
    inb { print > f }' "$md"
done
for f in "$dir"/*.lua; do
  [ -f "$f" ] || continue
  name=$(basename "$f" .lua)
  if "$TDS" -q "$f" > "$dir/out" 2>&1; then
    why=$("$TDS" -q -e "local ok, why = dofile('tests/doccheck.lua')('$f', '$dir/out')
if not ok then print(why) end" 2>&1)
    if [ -z "$why" ]; then
      echo "PASS doc/$name"
    else
      echo "FAIL doc/$name: $why"
    fi
  else
    echo "FAIL doc/$name: $(tail -n 2 "$dir/out" | tr '\n' ' ')"
  fi
done
missing=$(DOCS="README.md $(echo doc/*.md)" "$TDS" -q tests/doccover.lua 2>&1)
if [ -z "$missing" ]; then
  echo "PASS doc/coverage"
else
  echo "FAIL doc/coverage: undocumented: $(echo $missing)"
fi
