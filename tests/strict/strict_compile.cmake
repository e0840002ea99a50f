# cmake -P script behind the strict_warnings_* and no_exceptions_* tests: checks that hush's headers
# compile cleanly under the warning flags a strict consumer uses, with hush on the include path
# as ordinary headers (-I, not -isystem, so hush's own warnings count):
#   -std=c++STD -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion -Werror
# It compiles each example (examples/*.cpp) with -fsyntax-only: the conversion and shadowing
# warnings come from the front end, which -fsyntax-only runs in full, templates instantiated
# (GCC and Clang both report them so; a full g++ -O2 -c of basic_usage reports nothing more),
# and skipping code generation keeps the test short.
#   -DCXX_COMPILER=...  the compiler (g++ or clang++ command line)
#   -DSTD=17|20         the language standard
#   -DTREE=include|single  hush through the vendored include/ tree, or through the single
#                       header (single_include/ first on the path; the GLSL backend's headers
#                       still find the core headers they name in include/, which the single
#                       header's include guards make empty)
#   -DSOURCE_DIR=...    hush's source tree
#   -DEXTRA_FLAGS=...   more flags, ;-separated (e.g. -fno-exceptions)
#   -DHAVE_HWY=ON       compile batch_simd, and gabor_usage with HUSH_SIMD_DYNAMIC (as hush::simd's
#                       users do); -DHWY_INCLUDE_DIR=... Highway's include directory (-isystem)
#   -DHAVE_OSMESA=ON    compile glsl_headless and shader_*; -DOSMESA_INCLUDE_DIR=... GL/osmesa.h's
#                       directory
#                       (-isystem)
foreach(var CXX_COMPILER STD TREE SOURCE_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "strict_compile.cmake: -D${var}=... is required")
  endif()
endforeach()

set(flags -std=c++${STD} -fsyntax-only -Wall -Wextra -Wpedantic -Wshadow -Wconversion
          -Wsign-conversion -Werror ${EXTRA_FLAGS})
if(TREE STREQUAL "single")
  list(APPEND flags -I${SOURCE_DIR}/single_include)
endif()
list(APPEND flags -I${SOURCE_DIR}/backends/glsl/include -I${SOURCE_DIR}/include)
# Third-party headers: -isystem, so that their warnings do not count. A directory the compiler
# searches anyway (/usr/include) is left off: -isystem on it reorders the standard headers.
foreach(dir IN ITEMS ${HWY_INCLUDE_DIR} ${OSMESA_INCLUDE_DIR})
  if(NOT dir STREQUAL "/usr/include")
    list(APPEND flags -isystem ${dir})
  endif()
endforeach()

set(examples basic_usage gabor_usage anisotropic_surface coherent_stream)
if(HAVE_HWY)
  list(APPEND examples batch_simd)
endif()
if(HAVE_OSMESA)
  # glsl_headless and the shader_<noise> programs (each noise's kit in the user's own shader).
  file(GLOB _shader_examples RELATIVE ${SOURCE_DIR}/examples ${SOURCE_DIR}/examples/shader_*.cpp)
  string(REPLACE ".cpp" "" _shader_examples "${_shader_examples}")
  list(APPEND examples glsl_headless ${_shader_examples})
endif()
set(failed "")
foreach(example IN LISTS examples)
  set(defines "")
  if(HAVE_HWY AND example MATCHES "^(batch_simd|gabor_usage)$")
    set(defines -DHUSH_SIMD_DYNAMIC)  # as hush::simd's consumers compile
  elseif(example MATCHES "^shader_")
    set(defines -DHUSH_GLSL_HAVE_OSMESA=1)  # as hush::glsl_headless's consumers compile
  endif()
  set(command "${CXX_COMPILER}" ${flags} ${defines} "${SOURCE_DIR}/examples/${example}.cpp")
  string(REPLACE ";" " " shown "${command}")
  execute_process(COMMAND ${command} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(rc EQUAL 0)
    message(STATUS "ok: ${example}")
  else()
    message(NOTICE "${shown}\n${out}")  # verbatim; FATAL_ERROR would re-wrap compiler output
    list(APPEND failed ${example})
  endif()
endforeach()
if(failed)
  message(FATAL_ERROR "warnings or errors under strict flags (output above): ${failed}")
endif()
