#!/usr/bin/env bash
# The main job on the bundled sample: capture a recording into an archetype library, plant it on
# the bundled terrain, render the meadow as a picture and as five seconds of video, then the
# captured grass as a prairie of 10^8 blades from a close-up to the horizon. Called by
# `./meadow.sh demo` with the meadow binary.
#   samples/demo.sh MEADOW_BINARY [OUT_DIR]     (OUT_DIR defaults to out/demo)
set -euo pipefail
meadow=$1
here=$(cd "$(dirname "$0")" && pwd)
out=${2:-$(cd "$here/.." && pwd)/out/demo}
mkdir -p "$out"
recording=$here/recordings/quadratic-leaf

echo "1/4 capture: $recording -> $out/library.json (+ .glb)"
"$meadow" capture "$recording" --out "$out/library.json" --glb "$out/library.glb" --debug "$out/debug"

echo "2/4 render: samples/scenes/meadow.json with that library -> $out/render/"
"$meadow" render "$here/scenes/meadow.json" --library "$out/library.json" --out "$out/render" \
  --frames 1 --size 1280x720

echo "3/4 video: five seconds of the same meadow in the wind -> $out/meadow.mp4"
"$meadow" render "$here/scenes/meadow.json" --library "$out/library.json" --video "$out/meadow.mp4" \
  --frames 150 --size 640x360

echo "4/4 prairie: samples/prairie/prairie.json with that library, close-up to horizon -> $out/prairie.mp4"
"$meadow" render "$here/prairie/prairie.json" --library "$out/library.json" --video "$out/prairie.mp4" \
  --frames 180 --size 640x360

echo "done: the meadow is $out/render/frame_00000.png, in motion $out/meadow.mp4, the prairie $out/prairie.mp4"
