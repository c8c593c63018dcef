# Run by the source_line_limit test (tests/line_limit.cmake) with -DROOT=<project root>: fails
# naming every source, header or script under src/, tests/, bench/ and python/ longer than
# LIMIT lines (600 unless given). A file of one concept rarely needs more; a longer one is
# split along its concepts (docs/architecture.md). Data (scenes, golden files) is not counted.
if(NOT DEFINED LIMIT)
  set(LIMIT 600)
endif()
set(patterns "")
foreach(folder src tests bench python)
  foreach(ext cpp h hpp c cc py pyi sh cmake)
    list(APPEND patterns "${ROOT}/${folder}/*.${ext}")
  endforeach()
  list(APPEND patterns "${ROOT}/${folder}/CMakeLists.txt")
endforeach()
file(GLOB_RECURSE files ${patterns})

set(failures "")
set(checked 0)
foreach(f IN LISTS files)
  # what a build or an interpreter leaves inside these folders is not source
  file(RELATIVE_PATH shown "${ROOT}" "${f}")
  if(shown MATCHES "(^|/)(__pycache__|\\.pytest_cache|build[^/]*)/")
    continue()
  endif()
  math(EXPR checked "${checked} + 1")
  # lines as `wc -l` counts them: newline characters
  file(READ "${f}" text)
  string(REGEX MATCHALL "\n" newlines "${text}")
  list(LENGTH newlines lines)
  if(lines GREATER LIMIT)
    list(APPEND failures "${shown}: ${lines} lines")
  endif()
endforeach()

if(checked EQUAL 0)
  message(FATAL_ERROR "no source files found under ${ROOT}/{src,tests,bench,python}")
endif()
if(failures)
  list(JOIN failures "\n  " listed)
  message(FATAL_ERROR "files over ${LIMIT} lines (split them along their concepts):\n  ${listed}")
endif()
message(STATUS "${checked} files, none over ${LIMIT} lines")
