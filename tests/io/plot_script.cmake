# Runs scripts/grain_plot.py on a CSV history and on the 2D VTK series of vtk_readback, and checks
# that every picture is written (a PNG or GIF signature, not empty).
# cmake -DPYTHON=<python3> -DSCRIPT=<grain_plot.py> -DINPUT_DIR=<vtk_readback dir>
#       -DOUTPUT_DIR=<scratch> -P plot_script.cmake
file(REMOVE_RECURSE "${OUTPUT_DIR}")
file(MAKE_DIRECTORY "${OUTPUT_DIR}")
file(WRITE "${OUTPUT_DIR}/history.csv"
     "time [s],step,kinetic_energy [J],mean_temperature [K]\n0,0,1.0,300\n0.1,10,0.5,310\n0.2,20,0.25,315\n")
if(NOT EXISTS "${INPUT_DIR}/disks_particles_000000.vtk")
  message(FATAL_ERROR "plot_script: no ${INPUT_DIR}/disks_particles_000000.vtk (vtk_readback "
                      "writes it)")
endif()
# one run per element, its arguments separated by "|"
set(runs
    "history|${OUTPUT_DIR}/history.csv|-o|${OUTPUT_DIR}/history.png"
    "history|${OUTPUT_DIR}/history.csv|-y|mean_temperature|-x|kinetic_energy|-o|${OUTPUT_DIR}/xy.png"
    "disks|${INPUT_DIR}/disks_particles_000000.vtk|-f|velocity|-o|${OUTPUT_DIR}/disks.png"
    "animate|${INPUT_DIR}/disks|-f|omega|-o|${OUTPUT_DIR}/disks.gif")
set(outputs history.png xy.png disks.png disks.gif)
foreach(run IN LISTS runs)
  string(REPLACE "|" ";" args "${run}")
  execute_process(COMMAND "${PYTHON}" "${SCRIPT}" ${args} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "plot_script: grain_plot.py ${args} failed (${rc})")
  endif()
endforeach()
foreach(out IN LISTS outputs)
  set(path "${OUTPUT_DIR}/${out}")
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "plot_script: ${path} was not written")
  endif()
  file(READ "${path}" head LIMIT 4 HEX)
  if(NOT head MATCHES "^(89504e47|47494638)")
    message(FATAL_ERROR "plot_script: ${path} is not a PNG or GIF (starts with ${head})")
  endif()
endforeach()
message(STATUS "plot_script: ${outputs} written")
