# Runs scripts/grain_plot.py on CSV histories (graphs of one history, and two histories in one
# graph), on the 2D VTK series of vtk_readback and on its 3D sphere files, and checks that every
# picture is written (a PNG or GIF signature, not empty); the graph of two histories and the 3D
# pictures (POV-Ray and the matplotlib fallback) must also have the expected size and not be
# blank, and the 3D pictures must be drawn by the renderer asked for.
# cmake -DPYTHON=<python3> -DSCRIPT=<grain_plot.py> -DINPUT_DIR=<vtk_readback dir>
#       -DOUTPUT_DIR=<scratch> [-DPOVRAY=<povray or empty>] -P plot_script.cmake
file(REMOVE_RECURSE "${OUTPUT_DIR}")
file(MAKE_DIRECTORY "${OUTPUT_DIR}")
file(WRITE "${OUTPUT_DIR}/history.csv"
     "time [s],step,kinetic_energy [J],mean_temperature [K]\n0,0,1.0,300\n0.1,10,0.5,310\n0.2,20,0.25,315\n")
file(WRITE "${OUTPUT_DIR}/history2.csv"
     "time [s],step,mean_temperature [K]\n0,0,300\n0.05,5,302\n0.1,10,305\n0.2,20,309\n")
if(NOT EXISTS "${INPUT_DIR}/disks_particles_000000.vtk")
  message(FATAL_ERROR "plot_script: no ${INPUT_DIR}/disks_particles_000000.vtk (vtk_readback "
                      "writes it)")
endif()
# the last frame of the 3D thermal spheres, ASCII and binary
foreach(series spheres spheres_binary)
  file(GLOB frames "${INPUT_DIR}/${series}_particles_[0-9][0-9][0-9][0-9][0-9][0-9].vtk")
  list(SORT frames)
  list(LENGTH frames n)
  if(n EQUAL 0)
    message(FATAL_ERROR "plot_script: no ${INPUT_DIR}/${series}_particles_NNNNNN.vtk "
                        "(vtk_readback writes them)")
  endif()
  list(GET frames -1 ${series}_last)
endforeach()
# one run per element, its arguments separated by "|"
set(runs
    "history|${OUTPUT_DIR}/history.csv|-o|${OUTPUT_DIR}/history.png"
    "history|${OUTPUT_DIR}/history.csv|-y|mean_temperature|-x|kinetic_energy|-o|${OUTPUT_DIR}/xy.png"
    "disks|${INPUT_DIR}/disks_particles_000000.vtk|-f|velocity|-o|${OUTPUT_DIR}/disks.png"
    "disks|${INPUT_DIR}/disks_binary_particles_000000.vtk|-f|velocity|-o|${OUTPUT_DIR}/disks_binary.png"
    "animate|${INPUT_DIR}/disks|-f|omega|-o|${OUTPUT_DIR}/disks.gif"
    "animate|${INPUT_DIR}/disks|-f|velocity:x|--range|-1|1|--title|options|--window|-0.08|0.06|-0.06|0.1|--ids|--markers|--arrows|velocity|--wall-field|temperature|-o|${OUTPUT_DIR}/disks_options.gif"
    "lines|${OUTPUT_DIR}/history.csv|${OUTPUT_DIR}/history2.csv|-y|mean_temperature|--label|O'Brien|--label|pipe|--title|two runs|-o|${OUTPUT_DIR}/lines.png")
set(outputs history.png xy.png disks.png disks_binary.png disks.gif disks_options.gif lines.png)
foreach(run IN LISTS runs)
  string(REPLACE "|" ";" args "${run}")
  execute_process(COMMAND "${PYTHON}" "${SCRIPT}" ${args} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "plot_script: grain_plot.py ${args} failed (${rc})")
  endif()
endforeach()
# a view window whose limits are not in order is refused with a message
execute_process(COMMAND "${PYTHON}" "${SCRIPT}" animate "${INPUT_DIR}/disks" --window 1 0 0 1
                        -o "${OUTPUT_DIR}/bad.gif" RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "XMIN < XMAX")
  message(FATAL_ERROR "plot_script: animate --window 1 0 0 1 was not refused (${rc}: ${err})")
