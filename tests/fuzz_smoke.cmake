# The test fuzz.smoke of the default build (tests/CMakeLists.txt): the
# libFuzzer harnesses of fuzz/, briefly. Configures BUILD_DIR with clang and
# DFC_FUZZ=ON, builds the fuzz targets only (not the solvers), and runs the
# fuzz build's own tests (label "fuzz": each fuzzer SECONDS on its seed corpus).
# The long run (10^6 executions each) is bench/fuzz.sh, on the same folder.
#
#   cmake -DSOURCE_DIR=... -DBUILD_DIR=... -DJOBS=2 -DSECONDS=45 -P fuzz_smoke.cmake
foreach(var SOURCE_DIR BUILD_DIR JOBS SECONDS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "fuzz_smoke.cmake: -D${var}=... is required")
  endif()
endforeach()

function(step what)
  string(TIMESTAMP start "%s")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
  string(TIMESTAMP end "%s")
  math(EXPR seconds "${end} - ${start}")
  if(NOT status EQUAL 0)
    message("${output}")
    message(FATAL_ERROR "fuzz.smoke: ${what} failed (${status}) after ${seconds} s")
  endif()
  message("fuzz.smoke: ${what}: ${seconds} s")
  set(step_output "${output}" PARENT_SCOPE)
endfunction()

step("configure ${BUILD_DIR}"
     ${CMAKE_COMMAND} -E env CC=clang CXX=clang++
     ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BUILD_DIR} -DDFC_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDFC_FUZZ_SECONDS=${SECONDS})
step("build the fuzzers" ${CMAKE_COMMAND} --build ${BUILD_DIR} --target dfc_fuzzers -j ${JOBS})
step("run each fuzzer ${SECONDS} s" ${CMAKE_CTEST_COMMAND} --test-dir ${BUILD_DIR} -L fuzz --output-on-failure)
message("${step_output}")
