#!/usr/bin/env bash
# Regenerates every table and chart under docs/measurements: accuracy against the simulated
# sensor's truth (meadow_accuracy_tradeoff_bench), the sensor models against a real recording
# (meadow_sensor_calibration_bench), capture on real scanned plants (meadow_plant_bench), the
# capture front end's speed (meadow_segmentation_bench), the runtime passes
# (meadow_runtime_bench), whole rendered frames (meadow_frame_bench) and the large tiled prairie
# beside the per-blade meadow (meadow_prairie_bench, group large). Run through
# `./meadow.sh measure [--quick] [--out DIR] [--only GROUPS]`, which builds first; --quick is a
# smoke run (fewer presets, seeds, repetitions and frames, short timings).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=$root/build/default/tests
out=$root/docs/measurements
quick=0
only=""
usage="usage: meadow.sh measure [--quick] [--out DIR] [--only accuracy|sensors|plants|speed|large,...]"
while (($#)); do
  case $1 in
    --quick) quick=1 ;;
    --out) out=$2; shift ;;
    --only) only=,$2,; shift ;;
    *) echo "$usage" >&2; exit 2 ;;
  esac
  shift
done
# --only GROUPS: regenerate those groups' tables (and the index), leave the others as they are.
wanted() { [ -z "$only" ] || [[ $only == *,$1,* ]]; }
for group in ${only//,/ }; do
  case $group in accuracy|sensors|plants|speed|large) ;; *) echo "$usage" >&2; exit 2 ;; esac
done
mkdir -p "$out"
out=$(cd "$out" && pwd)

commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
git -C "$root" diff --quiet HEAD 2>/dev/null || commit="$commit with uncommitted changes"
cpu=$(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -1)
made="commit $commit on $(date -u +%F), $(nproc) cores ($cpu)"
((quick)) && made="$made, --quick"

export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
step() { echo "meadow measure: $*"; }

if wanted accuracy; then
  step "accuracy tables (simulated sensor's truth)"
  accuracy=(--out "$out" --made "$made")
  ((quick)) && accuracy+=(--quick)
  "$bin/meadow_accuracy_tradeoff_bench" "${accuracy[@]}" > "$out/.accuracy.log"
fi

if wanted sensors; then
  step "simulated sensors against the real Kinect recording"
  "$bin/meadow_sensor_calibration_bench" --out "$out" --made "$made" > "$out/.sensors.log"
fi

if wanted plants; then
  step "real plants: capture against the truth, beside a plain leaf counter"
  # The smoke run's four views go to their own folder, not over the full set's twelve.
  plants=(--out "$out" --made "$made" --set "$root/build/plant-bench")
  ((quick)) && plants=(--out "$out" --made "$made" --set "$root/build/plant-bench-quick" --quick)
  "$bin/meadow_plant_bench" "${plants[@]}" > "$out/.plants.log"
fi

# speed BENCH TABLE TITLE [extra Google Benchmark flags]: TABLE.md and .csv, and the raw .json.
speed() {
  local bench=$1 table=$2 title=$3
  shift 3
  local flags=(--benchmark_out="$out/$table.json" --benchmark_out_format=json "$@")
  ((quick)) && flags+=(--benchmark_min_time=0.01)
  step "$title"
  "$bin/$bench" "${flags[@]}" > /dev/null
  "$bin/meadow_bench_table" "$out/$table.json" "$title" "$made" "$out/$table.md" "$out/$table.csv"
}
if wanted speed; then
  speed meadow_segmentation_bench segmentation_speed \
    "Capture front end at 640x480 on one core, whole and per stage (meadow_segmentation_bench)"
  speed meadow_runtime_bench runtime_passes \
    "Physics and culling per blade: CPU reference and GPU pass (meadow_runtime_bench)"
  frames=(--benchmark_counters_tabular=true)
  ((quick)) && frames+=(--benchmark_filter='blades:10000/')
  speed meadow_frame_bench frame_bench \
    "Whole rendered frames, 640x360, 4x MSAA, over blade counts (meadow_frame_bench)" "${frames[@]}"
fi
if wanted large; then
  step "large meadows: the tiled prairie beside the per-blade meadow, frames and memory"
  large=(--out "$out" --made "$made")
  ((quick)) && large+=(--quick)
  "$bin/meadow_prairie_bench" "${large[@]}" > "$out/.large.log"
fi
rm -f "$out/.accuracy.log" "$out/.sensors.log" "$out/.plants.log" "$out/.large.log"

# What each table holds, for the index.
describe() {
  case $1 in
    segmentation_accuracy) echo "every preset x sensor noise: blade recall, precision, median IoU, flags raised" ;;
    segmentation_distance) echo "blade-type presets x camera distance: where segmentation works" ;;
    segmentation_fusion) echo "fused frames of a still tuft, by median and nearest recurring reading; with a perfect partition and a pixel's tolerance" ;;
    segmentation_missed) echo "what the sensor leaves of the missed blades, and the recall bound that follows" ;;
    segmentation_ablation) echo "recall and IoU with one sensor noise term off at a time" ;;
    capture_tradeoff) echo "median IoU against segmentation time: fusion, contour sigma, plane fit (+ chart)" ;;
    segmentation_speed) echo "the capture front end's time per frame, whole and per stage" ;;
    modeling_accuracy) echo "blade-type presets x noise x distance: spine, tip, height and width errors of one view" ;;
    modeling_tradeoff) echo "spine error against capture time: refined knots, fused frames, tolerance (+ charts)" ;;
    modeling_groups) echo "one archetype per blade fitted over 1-8 fused groups against one per group (+ chart)" ;;
    fig12) echo "Fan & Sheng's Fig. 12 on captured skeletons: refiners against knot count (+ chart)" ;;
    tracks_fusion) echo "tracked tips from capture's groups against one fused group of 12 frames" ;;
    tip_reach) echo "how far the readings reach toward each true tip, and where unextended tips stop" ;;
    motion_calibration) echo "the motion test on every preset and on gentler winds" ;;
    runtime_passes) echo "physics and culling per blade, CPU reference and GPU pass" ;;
    frame_bench) echo "whole rendered frames over blade counts: all on, no collisions, no culling" ;;
    plant_benchmark) echo "capture on real maize shoots x 12 views x 3 sensors against the truth, beside a plain leaf counter and the partition's two bounds (leaves carried to their true base, and as seen); what one library over all the views holds; the turntable registered and joined (--turntable); stem height error; time per frame, and of finding the plant and the partition" ;;
    large_meadow) echo "the tiled 1 km prairie beside the per-blade meadow: frame and stage times, blades drawn and planted, tiles" ;;
    large_meadow_memory) echo "the same runs' GPU bytes, bytes per planted and drawn blade, peak resident memory" ;;
    sensor_calibration) echo "the simulated sensors' noise figures against the real Kinect recording" ;;
    *) echo "" ;;
  esac
}

step "index"
{
  echo "# Measurements"
  echo
  echo "Generated by \`./meadow.sh measure\` ($made); never edited by hand. Each table has a CSV"
  echo "beside it; the speed tables also keep Google Benchmark's raw JSON."
  echo
  echo "| table | what it measures |"
  echo "|---|---|"
  for md in "$out"/*.md; do
    name=$(basename "$md" .md)
    [ "$name" = README ] && continue
    echo "| [$name]($name.md) | $(describe "$name") |"
  done
} > "$out/README.md.tmp"
mv "$out/README.md.tmp" "$out/README.md"
step "done: $out"
