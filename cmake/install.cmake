# Installation and the Debian package.
#   cmake --install build --prefix DIR   the program in DIR/bin, its shaders, colour maps and
#                                        scenes in DIR/share/periflex, the docs in DIR/share/doc/periflex
#   cpack -G DEB (in the build folder)   periflex_<version>_<arch>.deb of the same files
# The program finds share/periflex beside its own bin/ folder (src/core/resources.h), so the prefix
# can be moved after installation.
include(GNUInstallDirs)

install(TARGETS periflex RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY shaders assets scenes DESTINATION ${CMAKE_INSTALL_DATADIR}/periflex)
install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})

set(CPACK_PACKAGE_NAME periflex)
set(CPACK_PACKAGE_VENDOR "periflex")
set(CPACK_PACKAGE_CONTACT "periflex maintainers <periflex@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "flexible multibody dynamics in 2D with peridynamic bodies that crack")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# The shared libraries the program links are declared from the binary itself (dpkg-shlibdeps).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# What the program loads or runs without linking it: Mesa's drivers behind libglvnd draw off-screen
# and in the window; ffmpeg writes movies; gnuplot draws the plots of studies and sweeps.
if(PERIFLEX_WITH_GL)
  set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libegl-mesa0, libgl1-mesa-dri, ffmpeg, gnuplot-nox")
else()
  set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "gnuplot-nox")
endif()
# the Python module (lib/python3/dist-packages/periflex) needs an interpreter and NumPy
if(PERIFLEX_WITH_PYTHON)
  string(APPEND CPACK_DEBIAN_PACKAGE_RECOMMENDS ", python3, python3-numpy")
endif()
include(CPack)
