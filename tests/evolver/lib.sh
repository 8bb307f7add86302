# lib.sh: helpers for the Evolver comparison tests (sourced).
# EXAMPLES: evolver-doc's example datafiles; evolver_run FILE.fe CMDS runs
# evolver-nox-d headless on a copy of FILE.fe and prints its output.
EXAMPLES=${EXAMPLES:-/usr/share/doc/evolver/examples}
EVOLVER=${EVOLVER:-evolver-nox-d}
TDS=${TDS:-tds}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)

evolver_run() {
  _d=$(mktemp -d)
  cp "$1" "$_d/in.fe"
  printf '%s\nq\n' "$2" > "$_d/cmds"
  (cd "$_d" && "$EVOLVER" -f cmds in.fe < /dev/null 2>&1)
  rm -rf "$_d"
}

# Lines "KEY v1 v2 ..." printed by the Evolver commands, as "v1 v2 ...".
grab() { grep "^$1 " | head -n 1 | cut -d' ' -f2-; }
