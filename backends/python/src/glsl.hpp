// hush's Python module: backend="glsl", hush::exec::glsl on one headless GL device per process
// (hush/glsl/headless.hpp: OSMesa llvmpipe, or EGL on a GPU, picked by HUSH_GL_CONTEXT).
//
// The device and its context live on a thread of their own, created on the first glsl call:
// a GL context is current on one thread, and Python calls come from any thread (dask's
// workers, the GIL released). Calls from several threads run one at a time on it. Built
// without a headless context (no OSMesa or EGL found by CMake), glsl_available() is false and
// backend="glsl" raises ValueError saying so.
#ifndef HUSH_PYTHON_GLSL_HPP
#define HUSH_PYTHON_GLSL_HPP

#include <functional>
#include <string>

#include "hush/glsl/device.hpp"

namespace hush_python {

// Whether this module was built with a headless GL context.
bool glsl_available();

// Runs job(device) on the GL thread and returns when it is done, rethrowing what it threw
// (std::runtime_error when no context can be made: the same error on every later call).
// Call without the GIL.
void run_on_glsl_device(const std::function<void(hush::glsl::device&)>& job);

// GL_RENDERER and GL_VERSION of the device (creates it).
std::string glsl_renderer();

}  // namespace hush_python

#endif  // HUSH_PYTHON_GLSL_HPP
