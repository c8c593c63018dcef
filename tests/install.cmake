# The installed program, as a user gets it: installed to a prefix, the prefix moved, the program
# run from another folder with no variable set (a run, a movie drawn off-screen, the window under
# Xvfb); and the Debian package built, inspected and unpacked the same way
# (tests/install/install_check.sh). Label: install.
find_program(PERIFLEX_DPKG_DEB dpkg-deb)
add_test(NAME install_moved_prefix
         COMMAND bash "${CMAKE_CURRENT_SOURCE_DIR}/install/install_check.sh" prefix "${CMAKE_BINARY_DIR}"
                 "${CMAKE_CURRENT_BINARY_DIR}/install_check")
set_tests_properties(install_moved_prefix PROPERTIES LABELS install TIMEOUT 300 RESOURCE_LOCK install_check)
if(PERIFLEX_DPKG_DEB)
  add_test(NAME install_debian_package
           COMMAND bash "${CMAKE_CURRENT_SOURCE_DIR}/install/install_check.sh" deb "${CMAKE_BINARY_DIR}"
                   "${CMAKE_CURRENT_BINARY_DIR}/install_check")
  set_tests_properties(install_debian_package PROPERTIES LABELS install TIMEOUT 600 RESOURCE_LOCK install_check)
endif()
