// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::glsl::anisotropic_frame: a whole frame of anisotropic noise rendered on the GPU from
// GL textures the caller owns into a caller-owned R32F texture: no read-back and no per-pixel
// CPU work (one draw of a full-screen triangle whose fragment shader calls the kit's
// functions, hush/glsl/anisotropic/shader.hpp), so the host's time per frame does not depend
// on the pixel count. Per pixel (x, y) it reads texel (x, y) of
//   uv         RG32F or RGBA32F: (u, v), and in .w the coverage (0: background, written as 0;
//              an RG texture reads .w = 1: every pixel covered);
//   jacobian   RGBA32F (du/dx, du/dy, dv/dx, dv/dy) in uv units per pixel, hush::frame's
//              uv_jacobian layout; or none (0): the Jacobian from neighbouring uvs, central
//              differences (x +- 1, y +- 1), one-sided where a neighbour is background or
//              outside the frame, 0 (no filtering along that axis) where both are;
//   surface_map  RGBA32F (m00, m01, m10, m11) per pixel (hush::surface_map T, row by row),
//              or none (0): no distortion compensation;
// and writes the noise to texel (x, y) of the output (R32F, width x height). Inputs are read with
// texelFetch: they must be complete textures (GL_NEAREST filtering, or all mipmap levels; an
// incomplete one reads 0, all background). The Jacobian's y
// is along increasing texel rows, whichever way the caller's rows run (the footprint J J^T does
// not depend on its sign). Values: the kit's, within anisotropic_shader_tolerance of the CPU's
// float sample at the same inputs (with neighbour differences: of the Jacobian they form).
//
// GL state: render() binds its program, a vertex array, its framebuffer and the textures at
// units 0-2 (the kit, at its bindings) and 3-5 (the inputs), sets the viewport, then restores
// the draw framebuffer binding and the viewport it found; the program, vertex array and those
// texture units are left unbound (0). Blending, depth and scissor tests must be off for its
// draw. A GL 4.3 context current on this thread; not copyable; destroy it while the context
// lives.
//
// render_image() is the CPU-image convenience on top: it uploads a hush::frame's uv and
// uv_jacobian views (the depth view gives the size, as for every hush::frame) (object_id, when
// present, as the coverage) and per-pixel maps to textures it keeps, renders and reads the image
// back (width x height floats, row y of the frame at y * width).
#ifndef HUSH_GLSL_ANISOTROPIC_FRAME_HPP
#define HUSH_GLSL_ANISOTROPIC_FRAME_HPP

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "hush/anisotropic.hpp"
#include "hush/core/error.hpp"
#include "hush/core/frame.hpp"
#include "hush/glsl/anisotropic/shader.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/detail/gl_raster.hpp"
#include "hush/glsl/shader.hpp"

namespace hush {
namespace glsl {

class anisotropic_frame {
 public:
  using gl_uint = detail::gl_uint;
  // The caller's textures (GL names; 0 = not given, see the file comment).
  struct inputs {
    gl_uint uv = 0;
    gl_uint jacobian = 0;
    gl_uint surface_map = 0;
  };

  // Compiles the program and uploads the kit of `noise` (its block and tiles). Throws
  // std::runtime_error on a GL error, hush::invalid_argument for least-squares rules.
  anisotropic_frame(detail::loader_fn loader, const anisotropic& noise)
      : gl_(loader), gr_(loader), kit_(shader_for(noise)), bound_(loader, kit_) {
    program_ = detail::link_program(
        gl_, {{detail::kGlVertexShader, kVertexShader},
              {detail::kGlFragmentShader, "#version 430 core\n" + kit_.source + kFragmentMain}});
    gl_.UseProgram(program_.id());
    for (int t = 0; t < 3; ++t)
      gl_.Uniform1i(gl_.GetUniformLocation(program_.id(), kInputNames[t]), kFirstInputUnit + t);
    loc_size_ = gl_.GetUniformLocation(program_.id(), "hush_frame_size");
    loc_flags_ = gl_.GetUniformLocation(program_.id(), "hush_frame_flags");
    gl_.UseProgram(0u);
    gr_.GenFramebuffers(1, &fbo_);
    gr_.GenVertexArrays(1, &vao_);
    gl_.check("hush::glsl::anisotropic_frame: setting up");
  }
  anisotropic_frame(const anisotropic_frame&) = delete;
  anisotropic_frame& operator=(const anisotropic_frame&) = delete;
  ~anisotropic_frame() {
    gr_.DeleteFramebuffers(1, &fbo_);
    gr_.DeleteVertexArrays(1, &vao_);
    gl_.DeleteTextures(static_cast<detail::gl_sizei>(own_.size()), own_.data());
  }

