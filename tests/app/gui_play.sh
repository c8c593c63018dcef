#!/usr/bin/env bash
# `periflex play DIR` driven as a person drives it: a checkpoint folder written by `periflex run`
# (the notched plate, checkpoints every 1.37e-4 s, which dt does not divide), opened in the
# window under Xvfb, real key presses through xdotool. Right shows the next checkpoint, Left the
# one before, S writes the picture of the state shown (its name carries the time shown); the
# window reads its state through PERIFLEX_GUI_WIDGETS (src/app/widget_dump.h). A folder that
# cannot be replayed exits 2 before any window opens. Then the VTK series of a run, played the
# same way.
#
# Usage (inside an X display, e.g. under xvfb-run): gui_play.sh PERIFLEX SCENES_DIR OUT_DIR
set -uo pipefail

case_name=play periflex=$1 scenes=$2 out=$3
work="$out/play"
rm -rf "$work"
mkdir -p "$work"
widgets="$work/widgets.txt"
log="$work/stderr.txt"
pid=""
source "$(dirname "$0")/gui_driver.sh"

state() { awk -v k="$1" '$1 == "state" && $2 == k { print $3 }' "$widgets" 2>/dev/null; }
# a quick tap of 20 ms, shorter than a frame may take
tap() {
  xdotool keydown "$1" && sleep 0.02 && xdotool keyup "$1" || fail "xdotool key $1"
  sleep 0.3
}
# the time the window shows equals T (as the widget dump prints it, 9 digits)
shows() { awk -v a="$(state time)" -v b="$1" 'BEGIN { exit !(a != "" && (a - b) ^ 2 < 1e-24) }'; }

# opens the window on a folder, waits for its first frame and focuses it
open_play() {
  PERIFLEX_GUI_WIDGETS="$widgets" "$periflex" play "$1" 2>"$log" &
  pid=$!
  wait_until 60 "the window's first frame on $1" '[[ -n "$(state playback_count)" ]]'
  window=$(xdotool search --sync --pid "$pid" 2>/dev/null | head -n 1)
  [[ -n "$window" ]] || fail "no window of process $pid"
  xdotool windowfocus --sync "$window" 2>/dev/null || xdotool windowfocus "$window" || true
  xdotool mousemove --window "$window" 1200 100
}
# Ctrl+Q, then the program ends on its own with exit code 0
quit_play() {
  xdotool keydown ctrl q && sleep 0.1
  xdotool keyup q ctrl 2>/dev/null
  local end=$((SECONDS + 30)) code
  while kill -0 "$pid" 2>/dev/null; do
    ((SECONDS < end)) || fail "the program did not exit within 30 s of Ctrl+Q"
    sleep 0.1
  done
  wait "$pid"
  code=$?
  pid=""
  ((code == 0)) || fail "exit code $code"
}

# the run to replay
"$periflex" run "$scenes/notched_plate.toml" --quiet --until 6e-4 --checkpoint-every 1.37e-4 --threads 1 \
  --out "$work/run" >"$work/run.txt" 2>&1 || fail "the checkpointing run failed: $(cat "$work/run.txt")"
folder="$work/run/checkpoints"

# refused before a window opens: a folder without checkpoints
mkdir -p "$work/empty" && cp "$folder/run.json" "$work/empty/"
"$periflex" play "$work/empty" >"$work/empty.txt" 2>&1
code=$?
((code == 2)) || fail "an empty folder: exit $code, expected 2: $(cat "$work/empty.txt")"
grep -q "holds no checkpoint" "$work/empty.txt" || fail "an empty folder: $(cat "$work/empty.txt")"

cd "$work" || fail "cd $work"
open_play "$folder"

# the start and the four checkpoints; the window opens paused on the start
[[ "$(state playback_count)" == 5 ]] || fail "$(state playback_count) states listed, expected 5"
[[ "$(state running)" == 0 ]] || fail "the replay runs on its own"
shows 0 || fail "opened at t = $(state time), not at the start"
tap s
wait_until 10 "the screenshot of the start" '[[ -s periflex_notched_plate_t0.png ]]'

tap Right
wait_until 10 "Right to show the first checkpoint (t = 1.37e-4)" 'shows 1.37e-4'
[[ "$(state playback_index)" == 1 ]] || fail "index $(state playback_index) after Right"
tap s
wait_until 10 "the screenshot of t = 1.37e-4" '[[ -s periflex_notched_plate_t0.000137.png ]]'
cmp -s periflex_notched_plate_t0.png periflex_notched_plate_t0.000137.png &&
  fail "the pictures of t = 0 and t = 1.37e-4 are the same"

tap Right
tap Right
wait_until 10 "two more Right presses (t = 4.11e-4)" 'shows 4.11e-4'
tap Left
wait_until 10 "Left to go back one checkpoint (t = 2.74e-4)" 'shows 2.74e-4'
[[ "$(state playback_index)" == 2 ]] || fail "index $(state playback_index) after Left"
tap Right
tap Right
tap Right
wait_until 10 "Right past the last to stay on it (t = 5.48e-4)" 'shows 5.48e-4'
[[ "$(state running)" == 0 ]] || fail "stepping started the replay running"

quit_play

# the VTK series of a run (every 250 steps = 1e-4 s) played the same way: seven states
"$periflex" run "$scenes/notched_plate.toml" --quiet --until 6e-4 --vtk-every 250 --threads 1 \
  --out "$work/vtk_run" >"$work/vtk_run.txt" 2>&1 || fail "the VTK run failed: $(cat "$work/vtk_run.txt")"
mkdir -p "$work/vtk_shots" && cd "$work/vtk_shots" || fail "cd $work/vtk_shots"
rm -f "$widgets"
open_play "$work/vtk_run/vtk"
[[ "$(state playback_count)" == 7 ]] || fail "$(state playback_count) VTK states listed, expected 7"
shows 0 || fail "the VTK series opened at t = $(state time), not at the start"
tap s
wait_until 10 "the screenshot of the series' start" '[[ -s periflex_notched_plate_t0.png ]]'
tap Right
tap Right
wait_until 10 "two Right presses through the series (t = 2e-4)" 'shows 2e-4'
tap Left
wait_until 10 "Left back one state of the series (t = 1e-4)" 'shows 1e-4'
tap s
wait_until 10 "the screenshot of t = 1e-4" '[[ -s periflex_notched_plate_t0.0001.png ]]'
cmp -s periflex_notched_plate_t0.png periflex_notched_plate_t0.0001.png &&
  fail "the VTK states at t = 0 and t = 1e-4 draw the same picture"
quit_play
echo "play: ok"
