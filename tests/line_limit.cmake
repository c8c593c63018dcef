# No source file over 600 lines: every source, header and script under src/, tests/, bench/ and
# python/ is counted on each run (cmake/line_limit_check.cmake), and the test names any file
# above the limit.
add_test(NAME source_line_limit
         COMMAND ${CMAKE_COMMAND} -DROOT=${PROJECT_SOURCE_DIR} -P "${PROJECT_SOURCE_DIR}/cmake/line_limit_check.cmake")
set_tests_properties(source_line_limit PROPERTIES LABELS core)
