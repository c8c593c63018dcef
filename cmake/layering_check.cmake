# Run by the layering_includes test (tests/layering.cmake) with -DSOURCE_DIR=<src>: fails naming
# every file that includes a header its layer must not.
set(solver_layers core scene mbs pd coupling contact model solve output)
set(gl_headers "GL/|GLFW/|EGL/|imgui|backends/imgui")
set(failures "")

function(check_folder folder pattern)
  file(GLOB_RECURSE files "${SOURCE_DIR}/${folder}/*.cpp" "${SOURCE_DIR}/${folder}/*.h")
  foreach(f IN LISTS files)
    file(STRINGS "${f}" hits REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"](${pattern})")
    foreach(h IN LISTS hits)
      string(STRIP "${h}" h)
      list(APPEND failures "${f}: ${h}")
    endforeach()
  endforeach()
  set(failures "${failures}" PARENT_SCOPE)
endfunction()

# the solver: no GL, and nothing from the layers above it
foreach(layer IN LISTS solver_layers)
  check_folder(${layer} "${gl_headers}|io/|study/|stability/|render/|headless/|app/|cli/")
endforeach()
# files without GL, below the tools and the renderer
check_folder(io "${gl_headers}|study/|stability/|render/|headless/|app/|cli/")
# the tools: no GL, no renderer
foreach(layer study stability)
  check_folder(${layer} "${gl_headers}|render/|headless/|app/|cli/")
endforeach()
# the GPU backend: no window, no panels, no renderer (it computes in the off-screen context)
check_folder(gpu "imgui|backends/imgui|render/renderer|app/|cli/")
# the renderer and the off-screen path draw without Dear ImGui (the window's panels only use it)
foreach(folder render headless)
  check_folder(${folder} "imgui|backends/imgui|app/|cli/")
endforeach()

# the floors inside the solver, lowest first; a folder includes its own floor's folders and the
# floors below, never one above (folders on one floor do not include each other either):
#   core     small math, errors, time functions
#   scene    TOML to definition structs
#   mbs      joints, drivers, force elements (built from definitions)
#   pd, coupling   peridynamic bodies; the rigid-flexible joint (a constraint of mbs)
#   contact  contact elements (of rigid shapes and of peridynamic particles)
#   model    the model built from all of the above, once
#   solve    the stepper: reads the model, owns the state, fills snapshots
#   output   checkpoint files, the run record, series.csv's columns (of the state and snapshots)
set(solver_floors "core" "scene" "mbs" "pd coupling" "contact" "model" "solve" "output")
set(above "")
list(REVERSE solver_floors)
foreach(floor IN LISTS solver_floors)
  string(REPLACE " " ";" folders "${floor}")
  # what this floor must not include: every floor above it, and its neighbours on the floor
  foreach(folder IN LISTS folders)
    set(forbidden ${above})
    foreach(neighbour IN LISTS folders)
      if(NOT neighbour STREQUAL folder)
        list(APPEND forbidden ${neighbour})
      endif()
    endforeach()
    if(forbidden)
      list(JOIN forbidden "/|" pattern)
      check_folder(${folder} "${pattern}/")
    endif()
  endforeach()
  list(APPEND above ${folders})
endforeach()

if(failures)
  list(JOIN failures "\n  " text)
  message(FATAL_ERROR "headers a layer must not include:\n  ${text}")
endif()
message(STATUS "layering: no forbidden include")