  // Renders the frame into `output` (an R32F texture of width x height). Issues the draw and
  // returns: the caller synchronises (glFinish, a fence, or its next use of the texture).
  // Throws hush::invalid_argument for a missing uv texture or a non-positive size,
  // std::runtime_error when the output cannot be a colour attachment.
  void render(const inputs& in, gl_uint output, int width, int height) {
    if (in.uv == 0u || output == 0u || width <= 0 || height <= 0)
      hush::detail::raise_error(
          "hush::glsl::anisotropic_frame::render: a uv texture, an output texture and a "
          "positive size are needed");
    detail::gl_int old_fbo = 0, old_viewport[4] = {0, 0, 0, 0};
    gl_.GetIntegerv(detail::kGlDrawFramebufferBinding, &old_fbo);
    gl_.GetIntegerv(detail::kGlViewport, old_viewport);
    gr_.BindFramebuffer(detail::kGlDrawFramebuffer, fbo_);
    gr_.FramebufferTexture2D(detail::kGlDrawFramebuffer, detail::kGlColorAttachment0, detail::kGlTexture2d, output, 0);
    if (gr_.CheckFramebufferStatus(detail::kGlDrawFramebuffer) != detail::kGlFramebufferComplete) {
      gr_.BindFramebuffer(detail::kGlDrawFramebuffer, static_cast<gl_uint>(old_fbo));
      hush::detail::raise_error<std::runtime_error>(
          "hush::glsl::anisotropic_frame::render: the output texture is not renderable (R32F "
          "of the frame's size expected)");
    }
    gr_.Viewport(0, 0, width, height);
    gl_.UseProgram(program_.id());
    bound_.bind();
    const gl_uint tex[3] = {in.uv, in.jacobian, in.surface_map};
    for (int t = 0; t < 3; ++t) {
      gl_.ActiveTexture(detail::kGlTexture0 + static_cast<detail::gl_enum>(kFirstInputUnit + t));
      gl_.BindTexture(detail::kGlTexture2d, tex[t]);
    }
    gl_.Uniform2ui(loc_size_, static_cast<gl_uint>(width), static_cast<gl_uint>(height));
    gl_.Uniform2ui(loc_flags_, in.jacobian != 0u ? 1u : 0u, in.surface_map != 0u ? 1u : 0u);
    gr_.BindVertexArray(vao_);
    gr_.DrawArrays(detail::kGlTriangles, 0, 3);
    gr_.BindVertexArray(0u);
    for (int t = 0; t < 3 + 3; ++t) {
      gl_.ActiveTexture(detail::kGlTexture0 + static_cast<detail::gl_enum>(t));
      gl_.BindTexture(detail::kGlTexture2d, 0u);
    }
    gl_.ActiveTexture(detail::kGlTexture0);
    gl_.UseProgram(0u);
    gr_.FramebufferTexture2D(detail::kGlDrawFramebuffer, detail::kGlColorAttachment0, detail::kGlTexture2d, 0u, 0);
    gr_.BindFramebuffer(detail::kGlDrawFramebuffer, static_cast<gl_uint>(old_fbo));
    gr_.Viewport(old_viewport[0], old_viewport[1], old_viewport[2], old_viewport[3]);
    gl_.check("hush::glsl::anisotropic_frame::render");
  }

