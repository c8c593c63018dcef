# GUI smoke tests: the visualiser under a virtual X server (Xvfb) draws every shipped scene for a
# few frames and writes a screenshot; a small checker then verifies the picture is not blank and,
# for the notched plate, that the crack is drawn above the notch. One scripted run drives the
# controls (pause, step, a live setting, resume, a colour map) and checks they took effect;
# another records frames from the window and checks they carry the overlay.
# In a ThreadSanitizer build (PERIFLEX_SANITIZE=thread) a smaller set runs instead: scripted runs
# that drive the simulation thread and the render thread hard, failing on any TSan report.
# Label: gui (ctest -L gui). Needs xvfb-run; skipped when it or the visualiser is missing.
find_program(PERIFLEX_XVFB_RUN xvfb-run)
if(TARGET periflex_app AND PERIFLEX_XVFB_RUN)
  add_executable(gui_png_check "${CMAKE_CURRENT_SOURCE_DIR}/app/gui_png_check.cpp")
  target_link_libraries(gui_png_check PRIVATE periflex_app)

  set(gui_out "${CMAKE_CURRENT_BINARY_DIR}/gui_smoke")
  file(MAKE_DIRECTORY "${gui_out}")
  set(gui_xvfb ${PERIFLEX_XVFB_RUN} -a -s "-screen 0 1280x800x24")
  set(gui_program $<TARGET_FILE:periflex> gui)
  set(flexible "${PROJECT_SOURCE_DIR}/scenes/flexible_pendulum.toml")
  set(rigid "${PROJECT_SOURCE_DIR}/scenes/slider_crank.toml")
  set(notched "${PROJECT_SOURCE_DIR}/scenes/notched_plate.toml")

  # The window driven by real X input events (tests/app/gui_input.sh): xdotool clicks the Export
  # panel's buttons, presses the keys, types into a field and drags with the mouse; each case
  # must end on its own after Ctrl+Q (a frozen window fails within the time limit).
  find_program(PERIFLEX_XDOTOOL xdotool)
  function(gui_input_test case)
    if(NOT PERIFLEX_XDOTOOL)
      return()
    endif()
    add_test(NAME gui_input_${case}
             COMMAND ${gui_xvfb} bash "${CMAKE_CURRENT_SOURCE_DIR}/app/gui_input.sh" ${case}
                     $<TARGET_FILE:periflex> "${PROJECT_SOURCE_DIR}/scenes" "${gui_out}/input"
                     $<TARGET_FILE:gui_png_check>)
    set_tests_properties(gui_input_${case} PROPERTIES LABELS gui TIMEOUT 180 RESOURCE_LOCK xvfb
                         ENVIRONMENT "${ARGN}" FAIL_REGULAR_EXPRESSION "ThreadSanitizer")
  endfunction()
endif()

