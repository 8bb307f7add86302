#!/bin/sh
# campaign.sh: a long libFuzzer campaign of one harness that keeps going
# after a finding. Each finding (crash, timeout, out-of-memory) is kept in
# OUT/artifacts/ and the fuzzer restarts on the grown corpus OUT/corpus
# (seeded from tests/fuzz/corpus/NAME) until SECONDS have passed. At the
# end it prints the total executions and the number of findings.
# Usage: campaign.sh BUILD_DIR NAME SECONDS OUT [extra libFuzzer flags]
# Example: nice sh tests/fuzz/campaign.sh build-fuzz fe 1800 /tmp/camp-fe &
set -u
build=$1 name=$2 secs=$3 out=$4
shift 4
here=$(cd "$(dirname "$0")" && pwd)
bin=$(cd "$build" && pwd)/fuzz_$name
mkdir -p "$out/corpus" "$out/artifacts" "$out/tmp"
[ -n "$(ls "$out/corpus")" ] || cp "$here/corpus/$name"/* "$out/corpus/"
start=$(date +%s)
round=0
while :; do
  left=$((start + secs - $(date +%s)))
  [ "$left" -gt 5 ] || break
  round=$((round + 1))
  TMPDIR=$out/tmp "$bin" -max_total_time="$left" -timeout=30 -rss_limit_mb=2048 \
    -max_len=8192 -dict="$here/$name.dict" -artifact_prefix="$out/artifacts/" \
    -print_final_stats=1 "$@" "$out/corpus" > "$out/round$round.log" 2>&1
  echo "round $round: exit $? after $(($(date +%s) - start)) s" >> "$out/rounds.txt"
done
execs=$(cat "$out"/round*.log | sed -n 's/^stat::number_of_executed_units: *//p' |
        awk '{s += $1} END {print s + 0}')
echo "fuzz_$name: $round rounds, $execs executions in $(($(date +%s) - start)) s," \
     "$(ls "$out/artifacts" | wc -l) findings in $out/artifacts," \
     "corpus $(ls "$out/corpus" | wc -l) inputs" | tee "$out/summary.txt"
