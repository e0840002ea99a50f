// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// NPR Gabor noise (include/hush/npr_gabor.hpp; Benard et al. 2010) from the caller's own
// G-buffer and triangle buffers on the GPU, into the caller's R32F texture:
//
//   hush::glsl::npr_gabor_gl_frame f;      // GL names and sizes (hush/glsl/npr_gabor/gl_frame.hpp)
//   f.depth = depth_tex; f.object_id = object_tex; f.triangle_id = triangle_tex;
//   f.width = w; f.height = h;
//   f.vertices = vertex_ssbo; f.vertex_count = nv;        // vec4 (x, y, depth, -) per vertex
//   f.triangles = triangle_ssbo; f.triangle_count = nt;   // 5 uints per triangle
//   hush::glsl::npr_gabor_gl_render(gpu.device, noise, f, out_tex);   // out_tex: R32F, w x h
//
// Both stages run as hush/glsl/npr_gabor/renderer.hpp describes (its error bound against the
// CPU holds here: the same passes and the same splatting program; the CPU-image path,
// noise.render(exec::glsl{device}, ...), uploads the frame into textures and the triangles
// into buffers of these layouts and runs the same code), except that stage 1 reads the
// caller's buffers and stage 2 the caller's textures and renders into `output` (cleared to 0,
// then the kernels summed with additive blending; a framebuffer of the renderer's own,
// detached again afterwards): no read-back and no per-pixel or per-triangle host work per
// frame, and no wait for the GPU. Host work per frame: the per-object kernel table
// (npr_gabor::kernel_of_object, O(objects), uploaded), then a command sequence whose length
// depends on the capacities alone: per level of the point walk (all 22) the expand, prefix-sum,
// plan and children passes, the records pass per level and one draw per storage block of
// record capacity, each sized on the GPU (the plan pass writes every level's count, its
// glDispatchComputeIndirect commands and the glDrawArraysIndirect counts; renderer.hpp).
// Capacities (nodes per level, kept per device): the first call on a device walks with each
// level's two totals read back (8 bytes per prefix sum) and sets each to twice that level's
// nodes (at least 4096 and npr_gabor_state(dev).reserve_resident's nodes; level 0's at least the
// triangle count, known without a read); it also maps a small status buffer once
// (persistently, where the context has glBufferStorage).
// A frame that needs more nodes at a level than its capacity keeps the nodes that fit (no
// write out of bounds) and so is not exact; the GPU counts it in status words copied after
// each frame into a fenced ring, which later calls read only once the fence has signalled
// (never waiting; from the persistent mapping, or on a context without glBufferStorage with
// glGetBufferSubData of those 128 finished bytes: then one such call per frame); having seen
// one, the next call walks with read-backs again and sets the capacities from that frame,
// exact from then on (a scene that reserves enough nodes per level never has such a frame).
// resident_overflows() and resident_capacity(k) of npr_gabor_state(dev) report them.
// The output may be sampled, attached or read at once (GL orders rendering before later use).
//
// Requirements: the sources constant or per object (npr_gabor::per_object_at_most; per-pixel
// and per-vertex sources need the CPU-image path), every buffer of stage 1 within
// GL_MAX_SHADER_STORAGE_BLOCK_SIZE (each level's capacity included); frame sides up to
// GL_MAX_TEXTURE_SIZE, GL_MAX_VIEWPORT_DIMS and GL_MAX_RENDERBUFFER_SIZE and
// kNprGaborMaxImageSide; at most kNprGaborMaxTriangles triangles. Throws hush::invalid_argument
// where these fail (the sources by param_source::validate, as npr_gabor::render), for a missing
// texture a test reads, a missing buffer (with triangles), or a buffer smaller than its count says
// (GL_BUFFER_SIZE); the vertex indices are not checked (out-of-range indices read undefined values,
// as in any shader). std::runtime_error for GL errors. GL state: as renderer.hpp's contract
// (indexed uniform-buffer binding 0 included), and the textures of units 0 - 2 are rebound (the
// renderer's sampler object is bound there during the draws only).
#ifndef HUSH_GLSL_NPR_GABOR_FRAME_HPP
#define HUSH_GLSL_NPR_GABOR_FRAME_HPP

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "hush/glsl/device.hpp"
#include "hush/glsl/npr_gabor/gl_frame.hpp"
#include "hush/glsl/npr_gabor/renderer.hpp"
#include "hush/npr_gabor.hpp"

