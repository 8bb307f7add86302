#!/bin/sh
# deps.sh: install the Debian packages tds needs to build and test.
# Quiet and fast when everything is present; installs what is missing
# (needs root, as on CI). Usage: scripts/deps.sh [--check]
set -e
PKGS="gcc make pkg-config liblua5.4-dev libreadline-dev evolver-nox evolver-doc clang libclang-rt-14-dev libomp-14-dev llvm-14"

missing=""
for p in $PKGS; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $p"
  fi
done
[ -z "$missing" ] && exit 0
if [ "$1" = "--check" ]; then
  echo "missing Debian packages:$missing" >&2
  exit 1
fi
echo "deps: installing$missing" >&2
SUDO=""
[ "$(id -u)" = 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
# shellcheck disable=SC2086
$SUDO apt-get install -y -qq $missing >/dev/null
