// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::glsl::frame_upload: the G-buffer views of a hush::frame (core/frame.hpp) in shader
// storage buffers, for the scene-driven GLSL programs (coherent noise, NPR Gabor noise).
// Each present view is packed row by row (a view's stride may exceed its width) into one
// std430 SSBO of 32-bit words:
//   depth             float[W H]          (pixel (x, y) at y W + x)
//   velocity          float[3 W H]        (dx, dy, dz per pixel)
//   forward_velocity  float[3 W H]
//   object_id         uint[W H]
//   triangle_id       uint[W H]
// upload() checks every buffer against the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE
// (device::max_buffer_bytes()) before touching GL and throws hush::invalid_argument naming
// the view and the limit when a frame does not fit; bind() attaches a view's buffer to an
// indexed SSBO binding point. The buffers are reused from frame to frame (reallocated only
// when a frame is larger). Not copyable; destroy it while its context is alive.
#ifndef HUSH_GLSL_FRAME_UPLOAD_HPP
#define HUSH_GLSL_FRAME_UPLOAD_HPP

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "hush/core/error.hpp"
#include "hush/core/frame.hpp"
#include "hush/glsl/detail/gl.hpp"

namespace hush {
namespace glsl {

class frame_upload {
 public:
  // The views in buffer order (index of a view's buffer).
  static constexpr std::array<frame_view, 5> kViews = {
      frame_view::depth, frame_view::velocity, frame_view::forward_velocity, frame_view::object_id,
      frame_view::triangle_id};

  frame_upload(const detail::gl_api& gl, std::size_t max_buffer_bytes)
      : gl_(gl), max_bytes_(max_buffer_bytes) {
    gl_.GenBuffers(static_cast<detail::gl_sizei>(kViews.size()), buffers_.data());
    gl_.check("hush::glsl::frame_upload: creating buffers");
  }
  frame_upload(const frame_upload&) = delete;
  frame_upload& operator=(const frame_upload&) = delete;
  ~frame_upload() {
    gl_.DeleteBuffers(static_cast<detail::gl_sizei>(kViews.size()), buffers_.data());
  }

  // Bytes of a view's buffer for a w x h frame, and whether it fits one SSBO.
  static std::size_t bytes(frame_view v, std::size_t w, std::size_t h) {
    const bool three = v == frame_view::velocity || v == frame_view::forward_velocity;
    return w * h * (three ? 3 : 1) * sizeof(std::uint32_t);
  }
  // Throws hush::invalid_argument when the views in `which` of a w x h frame do not fit.
  void require_fits(const char* where, frame_view which, std::size_t w, std::size_t h) const {
    for (frame_view v : kViews)
      if (has_view(which, v) && bytes(v, w, h) > max_bytes_)
        hush::detail::throw_out_of_range(
            where, std::string("frame size (") + name(v) + " buffer)",
            std::to_string(w) + "x" + std::to_string(h),
            ("a frame whose " + std::string(name(v)) + " fits one shader storage block of " +
             std::to_string(max_bytes_) + " bytes (GL_MAX_SHADER_STORAGE_BLOCK_SIZE)")
                .c_str());
  }

  // Uploads the views of `f` in `which` (each must be present; validate the frame first).
  void upload(const frame& f, frame_view which) {
    require_fits("hush::glsl::frame_upload", which, f.width(), f.height());
    for (std::size_t k = 0; k < kViews.size(); ++k) {
      const frame_view v = kViews[k];
      if (!has_view(which, v)) continue;
      switch (v) {
        case frame_view::depth:
          pack(f.depth);
          break;
        case frame_view::velocity:
          pack(f.velocity);
          break;
        case frame_view::forward_velocity:
          pack(f.forward_velocity);
          break;
        case frame_view::object_id:
          pack(f.object_id);
          break;
        default:
          pack(f.triangle_id);
          break;
      }
      gl_.BindBuffer(detail::kGlShaderStorageBuffer, buffers_[k]);
      gl_.BufferData(detail::kGlShaderStorageBuffer,
                     static_cast<detail::gl_sizeiptr>(staging_.size()), staging_.data(),
                     detail::kGlStreamDraw);
    }
    gl_.check("hush::glsl::frame_upload: uploading a frame");
  }

  // Attaches view v's buffer to SSBO binding point `binding`.
  void bind(frame_view v, detail::gl_uint binding) const {
    gl_.BindBufferBase(detail::kGlShaderStorageBuffer, binding, buffer(v));
  }
  detail::gl_uint buffer(frame_view v) const {
    for (std::size_t k = 0; k < kViews.size(); ++k)
      if (kViews[k] == v) return buffers_[k];
    return 0;
  }

  static const char* name(frame_view v) {
    switch (v) {
      case frame_view::depth:
        return "depth";
      case frame_view::velocity:
        return "velocity";
      case frame_view::forward_velocity:
        return "forward_velocity";
      case frame_view::object_id:
        return "object_id";
      default:
        return "triangle_id";
    }
  }

 private:
  // The view's rows, packed, into staging_ (bytes).
  template <class T>
  void pack(const image_view<const T>& v) {
    const std::size_t row = v.width * sizeof(T);
    staging_.resize(row * v.height);
    for (std::size_t y = 0; y < v.height; ++y)
      std::memcpy(staging_.data() + y * row, v.row(y), row);
  }

  const detail::gl_api& gl_;
  std::size_t max_bytes_;
  std::array<detail::gl_uint, 5> buffers_{};
  std::vector<unsigned char> staging_;
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_FRAME_UPLOAD_HPP
