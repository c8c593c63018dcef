# Cases of gui_input.sh (sourced by it, which sets the helpers and variables they use):
# The plot window (a column picked, zoomed and exported; two series in one plot), the knife, and
# the inspector of a rigid body clicked.

input_case_plot() {
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
}

input_case_plot_series() {
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
}

input_case_knife() {
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
}

input_case_body() {
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
}
