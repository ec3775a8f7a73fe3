# cmake -DBUILD_DIR=<build tree> -DTARGET=<target> [-DCONFIG=<config>]
#       -DEXPECT=success|failure [-DMESSAGE=<text>] -P check_build.cmake
#
# Builds one target of the build tree. EXPECT=success: the build must succeed.
# EXPECT=failure: the build must fail and the first compiler error must contain MESSAGE (so the
# failure is the intended static_assert, not some other error).
cmake_minimum_required(VERSION 3.20)

set(config_args)
if(CONFIG)
  set(config_args --config ${CONFIG})
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target ${TARGET} ${config_args}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)

if(EXPECT STREQUAL "success")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${TARGET} should build but did not:\n${out}")
  endif()
  message(STATUS "${TARGET} builds")
elseif(EXPECT STREQUAL "failure")
  if(NOT MESSAGE)
    message(FATAL_ERROR "check_build.cmake: EXPECT=failure needs MESSAGE")
  endif()
  if(rc EQUAL 0)
    message(FATAL_ERROR "${TARGET} should not build but did:\n${out}")
  endif()
  string(REGEX MATCH "[^\n]*error( C[0-9]+)?:[^\n]*" first_error "${out}")
  string(FIND "${first_error}" "${MESSAGE}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${TARGET} failed to build, but its first error is not \"${MESSAGE}\":\n"
                        "${first_error}\n\nFull output:\n${out}")
  endif()
  message(STATUS "${TARGET} is rejected as expected:\n${first_error}")
else()
  message(FATAL_ERROR "check_build.cmake: EXPECT must be success or failure, not '${EXPECT}'")
endif()