  // The CPU-image convenience (file comment): f's uv and uv_jacobian views (object_id as the
  // coverage when present) and, when not empty, one surface map per pixel (row-major,
  // width * height). Returns width * height floats, background 0.
  std::vector<float> render_image(const hush::frame& f, const std::vector<surface_map>& maps = {}) {
    f.validate("hush::glsl::anisotropic_frame::render_image",
               frame_view::uv | frame_view::uv_jacobian, std::size_t(1) << 14);
    const std::size_t w = f.width(), h = f.height(), n = w * h;
    if (!maps.empty() && maps.size() != n)
      hush::detail::raise_error(
          "hush::glsl::anisotropic_frame::render_image: maps must be empty or one per pixel");
    std::vector<float> uv(4 * n), jac(4 * n), map(maps.empty() ? 0 : 4 * n);
    const bool ids = f.object_id.data != nullptr;
    for (std::size_t y = 0; y < h; ++y)
      for (std::size_t x = 0; x < w; ++x) {
        const std::size_t q = y * w + x;
        const vec2 p = f.uv(x, y);
        const vec4 j = f.uv_jacobian(x, y);
        const float cover = ids && f.object_id(x, y) == 0u ? 0.0f : 1.0f;
        uv[4 * q] = p.x;
        uv[4 * q + 1] = p.y;
        uv[4 * q + 3] = cover;
        jac[4 * q] = j.x;
        jac[4 * q + 1] = j.y;
        jac[4 * q + 2] = j.z;
        jac[4 * q + 3] = j.w;
        if (!maps.empty()) {
          map[4 * q] = maps[q].m00;
          map[4 * q + 1] = maps[q].m01;
          map[4 * q + 2] = maps[q].m10;
          map[4 * q + 3] = maps[q].m11;
        }
      }
    const auto gw = static_cast<int>(w), gh = static_cast<int>(h);
    if (own_.empty() || own_w_ != gw || own_h_ != gh) {
      gl_.DeleteTextures(static_cast<detail::gl_sizei>(own_.size()), own_.data());
      own_.assign(4, 0u);
      gl_.GenTextures(4, own_.data());
      for (std::size_t t = 0; t < 4; ++t) allocate(own_[t], gw, gh, t == 3, nullptr);
      own_w_ = gw;
      own_h_ = gh;
    }
    allocate(own_[0], gw, gh, false, uv.data());
    allocate(own_[1], gw, gh, false, jac.data());
    if (!maps.empty()) allocate(own_[2], gw, gh, false, map.data());
    render({own_[0], own_[1], maps.empty() ? 0u : own_[2]}, own_[3], gw, gh);
    std::vector<float> out(n);
    detail::gl_int old_fbo = 0;
    gl_.GetIntegerv(detail::kGlReadFramebufferBinding, &old_fbo);
    gr_.BindFramebuffer(detail::kGlReadFramebuffer, fbo_);
    gr_.FramebufferTexture2D(detail::kGlReadFramebuffer, detail::kGlColorAttachment0, detail::kGlTexture2d, own_[3], 0);
    gl_.PixelStorei(detail::kGlPackAlignment, 4);
    gr_.ReadPixels(0, 0, gw, gh, detail::kGlRedChannel, detail::kGlFloat, out.data());
    gr_.FramebufferTexture2D(detail::kGlReadFramebuffer, detail::kGlColorAttachment0, detail::kGlTexture2d, 0u, 0);
    gr_.BindFramebuffer(detail::kGlReadFramebuffer, static_cast<gl_uint>(old_fbo));
    gl_.check("hush::glsl::anisotropic_frame::render_image");
    return out;
  }

  const shader_kit& kit() const { return kit_; }

 private:
  // The inputs' texture units, after the kit's (0-2).
  static constexpr int kFirstInputUnit = 3;
  static constexpr const char* kInputNames[3] = {"hush_frame_uv", "hush_frame_jacobian",
                                                 "hush_frame_map"};

