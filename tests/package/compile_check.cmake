# cmake -P driver of the consumer_* tests: compiles one source file the way a user would
# (a compiler command line, no CMake target), then checks what the compiler said and, when
# asked, runs the program and checks what it printed.
# Variables (-D):
#   CXX_COMPILER  the C++ compiler (GCC or Clang command line)
#   SOURCE        the .cpp file
#   FLAGS         compiler flags, a ;-list (include paths, -D..., -W..., -march=...)
#   WORK_DIR      scratch directory, wiped first
#   LINK          ON: compile and link (FLAGS may end with libraries) and run the program;
#                 otherwise compile only (-c)
#   EXPECT        optional regex the compiler's output must match
#   FORBID        optional regex the compiler's output must not match
#   EXPECT_RUN    optional regex the program's output must match (LINK ON)
# The compile and the run must succeed; any failed check stops the test with the output.
foreach(var CXX_COMPILER SOURCE WORK_DIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "compile_check.cmake: -D${var}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

set(program "${WORK_DIR}/program")
if(LINK)
  set(command "${CXX_COMPILER}" "${SOURCE}" -o "${program}" ${FLAGS})
else()
  set(command "${CXX_COMPILER}" -c "${SOURCE}" -o "${WORK_DIR}/object.o" ${FLAGS})
endif()
string(REPLACE ";" " " shown "${command}")
message(STATUS "compile: ${shown}")
execute_process(COMMAND ${command} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message(NOTICE "${out}")  # verbatim: the diagnostics are what is checked
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "compile failed (${rc}), output above:\n${shown}")
endif()
if(DEFINED EXPECT AND NOT out MATCHES "${EXPECT}")
  message(FATAL_ERROR "the compiler's output does not say '${EXPECT}':\n${shown}")
endif()
if(DEFINED FORBID AND out MATCHES "${FORBID}")
  message(FATAL_ERROR "the compiler's output says '${FORBID}':\n${shown}")
endif()
if(LINK)
  execute_process(COMMAND "${program}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  message(STATUS "run: ${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the program failed (${rc})")
  endif()
  if(DEFINED EXPECT_RUN AND NOT out MATCHES "${EXPECT_RUN}")
    message(FATAL_ERROR "the program's output does not say '${EXPECT_RUN}'")
  endif()
endif()
