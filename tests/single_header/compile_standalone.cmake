# cmake -P script behind the `single_header_standalone` test: compiles
# standalone_main.cpp + standalone_second.cpp against nothing but the single
# header, with HUSH_NO_GLM and -std=c++17 -Wall -Wextra -Werror -pedantic, then
# runs the program. Any failing step stops with its output.
#   -DCXX_COMPILER=...   the C++ compiler (GCC or Clang command line)
#   -DSINGLE_INCLUDE=... directory holding hush/hush.hpp (single_include/)
#   -DSOURCE_DIR=...     this directory (tests/single_header)
#   -DWORK_DIR=...       scratch directory, wiped first
foreach(var CXX_COMPILER SINGLE_INCLUDE SOURCE_DIR WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "compile_standalone.cmake: -D${var}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

set(program "${WORK_DIR}/single_header_standalone")
set(command "${CXX_COMPILER}" -std=c++17 -Wall -Wextra -Werror -pedantic -O2 -DHUSH_NO_GLM
    -I "${SINGLE_INCLUDE}" "${SOURCE_DIR}/standalone_main.cpp"
    "${SOURCE_DIR}/standalone_second.cpp" -o "${program}")
foreach(step compile run)
  if(step STREQUAL "run")
    set(command "${program}")
  endif()
  string(REPLACE ";" " " shown "${command}")
  message(STATUS "${step}: ${shown}")
  execute_process(COMMAND ${command} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(NOTICE "${out}")  # verbatim; FATAL_ERROR would re-wrap compiler output
    message(FATAL_ERROR "single header standalone ${step} failed (${rc}), output above:\n${shown}")
  endif()
  message(STATUS "${out}")
endforeach()
