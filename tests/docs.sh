#!/bin/sh
# docs.sh: every ```lua block in README.md and doc/*.md must run: each is
# saved to a file and run with $TDS from the project root. Blocks that
# are not meant to run are fenced as ```text.
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
    echo "PASS doc/$name"
  else
    echo "FAIL doc/$name: $(tail -n 2 "$dir/out" | tr '\n' ' ')"
  fi
done
