# cmake -P driver of the package_* tests: builds tests/package/consumer, a
# separate project, against hush and runs it.
#   MODE=add_subdirectory  the consumer add_subdirectory()s the hush sources;
#   MODE=find_package      hush is configured fresh (tests, examples, benchmarks
#                          off), installed into a staging prefix, the prefix is
#                          moved (the package must be relocatable), and the
#                          consumer finds it with find_package(hush x.y CONFIG).
# Variables (-D): MODE, HUSH_SOURCE_DIR, CONSUMER_DIR, WORK_DIR (wiped first),
# GENERATOR, CXX_COMPILER; optional BUILD_TYPE, MAKE_PROGRAM, GENERATOR_PLATFORM,
# GENERATOR_TOOLSET. Any failing step stops the test with that step's output.
foreach(var MODE HUSH_SOURCE_DIR CONSUMER_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run_package_test.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT MODE MATCHES "^(add_subdirectory|find_package)$")
  message(FATAL_ERROR
          "run_package_test.cmake: MODE is add_subdirectory or find_package, not ${MODE}")
endif()

# The version, read from config.hpp as the top-level CMakeLists.txt does.
file(STRINGS "${HUSH_SOURCE_DIR}/include/hush/config.hpp" _line
     REGEX "^#define HUSH_VERSION_STRING \"[0-9.]+\"")
string(REGEX MATCH "[0-9]+\\.[0-9]+\\.[0-9]+" version "${_line}")
if(NOT version)
  message(FATAL_ERROR "no HUSH_VERSION_STRING in ${HUSH_SOURCE_DIR}/include/hush/config.hpp")
endif()

# Options every configure step shares: the outer build's generator and compiler.
set(configure_options -G "${GENERATOR}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
foreach(pair "GENERATOR_PLATFORM;-A" "GENERATOR_TOOLSET;-T")
  list(GET pair 0 var)
  list(GET pair 1 flag)
  if(${var})
    list(APPEND configure_options ${flag} "${${var}}")
  endif()
endforeach()
if(MAKE_PROGRAM)
  list(APPEND configure_options "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}")
endif()
set(config_options "")
if(BUILD_TYPE)
  list(APPEND configure_options "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}")
  set(config_options --config "${BUILD_TYPE}")
endif()

# run_step(NAME COMMAND...): runs a command, stops the test with its output on failure.
function(run_step name)
  string(REPLACE ";" " " shown "${ARGN}")
  message(STATUS "[${MODE}] ${name}: ${shown}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(NOTICE "${out}")  # verbatim; FATAL_ERROR would re-wrap compiler output
    message(FATAL_ERROR "[${MODE}] step '${name}' failed (${rc}), output above:\n${shown}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(consumer_build "${WORK_DIR}/consumer-build")
set(consumer_options -DHUSH_CONSUMER_MODE=${MODE} -DHUSH_EXPECTED_VERSION=${version})

if(MODE STREQUAL "add_subdirectory")
  list(APPEND consumer_options "-DHUSH_SOURCE_DIR=${HUSH_SOURCE_DIR}")
else()
  set(hush_build "${WORK_DIR}/hush-build")
  set(stage "${WORK_DIR}/stage")
  set(prefix "${WORK_DIR}/prefix")
  run_step("configure hush" "${CMAKE_COMMAND}" -S "${HUSH_SOURCE_DIR}" -B "${hush_build}"
           ${configure_options} -DHUSH_BUILD_TESTS=OFF -DHUSH_BUILD_EXAMPLES=OFF
           -DHUSH_BUILD_BENCH=OFF -DHUSH_INSTALL=ON)
  run_step("build hush" "${CMAKE_COMMAND}" --build "${hush_build}" ${config_options})
  run_step("install hush" "${CMAKE_COMMAND}" --install "${hush_build}" --prefix "${stage}"
           ${config_options})
  # Consumers must not depend on where the package was installed.
  file(RENAME "${stage}" "${prefix}")
  file(GLOB_RECURSE package_files RELATIVE "${prefix}" "${prefix}/*.cmake")
  foreach(required include/hush/hush.hpp include/hush/config.hpp)
    if(NOT EXISTS "${prefix}/${required}")
      message(FATAL_ERROR "[${MODE}] ${required} was not installed")
    endif()
  endforeach()
  foreach(required hushConfig.cmake hushConfigVersion.cmake hushTargets.cmake)
    if(NOT package_files MATCHES "(^|;)[^;]*/${required}(;|$)")
      message(FATAL_ERROR "[${MODE}] ${required} was not installed; installed: ${package_files}")
    endif()
  endforeach()
  list(APPEND consumer_options "-DCMAKE_PREFIX_PATH=${prefix}" "-DHUSH_EXPECTED_PREFIX=${prefix}"
       -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
endif()

run_step("configure consumer" "${CMAKE_COMMAND}" -S "${CONSUMER_DIR}" -B "${consumer_build}"
         ${configure_options} ${consumer_options})
run_step("build consumer" "${CMAKE_COMMAND}" --build "${consumer_build}" ${config_options})
file(GLOB program "${consumer_build}/bin/hush_consumer" "${consumer_build}/bin/hush_consumer.exe")
if(NOT program)
  message(FATAL_ERROR "[${MODE}] no hush_consumer program in ${consumer_build}/bin")
endif()
run_step("run consumer" ${program})
message(STATUS "[${MODE}] ${step_output}")
