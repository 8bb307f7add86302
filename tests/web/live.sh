#!/bin/sh
# live.sh: the live view in headless Chromium (tests/web/live.mjs; needs
# `make web`, which `make test` runs). Bounded: live.mjs stops itself
# after 240 s; timeout is the backstop.
cd "$(dirname "$0")/../.." || exit 1
timeout -k 10 300 node tests/web/live.mjs "$TDS"
