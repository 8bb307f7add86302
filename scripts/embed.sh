#!/bin/sh
# embed.sh: turn lua/*.lua into C data for the binary.
# Output: one byte array per file and a table { name, data, size }, where
# name is the module name (file name without .lua). Usage: embed.sh FILES...
set -e
n=0
for f in "$@"; do
  echo "static const unsigned char lua_src_$n[] = {"
  od -An -v -tx1 "$f" | sed 's/ *\([0-9a-f][0-9a-f]\)/0x\1,/g'
  echo "};"
  n=$((n + 1))
done
echo "static const struct { const char *name; const unsigned char *data; size_t size; } lua_sources[] = {"
n=0
for f in "$@"; do
  name=$(basename "$f" .lua)
  echo "  {\"$name\", lua_src_$n, sizeof lua_src_$n},"
  n=$((n + 1))
done
echo "  {0, 0, 0}"
echo "};"
