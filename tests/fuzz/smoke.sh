#!/bin/sh
# smoke.sh: run each libFuzzer harness for a bounded time on its seed
# corpus (make fuzz-smoke; part of CI). New inputs go to a scratch folder,
# never into tests/fuzz/corpus. A crash, sanitizer report, leak, timeout or
# out-of-memory fails the run; the input that did it is printed in base64
# (decode it with `base64 -d`) and kept under $FUZZ_OUT (default
# build-fuzz/smoke).
# Usage: smoke.sh BUILD_DIR SECONDS NAME...   (FUZZ_SEED: libFuzzer -seed)
set -u
build=$1 secs=$2
shift 2
out=${FUZZ_OUT:-$build/smoke}
here=$(dirname "$0")
status=0
for name in "$@"; do
  work=$out/$name
  rm -rf "$work"
  mkdir -p "$work/new" "$work/tmp"
  echo "fuzz-smoke: $name for ${secs}s"
  if TMPDIR=$work/tmp "$build/fuzz_$name" -seed="${FUZZ_SEED:-1}" \
      -max_total_time="$secs" -timeout=25 -rss_limit_mb=2048 -max_len=8192 \
      -dict="$here/$name.dict" -artifact_prefix="$work/" -print_final_stats=1 \
      "$work/new" "$here/corpus/$name" > "$work/log.txt" 2>&1; then
    grep -E '^(Done|stat::number_of_executed_units|#[0-9]+.*DONE)' "$work/log.txt" | tail -n 2
  else
    status=1
    echo "FAIL fuzz_$name: see $work/log.txt"
    grep -E 'ERROR|SUMMARY|invariant|runtime error' "$work/log.txt" | head -n 20
    for a in "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-*; do
      [ -f "$a" ] || continue
      echo "input $a (base64):"
      base64 "$a"
    done
  fi
done
exit $status
