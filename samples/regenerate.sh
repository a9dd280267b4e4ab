#!/usr/bin/env bash
# Rebuilds the committed synthetic recordings under samples/recordings/ with the exact commands
# that made them (tests/cli/synth_cli_test.cpp checks one stays identical).
#   samples/regenerate.sh [MEADOW_BINARY]    (defaults to build/default/cli/meadow)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
meadow=${1:-$here/../build/default/cli/meadow}
out=$here/recordings

"$meadow" synth --preset quadratic-leaf --frames 3 --seed 1 --out "$out/quadratic-leaf"
"$meadow" synth --preset slim-grass --frames 3 --seed 1 --out "$out/slim-grass"
"$meadow" synth --preset wind --frames 8 --seed 1 --out "$out/wind"
