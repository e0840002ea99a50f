// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The GL side of NPR Gabor noise's raster path (hush/glsl/npr_gabor/renderer.hpp): the limits
// the renderer depends on as the context reports them, the GL enums of the path (Khronos
// gl.xml), and the entry points beyond hush::glsl::device's (framebuffers, blending, the
// resident walk's indirect commands, copies and fences), loaded from the device's loader.
#ifndef HUSH_GLSL_NPR_GABOR_GL_RASTER_HPP
#define HUSH_GLSL_NPR_GABOR_GL_RASTER_HPP

#include <algorithm>

#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/npr_gabor/glsl.hpp"  // kNprGaborSpriteVertices, kNprGaborSpriteComponents

namespace hush {
namespace glsl {

// The GL limits the renderer depends on, as the context reports them.
struct npr_gabor_limits {
  int max_geometry_output_vertices = 0;    // GL_MAX_GEOMETRY_OUTPUT_VERTICES
  int max_geometry_output_components = 0;  // GL_MAX_GEOMETRY_TOTAL_OUTPUT_COMPONENTS
  int max_geometry_storage_blocks = 0;     // GL_MAX_GEOMETRY_SHADER_STORAGE_BLOCKS
  int max_fragment_storage_blocks = 0;     // GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS
  int max_frame_side =
      0;  // min(GL_MAX_TEXTURE_SIZE, GL_MAX_VIEWPORT_DIMS, GL_MAX_RENDERBUFFER_SIZE)
  // Whether one quad per input point fits the geometry-output limits.
  bool sprites_fit() const {
    return kNprGaborSpriteVertices <= max_geometry_output_vertices &&
           kNprGaborSpriteVertices * kNprGaborSpriteComponents <= max_geometry_output_components;
  }
};

namespace detail {

// GL enums of the raster path (Khronos gl.xml).
constexpr gl_enum kGlFramebuffer = 0x8D40;
constexpr gl_enum kGlColorAttachment0 = 0x8CE0;
constexpr gl_enum kGlFramebufferComplete = 0x8CD5;
constexpr gl_enum kGlDrawFramebufferBinding = 0x8CA6;
constexpr gl_enum kGlReadFramebufferBinding = 0x8CAA;
constexpr gl_enum kGlDrawFramebuffer = 0x8CA9;
constexpr gl_enum kGlReadFramebuffer = 0x8CA8;
constexpr gl_enum kGlR32f = 0x822E;
constexpr gl_enum kGlRed = 0x1903;
constexpr gl_enum kGlPoints = 0x0000;
constexpr gl_enum kGlBlend = 0x0BE2;
constexpr gl_enum kGlOne = 1;
constexpr gl_enum kGlFuncAdd = 0x8006;
constexpr gl_enum kGlDepthTest = 0x0B71;
constexpr gl_enum kGlScissorTest = 0x0C11;
constexpr gl_enum kGlCullFace = 0x0B44;
constexpr gl_enum kGlStencilTest = 0x0B90;
constexpr gl_bitfield kGlColorBufferBit = 0x4000;
constexpr gl_enum kGlViewport = 0x0BA2;
constexpr gl_enum kGlMaxGeometryOutputVertices = 0x8DE0;
constexpr gl_enum kGlMaxGeometryTotalOutputComponents = 0x8DE1;
constexpr gl_enum kGlMaxGeometryShaderStorageBlocks = 0x90D7;
constexpr gl_enum kGlMaxFragmentShaderStorageBlocks = 0x90DA;
constexpr gl_enum kGlMaxViewportDims = 0x0D3A;
constexpr gl_enum kGlMaxRenderbufferSize = 0x84E8;
constexpr gl_enum kGlPackAlignment = 0x0D05;
constexpr gl_enum kGlVertexArrayBinding = 0x85B5;
constexpr gl_enum kGlNearest = 0x2600;
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

// The entry points of the raster path (GL 3.x core), loaded from the device's loader.
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
  // The resident walk (GL 4.3 core): indirect commands, ranges, copies and fences.
  void(HUSH_GLAPI* BindBufferRange)(gl_enum, gl_uint, gl_uint, gl_intptr, gl_sizeiptr) = nullptr;
  void(HUSH_GLAPI* DispatchComputeIndirect)(gl_intptr) = nullptr;
  void(HUSH_GLAPI* DrawArraysIndirect)(gl_enum, const void*) = nullptr;
  void(HUSH_GLAPI* CopyBufferSubData)(gl_enum, gl_enum, gl_intptr, gl_intptr,
                                      gl_sizeiptr) = nullptr;
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
    gl_api::load(loader, BindBufferRange, "glBindBufferRange");
    gl_api::load(loader, DispatchComputeIndirect, "glDispatchComputeIndirect");
    gl_api::load(loader, DrawArraysIndirect, "glDrawArraysIndirect");
    gl_api::load(loader, CopyBufferSubData, "glCopyBufferSubData");
    gl_api::load(loader, FenceSync, "glFenceSync");
    gl_api::load(loader, ClientWaitSync, "glClientWaitSync");
    gl_api::load(loader, DeleteSync, "glDeleteSync");
  }
};

}  // namespace detail

// The limits of the context current on this thread (see npr_gabor_limits).
inline npr_gabor_limits npr_gabor_gl_limits(const detail::gl_api& gl) {
  npr_gabor_limits l;
  gl.GetIntegerv(detail::kGlMaxGeometryOutputVertices, &l.max_geometry_output_vertices);
  gl.GetIntegerv(detail::kGlMaxGeometryTotalOutputComponents, &l.max_geometry_output_components);
  gl.GetIntegerv(detail::kGlMaxGeometryShaderStorageBlocks, &l.max_geometry_storage_blocks);
  gl.GetIntegerv(detail::kGlMaxFragmentShaderStorageBlocks, &l.max_fragment_storage_blocks);
  detail::gl_int tex = 0, rb = 0, vp[2] = {0, 0};
  gl.GetIntegerv(detail::kGlMaxTextureSize, &tex);
  gl.GetIntegerv(detail::kGlMaxRenderbufferSize, &rb);
  gl.GetIntegerv(detail::kGlMaxViewportDims, vp);
  l.max_frame_side = std::min({tex, rb, vp[0], vp[1]});
  gl.check("hush::glsl::npr_gabor: querying limits");
  return l;
}

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_NPR_GABOR_GL_RASTER_HPP
