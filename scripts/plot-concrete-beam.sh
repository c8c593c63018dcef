#!/usr/bin/env bash
# The load-deflection curve of scenes/concrete_beam_3pb.toml: runs the scene to 8 ms, twice its
# end time, to show the tail (or reads the series.csv given as $1) and draws
# docs/figures/concrete_beam_3pb.png with gnuplot.
#
# series.csv has no load column: the pin's imposed motion is the only thing doing work on the beam,
# so the load is P = d(driver_work)/dt / v(t), v(t) the pin's speed (0.04 m/s reached linearly over
# the first millisecond, as the scene's table says); the deflection is the pin probe's fall.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
series=${1:-}
if [[ -z $series ]]; then
  out=$(mktemp -d)
  "$root/build/src/periflex" run "$root/scenes/concrete_beam_3pb.toml" --until 8e-3 --out "$out" --quiet
  series=$out/series.csv
fi
curve=$(mktemp)
# columns found by name; central differences of the driver work between neighbouring rows
awk -F, '
  NR == 1 { for (c = 1; c <= NF; ++c) col[$c] = c; next }
  { t[NR] = $(col["t"]); w[NR] = $(col["driver_work"]); y[NR] = $(col["probe.pin.y"]); n = NR }
  END {
    for (k = 3; k < n; ++k) {
      v = 0.04 * (t[k] < 1e-3 ? t[k] / 1e-3 : 1.0)
      if (v <= 0) continue
      p = (w[k + 1] - w[k - 1]) / (t[k + 1] - t[k - 1]) / v
      printf "%.6e %.6e\n", (y[2] - y[k]) * 1e3, p / 1e3
    }
  }' "$series" > "$curve"
gnuplot <<GP
set terminal pngcairo size 900,560 font "sans,12"
set output "$root/docs/figures/concrete_beam_3pb.png"
set title "Notched concrete beam, three-point bending (bilinear softening, G0 = 60 J/m^2)"
set xlabel "mid-span deflection [mm]"
set ylabel "load [kN]"
set grid
set key off
plot "$curve" using 1:2 with lines lw 2 lc rgb "#b03a2e"
GP
rm -f "$curve"
echo "wrote docs/figures/concrete_beam_3pb.png"
