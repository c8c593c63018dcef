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
#       spring | pull | deform | teach | inspect | plot | plot_series | knife | body | contacts | history
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

# moves the pointer onto a control and clicks it with the left button
click() {
  local name=$1 xy bottom height turns=0
  # a control below the window's edge (not shown, or partly): scroll the panel column with the
  # wheel until it is whole on screen
  read -r _ height < <(state window)
  while bottom=$(awk -v k="$name" '$1 == "widget" && $2 == k { print $6 }' "$widgets") &&
        [[ -z "$bottom" ]] || ((bottom > height - 2)); do
    ((turns++ < 40)) || fail "control $name stays below the window's edge"
    xdotool mousemove --window "$window" 100 $((height / 2)) click 5 || fail "xdotool wheel"
    sleep 0.2
  done
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
  click export_header
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

case "$case_name" in
  record_png)
    record "$work/frames"
    count=$(ls "$work/frames" | grep -c '^frame_[0-9]*\.png$')
    ((count == recorded)) || fail "$count PNG files for $recorded frames recorded"
    for f in "$work"/frames/frame_*.png; do
      [[ "$(head -c 8 "$f" | od -An -tx1 | tr -d ' \n')" == 89504e470d0a1a0a ]] || fail "$f is not a PNG"
    done
    if [[ -n "$png_check" ]]; then
      "$png_check" "$work/frames/frame_000003.png" --overlay || fail "frame 3 is not a picture with the overlay"
      "$png_check" "$work/frames/frame_000003.png" --no-plot || fail "frame 3 has a plot, with the plot window closed"
    fi
    ;;
  record_plot)
    # the plot window open while recording: the frames carry its plot (kinetic energy against
    # time), as `run --plot` draws it
    WITH_PLOT=1 record "$work/frames"
    [[ "$(state plot_series)" == kinetic ]] || fail "the plot shows $(state plot_series), not kinetic"
    count=$(ls "$work/frames" | grep -c '^frame_[0-9]*\.png$')
    ((count == recorded)) || fail "$count PNG files for $recorded frames recorded"
    if [[ -n "$png_check" ]]; then
      "$png_check" "$work/frames/frame_000004.png" --plot || fail "frame 4 has no plot"
      "$png_check" "$work/frames/frame_000004.png" --overlay || fail "frame 4 is not a picture with the overlay"
    fi
    ;;
  record_mp4)
    # in a 1024x768 window (a projector): the panel column scrolls to the buttons
    record "$work/movie.mp4" --size 1024x768
    [[ "$(state window)" == "1024 768" ]] || fail "window $(state window), asked 1024x768"
    frames=$(movie_frames "$work/movie.mp4")
    ((frames == recorded)) || fail "the movie has $frames frames, the window recorded $recorded"
    size=$(ffprobe -v error -select_streams v:0 -show_entries stream=width,height -of csv=p=0:s=x "$work/movie.mp4")
    [[ "$size" == 1024x768 ]] || fail "movie frames of $size, the window is 1024x768"
    ;;
  record_gif)
    # a GIF for slides, its format by the name typed: every frame recorded in it, and the
    # temporary file it was written under renamed, not left beside it
    record "$work/movie.gif"
    frames=$(movie_frames "$work/movie.gif")
    ((frames == recorded)) || fail "the GIF has $frames frames, the window recorded $recorded"
    [[ "$(ffprobe -v error -select_streams v:0 -show_entries stream=codec_name -of csv=p=0 "$work/movie.gif")" == gif ]] ||
      fail "movie.gif is not a GIF"
    ! ls -A "$work" | grep -q '\.part$' || fail "a temporary .part file was left beside the GIF"
    ;;
  record_interrupted)
    # Ctrl-C in the terminal that started the window, while it records: the window closes, the
    # movie is finished with every frame recorded, exit code 130
    begin_record "$work/movie.mp4"
    kill -INT "$pid"
    end=$((SECONDS + 30))
    while kill -0 "$pid" 2>/dev/null; do
      ((SECONDS < end)) || fail "the program did not exit within 30 s of SIGINT"
      sleep 0.1
    done
    wait "$pid"
    code=$?
    pid=""
    ((code == 130)) || fail "exit code $code after SIGINT, expected 130"
    grep -q "the window was closed by SIGINT" "$log" || fail "no word of the signal in the log"
    recorded=$(recorded_frames)
    [[ -n "$recorded" ]] && ((recorded >= 5)) || fail "the log reports no recording of 5 frames or more"
    frames=$(movie_frames "$work/movie.mp4")
    ((frames == recorded)) || fail "the movie has $frames frames, the window recorded $recorded"
    ;;
  keys)
    # the shortcuts as quick taps of 20 ms, shorter than a frame may take
    # a longer run than the scene's 2 s, which a quiet machine finishes in about two seconds
    start flexible_pendulum.toml --set solver.end_time=100
    # the pointer over the picture, away from the pendulum
    xdotool mousemove --window "$window" 1200 100
    wait_until 10 "running at start" '[[ "$(state running)" == 1 ]]'
    tap space
    wait_until 10 "Space to pause" '[[ "$(state running)" == 0 ]]'
    sleep 0.3
    s0=$(state step)
    tap Right
    wait_until 10 "Right to take one step" '(( $(state step) == s0 + 1 ))'
    tap Right
    tap Right
    wait_until 10 "two more steps" '(( $(state step) == s0 + 3 ))'
    [[ "$(state running)" == 0 ]] || fail "stepping resumed the run"
    tap BackSpace
    wait_until 10 "Backspace to reset to step 0" '(( $(state step) == 0 ))'
    holds "$(state time) == 0" || fail "time after reset is $(state time)"
    # Step N: 250 steps at once
    click step_count
    retype 250
    field_key Return
    click step_n
    wait_until 20 "Step N to take 250 steps" '(( $(state step) == 250 ))'
    # Step to t: 0.01013 s is not a whole number of steps of 2.5e-5 s: the first step after it
    click step_to_time
    retype 0.01013
    field_key Return
    click step_to
    wait_until 20 "Step to t to reach step 406" '(( $(state step) == 406 ))'
    holds "$(state time) >= 0.01013 && $(state time) < 0.01013 + 2.5e-5" || fail "time $(state time) after Step to t"
    sleep 0.5
    (( $(state step) == 406 )) && [[ "$(state running)" == 0 ]] || fail "stepping went on past the time asked"
    # the pointer back over the picture for the keys
    xdotool mousemove --window "$window" 1200 100
    tap space
    wait_until 10 "Space to run again" '[[ "$(state running)" == 1 ]] && (( $(state step) > 10 ))'
    quit
    ;;
  damping)
    # a longer run than the scene's 2 s: on a quiet machine it reaches its end (and pauses)
    # in about two seconds of wall time, before the change is typed
    start flexible_pendulum.toml --set solver.end_time=100
    before=$(state bond_damping)
    click bond_damping
    retype 0.25
    # not applied before Enter
    holds "$(state bond_damping) == $before" || fail "bond damping changed before Enter"
    field_key Return
    wait_until 10 "bond damping 0.25 applied" 'holds "$(state bond_damping) == 0.25"'
    grep -q "settings: .*(ui)" "$log" || fail "the change is not in the log"
    [[ "$(state running)" == 1 ]] || fail "the broken file stopped the run"
    quit
    ;;
  refusal)
    # a time step above the safe limit of the notched plate: refused, and said so under the field
    start notched_plate.toml
    dt0=$(state dt)
    click dt
    retype 2e-6
    field_key Return
    wait_until 10 "the refusal under the dt field" '[[ -n "$(centre dt_refusal)" ]]'
    holds "$(state dt) == $dt0" || fail "dt changed to $(state dt)"
    # the dialog that offers to run past the limit, declined
    wait_until 10 "the offer to run past the stable step" '[[ -n "$(centre unstable_cancel)" ]]'
    click unstable_cancel
    wait_until 10 "the offer closed" '[[ -z "$(centre unstable_cancel)" ]]'
    holds "$(state dt) == $dt0" || fail "dt changed to $(state dt) after the offer was declined"
    # (the panel takes clicks again once the dialog's fade is over)
    sleep 0.5
    dt_bottom=$(awk '$1 == "widget" && $2 == "dt" { print $6 }' "$widgets")
    refusal_top=$(awk '$1 == "widget" && $2 == "dt_refusal" { print $4 }' "$widgets")
    ((refusal_top >= dt_bottom && refusal_top < dt_bottom + 30)) ||
      fail "the refusal (top $refusal_top) is not right under the dt field (bottom $dt_bottom)"
    # an accepted value clears it
    click dt
    retype 2e-7
    field_key Return
    wait_until 10 "dt 2e-7 applied, the refusal gone" 'holds "$(state dt) == 2e-7" && [[ -z "$(centre dt_refusal)" ]]'
    quit
    ;;
  unstable)
    # a dt 100 times the notched plate's critical step typed into its field: refused, then run
    # anyway once the dialog is confirmed with a click; the explicit step diverges until the
    # divergence check stops the run and the numerical-failure dialog names the quantity
    start notched_plate.toml
    dt0=$(state dt)
    click dt
    retype 6.15e-5
    field_key Return
    wait_until 10 "the offer to run past the stable step" '[[ -n "$(centre unstable_confirm)" ]]'
    holds "$(state dt) == $dt0" || fail "dt $(state dt) applied before the confirmation"
    click unstable_confirm
    wait_until 10 "dt 6.15e-5 applied" 'holds "$(state dt) == 6.15e-5"'
    grep -q "settings: .*dt=6.15e-05.*(dt past the stable step allowed) (ui)" "$log" ||
      fail "the confirmed step is not in the log"
    wait_until 60 "the divergence stopped with the numerical-failure dialog" '[[ -n "$(state numerical_error)" ]]'
    quantity=$(state numerical_error)
    [[ "$quantity" == energy || "$quantity" == "kinetic energy" || "$quantity" == state* ]] ||
      fail "the failure names '$quantity', not the energy or the state"
    grep -q "solver.allow_unstable" "$log" || fail "the diagnostic does not say the step was past the limit on purpose"
    wait_until 10 "the run paused by the failure" '[[ "$(state running)" == 0 ]]'
    holds "$(state time) > 0 && $(state time) < 1" || fail "time $(state time) after the failure"
    echo "diverged: $quantity at t = $(state time) s, step $(state step)"
    # the dialog closed (a modal dialog keeps the keys from the window)
    click failure_close
    wait_until 10 "the failure dialog closed" '[[ -z "$(centre failure_close)" ]]'
    quit
    ;;
  pull)
    # the notched plate with its grips held still (any crack is the drag's): pressed just right
    # of the notch, below its tip, and dragged 10 mm to the right in about a second, as a hand
    # pulls. The anchor walks at its capped speed in simulated time and its pull stays under its
    # limit: the notch opens and a crack runs up from its tip, and the plate is not blown to dust.
    # (A patch pressed at the notch's mouth, 3 mm from the free edge, may also shear off the thin
    # strip between it and the held right grip: that strip gives at the same pull as the notch tip,
    # so MouseGrip.DragAcrossTheNotchTearsTheLigamentWithoutDust judges that case by its dust.)
    start notched_plate.toml --set driver.left_turn.function.rate=0 --set driver.right_turn.function.rate=0
    mapping=""
    wait_until 20 "a steady view" '[[ -n "$mapping" && "$mapping" == "$(state world_to_window)" ]] || { mapping=$(state world_to_window); sleep 0.5; false; }'
    read -r x y < <(to_window 0.003 -0.013)
    read -r x_end _ < <(to_window 0.013 -0.013)
    xdotool mousemove --window "$window" "$x" "$y"
    wait_until 10 "a particle under the pointer" '[[ -n "$(state pointed)" ]]'
    xdotool mousedown 1
    wait_until 10 "a grabbed particle" '[[ -n "$(state grabbed)" ]]'
    for i in 1 2 3 4 5 6 7 8 9 10; do
      xdotool mousemove --window "$window" $((x + (x_end - x) * i / 10)) "$y"
      sleep 0.1
    done
    # held there until a crack has run from the notch tip (x = 0, y = -12 mm) well up the
    # ligament: particles damaged over a quarter above y = -6 mm, all within 6 mm of x = 0
    # (`state damage`: over half, particles, over a quarter, and their reference box x0 x1 y0 y1)
    wait_until 150 "a crack up from the notch tip" \
      'read -r dust total cracked x0 x1 y0 y1 < <(state damage) && holds "$y1 > -0.006"'
    read -r ax ay force max_force speed < <(state grip)
    xdotool mouseup 1
    read -r dust total cracked x0 x1 y0 y1 < <(state damage)
    echo "t = $(state time) s: $dust of $total particles over half damaged, $cracked over a quarter in x $x0 .. $x1," \
      "y $y0 .. $y1; pull $force N of $max_force N, anchor $speed m/s at ($ax, $ay)"
    holds "$dust < 0.03 * $total" || fail "$dust of $total particles lost over half their bonds: dust"
    # a crack is a line of damaged particles (its two faces, a little more where it kinks: at most
    # four per millimetre of its height at dx = 1 mm), not an area; it leans away from the pull, so
    # its x reach is not judged, only that the held-still left side stays whole
    holds "$x0 > -0.006" || fail "damage reaches x = $x0, into the left half the drag does not pull"
    holds "$cracked < 4 * ($y1 - $y0) / 0.001 + 8" || \
      fail "$cracked particles over a quarter damaged in a band $(awk -v a="$y0" -v b="$y1" 'BEGIN { print b - a }') m high: an area, not a crack"
    holds "$y0 > -0.016" || fail "damage reaches y = $y0, below the notch tip: the patch held, not the notch, tore"
    holds "$max_force > 0 && $force <= 1.2 * $max_force" || fail "pull $force N over its limit $max_force N"
    holds "$ax < 0.013" || fail "the anchor reached the pointer ($ax): it did not walk at its capped speed"
    wait_until 10 "the release" '[[ -z "$(state grabbed)" ]]'
    quit
    ;;
  spring)
    start notched_plate.toml
    # once the view is framed (the same camera twice, 0.5 s apart), aim at a particle in the
    # upper right of the plate
    mapping=""
    wait_until 20 "a steady view" '[[ -n "$mapping" && "$mapping" == "$(state world_to_window)" ]] || { mapping=$(state world_to_window); sleep 0.5; false; }'
    read -r x y < <(to_window 0.025 0.012)
    xdotool mousemove --window "$window" "$x" "$y"
    wait_until 10 "a particle under the pointer" '[[ -n "$(state pointed)" ]]'
    # onto that particle's centre, so the nearest one stays the same while it jitters
    read -r i0 px0 py0 < <(state pointed)
    read -r x y < <(to_window "$px0" "$py0")
    xdotool mousemove --window "$window" "$x" "$y"
    sleep 0.3
    read -r i0 px0 py0 < <(state pointed)
    sleep 1.5
    read -r i1 px1 py1 < <(state pointed)
    [[ "$i0" == "$i1" ]] || fail "the pointed particle changed without moving the pointer"
    t1=$(state time)
    # its motion over 1.5 s of the run without the spring: the noise the drag must beat
    noise=$(awk -v a="$px0" -v b="$py0" -v c="$px1" -v d="$py1" 'BEGIN { print sqrt((c-a)^2 + (d-b)^2) }')
    xdotool mousedown 1
    wait_until 10 "a grabbed particle" '[[ -n "$(state grabbed)" ]]'
    for dy in 10 20 30 40 50 60; do
      xdotool mousemove --window "$window" "$x" $((y - dy))
      sleep 0.05
    done
    # the anchor walks at 1e-3 of the plate's wave speed in simulated time (1.6 m/s, a pull, not
    # an impact): held until the patch has followed more than half a grid spacing
    moved_by_drag() {
      read -r ig gx gy < <(state grabbed)
      moved=$(awk -v a="$px1" -v b="$py1" -v c="$gx" -v d="$gy" 'BEGIN { print sqrt((c-a)^2 + (d-b)^2) }')
      holds "$moved > 5e-4"
    }
    wait_until 90 "the patch pulled half a grid spacing" moved_by_drag
    t2=$(state time)
    # the spring is drawn with its force while held
    force=$(state spring_force)
    [[ -n "$force" ]] && holds "$force > 0" || fail "no spring force shown while dragging"
    xdotool mouseup 1
    [[ "$ig" == "$i1" ]] || fail "grabbed particle $ig, pointed at $i1"
    echo "particle $ig: noise $noise m over 1.5 s, moved $moved m by the drag (t $t1 .. $t2)"
    holds "$moved > 10 * $noise" || fail "moved $moved m, not 10x the noise $noise m"
    holds "$moved > 5e-4" || fail "moved $moved m: less than half a grid spacing"
    wait_until 10 "the release" '[[ -z "$(state grabbed)" ]]'
    quit
    ;;
  history)
    # the rigid pendulum: a state kept every 0.0333 s (33.3 steps of 1 ms, not a whole number),
    # the run stepped to t = 4 s, then taken back with Left, forward with Right and further back
    # with the timeline slider, all paused; resumed from there and stepped to t = 4 s again, it
    # shows the same series row, bit for bit, as the first time
    start pendulum.toml
    xdotool mousemove --window "$window" 1200 100
    tap space
    wait_until 10 "Space to pause" '[[ "$(state running)" == 0 ]]'
    click history_interval
    retype 0.0333
    field_key Return
    wait_until 10 "the cadence of 0.0333 s applied" 'holds "$(state history_interval) == 0.0333"'
    click step_to_time
    retype 4
    field_key Return
    click step_to
    wait_until 30 "Step to t to reach t = 4 s" '(( $(state step) == 4000 )) && [[ "$(state running)" == 0 ]]'
    hash=$(state series_hash) t1=$(state time) kept=$(state history_states)
    ((kept >= 80)) || fail "$kept states kept over 4 s"
    [[ "$(state scrub)" == -1 ]] || fail "showing a history state before any was asked"
    # Left three times: each press an earlier saved state (a press held past the X server's
    # auto-repeat delay on a loaded machine goes back further, as a held key does)
    xdotool mousemove --window "$window" 1200 100
    previous=$t1
    for press in 1 2 3; do
      tap Left
      wait_until 10 "Left press $press to show an earlier state" \
        '(( $(state scrub) >= 0 )) && holds "$(state time) < $previous"'
      previous=$(state time)
    done
    # the log names every state shown: one saved state back each time, 0.0333 s apart within a
    # step (the first step at or after each mark)
    sed -n 's/.*history: t = \([0-9.e+-]*\) (state \([0-9]*\) of .*(key)$/\1 \2/p' "$log" |
      awk '{ if (n++ && ($2 != i - 1 || t - $1 > 0.0343 || t - $1 < 0.0323)) bad = 1; t = $1; i = $2 }
           END { exit !(n >= 3 && !bad) }' || fail "the Left presses did not go back one saved state at a time"
    holds "$previous < $t1 - 2 * 0.0333" || fail "three Left presses show t = $previous"
    [[ "$(state running)" == 0 ]] || fail "the history is not shown paused"
    (( $(state step) < 4000 )) || fail "step $(state step) after going back"
    [[ "$(state series_hash)" != "$hash" ]] || fail "an earlier state shows the series row of t = 4 s"
    # Right: forward again
    back3=$previous
    tap Right
    wait_until 10 "Right to show a later saved state" 'holds "$(state time) > $back3 && $(state time) <= $t1"'
    # the newest saved state is the live one at t = 4 s: kept when the history was first shown,
    # unless t = 4 s fell on a mark of the cadence (which depends on when Space paused)
    total=$(state history_states)
    ((total == kept || total == kept + 1)) || fail "$total states after showing the history, $kept before"
    for press in 1 2 3 4 5 6; do
      shown=$(state scrub)
      ((shown == total - 1)) && break
      tap Right
      wait_until 10 "Right press to show the next saved state" '(( $(state scrub) > shown ))'
    done
    (( $(state scrub) == total - 1 )) || fail "Right does not reach the newest saved state"
    holds "$(state time) == $t1" || fail "the newest saved state is at t = $(state time), the live one was at $t1"
    # the slider pressed at a quarter of its width and dragged a little further left
    read -r x0 y0 x1 y1 < <(awk '$1 == "widget" && $2 == "history_slider" { print $3, $4, $5, $6 }' "$widgets")
    [[ -n "$x0" ]] || fail "no timeline slider"
    yc=$(((y0 + y1) / 2))
    xdotool mousemove --window "$window" $((x0 + (x1 - x0) / 4)) "$yc" mousedown 1 || fail "xdotool mousedown"
    sleep 0.3
    xdotool mousemove --window "$window" $((x0 + (x1 - x0) / 5)) "$yc" || fail "xdotool drag"
    sleep 0.3
    xdotool mouseup 1 || fail "xdotool mouseup"
    wait_until 10 "the slider to show a state near t = 0.8 s" 'holds "$(state time) > 0.5 && $(state time) < 1.1"'
    sleep 0.5
    t2=$(state time)
    [[ "$(state running)" == 0 ]] || fail "the slider started the run"
    kept=$total
    # resumed from there: the later states are dropped, the run goes on; stepped to t = 4 s
    click history_resume
    wait_until 10 "Resume from here to run" '[[ "$(state running)" == 1 ]] && (( $(state scrub) == -1 ))'
    (( $(state history_states) < kept )) || fail "$(state history_states) states after resuming at t = $t2, $kept before"
    click step_to
    wait_until 30 "Step to t to reach t = 4 s again" '(( $(state step) == 4000 )) && [[ "$(state running)" == 0 ]]'
    [[ "$(state time)" == "$t1" ]] || fail "t = $(state time), the first run was at $t1"
    echo "t = $t1 (series $hash), back to t = $t2 with Left, Right and the slider, resumed: series $(state series_hash)"
    [[ "$(state series_hash)" == "$hash" ]] || fail "the resumed run's series row at t = 4 s differs from the first run's"
    grep -q "history: t = .* (key)" "$log" || fail "the Left presses are not in the log"
    grep -q "resume (ui) from t = .*later history states dropped" "$log" || fail "the resume is not in the log"
    quit
    ;;
  contacts)
    # the hammer striking its beam: contacts are drawn after the C key, not after the box is
    # clicked off again; the program reports (state contacts) the flag and the contacts it has
    start hammer.toml
    [[ "$(state contacts)" == 0* ]] || fail "contacts drawn before asked: $(state contacts)"
    wait_until 60 "active contacts (the hammer on the beam)" '(( $(state contacts | cut -d" " -f2) > 0 ))'
    tap c
    wait_until 10 "contacts drawn after the C key" '[[ "$(state contacts)" == 1* ]]'
    grep -q "view: contacts on (key)" "$log" || fail "the key's change is not in the log"
    click show_contacts
    wait_until 10 "contacts off after the box is clicked" '[[ "$(state contacts)" == 0* ]]'
    quit
    ;;
  deform)
    # the notched plate bent by its grips, drawn undeformed (--deform 0), then magnified 100
    # times through the View panel's slider (Ctrl+click types a value), each picture taken with S
    cd "$work" || fail "cd $work"
    start notched_plate.toml --deform 0
    [[ "$(state deform)" == 0 ]] || fail "--deform 0 shows deformation x$(state deform)"
    wait_until 60 "the grips to bend the plate (t > 0.4 ms)" 'holds "$(state time) > 4e-4"'
    xdotool mousemove --window "$window" 1200 100
    tap space
    wait_until 10 "Space to pause" '[[ "$(state running)" == 0 ]]'
    shoot() {
      rm -f periflex_*.png
      tap s
      wait_until 20 "the screenshot" 'ls periflex_*.png >/dev/null 2>&1'
      sleep 0.5
      mv periflex_*.png "$1"
    }
    shoot k0.png
    # Ctrl+click on the slider, then the factor typed
    xy=$(centre deform)
    [[ -n "$xy" ]] || fail "no deformation slider"
    xdotool mousemove --window "$window" ${xy% *} ${xy#* } && sleep 0.2 &&
      xdotool keydown ctrl && sleep 0.1 && xdotool click 1 && sleep 0.1 && xdotool keyup ctrl ||
      fail "xdotool ctrl+click"
    sleep 0.3
    retype 100
    field_key Return
    wait_until 10 "the slider at 100" '[[ "$(state deform)" == 100 ]]'
    [[ "$(state deform_auto)" == 0 ]] || fail "still automatic"
    grep -q "view: deformation x100 (ui)" "$log" || fail "the change is not in the log"
    xdotool mousemove --window "$window" 1200 100
    shoot k100.png
    # D: undeformed, and back
    tap d
    wait_until 10 "D to show the undeformed plate" '[[ "$(state deform)" == 0 ]]'
    tap d
    wait_until 10 "D again to bring back x100" '[[ "$(state deform)" == 100 ]]'
    quit
    if [[ -n "$png_check" ]]; then
      "$png_check" k0.png --lower-edge-spread 0 3 || fail "the undeformed plate's lower edge is not flat"
      "$png_check" k100.png --lower-edge-spread 20 1000 || fail "the magnified plate's lower edge does not bend"
      # the grips (virtual bodies) drawn with the particles they hold, not at their true place
      "$png_check" k100.png --grip-holds || fail "the magnified plate's left grip does not hold its particles"
    fi
    ;;
  teach)
    # a copy of the pendulum scene, edited on disk while the window shows it
    cp "$scenes/pendulum.toml" "$work/scene.toml" || fail "copy of the scene"
    start "$work/scene.toml" --set solver.end_time=1000
    xdotool mousemove --window "$window" 1200 300
    # F1 shows every key and mouse action, F1 again hides them
    tap F1
    wait_until 10 "F1 to open the list of keys" '[[ -n "$(centre help_table)" && "$(state help)" == 1 ]]'
    read -r _ top _ bottom < <(awk '$1 == "widget" && $2 == "help_table" { print $3, $4, $5, $6 }' "$widgets")
    ((bottom - top > 15 * 12)) || fail "the list of keys is $((bottom - top)) px tall: not 15 rows"
    tap F1
    wait_until 10 "F1 to close it" '[[ -z "$(centre help_table)" && "$(state help)" == 0 ]]'
    # the description panel shows the file's opening comment
    first=$(awk '/^#/ { sub(/^# ?/, ""); print; exit }' "$work/scene.toml")
    click description_header
    wait_until 10 "the description panel" '[[ -n "$(centre description)" ]]'
    [[ "$(state description)" == "$first" ]] || fail "description '$(state description)', the file says '$first'"
    # the frame rate and the solver's pace over the picture
    wait_until 10 "the pace shown" '[[ "$(state performance)" == *fps*steps/s*"x real time"* ]]'
    holds "$(state fps) > 0" || fail "fps $(state fps)"
    # a view of one's own (a right-drag pans), kept by the reloads below
    xdotool mousemove --window "$window" 900 400 mousedown 3 mousemove --window "$window" 960 440 \
      mousemove --window "$window" 1000 460 mouseup 3 || fail "xdotool right-drag"
    sleep 0.5
    view=$(state world_to_window)
    generation=$(state scene_generation)
    # saved with a change: reloaded, the view kept
    sed -i 's/^end_time = .*/end_time = 7.0/' "$work/scene.toml"
    grep -q '^end_time = 7.0' "$work/scene.toml" || fail "the edit did not take"
    wait_until 10 "the saved file to be reloaded" '(( $(state scene_generation) > generation ))'
    [[ "$(state world_to_window)" == "$view" ]] || fail "the reload moved the view"
    grep -q "changed on disk: reloading" "$log" || fail "the reload is not in the log"
    # reloaded paused at t = 0, as by the Reload button: run it again
    wait_until 10 "paused at t = 0 after the reload" '[[ "$(state running)" == 0 ]] && (( $(state step) == 0 ))'
    tap space
    wait_until 10 "Space to run the reloaded scene" '[[ "$(state running)" == 1 ]] && (( $(state step) > 0 ))'
    # saved broken: the error over the picture, naming the file and line; the scene kept
    generation=$(state scene_generation)
    echo 'broken = [' >> "$work/scene.toml"
    wait_until 10 "the error shown over the picture" '[[ -n "$(centre load_error)" ]]'
    [[ "$(state load_error)" == *scene.toml:* ]] || fail "the error does not name the file: $(state load_error)"
    (( $(state scene_generation) == generation )) || fail "a broken file replaced the scene"
    [[ "$(state running)" == 1 ]] || fail "the run stopped"
    # mended: loaded, the error gone
    sed -i '$d' "$work/scene.toml"
    wait_until 10 "the mended file loaded, the error gone" \
      '(( $(state scene_generation) > generation )) && [[ -z "$(centre load_error)" ]]'
    quit
    ;;
  specimen_reload)
    # the bracket read from its DXF drawing; the drawing saved again while the window shows it
    mkdir -p "$work/specimens" || fail "folder for the drawing"
    cp "$scenes/bracket_dxf.toml" "$work/bracket.toml" || fail "copy of the scene"
    cp "$scenes/specimens/bracket.dxf" "$work/specimens/bracket.dxf" || fail "copy of the drawing"
    start "$work/bracket.toml" --set solver.end_time=1
    # About this scene: the particle count, and the drawing the bracket came from with its box
    click description_header
    wait_until 10 "the description panel" '[[ -n "$(centre description)" ]]'
    [[ "$(state geometry)" == "'bracket': dxf "*"bracket.dxf, x in [0, 0.06] m, y in [0, 0.06] m" ]] ||
      fail "About this scene says '$(state geometry)'"
    before=$(state particles)
    (( before > 1000 )) || fail "About this scene counts $before particles"
    generation=$(state scene_generation)
    # the bolt holes drawn smaller (radius 4 mm to 3 mm): reloaded
    perl -0pi -e 's/\n40\n4\n/\n40\n3\n/g' "$work/specimens/bracket.dxf"
    grep -q '^3$' "$work/specimens/bracket.dxf" || fail "the edit did not take"
    wait_until 10 "the saved drawing to be reloaded" '(( $(state scene_generation) > generation ))'
    grep -q "geometry file .*bracket.dxf changed on disk: reloading" "$log" || fail "the reload is not in the log"
    # smaller holes, more particles
    wait_until 10 "more particles counted" '(( $(state particles) > before ))'
    # saved broken (one line, no closed outline): the error over the picture naming the drawing
    generation=$(state scene_generation)
    printf '0\nSECTION\n2\nENTITIES\n0\nLINE\n8\noutline\n10\n0\n20\n0\n11\n1\n21\n0\n0\nENDSEC\n0\nEOF\n' \
      >"$work/specimens/bracket.dxf"
    wait_until 10 "the error shown over the picture" '[[ -n "$(centre load_error)" ]]'
    [[ "$(state load_error)" == *bracket.dxf*"not closed"* ]] || fail "the error does not name the drawing: $(state load_error)"
    (( $(state scene_generation) == generation )) || fail "a broken drawing replaced the scene"
    # mended: loaded, the error gone
    cp "$scenes/specimens/bracket.dxf" "$work/specimens/bracket.dxf" || fail "copy of the drawing"
    wait_until 10 "the mended drawing loaded, the error gone" \
      '(( $(state scene_generation) > generation )) && [[ -z "$(centre load_error)" ]]'
    quit
    ;;
  inspect)
    # hovering a particle of the notched plate (drawn at true scale) shows what it is doing
    start notched_plate.toml --deform 1
    mapping=""
    wait_until 20 "a steady view" '[[ -n "$mapping" && "$mapping" == "$(state world_to_window)" ]] || { mapping=$(state world_to_window); sleep 0.5; false; }'
    # the particle within a spacing of world point X Y is the one under the pointer (the
    # pointer's move has reached the window)
    near() {
      state pointed | awk -v X="$1" -v Y="$2" '{ exit !(($2 - X)^2 + ($3 - Y)^2 < 1e-6) }'
    }
    # an inner particle of the plate, far from the notch and the grips
    read -r x y < <(to_window 0.025 0.012)
    xdotool mousemove --window "$window" "$x" "$y"
    wait_until 10 "the pointer over (25, 12) mm" 'near 0.025 0.012'
    wait_until 10 "the inspector over a particle" '[[ -n "$(centre inspector)" && -n "$(state inspected)" ]]'
    read -r id intact broken < <(state inspected)
    read -r pointed _ < <(state pointed)
    [[ "$id" == "$pointed" ]] || fail "inspecting particle $id, the pointer is on $pointed"
    echo "inner particle $id: $intact intact, $broken broken bonds"
    ((intact >= 20 && broken == 0)) || fail "inner particle $id: $intact intact, $broken broken bonds"
    # a particle beside the notch, more than a horizon above the lower edge: the bonds across
    # the cut are missing or broken
    read -r x y < <(to_window 0.0005 -0.0145)
    xdotool mousemove --window "$window" "$x" "$y"
    wait_until 10 "the pointer beside the notch" 'near 0.0005 -0.0145'
    wait_until 10 "the inspector beside the notch" '[[ "$(state inspected)" == "$(state pointed | cut -d " " -f 1) "* ]]'
    read -r id2 intact2 broken2 < <(state inspected)
    echo "particle $id2 beside the notch: $intact2 intact, $broken2 broken bonds"
    ((id2 != id && intact2 < intact)) || fail "particle $id2 beside the notch: $intact2 intact bonds, inner one $intact"
    # away from the plate: no inspector
    xdotool mousemove --window "$window" 1200 150
    wait_until 10 "the inspector gone off the plate" '[[ -z "$(centre inspector)" && -z "$(state inspected)" ]]'
    quit
    ;;
  plot)
    # the pendulum's bob plotted against its own x (its path: a circle of the rod's length),
    # exported as CSV and PNG from the plot window's buttons; then kinetic energy against time,
    # zoomed with the wheel, exported again: only the points shown
    cd "$work" || fail "cd $work"
    start pendulum.toml --set solver.end_time=1000
    xdotool mousemove --window "$window" 1000 150
    tap p
    wait_until 10 "P to open the plot window" '[[ -n "$(centre plot_canvas)" ]]'
    # a full swing from 60 degrees to -60 degrees and back (period about 2.1 s at 1x real time)
    wait_until 60 "a swing (t > 2.2 s)" 'holds "$(state time) > 2.2"'
    pick plot_y probe.bob.y
    pick plot_x probe.bob.x
    wait_until 10 "the bob's path plotted" '[[ "$(state plot)" == "probe.bob.y probe.bob.x "* ]]'
    click plot_file
    retype "$work/bob"
    field_key Return
    click plot_csv
    click plot_png
    wait_until 10 "bob.csv and bob.png written" '[[ -s bob.csv && -s bob.png ]]'
    sleep 0.5
    [[ "$(head -n 1 bob.csv)" == "probe.bob.x,probe.bob.y" ]] || fail "bob.csv header: $(head -n 1 bob.csv)"
    rows=$(($(wc -l < bob.csv) - 1))
    # every point on the circle of radius 1 m about the pivot, never above the release height,
    # and the swing spanning most of the arc between x = +-0.866 m
    awk -F, 'NR > 1 { r = sqrt($1 * $1 + $2 * $2); if (r < 0.999 || r > 1.001 || $2 > -0.499) bad++;
                      if ($1 < lo) lo = $1; if ($1 > hi) hi = $1 }
             END { printf "%d rows, x %.4f .. %.4f, %d off the circle\n", NR - 1, lo, hi, bad;
                   exit !(NR > 50 && bad == 0 && hi - lo > 1.6) }' bob.csv ||
      fail "bob.csv is not the pendulum's path ($rows rows)"
    [[ "$(head -c 8 bob.png | od -An -tx1 | tr -d ' \n')" == 89504e470d0a1a0a ]] || fail "bob.png is not a PNG"
    if [[ -n "$png_check" ]]; then
      "$png_check" bob.png || fail "bob.png is blank"
    fi
    # kinetic energy against time, zoomed in three wheel turns about the plot's middle
    pick plot_y kinetic
    pick plot_x t
    read -r lo0 hi0 < <(state plot_range)
    xy=$(centre plot_canvas)
    xdotool mousemove --window "$window" ${xy% *} ${xy#* } click 4 click 4 click 4 || fail "xdotool wheel"
    sleep 0.5
    read -r lo hi < <(state plot_range)
    holds "$hi - $lo < 0.7 * ($hi0 - $lo0)" || fail "the wheel did not zoom: $lo0 .. $hi0, then $lo .. $hi"
    click plot_csv
    wait_until 10 "the zoomed plot written" '[[ "$(head -n 1 bob.csv)" == "t,kinetic" ]]'
    sleep 0.3
    awk -F, -v lo="$lo" -v hi="$hi" 'NR > 1 { if ($1 < lo || $1 > hi || $2 < 0) bad++ }
             END { printf "%d rows in t %s .. %s\n", NR - 1, lo, hi; exit !(NR > 5 && bad == 0) }' bob.csv ||
      fail "the zoomed export holds points outside the range shown"
    (( $(wc -l < bob.csv) < rows )) || fail "the zoomed export is not shorter than the whole swing"
    quit
    ;;
  plot_series)
    # two series in one plot: the work the grips' drivers put into the notched plate and the
    # fracture energy its crack releases, against time; exported as CSV with a column each, and
    # every row compared with the series.csv that `periflex run` writes for the same scene
    cd "$work" || fail "cd $work"
    until=7e-4
    start notched_plate.toml --set solver.end_time=$until
    xdotool mousemove --window "$window" 1000 150
    tap p
    wait_until 10 "P to open the plot window" '[[ -n "$(centre plot_canvas)" ]]'
    pick plot_y driver_work
    pick plot_add fracture
    [[ "$(state plot_series)" == "driver_work fracture" ]] || fail "plotted: $(state plot_series)"
    wait_until 120 "the run to its end (t = $until s)" '[[ "$(state running)" == 0 ]] && holds "$(state time) >= $until - 1e-9"'
    click plot_file
    retype "$work/two"
    field_key Return
    click plot_csv
    click plot_png
    wait_until 10 "two.csv and two.png written" '[[ -s two.csv && -s two.png ]]'
    sleep 0.5
    [[ "$(head -n 1 two.csv)" == "t,driver_work,fracture" ]] || fail "two.csv header: $(head -n 1 two.csv)"
    if [[ -n "$png_check" ]]; then
      "$png_check" two.png || fail "two.png is blank"
    fi
    # the same run from the command line, a row of series.csv at every step
    "$periflex" run "$scenes/notched_plate.toml" --set solver.end_time=$until --set solver.output_interval=4e-7 \
      --quiet --out "$work/run" 2>>"$log" || fail "periflex run"
    # every exported row at a time series.csv has, with its values (sums over threads may differ
    # in their last digits); the crack released energy by the end
    awk -F, 'NR == FNR { if (FNR == 1) { for (i = 1; i <= NF; ++i) col[$i] = i; next }
                         work[$1] = $col["driver_work"]; frac[$1] = $col["fracture"]; next }
             FNR == 1 { next }
             { ++rows; if (!($1 in work)) { missing++; next }
               dw = $2 - work[$1]; df = $3 - frac[$1]
               if (dw * dw > (1e-6 * work[$1] + 1e-12)^2 || df * df > (1e-6 * frac[$1] + 1e-12)^2) bad++
               if ($3 > top) top = $3 }
             END { printf "%d rows, %d not in series.csv, %d differing; fracture energy %.4g J\n", rows, missing, bad, top;
                   exit !(rows >= 10 && missing == 0 && bad == 0 && top > 0) }' run/series.csv two.csv ||
      fail "the exported series are not those of series.csv"
    # the second series removed: the plot holds the first alone
    click plot_remove=fracture
    wait_until 10 "fracture removed" '[[ "$(state plot_series)" == "driver_work" ]]'
    quit
    ;;
  knife)
    # the flexible pendulum, held at t = 0: a knife drag across the beam at x = 0.3 m cuts the
    # bonds there; run, the outer 0.2 m fall free of the part that swings
    start flexible_pendulum.toml --set solver.end_time=1000 --deform 1 --script 'pause@0'
    mapping=""
    wait_until 20 "a steady view" '[[ -n "$mapping" && "$mapping" == "$(state world_to_window)" ]] || { mapping=$(state world_to_window); sleep 0.5; false; }'
    [[ "$(state running)" == 0 ]] || fail "not paused"
    read -r tx ty < <(state probe_tip)
    read -r mx my < <(state probe_mid_span)
    d0=$(awk -v a="$tx" -v b="$ty" -v c="$mx" -v d="$my" 'BEGIN { print sqrt((a-c)^2 + (b-d)^2) }')
    xdotool mousemove --window "$window" 1000 150
    tap k
    wait_until 10 "K for the knife" '[[ "$(state knife)" == 1 ]]'
    # drag with the left button from (x, y0) to (x, y1) in world coordinates
    cut() {
      local x0 y0 x1 y1
      read -r x0 y0 < <(to_window "$1" "$2")
      read -r x1 y1 < <(to_window "$3" "$4")
      xdotool mousemove --window "$window" "$x0" "$y0" mousedown 1 || fail "xdotool mousedown"
      for f in 0.25 0.5 0.75 1; do
        sleep 0.05
        xdotool mousemove --window "$window" $(awk -v f=$f -v a="$x0" -v b="$y0" -v c="$x1" -v d="$y1" \
          'BEGIN { printf "%d %d", a + f * (c - a), b + f * (d - b) }') || fail "xdotool mousemove"
      done
      sleep 0.1
      xdotool mouseup 1 || fail "xdotool mouseup"
    }
    # above the beam: nothing to cut
    cut 0.1 0.05 0.4 0.06
    wait_until 10 "the empty cut in the log" 'grep -q "knife: 0 bonds cut (mouse)" "$log"'
    [[ "$(state broken_bonds)" == 0 ]] || fail "a cut through empty space broke $(state broken_bonds) bonds"
    cut 0.3 0.05 0.3 -0.05
    wait_until 10 "the cut across the beam" '(( $(state broken_bonds) > 0 ))'
    cut_count=$(state broken_bonds)
    grep -q "knife: $cut_count bonds cut (mouse)" "$log" || fail "the log does not report $cut_count bonds cut"
    [[ "$(state running)" == 0 ]] || fail "the cut started the run"
    echo "$cut_count bonds cut across the beam"
    tap k
    wait_until 10 "K for the knife off" '[[ "$(state knife)" == 0 ]]'
    tap space
    wait_until 60 "t > 0.3 s" 'holds "$(state time) > 0.3"'
    tap space
    wait_until 10 "paused" '[[ "$(state running)" == 0 ]]'
    read -r tx ty < <(state probe_tip)
    read -r mx my < <(state probe_mid_span)
    d1=$(awk -v a="$tx" -v b="$ty" -v c="$mx" -v d="$my" 'BEGIN { print sqrt((a-c)^2 + (b-d)^2) }')
    echo "tip to mid-span: $d0 m at t = 0, $d1 m at t = $(state time) s"
    # no bond broke but those cut (fracture is off in this scene)
    [[ "$(state broken_bonds)" == "$cut_count" ]] || fail "$(state broken_bonds) broken bonds, $cut_count cut"
    holds "$d1 > $d0 + 0.05 || $d1 < $d0 - 0.05" || fail "the beam did not come apart: tip to mid-span $d0 -> $d1 m"
    # Backspace (reset) undoes the cut
    tap BackSpace
    wait_until 10 "the reset" '(( $(state step) == 0 )) && [[ "$(state broken_bonds)" == 0 ]]'
    quit
    ;;
  body)
    # the pendulum paused mid-swing, its bob clicked: the inspector shows its q and qd, and the
    # rod's reaction, the tension m g cos(theta) + m v^2 / L along the rod towards the pivot
    start pendulum.toml --set solver.end_time=1000
    wait_until 60 "the swing under way (t > 0.7 s)" 'holds "$(state time) > 0.7"'
    xdotool mousemove --window "$window" 1200 100
    tap space
    wait_until 10 "Space to pause" '[[ "$(state running)" == 0 ]]'
    read -r bx by < <(state probe_bob)
    read -r x y < <(to_window "$bx" "$by")
    xdotool mousemove --window "$window" "$x" "$y" click 1 || fail "xdotool click on the bob"
    wait_until 10 "the inspector of the bob" '[[ -n "$(centre body_inspector)" && -n "$(state reaction_rod)" ]]'
    sleep 0.5
    read -r name qx qy qa vx vy w < <(state body_inspected)
    read -r fx fy m < <(state reaction_rod)
    [[ "$name" == bob ]] || fail "inspecting $name, not the bob"
    holds "($qx - $bx)^2 + ($qy - $by)^2 < 1e-12" || fail "q ($qx, $qy) is not where the bob is ($bx, $by)"
    # m = 1 kg, L = 1 m, g = 9.81 m/s^2: T = g (-y) + v^2, the force -T (x, y) on the bob
    echo "bob at ($qx, $qy), v ($vx, $vy); rod reaction ($fx, $fy) N, moment $m N m"
    awk -v x="$qx" -v y="$qy" -v vx="$vx" -v vy="$vy" -v fx="$fx" -v fy="$fy" -v m="$m" 'BEGIN {
      t = 9.81 * (-y) + vx * vx + vy * vy; ex = -t * x; ey = -t * y
      err = sqrt((fx - ex)^2 + (fy - ey)^2) / t
      printf "tension %.6g N, reaction off by %.2g of it\n", t, err
      exit !(t > 1 && err < 1e-6 && (m < 1e-6 * t && m > -1e-6 * t)) }' ||
      fail "the rod reaction is not the pendulum's tension"
    # the empty picture clicked (below the pivot, right of the swing): the inspector closes
    read -r x y < <(to_window 0.9 -1.2)
    xdotool mousemove --window "$window" "$x" "$y" click 1 || fail "xdotool click"
    wait_until 10 "the inspector closed" '[[ -z "$(centre body_inspector)" ]]'
    quit
    ;;
  *)
    fail "unknown case"
    ;;
esac
echo "ok ($case_name)"
