# Runs the vtk_readback test: write the files, then read them back.
# cmake -DWRITER=<grain_write_vtk> -DPYTHON=<python3 with vtk> -DCHECKER=<read_vtk.py>
#       -DOUTPUT_DIR=<scratch directory> -P vtk_readback.cmake
foreach(var WRITER PYTHON CHECKER OUTPUT_DIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "vtk_readback: -D${var}=... is required")
  endif()
endforeach()

# start from an empty directory so that files of an earlier run cannot be counted
file(REMOVE_RECURSE "${OUTPUT_DIR}")

execute_process(COMMAND "${WRITER}" "${OUTPUT_DIR}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "vtk_readback: writing the VTK files failed (${WRITER}: ${rc})")
endif()

execute_process(COMMAND "${PYTHON}" "${CHECKER}" "${OUTPUT_DIR}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "vtk_readback: the VTK files read back do not match the simulation "
                      "(${CHECKER}: ${rc})")
endif()
