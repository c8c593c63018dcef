# Every shipped scene, cut short, run by the program as typed at one and two threads: series.csv
# and the VTK files must equal, byte for byte, the ones kept in tests/golden/series/ (written by
# scripts/make-golden-series.sh, and rewritten only when the physics changes on purpose). A move
# of code changes no bit of any result; on a difference the test names the run, the file and the
# first differing row and column.
# The golden bits are those of the Release build on an AVX2 machine: a sanitizer build's other
# optimisation level may round differently, so it does not run there.
if(PERIFLEX_SANITIZE)
  return()
endif()
add_test(NAME series_golden
         COMMAND bash "${PROJECT_SOURCE_DIR}/tests/golden/series/check_series.sh" "$<TARGET_FILE:periflex>"
                 "${CMAKE_CURRENT_BINARY_DIR}/series_golden")
set_tests_properties(series_golden PROPERTIES LABELS "solve;scenes" TIMEOUT 600)
