# `periflex play DIR` under a virtual X server, driven by real key presses (tests/app/gui_play.sh):
# Right and Left move through a checkpoint folder's states, S writes the picture shown, Ctrl+Q
# ends it. Label: gui. Needs xvfb-run and xdotool; skipped when they or the visualiser are missing.
find_program(PERIFLEX_PLAY_XVFB_RUN xvfb-run)
find_program(PERIFLEX_PLAY_XDOTOOL xdotool)
if(TARGET periflex_app AND PERIFLEX_PLAY_XVFB_RUN AND PERIFLEX_PLAY_XDOTOOL)
  add_test(NAME gui_play_keys
           COMMAND ${PERIFLEX_PLAY_XVFB_RUN} -a -s "-screen 0 1280x800x24" bash
                   "${CMAKE_CURRENT_SOURCE_DIR}/app/gui_play.sh" $<TARGET_FILE:periflex>
                   "${PROJECT_SOURCE_DIR}/scenes" "${CMAKE_CURRENT_BINARY_DIR}/gui_play")
  set_tests_properties(gui_play_keys PROPERTIES LABELS gui TIMEOUT 180 RESOURCE_LOCK xvfb
                       FAIL_REGULAR_EXPRESSION "ThreadSanitizer")
  # under ThreadSanitizer as the other window tests (tests/gui_smoke.cmake): Mesa's threads
  # suppressed, OpenMP at one thread (libgomp is not instrumented, so TSan cannot see its
  # barriers: building the replay's model reported every parallel loop of the bond search)
  if(PERIFLEX_SANITIZE STREQUAL "thread")
    set_tests_properties(gui_play_keys PROPERTIES ENVIRONMENT
      "TSAN_OPTIONS=halt_on_error=1 second_deadlock_stack=1 suppressions=${PROJECT_SOURCE_DIR}/scripts/tsan.supp;OMP_NUM_THREADS=1")
  endif()
endif()
