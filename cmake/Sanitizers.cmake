# DFC_SANITIZE: AddressSanitizer + UndefinedBehaviorSanitizer on every target
# of the project (libraries, servers, coupler, tests), for `./vc test --sanitize`
# (build folder build-sanitize; docs/fuzzing.md, "Sanitizer build").
#
# Set for the whole directory tree, before any target is added, rather than
# through an interface library: a target that forgot to link one would run
# uninstrumented, and the e2e tests start the real server executables, whose
# memory errors are the ones a coupled run would hit.
#
# -fno-sanitize-recover=all: a UBSan report ends the process with an error,
# so the test that reached it fails instead of printing a line nobody reads.
# float-cast-overflow is undefined behaviour (a double out of the integer's
# range, NaN included, converted to an integer) that g++'s "undefined" group
# leaves out. float-divide-by-zero stays off: IEEE 754 defines it (inf, NaN),
# and the solvers rely on that.
# Not together with DFC_FUZZ: the fuzz build instruments its own targets
# with clang's fuzzer runtime (fuzz/CMakeLists.txt).
option(DFC_SANITIZE "Build every target with AddressSanitizer and UBSan (./vc test --sanitize)" OFF)
if(DFC_SANITIZE)
  if(DFC_FUZZ)
    message(FATAL_ERROR "DFC_SANITIZE and DFC_FUZZ are separate builds: the fuzz build already uses AddressSanitizer and UBSan.")
  endif()
  set(DFC_SANITIZER_FLAGS -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all -fno-omit-frame-pointer)
  # -Wno-maybe-uninitialized: the instrumentation makes g++ 12 warn inside
  # libstdc++ (std::regex's std::function moves, seen in tests/coupler) where
  # the plain build does not; GCC's manual warns that sanitizers raise the rate
  # of such false positives. The everyday build keeps the warning.
  add_compile_options(${DFC_SANITIZER_FLAGS} $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
  add_link_options(${DFC_SANITIZER_FLAGS})
  message(STATUS "DFC_SANITIZE: every target built with ${DFC_SANITIZER_FLAGS}")
endif()

# Test time limits: AddressSanitizer makes the solvers several times slower
# (the FDM verification problems took over 120 s under it, 20-40 s without),
# so every ctest TIMEOUT is multiplied by DFC_TEST_TIMEOUT_SCALE:
#   dfc_test_timeout(OUT_VARIABLE SECONDS)
if(DFC_SANITIZE)
  set(DFC_TEST_TIMEOUT_SCALE 4)
else()
  set(DFC_TEST_TIMEOUT_SCALE 1)
endif()
function(dfc_test_timeout out seconds)
  math(EXPR scaled "${seconds} * ${DFC_TEST_TIMEOUT_SCALE}")
  set(${out} ${scaled} PARENT_SCOPE)
endfunction()
