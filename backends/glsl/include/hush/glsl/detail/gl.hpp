// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The few OpenGL 4.3 entry points and enums the GLSL runner uses, loaded from
// a user-provided loader (name -> address: glfwGetProcAddress,
// SDL_GL_GetProcAddress, OSMesaGetProcAddress, eglGetProcAddress, ...). hush
// links no GL library and includes no GL header, so it sits beside whatever
// loader (glad, GLEW, epoxy) the application already uses without clashing.
// The enum values are the Khronos registry's (gl.xml); GL ABI values never change.
// GL failures (a missing entry point, a GL error, a shader that does not compile or link)
// throw std::runtime_error; without exceptions they go to hush's error handler with the
// same message (hush/core/error.hpp), as the backend's parameter errors do.
#ifndef HUSH_GLSL_DETAIL_GL_HPP
#define HUSH_GLSL_DETAIL_GL_HPP

#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "hush/core/error.hpp"

#if defined(_WIN32)
#define HUSH_GLAPI __stdcall
#else
#define HUSH_GLAPI
#endif

namespace hush {
namespace glsl {
namespace detail {

using gl_enum = unsigned int;
using gl_uint = unsigned int;
using gl_int = int;
using gl_sizei = int;
using gl_bitfield = unsigned int;
using gl_sizeiptr = std::ptrdiff_t;
using gl_intptr = std::ptrdiff_t;

// Enums (Khronos gl.xml).
constexpr gl_enum kGlNoError = 0;
constexpr gl_enum kGlRenderer = 0x1F01;
constexpr gl_enum kGlVersion = 0x1F02;
constexpr gl_enum kGlMajorVersion = 0x821B;
constexpr gl_enum kGlMinorVersion = 0x821C;
constexpr gl_enum kGlComputeShader = 0x91B9;
constexpr gl_enum kGlVertexShader = 0x8B31;
constexpr gl_enum kGlFragmentShader = 0x8B30;
constexpr gl_enum kGlGeometryShader = 0x8DD9;
constexpr gl_enum kGlCompileStatus = 0x8B81;
constexpr gl_enum kGlLinkStatus = 0x8B82;
constexpr gl_enum kGlInfoLogLength = 0x8B84;
constexpr gl_enum kGlShaderStorageBuffer = 0x90D2;
constexpr gl_enum kGlUniformBuffer = 0x8A11;
constexpr gl_enum kGlShaderStorageBufferBinding = 0x90D3;
constexpr gl_enum kGlCurrentProgram = 0x8B8D;
constexpr gl_enum kGlStreamDraw = 0x88E0;
constexpr gl_enum kGlStaticDraw = 0x88E4;
constexpr gl_enum kGlMaxShaderStorageBufferBindings = 0x90DD;
constexpr gl_enum kGlDynamicRead = 0x88E9;
constexpr gl_enum kGlMaxComputeWorkGroupCount = 0x91BE;
constexpr gl_enum kGlMaxShaderStorageBlockSize = 0x90DE;
constexpr gl_enum kGlTexture2d = 0x0DE1;
constexpr gl_enum kGlTexture0 = 0x84C0;
constexpr gl_enum kGlActiveTexture = 0x84E0;
constexpr gl_enum kGlTextureBinding2d = 0x8069;
constexpr gl_enum kGlRgba32f = 0x8814;
constexpr gl_enum kGlRgba = 0x1908;
constexpr gl_enum kGlFloat = 0x1406;
constexpr gl_enum kGlTextureMinFilter = 0x2801;
constexpr gl_enum kGlTextureMagFilter = 0x2800;
constexpr gl_enum kGlLinear = 0x2601;
constexpr gl_enum kGlTextureWrapS = 0x2802;
constexpr gl_enum kGlTextureWrapT = 0x2803;
constexpr gl_enum kGlRepeat = 0x2901;
constexpr gl_enum kGlMaxTextureSize = 0x0D33;
constexpr gl_enum kGlMaxCombinedTextureImageUnits = 0x8B4D;
constexpr gl_enum kGlUnpackAlignment = 0x0CF5;
constexpr gl_bitfield kGlShaderStorageBarrierBit = 0x2000;
constexpr gl_bitfield kGlBufferUpdateBarrierBit = 0x200;

// The loader signature of hush::glsl::device (and osmesa_context::loader()).
using loader_fn = void* (*)(const char* name);

// Function pointers to the entry points the runner and the tests use.
struct gl_api {
  const unsigned char*(HUSH_GLAPI* GetString)(gl_enum) = nullptr;
  void(HUSH_GLAPI* GetIntegerv)(gl_enum, gl_int*) = nullptr;
  void(HUSH_GLAPI* GetIntegeri_v)(gl_enum, gl_uint, gl_int*) = nullptr;
  void(HUSH_GLAPI* GetInteger64v)(gl_enum, long long*) = nullptr;
  gl_enum(HUSH_GLAPI* GetError)() = nullptr;
  gl_uint(HUSH_GLAPI* CreateShader)(gl_enum) = nullptr;
  void(HUSH_GLAPI* ShaderSource)(gl_uint, gl_sizei, const char* const*, const gl_int*) = nullptr;
  void(HUSH_GLAPI* CompileShader)(gl_uint) = nullptr;
  void(HUSH_GLAPI* GetShaderiv)(gl_uint, gl_enum, gl_int*) = nullptr;
  void(HUSH_GLAPI* GetShaderInfoLog)(gl_uint, gl_sizei, gl_sizei*, char*) = nullptr;
  void(HUSH_GLAPI* DeleteShader)(gl_uint) = nullptr;
  gl_uint(HUSH_GLAPI* CreateProgram)() = nullptr;
  void(HUSH_GLAPI* AttachShader)(gl_uint, gl_uint) = nullptr;
  void(HUSH_GLAPI* LinkProgram)(gl_uint) = nullptr;
  void(HUSH_GLAPI* GetProgramiv)(gl_uint, gl_enum, gl_int*) = nullptr;
  void(HUSH_GLAPI* GetProgramInfoLog)(gl_uint, gl_sizei, gl_sizei*, char*) = nullptr;
  void(HUSH_GLAPI* DeleteProgram)(gl_uint) = nullptr;
  void(HUSH_GLAPI* UseProgram)(gl_uint) = nullptr;
  gl_int(HUSH_GLAPI* GetUniformLocation)(gl_uint, const char*) = nullptr;
  void(HUSH_GLAPI* Uniform1ui)(gl_int, gl_uint) = nullptr;
  void(HUSH_GLAPI* Uniform2ui)(gl_int, gl_uint, gl_uint) = nullptr;
  void(HUSH_GLAPI* Uniform3ui)(gl_int, gl_uint, gl_uint, gl_uint) = nullptr;
  void(HUSH_GLAPI* Uniform1uiv)(gl_int, gl_sizei, const gl_uint*) = nullptr;
  void(HUSH_GLAPI* Uniform1i)(gl_int, gl_int) = nullptr;
  void(HUSH_GLAPI* Uniform1f)(gl_int, float) = nullptr;
  void(HUSH_GLAPI* Uniform1fv)(gl_int, gl_sizei, const float*) = nullptr;
  void(HUSH_GLAPI* Uniform1dv)(gl_int, gl_sizei, const double*) = nullptr;
  void(HUSH_GLAPI* GenTextures)(gl_sizei, gl_uint*) = nullptr;
  void(HUSH_GLAPI* DeleteTextures)(gl_sizei, const gl_uint*) = nullptr;
  void(HUSH_GLAPI* BindTexture)(gl_enum, gl_uint) = nullptr;
  void(HUSH_GLAPI* ActiveTexture)(gl_enum) = nullptr;
  void(HUSH_GLAPI* TexImage2D)(gl_enum, gl_int, gl_int, gl_sizei, gl_sizei, gl_int, gl_enum,
                               gl_enum, const void*) = nullptr;
  void(HUSH_GLAPI* TexParameteri)(gl_enum, gl_enum, gl_int) = nullptr;
  void(HUSH_GLAPI* PixelStorei)(gl_enum, gl_int) = nullptr;
  void(HUSH_GLAPI* GenBuffers)(gl_sizei, gl_uint*) = nullptr;
  void(HUSH_GLAPI* DeleteBuffers)(gl_sizei, const gl_uint*) = nullptr;
  void(HUSH_GLAPI* BindBuffer)(gl_enum, gl_uint) = nullptr;
  void(HUSH_GLAPI* BindBufferBase)(gl_enum, gl_uint, gl_uint) = nullptr;
  void(HUSH_GLAPI* BufferData)(gl_enum, gl_sizeiptr, const void*, gl_enum) = nullptr;
  void(HUSH_GLAPI* GetBufferSubData)(gl_enum, gl_intptr, gl_sizeiptr, void*) = nullptr;
  void(HUSH_GLAPI* DispatchCompute)(gl_uint, gl_uint, gl_uint) = nullptr;
  void(HUSH_GLAPI* MemoryBarrier)(gl_bitfield) = nullptr;
  void(HUSH_GLAPI* Finish)() = nullptr;
  // The loader these came from: programs that draw (hush/glsl/npr_gabor/renderer.hpp) load
  // their own entry points from it.
  loader_fn loader = nullptr;

