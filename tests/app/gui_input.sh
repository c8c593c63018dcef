#!/usr/bin/env bash
# The window driven as a person drives it: real X input events (xdotool moves the pointer onto a
# control and clicks, presses keys, drags with the left button) into `periflex gui` under Xvfb.
# The program tells where its controls are and what its state is through the file named by
# PERIFLEX_GUI_WIDGETS (src/app/widget_dump.h); the clicks themselves go through the X server and
# GLFW like anyone's. Every case ends with Ctrl+Q and requires the program to exit on its own
# within a time limit, so a frozen window fails the test instead of hanging it.
#
# Usage (inside an X display, e.g. under xvfb-run):
#   gui_input.sh CASE PERIFLEX SCENES_DIR OUT_DIR [GUI_PNG_CHECK]
# CASE: record_png | record_plot | record_mp4 | record_gif | record_interrupted | keys | damping | refusal | unstable |
#       spring | pull | pull_gpu | deform | teach | inspect | plot | plot_series | knife | body | contacts | history
set -uo pipefail

case_name=$1 periflex=$2 scenes=$3 out=$4 png_check=${5:-}
work="$out/$case_name"
rm -rf "$work"
mkdir -p "$work"
widgets="$work/widgets.txt"
log="$work/stderr.txt"
pid=""
source "$(dirname "$0")/gui_driver.sh"

# value of a state line (`state KEY VALUE...`), all its words
state() { awk -v k="$1" '$1 == "state" && $2 == k { $1 = ""; $2 = ""; sub(/^ +/, ""); print }' "$widgets" 2>/dev/null; }
# the centre of a control, "X Y" in window coordinates
centre() {
  awk -v k="$1" '$1 == "widget" && $2 == k { printf "%d %d\n", ($3 + $5) / 2, ($4 + $6) / 2 }' "$widgets" 2>/dev/null
}

# a control below the window's edge (not shown, or partly): scrolls the panel column with the
# wheel until it is whole on screen; false when 40 turns do not bring it
scroll_to() {
  local name=$1 bottom height turns=0
  read -r _ height < <(state window)
  while bottom=$(awk -v k="$name" '$1 == "widget" && $2 == k { print $6 }' "$widgets") &&
        [[ -z "$bottom" ]] || ((bottom > height - 2)); do
    ((turns++ < 40)) || return 1
    xdotool mousemove --window "$window" 100 $((height / 2)) click 5 || fail "xdotool wheel"
    sleep 0.2
  done
}

