// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Coherent noise (include/hush/coherent.hpp) on the GPU: one compute pass per frame, the
// history kept in shader storage buffers between frames. Include this header to use
// hush::exec::glsl{device} with hush::coherent_stream and hush::coherent_symmetric:
//
//   hush::glsl::headless_device gpu;               // or a device on the application's context
//   hush::coherent_stream stream{prm};
//   stream.advance(hush::exec::glsl{gpu.device}, frame, out);
//
// Per frame the frame's depth, motion and object ids are uploaded into textures and the
// resident pass runs (hush/glsl/coherent/frame.hpp: the same pass coherent_gl_stream runs on
// the caller's own textures): one dispatch of detail::coherent_pass_scalar's algorithm (the
// reprojection under GLSL `precise`, so no multiply-add is fused there and the visibility
// decisions equal the CPU's; the hashed white noise bit for bit; band-pass input as Perlin
// noise of CPU-split lattice coordinates, hush/glsl/library.hpp); then the new history is read
// back for the output. The reference frame's depth and ids and the history stay on the GPU
// (ping-pong buffers); the stream downloads them only when asked (serialize, copy, a CPU step,
// fresh(), history()).
//
// Tolerance against exec::scalar (tests/coherent/glsl_coherent_test.cpp): equal fresh flags
// (disocclusions), and values whose difference is float rounding of the blends (GLSL may fuse
// them) and, for band-pass input, of the Perlin evaluation (library.hpp: 2^-15): a recursion
// contracting by alpha, so bounded in the frame count (derived and measured in the test;
// docs/coherent.md has the table over frames).
//
// Limits: every buffer within GL_MAX_SHADER_STORAGE_BLOCK_SIZE (hush::invalid_argument naming
// it otherwise), 8 storage blocks, 3 textures and 4 images (GL 4.3 minimums). Throws
// std::runtime_error for GL errors.
#ifndef HUSH_GLSL_COHERENT_RENDERER_HPP
#define HUSH_GLSL_COHERENT_RENDERER_HPP

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "hush/coherent.hpp"
#include "hush/core/lattice.hpp"
#include "hush/glsl/coherent/frame.hpp"
#include "hush/glsl/coherent/glsl.hpp"
#include "hush/glsl/compute_source.hpp"
#include "hush/glsl/device.hpp"

namespace hush {
namespace glsl {

namespace detail {

// The GPU side of a coherent stream's state: the pass (hush/glsl/coherent/frame.hpp, the
// resident path) and the textures each CPU frame is uploaded into.
class coherent_gpu_state final : public hush::detail::coherent_device_state {
 public:
  coherent_gpu_state(glsl::device& dev, std::uint32_t width, std::uint32_t height, int channels)
      : pass_(dev, width, height, channels), gl_(dev.gl()), gr_(dev.gl().loader) {
    gl_.GenTextures(3, textures_);
    allocate_texture(gl_, textures_[kDepth], width, height, kGlR32fFormat, kGlRedChannel, kGlFloat);
    allocate_texture(gl_, textures_[kIds], width, height, kGlR32uiFormat, kGlRedInteger,
                     kGlUnsignedInt);
    allocate_texture(gl_, textures_[kMotion], width, height, kGlRgb32fFormat, kGlRgbChannels,
                     kGlFloat);
    gl_.check("hush::glsl::coherent: setting up");
  }
  coherent_gpu_state(const coherent_gpu_state&) = delete;
  coherent_gpu_state& operator=(const coherent_gpu_state&) = delete;
  ~coherent_gpu_state() override { gl_.DeleteTextures(3, textures_); }

  const void* device() const override { return &pass_.device(); }
  bool fits(std::uint32_t w, std::uint32_t h, int channels) const {
    return w == pass_.width() && h == pass_.height() && channels == pass_.channels();
  }

  // The host state into the buffers (a stream that ran on the CPU continues here).
  void upload(const hush::detail::coherent_state<float>& st) { pass_.upload(st); }

  void download(void* host) override {
    pass_.download(*static_cast<hush::detail::coherent_state<float>*>(host));
  }

  // One pass step (see coherent_glsl_step): the frame's views into the textures, the
  // resident pass, the new history read back for the output.
  void step(hush::detail::coherent_state<float>& st, const hush::detail::coherent_step<float>& s) {
    const frame& f = *s.f;
    const bool ids = f.object_id.data != nullptr;
    put(kDepth, f.depth, kGlRedChannel, kGlFloat);
    put(kMotion, s.backward ? f.forward_velocity : f.velocity, kGlRgbChannels, kGlFloat);
    if (ids) put(kIds, f.object_id, kGlRedInteger, kGlUnsignedInt);
    gl_.check("hush::glsl::coherent: uploading a frame");
    coherent_pass_args a;
    a.prm = s.prm;
    a.frame_index = st.next_frame;
    a.has_reference = st.has_reference;
    a.backward = s.backward;
    a.depth = textures_[kDepth];
    a.motion = textures_[kMotion];
    a.ids = ids ? textures_[kIds] : 0u;
    a.input = s.input;
    pass_.run(a);
    // The output: gain * history, formed on the CPU as the CPU pass forms it.
    if (s.out_count) {
      const std::size_t n = pass_.pixels(), w = pass_.width(), h = pass_.height();
      out_.resize(pass_.history_bytes() / sizeof(float));
      gl_.BindBuffer(kGlShaderStorageBuffer, pass_.history_buffer());
      gl_.GetBufferSubData(kGlShaderStorageBuffer, 0,
                           static_cast<gl_sizeiptr>(n * s.out_count * sizeof(float)), out_.data());
      gl_.check("hush::glsl::coherent: reading a buffer");
      for (std::size_t ch = 0; ch < s.out_count; ++ch)
        for (std::size_t y = 0; y < h; ++y)
          for (std::size_t x = 0; x < w; ++x) s.out[ch](x, y) = s.gain * out_[ch * n + y * w + x];
    }
  }

 private:
  enum : int { kDepth = 0, kIds = 1, kMotion = 2 };  // textures_
  static_assert(sizeof(vec3) == 3 * sizeof(float), "a velocity is one RGB32F texel");

  template <class T>
  void put(int k, const image_view<const T>& v, gl_enum layout, gl_enum type) {
    upload_view(gl_, gr_, textures_[k], v, layout, type);
  }

  coherent_gl_pass pass_;
  const gl_api& gl_;
  gl_resident_api gr_;
  gl_uint textures_[3] = {};
  std::vector<float> out_;
};

}  // namespace detail

// One coherent pass step on `dev` (what hush::coherent_stream::advance and
// hush::coherent_symmetric call for exec::glsl, found by argument-dependent lookup).
inline void coherent_glsl_step(device& dev, hush::detail::coherent_state<float>& st,
                               const hush::detail::coherent_step<float>& s) {
  auto* gpu = dynamic_cast<detail::coherent_gpu_state*>(st.device.get());
  if (!gpu || gpu->device() != &dev || !gpu->fits(st.width, st.height, s.prm->channels)) {
    st.sync_host();
    auto fresh =
        std::make_shared<detail::coherent_gpu_state>(dev, st.width, st.height, s.prm->channels);
    gpu = fresh.get();
    st.device = fresh;
    st.host_current = true;
  }
  if (st.host_current) gpu->upload(st);
  gpu->step(st, s);
  st.host_current = false;
  st.has_reference = true;
  ++st.next_frame;
}

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_COHERENT_RENDERER_HPP
