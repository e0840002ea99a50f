// A GL loader that hands out a wrapper for every entry point hush's GLSL backend loads, for the
// resident-frame suites (readback_counter.hpp) and the benchmark's resident rows
// (bench/gl_timing.hpp). Each wrapper counts the call (wrapped_gl::calls(), all entry points
// together), then calls the entry's replacement when one is set (a suite's counting function,
// which calls the real entry point itself) or else the real entry point. The entry points that
// make the GPU work (draws, dispatches, clears) become no-ops while wrapped_gl::skip_gpu_work()
// is set: on Mesa's llvmpipe a dispatch or draw runs inside the call, so only with them skipped
// does the host time of a frame show the host's own work (state, binds, uniforms, buffer
// allocation and uploads still run for real).
//
// The wrappers hold process-wide state (a GL loader is a plain function pointer, so a wrapper
// cannot carry context): one real loader per process (install()), and the addresses it gave,
// which are the same for every context of that loader (OSMesa's and EGL's getProcAddress).
// Names the table below lacks resolve to the real entry point, uncounted, and are listed in
// wrapped_gl::unwrapped(); the suites check it stays empty, so calls() is every GL call hush
// made. No GL context or test framework here (only hush's GL types), so bench/ includes it too.
#ifndef HUSH_TESTS_GLSL_WRAPPED_LOADER_HPP
#define HUSH_TESTS_GLSL_WRAPPED_LOADER_HPP

#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/detail/gl_resident.hpp"
#include "hush/glsl/device.hpp"
#include "hush/glsl/detail/gl_raster.hpp"

