# Cases of gui_input.sh (sourced by it, which sets the helpers and variables they use):
# The controls: the keys, a live setting typed into its field, a dt past the stable limit refused
# and then run once confirmed, the mouse spring and a slow pull across the notch.

input_case_keys() {
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
}

input_case_damping() {
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
}

input_case_refusal() {
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
}

input_case_unstable() {
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
}

input_case_pull() { pull_across_the_notch; }

# the same pull with the plate's bond forces on the GPU (OpenGL compute through EGL beside the
# window's own context; Mesa llvmpipe in CI): the drag tears it the same way
input_case_pull_gpu() {
  pull_across_the_notch --device gpu
  grep -q "bond forces on the GPU in fp64" "$log" || fail "the log does not say the forces ran on the GPU"
}

# Extra arguments go to `periflex gui`.
pull_across_the_notch() {
  # the notched plate with its grips held still (any crack is the drag's): pressed just right
  # of the notch, below its tip, and dragged 10 mm to the right in about a second, as a hand
  # pulls. The anchor walks at its capped speed in simulated time and its pull stays under its
  # limit: the notch opens and a crack runs up from its tip, and the plate is not blown to dust.
  # (A patch pressed at the notch's mouth, 3 mm from the free edge, may also shear off the thin
  # strip between it and the held right grip: that strip gives at the same pull as the notch tip,
  # so MouseGrip.DragAcrossTheNotchTearsTheLigamentWithoutDust judges that case by its dust.)
  start notched_plate.toml --set driver.left_turn.function.rate=0 --set driver.right_turn.function.rate=0 "$@"
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
}

input_case_spring() {
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
}
