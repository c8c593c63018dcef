# The Python module's tests (python/tests/), one ctest entry per file, run by pytest against the
# module in the build tree (PYTHONPATH=build/python) with the interpreter it was built for.
# Label: python.
if(TARGET periflex_python)
  file(GLOB python_test_files CONFIGURE_DEPENDS "${PROJECT_SOURCE_DIR}/python/tests/test_*.py")
  foreach(file IN LISTS python_test_files)
    get_filename_component(name "${file}" NAME_WE)
    add_test(NAME python_${name}
             COMMAND ${Python3_EXECUTABLE} -m pytest -q -p no:cacheprovider "${file}"
             WORKING_DIRECTORY "${PROJECT_SOURCE_DIR}/python/tests")
    set_tests_properties(python_${name} PROPERTIES LABELS python TIMEOUT 300
      ENVIRONMENT "PYTHONPATH=${PROJECT_BINARY_DIR}/python;PERIFLEX_BINARY=$<TARGET_FILE:periflex>;OMP_WAIT_POLICY=passive")
  endforeach()
endif()
