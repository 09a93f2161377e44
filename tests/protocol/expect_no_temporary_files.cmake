# Runs dfc_conformance against the fixture server, honest and broken (a failed
# check brings fresh server processes), with TMPDIR a folder of its own, and
# succeeds only if the checker leaves nothing there (before, a folder
# dfc-conformance-<pid> of checkpoint scratch files stayed in /tmp after every run).
#   cmake -DCHECKER=... -DSERVER=... -DCONFIG=section.json -DSCRATCH=folder -DLIMIT=seconds -P expect_no_temporary_files.cmake
file(REMOVE_RECURSE "${SCRATCH}")
file(MAKE_DIRECTORY "${SCRATCH}")
set(ENV{TMPDIR} "${SCRATCH}")
foreach(server_options IN ITEMS "" "--break throw")
  separate_arguments(options UNIX_COMMAND "${server_options}")
  execute_process(COMMAND ${CHECKER} --config ${CONFIG} -- ${SERVER} ${options}
                  OUTPUT_VARIABLE output ERROR_VARIABLE errors RESULT_VARIABLE status TIMEOUT ${LIMIT})
  if(NOT output MATCHES "\n[0-9]+ passed, [0-9]+ failed\n$")
    message(FATAL_ERROR "dfc_conformance against the fixture '${server_options}' did not finish (${status}):\n${output}${errors}")
  endif()
  file(GLOB_RECURSE left LIST_DIRECTORIES true "${SCRATCH}/*")
  if(left)
    message(FATAL_ERROR "dfc_conformance against the fixture '${server_options}' left in TMPDIR: ${left}")
  endif()
endforeach()
file(REMOVE_RECURSE "${SCRATCH}")
