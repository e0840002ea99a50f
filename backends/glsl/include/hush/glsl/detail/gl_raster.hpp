// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The GL entry points and enums of hush's raster paths, beyond what hush::glsl::device loads
// (hush/glsl/detail/gl.hpp): framebuffers, vertex arrays, draws, blending, read-back, and the
// NPR Gabor resident walk's indirect commands and fences (texture formats, samplers and copies:
// gl_resident.hpp). Used by the NPR Gabor renderer, the anisotropic frame, and the tests' and
// benchmarks' fragment-shader harnesses.
#ifndef HUSH_GLSL_DETAIL_GL_RASTER_HPP
#define HUSH_GLSL_DETAIL_GL_RASTER_HPP

#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/detail/gl_resident.hpp"  // kGlR32fFormat, kGlRedChannel, kGlNearestFilter

namespace hush {
namespace glsl {
namespace detail {

// GL enums of the raster paths (Khronos gl.xml).
constexpr gl_enum kGlFramebuffer = 0x8D40;
constexpr gl_enum kGlColorAttachment0 = 0x8CE0;
constexpr gl_enum kGlFramebufferComplete = 0x8CD5;
constexpr gl_enum kGlDrawFramebufferBinding = 0x8CA6;
constexpr gl_enum kGlReadFramebufferBinding = 0x8CAA;
constexpr gl_enum kGlDrawFramebuffer = 0x8CA9;
constexpr gl_enum kGlReadFramebuffer = 0x8CA8;
constexpr gl_enum kGlPoints = 0x0000;
constexpr gl_enum kGlTriangles = 0x0004;
constexpr gl_enum kGlBlend = 0x0BE2;
constexpr gl_enum kGlOne = 1;
constexpr gl_enum kGlFuncAdd = 0x8006;
constexpr gl_enum kGlDepthTest = 0x0B71;
constexpr gl_enum kGlScissorTest = 0x0C11;
constexpr gl_enum kGlCullFace = 0x0B44;
constexpr gl_enum kGlStencilTest = 0x0B90;
constexpr gl_bitfield kGlColorBufferBit = 0x4000;
constexpr gl_enum kGlViewport = 0x0BA2;
constexpr gl_enum kGlPackAlignment = 0x0D05;
constexpr gl_enum kGlVertexArrayBinding = 0x85B5;
constexpr gl_enum kGlBlendSrcRgb = 0x80C9;
constexpr gl_enum kGlBlendDstRgb = 0x80C8;
constexpr gl_enum kGlBlendSrcAlpha = 0x80CB;
constexpr gl_enum kGlBlendDstAlpha = 0x80CA;
constexpr gl_enum kGlBlendEquationRgb = 0x8009;
constexpr gl_enum kGlBlendEquationAlpha = 0x883D;
// The resident walk's plan: indirect commands, the level slots as a uniform block, the status.
constexpr gl_enum kGlUniformBufferBinding = 0x8A28;
constexpr gl_enum kGlUniformBufferOffsetAlignment = 0x8A34;
constexpr gl_enum kGlDispatchIndirectBuffer = 0x90EE;
constexpr gl_enum kGlDispatchIndirectBufferBinding = 0x90EF;
constexpr gl_enum kGlDrawIndirectBuffer = 0x8F3F;
constexpr gl_enum kGlDrawIndirectBufferBinding = 0x8F43;
constexpr gl_enum kGlSyncGpuCommandsComplete = 0x9117;
constexpr gl_enum kGlAlreadySignaled = 0x911A;
constexpr gl_enum kGlConditionSatisfied = 0x911C;
constexpr gl_bitfield kGlUniformBarrierBit = 0x4;
constexpr gl_bitfield kGlCommandBarrierBit = 0x40;
constexpr gl_bitfield kGlMapReadBit = 0x1;
constexpr gl_bitfield kGlMapPersistentBit = 0x40;
constexpr gl_bitfield kGlMapCoherentBit = 0x80;

// The entry points of the raster paths beyond hush::glsl::device's (GL 3.x core; the resident
// walk's GL 4.3), loaded from a context's loader.
struct gl_raster_api {
  void(HUSH_GLAPI* GenFramebuffers)(gl_sizei, gl_uint*) = nullptr;
  void(HUSH_GLAPI* DeleteFramebuffers)(gl_sizei, const gl_uint*) = nullptr;
  void(HUSH_GLAPI* BindFramebuffer)(gl_enum, gl_uint) = nullptr;
  void(HUSH_GLAPI* FramebufferTexture2D)(gl_enum, gl_enum, gl_enum, gl_uint, gl_int) = nullptr;
  gl_enum(HUSH_GLAPI* CheckFramebufferStatus)(gl_enum) = nullptr;
  void(HUSH_GLAPI* GenVertexArrays)(gl_sizei, gl_uint*) = nullptr;
  void(HUSH_GLAPI* DeleteVertexArrays)(gl_sizei, const gl_uint*) = nullptr;
  void(HUSH_GLAPI* BindVertexArray)(gl_uint) = nullptr;
  void(HUSH_GLAPI* DrawArrays)(gl_enum, gl_int, gl_sizei) = nullptr;
  void(HUSH_GLAPI* Viewport)(gl_int, gl_int, gl_sizei, gl_sizei) = nullptr;
  void(HUSH_GLAPI* Enable)(gl_enum) = nullptr;
  void(HUSH_GLAPI* Disable)(gl_enum) = nullptr;
  unsigned char(HUSH_GLAPI* IsEnabled)(gl_enum) = nullptr;
  void(HUSH_GLAPI* BlendFuncSeparate)(gl_enum, gl_enum, gl_enum, gl_enum) = nullptr;
  void(HUSH_GLAPI* BlendEquationSeparate)(gl_enum, gl_enum) = nullptr;
  void(HUSH_GLAPI* ClearColor)(float, float, float, float) = nullptr;
  void(HUSH_GLAPI* Clear)(gl_bitfield) = nullptr;
  void(HUSH_GLAPI* ReadPixels)(gl_int, gl_int, gl_sizei, gl_sizei, gl_enum, gl_enum,
                               void*) = nullptr;
  void(HUSH_GLAPI* DrawBuffers)(gl_sizei, const gl_enum*) = nullptr;
  void(HUSH_GLAPI* GetTexImage)(gl_enum, gl_int, gl_enum, gl_enum, void*) = nullptr;
  // The resident walk (GL 4.3 core): indirect commands, ranges and fences.
  void(HUSH_GLAPI* BindBufferRange)(gl_enum, gl_uint, gl_uint, gl_intptr, gl_sizeiptr) = nullptr;
  void(HUSH_GLAPI* DispatchComputeIndirect)(gl_intptr) = nullptr;
  void(HUSH_GLAPI* DrawArraysIndirect)(gl_enum, const void*) = nullptr;
  void*(HUSH_GLAPI* FenceSync)(gl_enum, gl_bitfield) = nullptr;
  gl_enum(HUSH_GLAPI* ClientWaitSync)(void*, gl_bitfield, unsigned long long) = nullptr;
  void(HUSH_GLAPI* DeleteSync)(void*) = nullptr;

