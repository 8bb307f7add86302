#!/bin/sh
# deps.sh: install the Debian packages tds needs.
# Quiet and fast when everything is present; installs what is missing
# (needs root, as on CI).
# Usage: scripts/deps.sh [build|test] [--check]
#   build: what `make` needs to build the program (the default)
#   test:  also what the tests and benchmarks compare against
set -e
# The program: Lua, readline, libmicrohttpd (the live view's server),
# cairo and a font (pictures); MUMPS (sequential), CHOLMOD (SuiteSparse:
# Cholesky of definite systems) and LAPACK (hessian, eigenvalues:
# src/la_mumps.c, src/la_chol.c, src/newton*.c); OpenBLAS (single-threaded),
# which becomes the system's libblas.so.3 and liblapack.so.3: MUMPS's
# factorisation runs twice as fast on it as on the reference BLAS.
BUILD_PKGS="gcc make pkg-config liblua5.4-dev libreadline-dev libmicrohttpd-dev
  libcairo2-dev fonts-dejavu-core libmumps-seq-dev libsuitesparse-dev liblapack-dev
  libopenblas0-serial"
# The tests: Surface Evolver; meshio, VTK and NumPy for /usr/bin/python3
# (export round trips, tests/export); Chromium (the live view's browser
# test, tests/web); the stock Lua interpreter (the module tds.so, tests/module).
TEST_PKGS="evolver-nox evolver-doc python3-meshio python3-vtk9 python3-numpy
  chromium chromium-driver lua5.4"
# The fuzzers (make fuzz, make fuzz-smoke): clang with libFuzzer and OpenMP.
FUZZ_PKGS="clang libclang-rt-14-dev libomp-14-dev llvm-14"

what=build
check=""
for a in "$@"; do
  case $a in
    build|test|fuzz) what=$a ;;
    --check) check=1 ;;
    *) echo "deps.sh: unknown argument '$a' (use build, test, fuzz, --check)" >&2; exit 2 ;;
  esac
done
PKGS=$BUILD_PKGS
[ "$what" = test ] && PKGS="$BUILD_PKGS $TEST_PKGS"
[ "$what" = fuzz ] && PKGS="$BUILD_PKGS $FUZZ_PKGS"

missing=""
for p in $PKGS; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $p"
  fi
done
# The live view's page is built with npm (three.js); the machine's own
# Node.js may come with npm, else Debian's packages provide both.
command -v npm >/dev/null 2>&1 || missing="$missing nodejs npm"
[ -z "$missing" ] && exit 0
if [ -n "$check" ]; then
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
