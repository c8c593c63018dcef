# Warnings on, for every target of the project (not for dependencies).
add_compile_options(-Wall -Wextra -Wpedantic -Wshadow=local -Wno-unused-parameter)
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  # Eigen 3.4 trips these in GCC 12 for reasons outside our code.
  add_compile_options(-Wno-maybe-uninitialized -Wno-array-bounds -Wno-stringop-overflow)
endif()