  // Loads every entry point; throws std::runtime_error naming the first the
  // loader does not know (the context is missing or older than GL 4.3).
  explicit gl_api(loader_fn loader_) : loader(loader_) {
    if (!loader) hush::detail::raise_error<std::runtime_error>("hush::glsl: the GL loader is null");
    load(loader, GetString, "glGetString");
    load(loader, GetIntegerv, "glGetIntegerv");
    load(loader, GetIntegeri_v, "glGetIntegeri_v");
    load(loader, GetInteger64v, "glGetInteger64v");
    load(loader, GetError, "glGetError");
    load(loader, CreateShader, "glCreateShader");
    load(loader, ShaderSource, "glShaderSource");
    load(loader, CompileShader, "glCompileShader");
    load(loader, GetShaderiv, "glGetShaderiv");
    load(loader, GetShaderInfoLog, "glGetShaderInfoLog");
    load(loader, DeleteShader, "glDeleteShader");
    load(loader, CreateProgram, "glCreateProgram");
    load(loader, AttachShader, "glAttachShader");
    load(loader, LinkProgram, "glLinkProgram");
    load(loader, GetProgramiv, "glGetProgramiv");
    load(loader, GetProgramInfoLog, "glGetProgramInfoLog");
    load(loader, DeleteProgram, "glDeleteProgram");
    load(loader, UseProgram, "glUseProgram");
    load(loader, GetUniformLocation, "glGetUniformLocation");
    load(loader, Uniform1ui, "glUniform1ui");
    load(loader, Uniform2ui, "glUniform2ui");
    load(loader, Uniform3ui, "glUniform3ui");
    load(loader, Uniform1uiv, "glUniform1uiv");
    load(loader, Uniform1i, "glUniform1i");
    load(loader, Uniform1f, "glUniform1f");
    load(loader, Uniform1fv, "glUniform1fv");
    load(loader, Uniform1dv, "glUniform1dv");
    load(loader, GenTextures, "glGenTextures");
    load(loader, DeleteTextures, "glDeleteTextures");
    load(loader, BindTexture, "glBindTexture");
    load(loader, ActiveTexture, "glActiveTexture");
    load(loader, TexImage2D, "glTexImage2D");
    load(loader, TexParameteri, "glTexParameteri");
    load(loader, PixelStorei, "glPixelStorei");
    load(loader, GenBuffers, "glGenBuffers");
    load(loader, DeleteBuffers, "glDeleteBuffers");
    load(loader, BindBuffer, "glBindBuffer");
    load(loader, BindBufferBase, "glBindBufferBase");
    load(loader, BufferData, "glBufferData");
    load(loader, GetBufferSubData, "glGetBufferSubData");
    load(loader, DispatchCompute, "glDispatchCompute");
    load(loader, MemoryBarrier, "glMemoryBarrier");
    load(loader, Finish, "glFinish");
  }

