#!/bin/sh
# run.sh: run tests/module/NAME.lua in the stock Lua interpreter (lua5.4)
# with the module BUILD_DIR/tds.so (`require "tds"`), and print
# "PASS module/NAME" or "FAIL module/NAME: why". Usage: run.sh BUILD_DIR NAME
# A module built with the sanitizers (make test-asan) needs their runtimes
# loaded first into the interpreter, which is not built with them.
build=$1
name=$2
cd "$(dirname "$0")" || exit 1
if ! command -v lua5.4 > /dev/null; then
  echo "FAIL module/$name: lua5.4 is not installed (scripts/deps.sh test)"
  exit 0
fi
pre=""
if ldd "$build/tds.so" 2> /dev/null | grep -q libasan; then
  for lib in libasan.so libubsan.so; do
    pre="$pre $(${CC:-cc} -print-file-name=$lib)"
  done
fi
log=$(mktemp)
if LD_PRELOAD="$pre" LUA_CPATH_5_4="$build/?.so" lua5.4 "$name.lua" > "$log" 2>&1; then
  echo "PASS module/$name"
else
  echo "FAIL module/$name: $(tail -n 4 "$log" | tr '\n' ' ')"
fi
rm -f "$log"
