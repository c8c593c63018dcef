# GUI smoke tests: the visualiser under a virtual X server (Xvfb) draws every shipped scene for a
# few frames and writes a screenshot; a small checker then verifies the picture is not blank and,
# for the notched plate, that the crack is drawn above the notch. One scripted run drives the
# controls (pause, step, a live setting, resume, a colour map) and checks they took effect;
# another records frames from the window and checks they carry the overlay.
# Label: gui (ctest -L gui). Needs xvfb-run; skipped when it or the visualiser is missing.
find_program(PERIFLEX_XVFB_RUN xvfb-run)
if(TARGET periflex_app AND PERIFLEX_XVFB_RUN)
  add_executable(gui_png_check "${CMAKE_CURRENT_SOURCE_DIR}/app/gui_png_check.cpp")
  target_link_libraries(gui_png_check PRIVATE periflex_app)

  set(gui_out "${CMAKE_CURRENT_BINARY_DIR}/gui_smoke")
  file(MAKE_DIRECTORY "${gui_out}")
  set(gui_xvfb ${PERIFLEX_XVFB_RUN} -a -s "-screen 0 1280x800x24")
  set(gui_program $<TARGET_FILE:periflex> gui)

  # one picture per shipped scene, then the checker on it
  file(GLOB gui_scenes CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/scenes/*.toml")
  foreach(scene IN LISTS gui_scenes)
    get_filename_component(name "${scene}" NAME_WE)
    add_test(NAME gui_smoke_${name}
             COMMAND ${gui_xvfb} ${gui_program} "${scene}" --frames 40 --screenshot "${gui_out}/${name}.png")
    set_tests_properties(gui_smoke_${name} PROPERTIES LABELS gui TIMEOUT 60 RESOURCE_LOCK xvfb
                         FIXTURES_SETUP gui_picture_${name})
    add_test(NAME gui_smoke_${name}_picture COMMAND gui_png_check "${gui_out}/${name}.png")
    set_tests_properties(gui_smoke_${name}_picture PROPERTIES LABELS gui
                         FIXTURES_REQUIRED gui_picture_${name})
  endforeach()

  # the crack: run the notched plate to t = 0.8 ms, well after the crack starts (near 0.4 ms),
  # without the probe crosses and markers (yellow and orange, like the upper colour map) or the
  # overlay legend
  set(notched "${PROJECT_SOURCE_DIR}/scenes/notched_plate.toml")
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
  endif()

  # the controls: pause, step, change a live setting, resume, switch colour map (each checked),
  # then from the start pull the pendulum's free end up with the mouse spring and let go
  set(flexible "${PROJECT_SOURCE_DIR}/scenes/flexible_pendulum.toml")
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