  // Throws std::runtime_error "<where>: GL error 0x..." when GL has recorded an error.
  void check(const char* where) const {
    const gl_enum e = GetError();
    if (e == kGlNoError) return;
    while (GetError() != kGlNoError) {
    }  // drain the other queued flags
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%04X", e);
    hush::detail::raise_error<std::runtime_error>(std::string(where) + ": GL error " + hex);
  }

  std::string string(gl_enum name) const {
    const unsigned char* s = GetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("(null)");
  }

  // Sets f to the entry point `name` from `loader`; throws std::runtime_error when absent.
  template <class F>
  static void load(loader_fn loader, F& f, const char* name) {
    void* p = loader(name);
    if (!p)
      hush::detail::raise_error<std::runtime_error>(std::string("hush::glsl: the GL loader has no ") + name +
                               " (needs an OpenGL 4.3 context current on this thread)");
    // Object-to-function pointer conversion: conditionally supported, and what
    // every GL loader relies on (POSIX dlsym guarantees it).
    f = reinterpret_cast<F>(p);
  }
};

// An owned GL object name, deleted with the given function.
class gl_program {
 public:
  gl_program() = default;
  gl_program(const gl_api* api, gl_uint id) : api_(api), id_(id) {}
  gl_program(gl_program&& o) noexcept : api_(o.api_), id_(std::exchange(o.id_, 0u)) {}
  gl_program& operator=(gl_program&& o) noexcept {
    std::swap(api_, o.api_);
    std::swap(id_, o.id_);
    return *this;
  }
  gl_program(const gl_program&) = delete;
  gl_program& operator=(const gl_program&) = delete;
  ~gl_program() {
    if (id_ != 0u) api_->DeleteProgram(id_);
  }
  gl_uint id() const { return id_; }