endif()
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

# 3D pictures: "renderer|width|height|arguments of grain_plot.py spheres separated by |"
set(pictures
    "matplotlib|300|200|${spheres_binary_last}|-f|velocity|--view|30,20|--renderer|matplotlib"
    "matplotlib|320|240|${spheres_last}|-f|orientation|--renderer|matplotlib")
if(POVRAY)
  list(APPEND pictures
       "povray|320|240|${spheres_last}|-f|temperature|--renderer|povray"
       "povray|301|233|${spheres_binary_last}|-f|velocity:z|--view|top|--renderer|povray")
else()
  message(STATUS "plot_script: povray not found (Debian package povray): the POV-Ray pictures "
                 "are not checked")
endif()
# the size, and a picture that is more than a colour bar on a plain background: many colours,
# also in the part left of the colour bar
set(check [=[
import sys
import matplotlib.image as mpimg
bad = 0
for path, width, height in zip(*[iter(sys.argv[1:])] * 3):
    width, height = int(width), int(height)
    rgb = mpimg.imread(path)[:, :, :3]
    if rgb.shape[:2] != (height, width):
        print(f"{path}: {rgb.shape[1]}x{rgb.shape[0]} pixels, expected {width}x{height}")
        bad += 1
        continue
    for part, pixels in (("picture", rgb), ("scene", rgb[:, : width * 3 // 5])):
        colours = len({tuple(p) for p in (pixels.reshape(-1, 3) * 255).round().astype(int)})
        if colours < 20:
            print(f"{path}: its {part} has {colours} colours: blank")
            bad += 1
sys.exit(bad > 0)
]=])
# the graph of several histories (lines): 960x600 pixels and more than a blank frame
set(checked "${OUTPUT_DIR}/lines.png" 960 600)
set(k 0)
foreach(picture IN LISTS pictures)
  string(REPLACE "|" ";" args "${picture}")
  list(POP_FRONT args renderer width height)
  math(EXPR k "${k} + 1")
  set(path "${OUTPUT_DIR}/spheres${k}_${renderer}.png")
  execute_process(COMMAND "${PYTHON}" "${SCRIPT}" spheres ${args} --size ${width}x${height}
                          -o "${path}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "plot_script: grain_plot.py spheres ${args} failed (${rc})")
  endif()
  if(NOT out MATCHES "drawn by ${renderer} in")
    message(FATAL_ERROR "plot_script: grain_plot.py spheres ${args}: not drawn by ${renderer}:\n${out}")
  endif()
  list(APPEND checked "${path}" ${width} ${height})
  list(APPEND outputs "spheres${k}_${renderer}.png")
  string(REGEX MATCH "in [0-9.]+ s" took "${out}")
  message(STATUS "plot_script: spheres${k}_${renderer}.png drawn ${took}")
endforeach()
execute_process(COMMAND "${PYTHON}" -c "${check}" ${checked} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "plot_script: a graph or 3D picture has the wrong size or is blank")
endif()

# an empty group has no spheres to draw: an error (status 2), no picture
execute_process(COMMAND "${PYTHON}" "${SCRIPT}" spheres
                        "${INPUT_DIR}/spheres_empty_particles_000000.vtk"
                        -o "${OUTPUT_DIR}/empty.png"
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 2 OR EXISTS "${OUTPUT_DIR}/empty.png")
  message(FATAL_ERROR "plot_script: grain_plot.py spheres of an empty file: status ${rc}, "
                      "expected 2 and no picture")
endif()
# lines with one label for two files: an error (status 2), no graph
execute_process(COMMAND "${PYTHON}" "${SCRIPT}" lines "${OUTPUT_DIR}/history.csv"
                        "${OUTPUT_DIR}/history2.csv" -y mean_temperature --label one
                        -o "${OUTPUT_DIR}/one_label.png"
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 2 OR EXISTS "${OUTPUT_DIR}/one_label.png")
  message(FATAL_ERROR "plot_script: grain_plot.py lines with one label for two files: status "
                      "${rc}, expected 2 and no graph")
endif()
message(STATUS "plot_script: ${outputs} written")