  static constexpr const char* kVertexShader =
      "#version 430 core\n"
      "void main() {\n"
      "  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - "
      "1.0);\n"
      "  gl_Position = vec4(p, 0.0, 1.0);\n"
      "}\n";
  // Per pixel: its uv and coverage, the Jacobian (given, or central differences of covered
  // neighbours), the map, the kit's function.
  static constexpr const char* kFragmentMain = R"glsl(
uniform sampler2D hush_frame_uv;
uniform sampler2D hush_frame_jacobian;
uniform sampler2D hush_frame_map;
uniform uvec2 hush_frame_size;
uniform uvec2 hush_frame_flags;  // (Jacobian given, maps given)
layout(location = 0) out float hush_frame_out;
// uv of the texel at p when covered and inside the frame.
bool hush_frame_fetch(ivec2 p, out vec2 uv) {
  if (p.x < 0 || p.y < 0 || p.x >= int(hush_frame_size.x) || p.y >= int(hush_frame_size.y))
    return false;
  vec4 t = texelFetch(hush_frame_uv, p, 0);
  uv = t.xy;
  return t.w != 0.0;
}
// d(uv) along one axis at p: central, one-sided at the frame's and the coverage's edges.
vec2 hush_frame_difference(ivec2 p, ivec2 step, vec2 uv) {
  vec2 lo, hi;
  bool has_lo = hush_frame_fetch(p - step, lo), has_hi = hush_frame_fetch(p + step, hi);
  if (has_lo && has_hi) return (hi - lo) / 2.0;
  if (has_hi) return hi - uv;
  if (has_lo) return uv - lo;
  return vec2(0.0);
}
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 uv;
  if (!hush_frame_fetch(p, uv)) {
    hush_frame_out = 0.0;
    return;
  }
  vec2 dx, dy;
  if (hush_frame_flags.x != 0u) {
    vec4 j = texelFetch(hush_frame_jacobian, p, 0);  // du/dx, du/dy, dv/dx, dv/dy
    dx = j.xz;
    dy = j.yw;
  } else {
    dx = hush_frame_difference(p, ivec2(1, 0), uv);
    dy = hush_frame_difference(p, ivec2(0, 1), uv);
  }
  if (hush_frame_flags.y != 0u) {
    vec4 m = texelFetch(hush_frame_map, p, 0);  // m00, m01, m10, m11
    hush_frame_out = hush_anisotropic_mapped(uv, dx, dy, mat2(m.x, m.z, m.y, m.w));
  } else {
    hush_frame_out = hush_anisotropic(uv, dx, dy);
  }
}
)glsl";

  // (Re)specifies texture t as RGBA32F (or R32F for the output) of w x h with `data`.
  void allocate(gl_uint t, int w, int h, bool r32f, const float* data) {
    gl_.BindTexture(detail::kGlTexture2d, t);
    gl_.PixelStorei(detail::kGlUnpackAlignment, 4);
    gl_.TexImage2D(detail::kGlTexture2d, 0,
                   static_cast<detail::gl_int>(r32f ? detail::kGlR32fFormat : detail::kGlRgba32f), w, h, 0,
                   r32f ? detail::kGlRedChannel : detail::kGlRgba, detail::kGlFloat, data);
    gl_.TexParameteri(detail::kGlTexture2d, detail::kGlTextureMinFilter,
                      static_cast<detail::gl_int>(detail::kGlNearestFilter));
    gl_.TexParameteri(detail::kGlTexture2d, detail::kGlTextureMagFilter,
                      static_cast<detail::gl_int>(detail::kGlNearestFilter));
    gl_.BindTexture(detail::kGlTexture2d, 0u);
  }

  detail::gl_api gl_;
  detail::gl_raster_api gr_;
  shader_kit kit_;
  bound_kit bound_;
  detail::gl_program program_;
  detail::gl_int loc_size_ = -1, loc_flags_ = -1;
  gl_uint fbo_ = 0, vao_ = 0;
  std::vector<gl_uint> own_;  // render_image's uv, Jacobian, map and output textures
  int own_w_ = 0, own_h_ = 0;
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_ANISOTROPIC_FRAME_HPP
