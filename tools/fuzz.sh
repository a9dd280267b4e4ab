#!/usr/bin/env bash
# Runs every libFuzzer target of tests/fuzz for SECONDS each (default 60) and reports, per target,
# the inputs it executed and the crashes it found. Run through `./meadow.sh fuzz [SECONDS]`, which
# builds the `fuzz` preset first. Corpora grow in build/fuzz/corpus/<target>; a crash's input is
# kept as build/fuzz/crashes/<target>-crash-<hash> (rerun a target on it to see the report).
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
bin=$root/build/fuzz/tests/fuzz
work=$root/build/fuzz
samples=$root/samples
mkdir -p "$work/crashes"

seeds_of() {
  case $1 in
    recording_json) echo "$samples"/recordings/*/recording.json ;;
    depth_png) echo "$samples/recordings/quadratic-leaf/depth/000000.png" ;;
    archetype_library) echo "$root/tests/fuzz/seeds/library.json" ;;
    scene) echo "$samples/scenes/meadow.json" ;;
    glb) echo "$samples/scenes/terrain.glb" ;;
    synth_truth) echo "$samples/recordings/quadratic-leaf/truth/blades.json" ;;
  esac
}

failed=0
printf '%-20s %12s %8s\n' target executions crashes
for target in recording_json depth_png archetype_library scene glb synth_truth; do
  corpus=$work/corpus/$target
  mkdir -p "$corpus"
  cp -n $(seeds_of "$target") "$corpus/" 2>/dev/null
  dict=()
  case $target in depth_png|glb) ;; *) dict=(-dict="$root/tests/fuzz/json.dict") ;; esac
  log=$work/$target.log
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    "$bin/meadow_fuzz_$target" "$corpus" "${dict[@]}" -max_total_time="$seconds" \
    -max_len=65536 -rss_limit_mb=4096 -print_final_stats=1 \
    -artifact_prefix="$work/crashes/$target-" > "$log" 2>&1
  status=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  crashes=$(ls "$work/crashes" | grep -c "^$target-" || true)
  printf '%-20s %12s %8s\n' "$target" "${runs:-?}" "$crashes"
  if [ "$status" -ne 0 ] || [ "$crashes" -ne 0 ]; then
    failed=1
    echo "  see $log" >&2
  fi
done
exit $failed
