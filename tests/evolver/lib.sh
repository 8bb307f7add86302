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