if(TARGET periflex_app AND PERIFLEX_XVFB_RUN AND PERIFLEX_SANITIZE STREQUAL "thread")
  # Under ThreadSanitizer: the first report ends the program with exit code 66 (and the output
  # check catches one in any case). Suppressions cover only uninstrumented third-party code (Mesa,
  # see scripts/tsan.supp). OpenMP stays at one thread: GCC's libgomp is not instrumented, so
  # TSan cannot see its barriers and would report every parallel loop of the solver.
  set(gui_tsan_env
      "TSAN_OPTIONS=halt_on_error=1 second_deadlock_stack=1 suppressions=${PROJECT_SOURCE_DIR}/scripts/tsan.supp"
      "OMP_NUM_THREADS=1")
  # a scripted run of SCENE for FRAMES frames whose last one is NAME.png, then the picture check
  function(gui_tsan_test name scene frames script)
    add_test(NAME ${name} COMMAND ${gui_xvfb} ${gui_program} "${scene}" --frames ${frames}
                                  --screenshot "${gui_out}/${name}.png" --script "${script}")
    set_tests_properties(${name} PROPERTIES LABELS gui TIMEOUT 300 RESOURCE_LOCK xvfb
                         ENVIRONMENT "${gui_tsan_env}" FAIL_REGULAR_EXPRESSION "ThreadSanitizer"
                         FIXTURES_SETUP ${name})
    add_test(NAME ${name}_picture COMMAND gui_png_check "${gui_out}/${name}.png")
    set_tests_properties(${name}_picture PROPERTIES LABELS gui FIXTURES_REQUIRED ${name})
  endfunction()

  # particles: every control while the simulation thread steps (pause, single steps, live bond
  # damping and correction, resume, changes while running), recording from the window, the mouse
  # spring, reset, then a switch to a rigid scene that keeps running
  string(JOIN "; " tsan_particles "pause@3" "expect paused@3" "step@4" "step 5@5" "expect paused@5"
         "set bond_damping=0.1@6" "set correction=baumgarte@6" "expect bond_damping=0.1@6"
         "expect correction=baumgarte@6" "resume@7" "expect running@7" "set global_damping=0.5@9"
         "set correction=projection@10" "expect correction=projection@10" "expect running@10"
         "record ${gui_out}/tsan_record 0.005@11" "grab 0.45 0@12" "drag 0.45 0.1@13" "release@15"
         "wait 0.05@16" "stop_record@17" "reset@18" "run@18" "colormap viridis@19"
         "scene pendulum.toml@20" "expect scene=pendulum@21" "run@21" "set correction=projection@22"
         "expect running@23")
  gui_tsan_test(gui_tsan_particles "${flexible}" 28 "${tsan_particles}")

  # a large particle body stepping flat out (the snapshot's damage pass, big snapshots handed
  # over while drawn): fracture off and on, single steps, damping, colour field and range
  string(JOIN "; " tsan_plate "speed max@0" "run@0" "wait 1e-4@1" "set fracture=off@2"
         "expect fracture=off@2" "pause@3" "step 2@4" "set fracture=on@5" "set global_damping=10@5"
         "resume@6" "expect running@6" "field strain@7" "range auto@7" "wait 3e-4@8" "field damage@9"
         "show bonds on@9")
  gui_tsan_test(gui_tsan_plate "${notched}" 12 "${tsan_plate}")

  # rigid bodies: live correction and time step, single steps, flat-out stepping, a movie through
  # the ffmpeg pipe when ffmpeg is there (else a PNG sequence), following a body, reload
  find_program(PERIFLEX_FFMPEG ffmpeg)
  set(tsan_movie "${gui_out}/tsan_rigid")
  if(PERIFLEX_FFMPEG)
    set(tsan_movie "${gui_out}/tsan_rigid.mp4")
  endif()
  string(JOIN "; " tsan_rigid "set correction=projection@2" "expect correction=projection@2" "pause@4"
         "expect paused@4" "step@5" "step 3@6" "set dt=5e-4@7" "set correction=baumgarte@7"
         "expect dt=5e-4@7" "resume@8" "expect running@8" "set alpha=5@9" "speed max@10"
         "record ${tsan_movie} 0.02@11" "wait 0.5@12" "stop_record@13" "follow crank@14" "reload@15"
         "run@16" "expect running@16" "follow none@17")
  gui_tsan_test(gui_tsan_rigid "${rigid}" 20 "${tsan_rigid}")

  # recording started and stopped with the Export panel's buttons (real clicks)
  gui_input_test(record_mp4 ${gui_tsan_env})
