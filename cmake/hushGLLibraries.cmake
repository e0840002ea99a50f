# The system libraries behind the GLSL backend's headless contexts, as imported targets:
#   hush::OSMesa  libOSMesa and GL/osmesa.h (hush::glsl_osmesa: llvmpipe)
#   hush::EGL     libEGL and EGL/egl.h      (hush::glsl_egl: a machine's GPU)
# Used twice, so the two agree: by hush's build (backends/glsl/CMakeLists.txt), and by the
# installed package (hushConfig.cmake), which finds them again on the consumer's machine when
# the component that needs them is asked for. The cache variables HUSH_<KIND>_LIBRARY and
# HUSH_<KIND>_INCLUDE_DIR (KIND OSMESA or EGL) hold what was found and may be set to override.

# hush_import_gl_library(KIND FOUND_VAR [GLOBAL]): KIND is osmesa or egl. Sets FOUND_VAR to TRUE
# and defines the imported target (once) when both the library and its header are found, else
# FALSE. GLOBAL makes the target visible in every directory (hush's own build, where tests in other
# directories link it); a package's imported targets are local to the directory that found it.
function(hush_import_gl_library kind found_var)
  if(kind STREQUAL "osmesa")
    set(library OSMesa)
    set(header GL/osmesa.h)
  elseif(kind STREQUAL "egl")
    set(library EGL)
    set(header EGL/egl.h)
  else()
    message(FATAL_ERROR "hush_import_gl_library: KIND is osmesa or egl, not '${kind}'")
  endif()
  string(TOUPPER ${kind} upper)
  set(target hush::${library})
  if(TARGET ${target})
    set(${found_var} TRUE PARENT_SCOPE)
    return()
  endif()
  find_library(HUSH_${upper}_LIBRARY NAMES ${library})
  find_path(HUSH_${upper}_INCLUDE_DIR ${header})
  if(NOT HUSH_${upper}_LIBRARY OR NOT HUSH_${upper}_INCLUDE_DIR)
    set(${found_var} FALSE PARENT_SCOPE)
    return()
  endif()
  if("GLOBAL" IN_LIST ARGN)
    add_library(${target} UNKNOWN IMPORTED GLOBAL)
  else()
    add_library(${target} UNKNOWN IMPORTED)
  endif()
  set_target_properties(${target} PROPERTIES
    IMPORTED_LOCATION "${HUSH_${upper}_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${HUSH_${upper}_INCLUDE_DIR}")
  set(${found_var} TRUE PARENT_SCOPE)
endfunction()
