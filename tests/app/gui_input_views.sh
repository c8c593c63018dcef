# Cases of gui_input.sh (sourced by it, which sets the helpers and variables they use):
# What the window shows: the history (Left, Right, the timeline slider, resume), the active
# contacts, the deformation slider and key, the teaching aids, the inspector of a particle.

input_case_history() {
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
}

input_case_contacts() {
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
}

input_case_deform() {
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
}

input_case_teach() {
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
  open_section description_header description
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
}

input_case_inspect() {
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
}

input_case_specimen_reload() {
  # the bracket read from its DXF drawing; the drawing saved again while the window shows it
  mkdir -p "$work/specimens" || fail "folder for the drawing"
  cp "$scenes/bracket_dxf.toml" "$work/bracket.toml" || fail "copy of the scene"
  cp "$scenes/specimens/bracket.dxf" "$work/specimens/bracket.dxf" || fail "copy of the drawing"
  start "$work/bracket.toml" --set solver.end_time=1
  # About this scene: the particle count, and the drawing the bracket came from with its box
  open_section description_header description
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
}
