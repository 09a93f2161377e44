# Runs dfc_conformance against a deliberately broken server and succeeds only
# if the checker caught it: non-zero exit status, a final "N passed, M failed"
# line with M > 0, and a line matching EXPECTED_FAILURE.
#   cmake -DCHECKER=... -DCHECKER_OPTIONS="..." -DSERVER=... -DSERVER_OPTIONS="..."
#         -DEXPECTED_FAILURE=regex -DLIMIT=seconds -P expect_conformance_failure.cmake
separate_arguments(checker_options UNIX_COMMAND "${CHECKER_OPTIONS}")
separate_arguments(server_options UNIX_COMMAND "${SERVER_OPTIONS}")
execute_process(COMMAND ${CHECKER} ${checker_options} -- ${SERVER} ${server_options}
                OUTPUT_VARIABLE output ERROR_VARIABLE errors RESULT_VARIABLE status TIMEOUT ${LIMIT})
message("${output}${errors}")
if(status EQUAL 0)
  message(FATAL_ERROR "dfc_conformance passed a server broken with '${SERVER_OPTIONS}' (exit status 0)")
endif()
if(NOT status MATCHES "^[0-9]+$")
  message(FATAL_ERROR "dfc_conformance did not finish normally: ${status}")
endif()
if(NOT output MATCHES "\n[0-9]+ passed, [1-9][0-9]* failed\n$")
  message(FATAL_ERROR "the last line is not 'N passed, M failed' with M > 0")
endif()
if(NOT output MATCHES "${EXPECTED_FAILURE}")
  message(FATAL_ERROR "no line matches '${EXPECTED_FAILURE}'")
endif()