namespace hush_glsl_test {

namespace wrapped_types {
namespace hgl = hush::glsl::detail;
// The entry points hush loads as locals, not as members of its API structs (their types as the
// loading code spells them), and glBufferSubData, which only callers load today (an upload
// the suites count).
using buffer_storage = void(HUSH_GLAPI*)(hgl::gl_enum, hgl::gl_sizeiptr, const void*,
                                         hgl::gl_bitfield);
using map_buffer_range = void*(HUSH_GLAPI*)(hgl::gl_enum, hgl::gl_intptr, hgl::gl_sizeiptr,
                                            hgl::gl_bitfield);
using get_buffer_parameteriv = void(HUSH_GLAPI*)(hgl::gl_enum, hgl::gl_enum, hgl::gl_int*);
using tex_image_3d = void(HUSH_GLAPI*)(hgl::gl_enum, hgl::gl_int, hgl::gl_int, hgl::gl_sizei,
                                       hgl::gl_sizei, hgl::gl_sizei, hgl::gl_int, hgl::gl_enum,
                                       hgl::gl_enum, const void*);
using buffer_sub_data = void(HUSH_GLAPI*)(hgl::gl_enum, hgl::gl_intptr, hgl::gl_sizeiptr,
                                          const void*);
}  // namespace wrapped_types

// Every entry point hush's backend loads: X(name without "gl", type, makes the GPU work).
// Types come from the API structs that load them, so a changed signature changes here too.
#define HUSH_TEST_GL_API(X, name) X(name, decltype(::hush::glsl::detail::gl_api::name), false)
#define HUSH_TEST_GL_RESIDENT(X, name) \
  X(name, decltype(::hush::glsl::detail::gl_resident_api::name), false)
#define HUSH_TEST_GL_RASTER(X, name, work) \
  X(name, decltype(::hush::glsl::detail::gl_raster_api::name), work)
#define HUSH_TEST_GL_ENTRIES(X)                                                           \
  HUSH_TEST_GL_API(X, GetString)                                                          \
  HUSH_TEST_GL_API(X, GetIntegerv)                                                        \
  HUSH_TEST_GL_API(X, GetIntegeri_v)                                                      \
  HUSH_TEST_GL_API(X, GetInteger64v)                                                      \
  HUSH_TEST_GL_API(X, GetError)                                                           \
  HUSH_TEST_GL_API(X, CreateShader)                                                       \
  HUSH_TEST_GL_API(X, ShaderSource)                                                       \
  HUSH_TEST_GL_API(X, CompileShader)                                                      \
  HUSH_TEST_GL_API(X, GetShaderiv)                                                        \
  HUSH_TEST_GL_API(X, GetShaderInfoLog)                                                   \
  HUSH_TEST_GL_API(X, DeleteShader)                                                       \
  HUSH_TEST_GL_API(X, CreateProgram)                                                      \
  HUSH_TEST_GL_API(X, AttachShader)                                                       \
  HUSH_TEST_GL_API(X, LinkProgram)                                                        \
  HUSH_TEST_GL_API(X, GetProgramiv)                                                       \
  HUSH_TEST_GL_API(X, GetProgramInfoLog)                                                  \
  HUSH_TEST_GL_API(X, DeleteProgram)                                                      \
  HUSH_TEST_GL_API(X, UseProgram)                                                         \
  HUSH_TEST_GL_API(X, GetUniformLocation)                                                 \
  HUSH_TEST_GL_API(X, Uniform1ui)                                                         \
  HUSH_TEST_GL_API(X, Uniform2ui)                                                         \
  HUSH_TEST_GL_API(X, Uniform3ui)                                                         \
  HUSH_TEST_GL_API(X, Uniform1uiv)                                                        \
  HUSH_TEST_GL_API(X, Uniform1i)                                                          \
  HUSH_TEST_GL_API(X, Uniform1f)                                                          \
  HUSH_TEST_GL_API(X, Uniform1fv)                                                         \
  HUSH_TEST_GL_API(X, Uniform1dv)                                                         \
  HUSH_TEST_GL_API(X, GenTextures)                                                        \
  HUSH_TEST_GL_API(X, DeleteTextures)                                                     \
  HUSH_TEST_GL_API(X, BindTexture)                                                        \
  HUSH_TEST_GL_API(X, ActiveTexture)                                                      \
  HUSH_TEST_GL_API(X, TexImage2D)                                                         \
  HUSH_TEST_GL_API(X, TexParameteri)                                                      \
  HUSH_TEST_GL_API(X, PixelStorei)                                                        \
  HUSH_TEST_GL_API(X, GenBuffers)                                                         \
  HUSH_TEST_GL_API(X, DeleteBuffers)                                                      \
  HUSH_TEST_GL_API(X, BindBuffer)                                                         \
  HUSH_TEST_GL_API(X, BindBufferBase)                                                     \
  HUSH_TEST_GL_API(X, BufferData)                                                         \
  HUSH_TEST_GL_API(X, GetBufferSubData)                                                   \
  X(DispatchCompute, decltype(::hush::glsl::detail::gl_api::DispatchCompute), true)       \
  HUSH_TEST_GL_API(X, MemoryBarrier)                                                      \
  HUSH_TEST_GL_API(X, Finish)                                                             \
  HUSH_TEST_GL_RESIDENT(X, GenSamplers)                                                   \
  HUSH_TEST_GL_RESIDENT(X, DeleteSamplers)                                                \
  HUSH_TEST_GL_RESIDENT(X, BindSampler)                                                   \
  HUSH_TEST_GL_RESIDENT(X, SamplerParameteri)                                             \
  HUSH_TEST_GL_RESIDENT(X, BindImageTexture)                                              \
  HUSH_TEST_GL_RESIDENT(X, TexSubImage2D)                                                 \
  HUSH_TEST_GL_RESIDENT(X, CopyBufferSubData)                                             \
  HUSH_TEST_GL_RASTER(X, GenFramebuffers, false)                                          \
  HUSH_TEST_GL_RASTER(X, DeleteFramebuffers, false)                                       \
  HUSH_TEST_GL_RASTER(X, BindFramebuffer, false)                                          \
  HUSH_TEST_GL_RASTER(X, FramebufferTexture2D, false)                                     \
  HUSH_TEST_GL_RASTER(X, CheckFramebufferStatus, false)                                   \
  HUSH_TEST_GL_RASTER(X, GenVertexArrays, false)                                          \
  HUSH_TEST_GL_RASTER(X, DeleteVertexArrays, false)                                       \
  HUSH_TEST_GL_RASTER(X, BindVertexArray, false)                                          \
  HUSH_TEST_GL_RASTER(X, DrawArrays, true)                                                \
  HUSH_TEST_GL_RASTER(X, Viewport, false)                                                 \
  HUSH_TEST_GL_RASTER(X, Enable, false)                                                   \
  HUSH_TEST_GL_RASTER(X, Disable, false)                                                  \
  HUSH_TEST_GL_RASTER(X, IsEnabled, false)                                                \
  HUSH_TEST_GL_RASTER(X, BlendFuncSeparate, false)                                        \
  HUSH_TEST_GL_RASTER(X, BlendEquationSeparate, false)                                    \
  HUSH_TEST_GL_RASTER(X, ClearColor, false)                                               \
  HUSH_TEST_GL_RASTER(X, Clear, true)                                                     \
  HUSH_TEST_GL_RASTER(X, ReadPixels, false)                                               \
  HUSH_TEST_GL_RASTER(X, DrawBuffers, false)                                              \
  HUSH_TEST_GL_RASTER(X, GetTexImage, false)                                              \
  HUSH_TEST_GL_RASTER(X, BindBufferRange, false)                                          \
  HUSH_TEST_GL_RASTER(X, DispatchComputeIndirect, true)                                   \
  HUSH_TEST_GL_RASTER(X, DrawArraysIndirect, true)                                        \
  HUSH_TEST_GL_RASTER(X, FenceSync, false)                                                \
  HUSH_TEST_GL_RASTER(X, ClientWaitSync, false)                                           \
  HUSH_TEST_GL_RASTER(X, DeleteSync, false)                                               \
  X(BufferStorage, ::hush_glsl_test::wrapped_types::buffer_storage, false)                \
  X(MapBufferRange, ::hush_glsl_test::wrapped_types::map_buffer_range, false)             \
  X(GetBufferParameteriv, ::hush_glsl_test::wrapped_types::get_buffer_parameteriv, false) \
  X(TexImage3D, ::hush_glsl_test::wrapped_types::tex_image_3d, false)                     \
  X(BufferSubData, ::hush_glsl_test::wrapped_types::buffer_sub_data, false)

// One id per entry point of the table.
enum class gl_entry_id {
#define HUSH_TEST_GL_ID(name, type, work) name,
  HUSH_TEST_GL_ENTRIES(HUSH_TEST_GL_ID)
#undef HUSH_TEST_GL_ID
};

// An entry's type, GL name and whether it makes the GPU work.
template <gl_entry_id Id>
struct gl_entry_traits;
#define HUSH_TEST_GL_TRAITS(name_, type, work)       \
  template <>                                        \
  struct gl_entry_traits<gl_entry_id::name_> {       \
    using fn = type;                                 \
    static constexpr const char* name = "gl" #name_; \
    static constexpr bool gpu_work = work;           \
  };
HUSH_TEST_GL_ENTRIES(HUSH_TEST_GL_TRAITS)
#undef HUSH_TEST_GL_TRAITS

// The switches and counters every wrapper shares.
struct wrapped_gl {
  // GL calls made through the wrappers since the process started.
  static long long& calls() {
    static long long n = 0;
    return n;
  }
  // The calls of those that make the GPU work (draws, dispatches, clears), a part of calls().
  static long long& gpu_work_calls() {
    static long long n = 0;
    return n;
  }
  // While true, the entries that make the GPU work return at once (counted all the same).
  static bool& skip_gpu_work() {
    static bool on = false;
    return on;
  }
  // Names the loader was asked for that the table lacks (resolved unwrapped and uncounted).
  static std::vector<std::string>& unwrapped() {
    static std::vector<std::string> names;
    return names;
  }
  static hush::glsl::detail::loader_fn& real_loader() {
    static hush::glsl::detail::loader_fn f = nullptr;
    return f;
  }
  // Sets the real loader; a second, different one is an error (std::logic_error through
  // hush::detail::raise_error): the wrappers hold one address per entry point.
  static void install(hush::glsl::detail::loader_fn real) {
    if (real_loader() && real_loader() != real)
      hush::detail::raise_error<std::logic_error>("wrapped_gl: one real GL loader per process");
    real_loader() = real;
  }
  // The wrapped loader (hush::glsl::device's loader_fn): the wrapper for a name of the table,
  // the real address for any other, null where the real loader has none.
  static void* loader(const char* name);
};

// The wrapper of one entry point: counts, then the replacement, the real call or (GPU work
// while skipping) nothing.
template <gl_entry_id Id, class Fn = typename gl_entry_traits<Id>::fn>
struct gl_entry;
template <gl_entry_id Id, class R, class... A>
struct gl_entry<Id, R(HUSH_GLAPI*)(A...)> {
  using fn = R(HUSH_GLAPI*)(A...);
  static inline fn real = nullptr;         // the real loader's address
  static inline fn replacement = nullptr;  // called instead of `real` when set
  static R HUSH_GLAPI call(A... a) {
    ++wrapped_gl::calls();
    if constexpr (gl_entry_traits<Id>::gpu_work) {
      static_assert(std::is_void_v<R>, "a skipped entry point returns nothing");
      ++wrapped_gl::gpu_work_calls();
      if (wrapped_gl::skip_gpu_work()) return;
    }
    return (replacement ? replacement : real)(a...);
  }
  // Records the real address and gives the wrapper's. Object-to-function pointer casts as
  // every GL loader makes them (hush::glsl::detail::gl_api::load).
  static void* wrap(void* address) {
    real = reinterpret_cast<fn>(address);
    return reinterpret_cast<void*>(&call);
  }
};

inline void* wrapped_gl::loader(const char* name) {
  // Built once: the lookup runs on every load, some of them per frame (a buffer size query).
  static const std::unordered_map<std::string_view, void* (*)(void*)> table = {
#define HUSH_TEST_GL_WRAP(name_, type, work) \
  {gl_entry_traits<gl_entry_id::name_>::name, &gl_entry<gl_entry_id::name_>::wrap},
      HUSH_TEST_GL_ENTRIES(HUSH_TEST_GL_WRAP)
#undef HUSH_TEST_GL_WRAP
  };
  if (!real_loader())
    hush::detail::raise_error<std::logic_error>("wrapped_gl: install() a real loader first");
  void* p = real_loader()(name);
  if (!p) return p;
  const auto it = table.find(name);
  if (it == table.end()) {
    unwrapped().emplace_back(name);
    return p;
  }
  return it->second(p);
}

// A hush::glsl::device whose GL calls all go through the wrappers, on the context current
// now, whose loader is `real`; one per process, made on the first call.
inline hush::glsl::device& wrapped_device(hush::glsl::detail::loader_fn real) {
  wrapped_gl::install(real);
  static hush::glsl::device d(&wrapped_gl::loader);
  return d;
}

// While alive, the GPU work of the wrapped entry points is skipped.
class skipping_gpu_work {
 public:
  skipping_gpu_work() { wrapped_gl::skip_gpu_work() = true; }
  ~skipping_gpu_work() { wrapped_gl::skip_gpu_work() = false; }
  skipping_gpu_work(const skipping_gpu_work&) = delete;
  skipping_gpu_work& operator=(const skipping_gpu_work&) = delete;
};

// The GL calls `f()` makes through the wrappers.
template <class F>
long long gl_calls_of(F&& f) {
  const long long before = wrapped_gl::calls();
  f();
  return wrapped_gl::calls() - before;
}

}  // namespace hush_glsl_test

#endif  // HUSH_TESTS_GLSL_WRAPPED_LOADER_HPP
