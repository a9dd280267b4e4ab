#!/usr/bin/env bash
# The main job on the bundled sample: capture a recording into an archetype library, plant it on
# the bundled terrain, render the meadow as a picture and as five seconds of video. Called by
# `./meadow.sh demo` with the meadow binary.
#   samples/demo.sh MEADOW_BINARY [OUT_DIR]     (OUT_DIR defaults to out/demo)
set -euo pipefail
meadow=$1
here=$(cd "$(dirname "$0")" && pwd)
out=${2:-$(cd "$here/.." && pwd)/out/demo}
mkdir -p "$out"
recording=$here/recordings/quadratic-leaf

echo "1/2 capture: $recording -> $out/library.json (+ .glb)"
"$meadow" capture "$recording" --out "$out/library.json" --glb "$out/library.glb" --debug "$out/debug"

echo "2/3 render: samples/scenes/meadow.json with that library -> $out/render/"
"$meadow" render "$here/scenes/meadow.json" --library "$out/library.json" --out "$out/render" \
  --frames 1 --size 1280x720

echo "3/3 video: five seconds of the same meadow in the wind -> $out/meadow.mp4"
"$meadow" render "$here/scenes/meadow.json" --library "$out/library.json" --video "$out/meadow.mp4" \
  --frames 150 --size 640x360

echo "done: the meadow is $out/render/frame_00000.png, in motion $out/meadow.mp4"
