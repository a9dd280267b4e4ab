#!/usr/bin/env bash
# CSV -> PNG line chart, one line per series, with gnuplot (Debian's gnuplot-nox).
#   tools/chart.sh CSV OUT.png "Title" XCOL YCOL SERIESCOL "x label" "y label" [logx|logy|logxy]
# Columns are named by their CSV header. Points of a series are drawn in file order, so write
# them sorted along the x axis. Used for meadow's speed-versus-accuracy charts (README).
set -euo pipefail
if [ $# -lt 8 ]; then sed -n '2,5p' "$0"; exit 2; fi
csv=$1 out=$2 title=$3 xcol=$4 ycol=$5 scol=$6 xlabel=$7 ylabel=$8 scale=${9:-}
command -v gnuplot >/dev/null || { echo "chart.sh: gnuplot is missing (apt-get install gnuplot-nox)" >&2; exit 2; }
[ -r "$csv" ] || { echo "chart.sh: cannot read $csv" >&2; exit 2; }

header=$(head -1 "$csv")
col() { # 1-based index of a header name
  local i=1
  IFS=, read -ra names <<<"$header"
  for n in "${names[@]}"; do [ "$n" = "$1" ] && { echo $i; return; }; i=$((i + 1)); done
  echo "chart.sh: $csv has no column '$1' (columns: $header)" >&2; exit 2
}
x=$(col "$xcol"); y=$(col "$ycol"); s=$(col "$scol")
series=$(tail -n +2 "$csv" | cut -d, -f"$s" | awk '!seen[$0]++' | tr '\n' ' ')
tmp="$out.tmp.$$.png"
gnuplot <<GP
set terminal pngcairo size 900,560 font "sans,11"
set output "$tmp"
set datafile separator ","
set key outside right top
set grid
set termoption noenhanced  # series and column names are literal text (no _ subscripts)
set title "$title"
set xlabel "$xlabel"
set ylabel "$ylabel"
$( [[ $scale == logx || $scale == logxy ]] && echo "set logscale x" )
$( [[ $scale == logy || $scale == logxy ]] && echo "set logscale y" )
series = "$series"
plot for [name in series] "$csv" every ::1 using (strcol($s) eq name ? column($x) : NaN):(strcol($s) eq name ? column($y) : NaN) with linespoints lw 2 pt 7 title name
GP
mv "$tmp" "$out"
