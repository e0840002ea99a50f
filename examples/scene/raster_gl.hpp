// hush — test scenes: the G-buffer of gbuffer.hpp rendered by OpenGL 4.5 core
// through OSMesa (llvmpipe; headless, no GPU needed). Built only with OSMesa
// (HUSH_SCENE_HAVE_GL). A second, independent producer of the same G-buffer as
// render_cpu: tests compare the two (docs/scenes.md states the agreement).
//
// One draw per object into 8 render targets (RGBA32F: position + depth, normal,
// barycentric, velocity, forward velocity, uv, uv Jacobian; RG32UI: object and
// triangle ID) with a
// 32-bit float depth buffer. Meshes are drawn unindexed (3 vertices per triangle,
// each carrying its barycentric corner), so gl_PrimitiveID is the triangle index
// and the interpolated corner is the perspective-correct barycentric coordinate.
// Velocity: the vertex shader also outputs the vertex's clip position under frame
// i-1's transforms (and frame i+1's, for the forward velocity); interpolated
// (perspective-correct, exact for an affine function of the surface point) and
// projected in the fragment shader. The uv
// Jacobian is analytic: (uv/w, 1/w) are affine in screen space, so their fine
// screen derivatives are exact and d(uv)/dx = ((uv/w)_x (1/w) - (uv/w) (1/w)_x) w^2.
// Back faces of closed meshes are culled, the near plane is the camera's
// (projection_matrix), as in render_cpu. Precision is float32 throughout.
#ifndef HUSH_SCENE_RASTER_GL_HPP
#define HUSH_SCENE_RASTER_GL_HPP

#include <memory>
#include <string>

#include "gbuffer.hpp"
#include "scene.hpp"

namespace hush_tools {
namespace scene {

class gl_rasterizer {
 public:
  // Creates an OSMesa GL 4.5 core context, current on the calling thread, and
  // compiles the shaders. Throws std::runtime_error when either fails.
  gl_rasterizer();
  ~gl_rasterizer();
  gl_rasterizer(const gl_rasterizer&) = delete;
  gl_rasterizer& operator=(const gl_rasterizer&) = delete;

  // Frame `frame` (>= 0) of `s`, width x height pixels (1 ... kMaxImageSize and at
  // most GL_MAX_RENDERBUFFER_SIZE). Meshes are uploaded once and kept while this
  // object lives. Throws hush::invalid_argument for bad arguments, std::runtime_error
  // on a GL error.
  gbuffer render(const scene& s, int frame, int width, int height);

  // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits); 4.5 (Core Profile)
  // Mesa 22.3.6".
  std::string renderer() const;

 private:
  struct impl;
  std::unique_ptr<impl> impl_;
};

// One frame with a temporary gl_rasterizer (context creation costs ~0.1 s: reuse a
// gl_rasterizer for sequences).
gbuffer render_gl(const scene& s, int frame, int width, int height);

}  // namespace scene
}  // namespace hush_tools

#endif  // HUSH_SCENE_RASTER_GL_HPP
