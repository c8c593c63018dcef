# The layers' include rules, checked on the sources (cmake/layering_check.cmake): the solver
# library (src/core .. src/output) includes no OpenGL, GLFW, EGL or Dear ImGui header and nothing
# from the layers above it; inside it, a floor never includes a higher one (core < scene < mbs <
# pd, coupling < contact < model < solve < output); io and the tools (study, stability) no GL; the renderer and the
# off-screen path no Dear ImGui (overlay text is the renderer's own; ImGui draws the window's
# panels only, in src/app).
add_test(NAME layering_includes
         COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}/src
                 -P "${PROJECT_SOURCE_DIR}/cmake/layering_check.cmake")
set_tests_properties(layering_includes PROPERTIES LABELS core)
