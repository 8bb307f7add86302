# lib.sh: helpers for the Evolver comparison tests (sourced).
# EXAMPLES: evolver-doc's example datafiles; evolver_run FILE.fe CMDS runs
# evolver-nox-d headless on a copy of FILE.fe and prints its output.
EXAMPLES=${EXAMPLES:-/usr/share/doc/evolver/examples}
EVOLVER=${EVOLVER:-evolver-nox-d}
TDS=${TDS:-tds}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)

# With TDS_EVOLVER_CACHE set to a directory, outputs are kept there by a
# hash of the datafile and the commands, so the sanitizer run of the suite
# reuses the first run's Evolver results (Evolver is deterministic).
# Commands that write files (dump) always run.
evolver_run() {
  _key=""
  if [ -n "$TDS_EVOLVER_CACHE" ] && ! printf '%s' "$2" | grep -q dump; then
    mkdir -p "$TDS_EVOLVER_CACHE"
    _key=$TDS_EVOLVER_CACHE/$( (cat "$1"; printf '%s' "$2") | md5sum | cut -d' ' -f1)
    if [ -f "$_key" ]; then cat "$_key"; return; fi
  fi
  _d=$(mktemp -d)
  cp "$1" "$_d/in.fe"
  printf '%s\nq\n' "$2" > "$_d/cmds"
  (cd "$_d" && "$EVOLVER" -f cmds in.fe < /dev/null 2>&1) > "$_d/out"
  cat "$_d/out"
  [ -n "$_key" ] && cp "$_d/out" "$_key.tmp" && mv "$_key.tmp" "$_key"
  rm -rf "$_d"
}

# Lines "KEY v1 v2 ..." printed by the Evolver commands, as "v1 v2 ...".
grab() { grep "^$1 " | head -n 1 | cut -d' ' -f2-; }

# The two helpers below work in the caller's scratch directory $tmp.
# evolver_dump TEST NAME FE CMDS: Evolver runs CMDS on FE and dumps
# $tmp/NAME.dmp (a FAIL line for TEST/NAME when it did not).
evolver_dump() {
  cp "$3" "$tmp/in.fe"
  printf '%s\ndump "%s.dmp"\nq\n' "$4" "$2" > "$tmp/mk.cmd"
  (cd "$tmp" && $EVOLVER -f mk.cmd in.fe < /dev/null > /dev/null 2>&1)
  [ -s "$tmp/$2.dmp" ] || echo "FAIL $1/$2: Evolver did not dump"
}

# kcompare NAME FE TOL CMDS: CMDS (printing lines "K...") run on FE in
# Evolver and in tds; the K lines must agree (numcmp.lua: integers
# exactly, reals to TOL relative), reported as NAME.
kcompare() {
  evolver_run "$2" "$4" | grep '^K' > "$tmp/ev.k"
  printf '%s\n' "$4" > "$tmp/c.cmd"
  cp "$2" "$tmp/run.fe"
  (cd "$tmp" && "$TDS" -q run.fe -f c.cmd) > "$tmp/tds.out" 2>&1
  grep '^K' "$tmp/tds.out" > "$tmp/tds.k"
  "$TDS" -q -e "
dofile('$ROOT/tests/evolver/numcmp.lua')
numcmp('$1', lines_of('$tmp/ev.k', '^K'), lines_of('$tmp/tds.k', '^K'), $3)"
}