elseif(TARGET periflex_app AND PERIFLEX_XVFB_RUN)

  # one picture per shipped scene, then the checker on it (the time limit catches a frozen window;
  # the largest scenes take a minute to set up and draw 40 frames on a loaded two-core machine)
  file(GLOB gui_scenes CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/scenes/*.toml")
  foreach(scene IN LISTS gui_scenes)
    get_filename_component(name "${scene}" NAME_WE)
    add_test(NAME gui_smoke_${name}
             COMMAND ${gui_xvfb} ${gui_program} "${scene}" --frames 40 --screenshot "${gui_out}/${name}.png")
    set_tests_properties(gui_smoke_${name} PROPERTIES LABELS gui TIMEOUT 180 RESOURCE_LOCK xvfb
                         FIXTURES_SETUP gui_picture_${name})
    add_test(NAME gui_smoke_${name}_picture COMMAND gui_png_check "${gui_out}/${name}.png")
    set_tests_properties(gui_smoke_${name}_picture PROPERTIES LABELS gui
                         FIXTURES_REQUIRED gui_picture_${name})
  endforeach()

  # every shipped scene recorded from the window over its whole run (a frame every seventh of the
  # end time, an interval no whole number of steps): exit 0 and exactly 8 frames
  foreach(scene IN LISTS gui_scenes)
    get_filename_component(name "${scene}" NAME_WE)
    add_test(NAME gui_record_scene_${name}
             COMMAND ${gui_xvfb} bash "${CMAKE_CURRENT_SOURCE_DIR}/app/gui_record_scene.sh"
                     $<TARGET_FILE:periflex> "${scene}" "${gui_out}/record_scene")
    set_tests_properties(gui_record_scene_${name} PROPERTIES LABELS gui TIMEOUT 400 RESOURCE_LOCK xvfb)
  endforeach()

  # the crack: run the notched plate to t = 0.8 ms, well after the crack starts (near 0.4 ms),
  # without the probe crosses and markers (yellow and orange, like the upper colour map) or the
  # overlay legend
  set(gui_plain "show probes off@0; show markers off@0; show overlay off@0")
  if(EXISTS "${notched}")
    add_test(NAME gui_smoke_crack
             COMMAND ${gui_xvfb} ${gui_program} "${notched}" --frames 6 --screenshot "${gui_out}/crack.png"
                     --script "${gui_plain}; speed max@0; run@0; wait 0.8e-3@2")
    set_tests_properties(gui_smoke_crack PROPERTIES LABELS gui TIMEOUT 120 RESOURCE_LOCK xvfb
                         FIXTURES_SETUP gui_picture_crack)
    add_test(NAME gui_smoke_crack_picture COMMAND gui_png_check "${gui_out}/crack.png" --crack "${notched}")
    set_tests_properties(gui_smoke_crack_picture PROPERTIES LABELS gui FIXTURES_REQUIRED gui_picture_crack)

    # the same picture before the crack grows must fail the crack check (so the check can fail)
    add_test(NAME gui_smoke_no_crack
             COMMAND ${gui_xvfb} ${gui_program} "${notched}" --frames 4 --screenshot "${gui_out}/no_crack.png"
                     --script "pause@0; reset@0; ${gui_plain}")
    set_tests_properties(gui_smoke_no_crack PROPERTIES LABELS gui TIMEOUT 60 RESOURCE_LOCK xvfb
                         FIXTURES_SETUP gui_picture_no_crack)
    add_test(NAME gui_smoke_no_crack_picture
             COMMAND gui_png_check "${gui_out}/no_crack.png" --no-crack "${notched}")
    set_tests_properties(gui_smoke_no_crack_picture PROPERTIES LABELS gui
                         FIXTURES_REQUIRED gui_picture_no_crack)

    # the script's plot with several series (how the page's plot picture is taken): both series
    # in the plot the window dumps (an older dump is removed first, so it cannot pass)
    set(plot_dump "${gui_out}/plot_series_widgets.txt")
    add_test(NAME gui_script_plot_series
             COMMAND ${gui_xvfb} bash -c "rm -f \"$1\" && PERIFLEX_GUI_WIDGETS=\"$1\" \"$2\" gui \"$3\" --frames 8 --script 'plot driver_work+fracture@1' && grep -qx 'state plot_series driver_work fracture' \"$1\""
                     plot_series "${plot_dump}" $<TARGET_FILE:periflex> "${notched}")
    set_tests_properties(gui_script_plot_series PROPERTIES LABELS gui TIMEOUT 120 RESOURCE_LOCK xvfb)
  endif()

  # real input: recording from the Export panel (PNG folder, MP4, GIF, MP4 ended by Ctrl-C in the
  # terminal), the keys, a live setting
  # typed into its field, a dt past the stable limit refused and then run once confirmed, the mouse
  # spring on the notched plate, a slow pull across its notch, the deformation slider and key,
  # the teaching aids (F1 list, description, pace, reload of a scene file saved on disk), the
  # inspector of the particle under the pointer, the plot window (a column picked, zoomed and
  # exported; two series in one plot, exported and compared with series.csv), the knife, the
  # inspector of a rigid body clicked, the drawing of active contacts (key and box), the history
  # (Left, Right, the timeline slider, resume), the reload of a DXF drawing the scene reads
  foreach(case record_png record_plot record_mp4 record_gif record_interrupted keys damping refusal unstable spring pull
               pull_gpu deform teach inspect plot plot_series knife body contacts history specimen_reload)
    gui_input_test(${case})
  endforeach()

  # the controls: pause, step, change a live setting, resume, switch colour map (each checked),
  # then from the start pull the pendulum's free end up with the mouse spring and let go
  string(JOIN "; " gui_controls "pause@5" "expect paused@5" "step@6" "set bond_damping=0.1@7"
         "expect bond_damping=0.1@7" "resume@8" "expect running@8" "colormap viridis@9"
         "expect colormap=viridis@9" "fit@10" "reset@10" "grab 0.45 0@11"
         "drag 0.45 0.1@12" "run@12" "release@14")
  if(EXISTS "${flexible}")
    add_test(NAME gui_smoke_script
             COMMAND ${gui_xvfb} ${gui_program} "${flexible}" --frames 16
                     --script "${gui_controls}")
    set_tests_properties(gui_smoke_script PROPERTIES LABELS gui TIMEOUT 60 RESOURCE_LOCK xvfb)

    # recording from the window: a PNG every 10 ms of simulated time for 50 ms; the fourth frame
    # must be a real picture carrying the overlay a screenshot has (scene name and time, colour
    # legend); the folders are emptied first, so old frames cannot pass
    add_test(NAME gui_smoke_record_clean
             COMMAND ${CMAKE_COMMAND} -E rm -rf "${gui_out}/record" "${gui_out}/record_plain")
    set_tests_properties(gui_smoke_record_clean PROPERTIES LABELS gui FIXTURES_SETUP gui_record_clean)
    add_test(NAME gui_smoke_record
             COMMAND ${gui_xvfb} ${gui_program} "${flexible}" --frames 6
                     --script "speed max@0; record ${gui_out}/record 0.01@1; wait 0.05@2; stop_record@3")
    set_tests_properties(gui_smoke_record PROPERTIES LABELS gui TIMEOUT 60 RESOURCE_LOCK xvfb
                         FIXTURES_REQUIRED gui_record_clean FIXTURES_SETUP gui_record)
    add_test(NAME gui_smoke_record_picture
             COMMAND gui_png_check "${gui_out}/record/frame_000003.png" --overlay)
    set_tests_properties(gui_smoke_record_picture PROPERTIES LABELS gui FIXTURES_REQUIRED gui_record)

    # the same recording with the overlay turned off must fail the overlay check (so it can fail)
    set(record_plain "show overlay off@0; speed max@0; record ${gui_out}/record_plain 0.01@1; wait 0.05@2")
    add_test(NAME gui_smoke_record_plain
             COMMAND ${gui_xvfb} ${gui_program} "${flexible}" --frames 6 --script "${record_plain}; stop_record@3")
    set_tests_properties(gui_smoke_record_plain PROPERTIES LABELS gui TIMEOUT 60 RESOURCE_LOCK xvfb
                         FIXTURES_REQUIRED gui_record_clean FIXTURES_SETUP gui_record_plain)
    add_test(NAME gui_smoke_record_plain_picture
             COMMAND gui_png_check "${gui_out}/record_plain/frame_000003.png" --no-overlay)
    set_tests_properties(gui_smoke_record_plain_picture PROPERTIES LABELS gui
                         FIXTURES_REQUIRED gui_record_plain)
  endif()
endif()
