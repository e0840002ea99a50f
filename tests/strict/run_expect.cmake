# cmake -P script behind the error_handler_* tests: runs PROGRAM MODE and checks how it ended.
#   -DPROGRAM=...      the program (error_handler_test)
#   -DMODE=...         its argument
#   -DEXPECT_RC=...    the exit code, or "abort" for a process ended by SIGABRT
#   -DEXPECT_OUTPUT=...  a regular expression its stderr must match
foreach(var PROGRAM MODE EXPECT_RC EXPECT_OUTPUT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_expect.cmake: -D${var}=... is required")
  endif()
endforeach()
execute_process(COMMAND "${PROGRAM}" "${MODE}" RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
message(STATUS "${PROGRAM} ${MODE}: result [${rc}], stderr:\n${err}")
if(EXPECT_RC STREQUAL "abort")
  # CMake reports a process ended by a signal as text ("Subprocess aborted"), not a number.
  if(NOT rc MATCHES "abort")
    message(FATAL_ERROR "expected the program to abort, got result [${rc}]")
  endif()
elseif(NOT rc STREQUAL EXPECT_RC)
  message(FATAL_ERROR "expected exit code ${EXPECT_RC}, got [${rc}]")
endif()
if(NOT err MATCHES "${EXPECT_OUTPUT}")
  message(FATAL_ERROR "stderr does not match: ${EXPECT_OUTPUT}")
endif()
