#!/bin/sh
# coverage.sh: line and region coverage of the source files each harness
# targets, from running it once over a corpus (make fuzz-cov). The
# harnesses must be built with -fprofile-instr-generate -fcoverage-mapping
# (the fuzz-cov target does that in build-fuzzcov/).
# Usage: coverage.sh BUILD_DIR NAME...   (FUZZ_CORPUS: folder holding one
# folder per harness, with the inputs or, as campaign.sh leaves them, a
# corpus/ folder of them; default tests/fuzz/corpus)
set -eu
build=$1
shift
corpora=${FUZZ_CORPUS:-$(dirname "$0")/corpus}
for name in "$@"; do
  case $name in
    fe) files="src/datafile*.c src/dump.c" ;;
    tds) files="src/lua_*.c src/datafile*.c src/iterate.c src/topo_*.c src/pg*.c" ;;
    expr) files="src/expr_*.c" ;;
    *) files="src/*.c" ;;
  esac
  dir=$corpora/$name
  [ -d "$dir/corpus" ] && dir=$dir/corpus # a campaign.sh output folder
  rm -rf "$build/prof-$name"
  mkdir -p "$build/prof-$name"
  # One process per input, so an input that crashes loses only its own
  # profile (a crash stops the profile from being written).
  failed=0
  for f in "$dir"/*; do
    LLVM_PROFILE_FILE=$build/prof-$name/%p.profraw TMPDIR=${TMPDIR:-/tmp} \
      "$build/fuzz_$name" -timeout=60 -rss_limit_mb=4096 "$f" > /dev/null 2>&1 ||
      failed=$((failed + 1))
  done
  llvm-profdata-14 merge -sparse -o "$build/$name.profdata" "$build/prof-$name"/*.profraw
  echo "== fuzz_$name on $dir: $(ls "$dir" | wc -l) inputs, $failed failing"
  echo "file regions lines branches (percent covered)"
  # shellcheck disable=SC2086
  llvm-cov-14 report "$build/fuzz_$name" -instr-profile="$build/$name.profdata" $files |
    awk '$1 ~ /\.c$|^TOTAL$/ { n = split($1, p, "/"); print p[n], $4, $10, $13 }'
done