  explicit gl_raster_api(loader_fn loader) {
    gl_api::load(loader, GenFramebuffers, "glGenFramebuffers");
    gl_api::load(loader, DeleteFramebuffers, "glDeleteFramebuffers");
    gl_api::load(loader, BindFramebuffer, "glBindFramebuffer");
    gl_api::load(loader, FramebufferTexture2D, "glFramebufferTexture2D");
    gl_api::load(loader, CheckFramebufferStatus, "glCheckFramebufferStatus");
    gl_api::load(loader, GenVertexArrays, "glGenVertexArrays");
    gl_api::load(loader, DeleteVertexArrays, "glDeleteVertexArrays");
    gl_api::load(loader, BindVertexArray, "glBindVertexArray");
    gl_api::load(loader, DrawArrays, "glDrawArrays");
    gl_api::load(loader, Viewport, "glViewport");
    gl_api::load(loader, Enable, "glEnable");
    gl_api::load(loader, Disable, "glDisable");
    gl_api::load(loader, IsEnabled, "glIsEnabled");
    gl_api::load(loader, BlendFuncSeparate, "glBlendFuncSeparate");
    gl_api::load(loader, BlendEquationSeparate, "glBlendEquationSeparate");
    gl_api::load(loader, ClearColor, "glClearColor");
    gl_api::load(loader, Clear, "glClear");
    gl_api::load(loader, ReadPixels, "glReadPixels");
    gl_api::load(loader, DrawBuffers, "glDrawBuffers");
    gl_api::load(loader, GetTexImage, "glGetTexImage");
    gl_api::load(loader, BindBufferRange, "glBindBufferRange");
    gl_api::load(loader, DispatchComputeIndirect, "glDispatchComputeIndirect");
    gl_api::load(loader, DrawArraysIndirect, "glDrawArraysIndirect");
    gl_api::load(loader, FenceSync, "glFenceSync");
    gl_api::load(loader, ClientWaitSync, "glClientWaitSync");
    gl_api::load(loader, DeleteSync, "glDeleteSync");
  }
};

}  // namespace detail
}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_DETAIL_GL_RASTER_HPP