 private:
  const gl_api* api_ = nullptr;
  gl_uint id_ = 0;
};

inline const char* stage_name(gl_enum stage) {
  switch (stage) {
    case kGlComputeShader:
      return "compute";
    case kGlVertexShader:
      return "vertex";
    case kGlFragmentShader:
      return "fragment";
    case kGlGeometryShader:
      return "geometry";
    default:
      return "shader";
  }
}

// Compiles the given (stage, source) pairs and links them into a program.
// Throws std::runtime_error with the compiler's or linker's log on failure.
inline gl_program link_program(const gl_api& gl,
                               const std::vector<std::pair<gl_enum, std::string>>& stages) {
  std::vector<gl_uint> shaders;
  auto cleanup = [&] {
    for (gl_uint s : shaders) gl.DeleteShader(s);
  };
  auto log_of = [&](gl_uint id, bool program) {
    gl_int n = 0;
    (program ? gl.GetProgramiv : gl.GetShaderiv)(id, kGlInfoLogLength, &n);
    std::string log(static_cast<std::size_t>(n > 1 ? n : 1), '\0');
    (program ? gl.GetProgramInfoLog : gl.GetShaderInfoLog)(id, static_cast<gl_sizei>(log.size()),
                                                           nullptr, &log[0]);
    log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
    return log;
  };
  for (const auto& st : stages) {
    const gl_uint s = gl.CreateShader(st.first);
    if (s == 0u) {
      cleanup();
      hush::detail::raise_error<std::runtime_error>(std::string("hush::glsl: glCreateShader(") + stage_name(st.first) +
                               ") failed");
    }
    shaders.push_back(s);
    const char* text = st.second.c_str();
    gl.ShaderSource(s, 1, &text, nullptr);
    gl.CompileShader(s);
    gl_int ok = 0;
    gl.GetShaderiv(s, kGlCompileStatus, &ok);
    if (!ok) {
      const std::string log = log_of(s, false);
      cleanup();
      hush::detail::raise_error<std::runtime_error>(std::string("hush::glsl: the ") + stage_name(st.first) +
                               " shader does not compile:\n" + log);
    }
  }
  gl_program prog(&gl, gl.CreateProgram());
  for (gl_uint s : shaders) gl.AttachShader(prog.id(), s);
  gl.LinkProgram(prog.id());
  cleanup();  // flagged for deletion; freed with the program
  gl_int ok = 0;
  gl.GetProgramiv(prog.id(), kGlLinkStatus, &ok);
  if (!ok)
    hush::detail::raise_error<std::runtime_error>("hush::glsl: the program does not link:\n" + log_of(prog.id(), true));
  gl.check("hush::glsl: linking a program");
  return prog;
}

}  // namespace detail
}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_DETAIL_GL_HPP
