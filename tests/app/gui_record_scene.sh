#!/usr/bin/env bash
# A shipped scene recorded from the window over its whole run: from t = 0 to the scene's end
# time, one PNG every seventh of it (an interval that is no whole number of steps), in a small
# window to keep it cheap. The run must end by itself with exit code 0 and leave exactly 8
# frames (t = 0 and the seven marks up to the end time).
# Usage (inside an X display): gui_record_scene.sh PERIFLEX SCENE OUT_DIR
set -uo pipefail
periflex=$1 scene=$2 out=$3
name=$(basename "$scene" .toml)
frames="$out/$name"
rm -rf "$frames"
mkdir -p "$out"

# the end time as the scene file gives it ([solver] end_time = ...)
end=$(awk -F= '/^[[:space:]]*end_time[[:space:]]*=/ { sub(/#.*/, "", $2); gsub(/[[:space:]]/, "", $2); print $2; exit }' "$scene")
[[ -n "$end" ]] || { echo "FAIL: no end_time in $scene"; exit 1; }
interval=$(awk -v e="$end" 'BEGIN { printf "%.17g", e / 7 }')
expected=8

script="pause@0; reset@0; speed max@0; record $frames $interval@0; run@1; wait $end@2; stop_record@3"
timeout 300 "$periflex" gui "$scene" --size 640x480 --frames 5 --script "$script" 2>"$out/$name.log"
code=$?
((code == 0)) || { echo "FAIL: exit code $code"; tail -n 20 "$out/$name.log"; exit 1; }
grep -q "reached the scene's end time" "$out/$name.log" || { echo "FAIL: the run did not reach the end time"; exit 1; }
count=$(ls "$frames" 2>/dev/null | grep -c '^frame_[0-9]*\.png$')
echo "$name: end time $end s, a frame every $interval s: $count frames"
((count == expected)) || { echo "FAIL: $count frames, expected $expected"; exit 1; }
