// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The caller's GL objects of one NPR Gabor frame (hush/glsl/npr_gabor/frame.hpp renders from
// them) and the packing of a hush::triangle_list into the two triangle buffers: the layouts
// GPU stage 1 reads (hush/glsl/npr_gabor/glsl.hpp, bindings 0 and 1), whether the CPU-image
// path uploads them (renderer.hpp packs with npr_gabor_gl_pack) or the caller owns them.
#ifndef HUSH_GLSL_NPR_GABOR_GL_FRAME_HPP
#define HUSH_GLSL_NPR_GABOR_GL_FRAME_HPP

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hush/core/triangles.hpp"
#include "hush/glsl/detail/gl.hpp"

namespace hush {
namespace glsl {

// Bytes per vertex and per triangle in the two buffers.
constexpr std::size_t kNprGaborVertexBytes = 16;    // vec4: screen x, y (pixels), depth, unused
constexpr std::size_t kNprGaborTriangleBytes = 20;  // 5 uint: 3 vertex indices, triangle, object

// One frame as GL names (hush::frame and hush::triangle_list's meaning, core/frame.hpp and
// core/triangles.hpp). Textures: texel (x, y) is pixel (x, y), row 0 first; level 0 is read
// with texelFetch through the renderer's GL_NEAREST sampler; only those the noise's tests read
// (params::depth_test, object_test, triangle_test) must be present.
//   depth        GL_R32F   linear view depth (positive and finite on surfaces)
//   object_id    GL_R32UI  object id per pixel
//   triangle_id  GL_R32UI  triangle id per pixel
// Buffers (std430 shader storage, read from offset 0):
//   vertices     vertex_count vec4s: (screen x, screen y, depth, unused), pixels, y down
//   triangles    triangle_count x 5 uints: vertex indices i0, i1, i2 (each below vertex_count:
//                not checked, the data stays on the GPU), triangle id, object id
struct npr_gabor_gl_frame {
  detail::gl_uint depth = 0, object_id = 0, triangle_id = 0;
  std::uint32_t width = 0, height = 0;
  detail::gl_uint vertices = 0, triangles = 0;
  std::uint32_t vertex_count = 0, triangle_count = 0;
};

// `tris` (validated) in the two buffers' layouts: 4 floats per vertex, 5 words per triangle
// (at least one element each, so that an empty list still binds a buffer).
inline void npr_gabor_gl_pack(const triangle_list& tris, std::vector<float>& vertices,
                              std::vector<std::uint32_t>& triangles) {
  const std::size_t nv = tris.vertices(), nt = tris.triangles();
  vertices.assign(std::max<std::size_t>(nv, 1) * 4, 0.0f);
  for (std::size_t v = 0; v < nv; ++v) {
    vertices[4 * v] = tris.screen[v].x;
    vertices[4 * v + 1] = tris.screen[v].y;
    vertices[4 * v + 2] = tris.depth[v];
  }
  triangles.assign(std::max<std::size_t>(nt, 1) * 5, 0u);
  for (std::size_t t = 0; t < nt; ++t) {
    for (std::size_t i = 0; i < 3; ++i) triangles[5 * t + i] = tris.indices[3 * t + i];
    triangles[5 * t + 3] = tris.triangle_id[t];
    triangles[5 * t + 4] = tris.object_of(t);
  }
}

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_NPR_GABOR_GL_FRAME_HPP
