// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The GL side of NPR Gabor noise's raster path (hush/glsl/npr_gabor/renderer.hpp): the limits
// the renderer depends on, as the context reports them. The raster entry points and enums are
// hush/glsl/detail/gl_raster.hpp's.
#ifndef HUSH_GLSL_NPR_GABOR_GL_RASTER_HPP
#define HUSH_GLSL_NPR_GABOR_GL_RASTER_HPP

#include <algorithm>

#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/detail/gl_raster.hpp"
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

// The limits the NPR raster path queries (Khronos gl.xml).
constexpr gl_enum kGlMaxGeometryOutputVertices = 0x8DE0;
constexpr gl_enum kGlMaxGeometryTotalOutputComponents = 0x8DE1;
constexpr gl_enum kGlMaxGeometryShaderStorageBlocks = 0x90D7;
constexpr gl_enum kGlMaxFragmentShaderStorageBlocks = 0x90DA;
constexpr gl_enum kGlMaxViewportDims = 0x0D3A;
constexpr gl_enum kGlMaxRenderbufferSize = 0x84E8;

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
