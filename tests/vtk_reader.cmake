# The VTK snapshots of a run read by VTK's own Python readers (tests/io/vtk_reader_check.py),
# the way ParaView reads them. Skipped (exit 77) when python3-vtk9 is not installed: it is a large
# package, so the project's dependencies do not include it.
find_program(PERIFLEX_SYSTEM_PYTHON NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(PERIFLEX_SYSTEM_PYTHON)
  add_test(NAME vtk_reader_check
           COMMAND ${PERIFLEX_SYSTEM_PYTHON} "${CMAKE_CURRENT_SOURCE_DIR}/io/vtk_reader_check.py"
                   $<TARGET_FILE:periflex> "${PROJECT_SOURCE_DIR}/scenes/flexible_pendulum.toml"
                   "${CMAKE_CURRENT_BINARY_DIR}/vtk_reader_check")
  set_tests_properties(vtk_reader_check PROPERTIES LABELS io SKIP_RETURN_CODE 77 TIMEOUT 120)
endif()
