# cmake -P driver of the package_* tests: installs hush, or builds a consumer (a separate
# project: CONSUMER_DIR) against hush and runs it.
#   MODE=install           installs hush's build tree HUSH_BUILD_DIR (what its build compiled,
#                          hush::simd included) into a staging prefix and moves it to PREFIX
#                          (wiped first; the package must be relocatable). The others with
#                          PREFIX need this done (a CTest fixture).
#   MODE=add_subdirectory  the consumer add_subdirectory()s the hush sources;
#   MODE=find_package      the consumer finds the package in PREFIX with
#                          find_package(hush x.y CONFIG) (and COMPONENTS simd when
#                          CONSUMER_SIMD is ON);
#   MODE=header_only       the same with Highway unfindable
#                          (-DCMAKE_DISABLE_FIND_PACKAGE_hwy=ON): hush::hush must be found and
#                          work, and asking for simd must fail saying why;
#   MODE=glsl              the consumer (consumer_glsl/) finds the GLSL backend in PREFIX with
#                          find_package(hush CONFIG COMPONENTS glsl glsl_headless).
#   MODE=minimal           hush is configured fresh without its optional parts (no Highway, no
#                          OSMesa or EGL; tests, examples, benchmarks off), installed into its
#                          own prefix under WORK_DIR, and consumer/ checks that asking for
#                          a component this hush was built without fails saying so.
# Variables (-D): MODE, HUSH_SOURCE_DIR, WORK_DIR (wiped first), GENERATOR, CXX_COMPILER;
# CONSUMER_DIR and CONSUMER_PROGRAM except for install; HUSH_BUILD_DIR for install; PREFIX
# except for add_subdirectory; optional BUILD_TYPE, MAKE_PROGRAM, GENERATOR_PLATFORM,
# GENERATOR_TOOLSET, CONSUMER_SIMD. Any failing step stops the test with that step's output.
cmake_minimum_required(VERSION 3.16)  # IN_LIST, as in the projects it drives
set(_modes add_subdirectory install find_package header_only glsl minimal)
if(NOT MODE IN_LIST _modes)
  string(REPLACE ";" ", " _modes "${_modes}")
  message(FATAL_ERROR "run_package_test.cmake: MODE is one of ${_modes}, not '${MODE}'")
endif()
set(_required MODE HUSH_SOURCE_DIR WORK_DIR GENERATOR CXX_COMPILER)
if(MODE STREQUAL "install")
  list(APPEND _required HUSH_BUILD_DIR PREFIX)
else()
  list(APPEND _required CONSUMER_DIR CONSUMER_PROGRAM)
  if(NOT MODE MATCHES "^(add_subdirectory|minimal)$")
    list(APPEND _required PREFIX)
  endif()
endif()
foreach(var IN LISTS _required)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run_package_test.cmake: -D${var}=... is required for MODE=${MODE}")
  endif()
endforeach()

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

if(MODE STREQUAL "install")
  set(stage "${WORK_DIR}/stage")
  file(REMOVE_RECURSE "${PREFIX}")
  run_step("install hush" "${CMAKE_COMMAND}" --install "${HUSH_BUILD_DIR}" --prefix "${stage}"
           ${config_options})
  # Consumers must not depend on where the package was installed.
  file(RENAME "${stage}" "${PREFIX}")
  file(GLOB_RECURSE package_files RELATIVE "${PREFIX}" "${PREFIX}/*.cmake")
  # The core's headers and the GLSL backend's (hush/glsl/, its per-noise folders too).
  foreach(required hush/hush.hpp hush/config.hpp hush/glsl/device.hpp hush/glsl/headless.hpp
                   hush/glsl/perlin)
    if(NOT EXISTS "${PREFIX}/include/${required}")
      message(FATAL_ERROR "[${MODE}] include/${required} was not installed")
    endif()
  endforeach()
  foreach(required hushConfig.cmake hushConfigVersion.cmake hushTargets.cmake
                   hushGLLibraries.cmake hush_glslTargets.cmake)
    if(NOT package_files MATCHES "(^|;)[^;]*/${required}(;|$)")
      message(FATAL_ERROR "[${MODE}] ${required} was not installed; installed: ${package_files}")
    endif()
  endforeach()
  message(STATUS "[${MODE}] hush installed in ${PREFIX}")
  return()
endif()

if(MODE STREQUAL "minimal")
  set(hush_build "${WORK_DIR}/hush-build")
  set(PREFIX "${WORK_DIR}/prefix")
  run_step("configure hush" "${CMAKE_COMMAND}" -S "${HUSH_SOURCE_DIR}" -B "${hush_build}"
           ${configure_options} -DHUSH_BUILD_TESTS=OFF -DHUSH_BUILD_EXAMPLES=OFF
           -DHUSH_BUILD_BENCH=OFF -DHUSH_INSTALL=ON -DCMAKE_DISABLE_FIND_PACKAGE_hwy=ON
           -DHUSH_WITH_OSMESA=OFF -DHUSH_WITH_EGL=OFF)
  run_step("build hush" "${CMAKE_COMMAND}" --build "${hush_build}" ${config_options})
  run_step("install hush" "${CMAKE_COMMAND}" --install "${hush_build}" --prefix "${PREFIX}"
           ${config_options})
endif()

set(consumer_build "${WORK_DIR}/consumer-build")
if(MODE STREQUAL "add_subdirectory")
  set(consumer_options -DHUSH_CONSUMER_MODE=add_subdirectory -DHUSH_EXPECTED_VERSION=${version}
      "-DHUSH_SOURCE_DIR=${HUSH_SOURCE_DIR}")
else()
  if(NOT EXISTS "${PREFIX}/include/hush/hush.hpp")
    message(FATAL_ERROR "[${MODE}] no hush installed in ${PREFIX}: run the package_install test")
  endif()
  set(consumer_options "-DCMAKE_PREFIX_PATH=${PREFIX}" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
  if(NOT MODE STREQUAL "glsl")  # consumer/: the version and where the headers come from
    list(APPEND consumer_options -DHUSH_CONSUMER_MODE=find_package
         -DHUSH_EXPECTED_VERSION=${version} "-DHUSH_EXPECTED_PREFIX=${PREFIX}")
  endif()
  if(MODE STREQUAL "header_only")
    list(APPEND consumer_options -DCMAKE_DISABLE_FIND_PACKAGE_hwy=ON -DHUSH_CONSUMER_NO_HWY=ON)
  elseif(MODE STREQUAL "minimal")
    list(APPEND consumer_options -DHUSH_CONSUMER_MINIMAL=ON)
  elseif(MODE STREQUAL "find_package" AND CONSUMER_SIMD)
    list(APPEND consumer_options -DHUSH_CONSUMER_SIMD=ON)
  endif()
endif()

run_step("configure consumer" "${CMAKE_COMMAND}" -S "${CONSUMER_DIR}" -B "${consumer_build}"
         ${configure_options} ${consumer_options})
run_step("build consumer" "${CMAKE_COMMAND}" --build "${consumer_build}" ${config_options})
file(GLOB program "${consumer_build}/bin/${CONSUMER_PROGRAM}"
     "${consumer_build}/bin/${CONSUMER_PROGRAM}.exe")
if(NOT program)
  message(FATAL_ERROR "[${MODE}] no ${CONSUMER_PROGRAM} program in ${consumer_build}/bin")
endif()
run_step("run consumer" ${program})
message(STATUS "[${MODE}] ${step_output}")
