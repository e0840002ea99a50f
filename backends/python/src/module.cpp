// hush's Python module (_hush, wrapped by the package hush/): every noise of the registry
// (HUSH_NOISE_LIST, generated from HUSH_NOISES), each from its own src/noise_<noise>.cpp.
#include "bindings.hpp"
#include "glsl.hpp"
#include "hush_tools/noise_list.hpp"

namespace hush_python {
#define HUSH_PYTHON_DECLARE(noise) void add_##noise##_python(py::module_& m);
HUSH_NOISE_LIST(HUSH_PYTHON_DECLARE)
#undef HUSH_PYTHON_DECLARE
}  // namespace hush_python

PYBIND11_MODULE(_hush, m) {
  namespace py = pybind11;
  m.doc() = "hush: procedural noise for rendering (C++ bindings; see the package hush)";
  m.attr("version") = HUSH_VERSION_STRING;
  // hush::invalid_argument (a parameter outside its domain) is a ValueError naming it.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const hush::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  m.def(
      "simd_target", [] { return hush::simd::chosen_target(); },
      "The SIMD target exec::simd dispatches to on this machine.");
  m.def("glsl_available", &hush_python::glsl_available,
        "Whether this module was built with the GL backend (backend='glsl': a headless OSMesa "
        "or EGL context, picked by the environment variable HUSH_GL_CONTEXT).");
  m.def(
      "glsl_renderer",
      [] {
        py::gil_scoped_release release;
        return hush_python::glsl_renderer();
      },
      "GL_RENDERER and GL_VERSION of the process's GL device, created on first use (the first "
      "backend='glsl' call or this one). RuntimeError when no GL context can be made or the "
      "module was built without the GL backend.");
#define HUSH_PYTHON_ADD(noise) hush_python::add_##noise##_python(m);
  HUSH_NOISE_LIST(HUSH_PYTHON_ADD)
#undef HUSH_PYTHON_ADD
}