namespace hush {
namespace glsl {

namespace detail {

constexpr gl_enum kGlBufferSize = 0x8764;  // GL_BUFFER_SIZE

// Throws hush::invalid_argument when `buffer` (non-zero) holds fewer than `bytes`.
inline void require_buffer(const gl_api& gl, const char* where, const char* name, gl_uint buffer,
                           std::size_t bytes) {
  if (bytes == 0) return;
  if (buffer == 0u)
    hush::detail::throw_out_of_range(where, name, "0", "a buffer name (there are elements)");
  using get_fn = void(HUSH_GLAPI*)(gl_enum, gl_enum, gl_int*);
  get_fn get = nullptr;
  gl_api::load(gl.loader, get, "glGetBufferParameteriv");
  gl_int previous = 0, size = 0;
  gl.GetIntegerv(kGlShaderStorageBufferBinding, &previous);
  gl.BindBuffer(kGlShaderStorageBuffer, buffer);
  get(kGlShaderStorageBuffer, kGlBufferSize, &size);
  gl.BindBuffer(kGlShaderStorageBuffer, static_cast<gl_uint>(previous));
  gl.check(where);
  if (size < 0 || static_cast<std::size_t>(size) < bytes)
    hush::detail::throw_out_of_range(where, std::string(name) + " buffer size",
                                     static_cast<long long>(size),
                                     ("at least " + std::to_string(bytes) + " bytes").c_str());
}

}  // namespace detail

// Renders `noise` over the frame `f` (the caller's GL objects, gl_frame.hpp) into `output`
// (GL_R32F, f.width x f.height), with per-object sources `src`. Contract above.
inline void npr_gabor_gl_render(device& dev, const npr_gabor& noise, const npr_gabor_gl_frame& f,
                                detail::gl_uint output, const npr_gabor::sources& src = {}) {
  namespace c = hush::detail::constants;
  const char* where = "hush::glsl::npr_gabor_gl_render";
  if (f.width == 0 || f.height == 0 || f.width > c::kNprGaborMaxImageSide ||
      f.height > c::kNprGaborMaxImageSide)
    hush::detail::throw_out_of_range(
        where, "frame size", std::to_string(f.width) + "x" + std::to_string(f.height),
        ("sides 1 ... " + std::to_string(c::kNprGaborMaxImageSide)).c_str());
  if (f.triangle_count > c::kNprGaborMaxTriangles)
    hush::detail::throw_out_of_range(where, "triangle_count", f.triangle_count,
                                     "at most kNprGaborMaxTriangles");
  const npr_gabor::params& p = noise.parameters();
  const struct {
    bool read;
    detail::gl_uint name;
    const char* what;
  } textures[3] = {{p.depth_test, f.depth, "depth"},
                   {p.object_test, f.object_id, "object_id"},
                   {p.triangle_test, f.triangle_id, "triangle_id"}};
  for (const auto& t : textures)
    if (t.read && t.name == 0u)
      hush::detail::throw_out_of_range(where, t.what, "0",
                                       "a texture name (the noise's tests read it)");
  if (output == 0u) hush::detail::throw_out_of_range(where, "output", "0", "a GL_R32F texture");
  // The sources, as npr_gabor::render checks them (no pixel or vertex is read: per-object
  // sources only reach stage 1 here).
  if (!npr_gabor::per_object_at_most(src))
    hush::detail::throw_out_of_range(where, "sources", "per pixel or per vertex",
                                     "constant or per object (npr_gabor::per_object_at_most)");
  src.frequency.validate(where, "frequency", 0.0, c::kNprGaborMaxFrequency,
                         "0 <= frequency <= 0.5 (cycles per pixel)", f.width, f.height, 0);
  src.orientation.validate(where, "orientation", -std::numeric_limits<double>::max(),
                           std::numeric_limits<double>::max(), "finite (radians)", f.width,
                           f.height, 0);
  src.bandwidth.validate(where, "bandwidth", c::kNprGaborMinBandwidth, c::kNprGaborMaxBandwidth,
                         "0.01 <= bandwidth <= 10 (1/pixel)", f.width, f.height, 0);
  src.impulses.validate(where, "impulses", std::numeric_limits<double>::min(), c::kGaborMaxImpulses,
                        "0 < impulses <= 256", f.width, f.height, 0);
  const detail::gl_api& gl = dev.gl();
  detail::require_buffer(gl, where, "vertices", f.vertices,
                         std::size_t(f.vertex_count) * kNprGaborVertexBytes);
  detail::require_buffer(gl, where, "triangles", f.triangles,
                         std::size_t(f.triangle_count) * kNprGaborTriangleBytes);
  if (!npr_gabor_state(dev).render_resident(noise, f, src, output))
    hush::detail::throw_out_of_range(
        where, "frame", std::to_string(f.triangle_count) + " triangles",
        ("stage 1 within one shader storage block per buffer (" +
         std::to_string(dev.max_buffer_bytes()) + " bytes, GL_MAX_SHADER_STORAGE_BLOCK_SIZE)")
            .c_str());
}

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_NPR_GABOR_FRAME_HPP