# moves the pointer onto a control and clicks it with the left button
click() {
  local name=$1 xy
  scroll_to "$name" || fail "control $name stays below the window's edge"
  xy=$(centre "$name")
  xdotool mousemove --window "$window" ${xy% *} ${xy#* } || fail "xdotool mousemove"
  sleep 0.2
  xdotool click 1 || fail "xdotool click"
  sleep 0.2
}

# world point to window coordinates through the program's camera
to_window() {
  state world_to_window | awk -v X="$1" -v Y="$2" '{ printf "%d %d\n", $1 * X + $2, $3 * Y + $4 }'
}

start() {
  local scene=$1
  shift
  # a scene file name is looked for among the shipped scenes, a path taken as it is
  [[ "$scene" == */* ]] || scene="$scenes/$scene"
  PERIFLEX_GUI_WIDGETS="$widgets" "$periflex" gui "$scene" "$@" 2>"$log" &
  pid=$!
  wait_until 60 "the window's first frame" '[[ -n "$(state running)" ]]'
  window=$(xdotool search --sync --pid "$pid" 2>/dev/null | head -n 1)
  [[ -n "$window" ]] || fail "no window of process $pid"
  xdotool windowfocus --sync "$window" 2>/dev/null || xdotool windowfocus "$window" || true
}

# Ctrl+Q, then the program must end on its own with exit code 0 within 30 s
quit() {
  # the program may be gone before the keys are let go: their release is not checked
  xdotool keydown ctrl q || fail "xdotool keydown ctrl+q"
  sleep 0.1
  xdotool keyup q ctrl 2>/dev/null
  local end=$((SECONDS + 30))
  while kill -0 "$pid" 2>/dev/null; do
    ((SECONDS < end)) || fail "the program did not exit within 30 s of Ctrl+Q (frozen window)"
    sleep 0.1
  done
  wait "$pid"
  local code=$?
  pid=""
  ((code == 0)) || fail "exit code $code"
}

# key presses, KEY or MOD+KEY, each held for HOLD seconds (0.1 by default, as a quick tap)
key() {
  local k
  for k in "$@"; do
    xdotool keydown ${k//+/ } && sleep "${HOLD:-0.1}" &&
      xdotool keyup $(echo ${k//+/ } | awk '{ for (i = NF; i > 0; --i) printf "%s ", $i }') ||
      fail "xdotool key $k"
    sleep 0.1
  done
  sleep 0.2
}
# a quick tap: a shortcut must not miss a press shorter than a frame
tap() { HOLD=0.02 key "$@"; }
# Keys into a text field are read by Dear ImGui 1.86 itself, which sees only the keys held at
# each frame: they are held for 0.3 s, longer than a frame under load (and shorter than the X
# server's auto-repeat delay)
field_key() { HOLD=0.3 key "$@"; }
# replaces the text of the active field
retype() {
  field_key ctrl+a BackSpace
  xdotool type --delay 30 "$1" || fail "typing $1"
  sleep 0.2
}

# opens the section under HEADER, whose first control is INSIDE: a click the window missed under
# load leaves the section shut (nothing more to scroll to), so the header is clicked again
open_section() {
  local header=$1 inside=$2 attempt
  for attempt in 1 2 3; do
    click "$header"
    scroll_to "$inside" && return 0
  done
  fail "section $header does not open: no $inside after three clicks on it"
}

# floating-point comparison through awk: holds "A OP B"
holds() { awk "BEGIN { exit !($1) }"; }

# recording from the Export panel: open it, name the target, Start, until 5 frames are written
begin_record() {
  local target=$1
  shift
  # a run that does not reach its end (and pause) while it records
  start flexible_pendulum.toml --set solver.end_time=1000 "$@"
  # with the plot window open (P), the recorded frames carry its plot
  if [[ -n "${WITH_PLOT:-}" ]]; then
    xdotool mousemove --window "$window" 1000 150
    tap p
    wait_until 10 "P to open the plot window" '[[ -n "$(centre plot_canvas)" ]]'
  fi
  open_section export_header record_path
  click record_path
  retype "$target"
  field_key Return
  click record_interval
  retype 0.02
  field_key Return
  click start_recording
  wait_until 30 "recording to start (Stop recording shown)" '[[ -n "$(centre stop_recording)" ]]'
  view=$(state world_to_window)
  wait_until 60 "at least 5 recorded frames" '(( $(state frames_written) >= 5 ))'
}

# the frames the log says the window recorded last
recorded_frames() { sed -n 's/.*recorded \([0-9]*\) frames.*/\1/p' "$log" | tail -n 1; }

# begin_record, then Stop and quit
record() {
  begin_record "$@"
  # the swinging pendulum would make the view grow: not while recording
  sleep 1
  [[ "$(state world_to_window)" == "$view" ]] || fail "the view changed during the recording"
  click stop_recording
  wait_until 30 "recording to stop (Start recording shown again)" \
    '[[ "$(state recording)" == 0 && -n "$(centre start_recording)" ]]'
  quit
  recorded=$(recorded_frames)
  [[ -n "$recorded" ]] && ((recorded >= 5)) || fail "the log reports no recording of 5 frames or more"
}

# the frames of a movie as ffprobe decodes them
movie_frames() {
  ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 "$1" ||
    fail "ffprobe cannot read $1"
}

# a column chosen from a plot's list (once the list stands still: a list lays itself out over
# its first frames); the plot then shows it (`state plot`: y column, x column, points; `state
# plot_series`: every y column)
pick() {
  item="$1=$2" chosen=$2 at=""
  click "$1"
  wait_until 10 "the list of $1 in place" '[[ -n "$at" && "$at" == "$(centre "$item")" ]] || { at=$(centre "$item"); sleep 0.3; false; }'
  click "$item"
  case "$1" in
    plot_y) wait_until 10 "$2 chosen for $1" '[[ -z "$(centre "$item")" && "$(state plot | cut -d " " -f 1)" == "$chosen" ]]' ;;
    plot_x) wait_until 10 "$2 chosen for $1" '[[ -z "$(centre "$item")" && "$(state plot | cut -d " " -f 2)" == "$chosen" ]]' ;;
    *) wait_until 10 "$2 added to the plot" '[[ -z "$(centre "$item")" && " $(state plot_series) " == *" $chosen "* ]]' ;;
  esac
}

# the cases, one function each, in four files by what they drive
for group in record controls views tools; do source "$(dirname "$0")/gui_input_$group.sh"; done
if declare -F "input_case_$case_name" >/dev/null; then
  "input_case_$case_name"
else
  fail "unknown case"
fi
echo "ok ($case_name)"
