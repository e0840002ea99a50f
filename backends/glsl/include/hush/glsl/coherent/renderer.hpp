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
// Per frame the frame's depth, motion and object ids are uploaded (hush/glsl/frame_upload.hpp),
// one dispatch runs detail::coherent_pass_scalar's algorithm (the reprojection under GLSL
// `precise`, so no multiply-add is fused there and the visibility decisions equal the CPU's;
// the hashed white noise bit for bit; band-pass input as Perlin noise of CPU-split lattice
// coordinates, hush/glsl/library.hpp), and the new history is read back for the output. The
// reference frame's depth and ids and the history stay on the GPU (ping-pong buffers); the
// stream downloads them only when asked (serialize, copy, a CPU step, fresh(), history()).
//
// Tolerance against exec::scalar (tests/coherent/glsl_coherent_test.cpp): equal fresh flags
// (disocclusions), and values whose difference is float rounding of the blends (GLSL may fuse
// them) and, for band-pass input, of the Perlin evaluation (library.hpp: 2^-15): a recursion
// contracting by alpha, so bounded in the frame count (derived and measured in the test;
// docs/coherent.md has the table over frames).
//
// Limits: every buffer within GL_MAX_SHADER_STORAGE_BLOCK_SIZE (hush::invalid_argument naming
// it otherwise), 8 storage blocks (the GL 4.3 minimum). Throws std::runtime_error for GL errors.
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
#include "hush/glsl/coherent/glsl.hpp"
#include "hush/glsl/compute_source.hpp"
#include "hush/glsl/device.hpp"
#include "hush/glsl/frame_upload.hpp"

namespace hush {
namespace glsl {

namespace detail {

// The GPU side of a coherent stream's state: frames (ping-pong: the reference is the other
// one), motion, history (ping-pong), field planes; and the compiled program.
class coherent_gpu_state final : public hush::detail::coherent_device_state {
 public:
  coherent_gpu_state(glsl::device& dev, std::uint32_t width, std::uint32_t height, int channels)
      : dev_(dev), gl_(dev.gl()), width_(width), height_(height), channels_(channels) {
    frames_[0] = std::make_unique<frame_upload>(gl_, dev.max_buffer_bytes());
    frames_[1] = std::make_unique<frame_upload>(gl_, dev.max_buffer_bytes());
    gl_.GenBuffers(3, buffers_);
    gl_.check("hush::glsl::coherent: setting up");
  }
  coherent_gpu_state(const coherent_gpu_state&) = delete;
  coherent_gpu_state& operator=(const coherent_gpu_state&) = delete;
  ~coherent_gpu_state() override { gl_.DeleteBuffers(3, buffers_); }

  const void* device() const override { return &dev_; }
  bool fits(std::uint32_t w, std::uint32_t h, int channels) const {
    return w == width_ && h == height_ && channels == channels_;
  }

  // The host state into the buffers (a stream that ran on the CPU continues here).
  void upload(const hush::detail::coherent_state<float>& st) {
    const std::size_t n = st.pixels();
    history_bytes(n);
    if (!st.has_reference) return;  // the pass will not read a history
    std::vector<float> all(n * (static_cast<std::size_t>(channels_) + 1));
    std::copy(st.history.begin(), st.history.end(), all.begin());
    for (std::size_t p = 0; p < st.fresh.size(); ++p)
      all[n * static_cast<std::size_t>(channels_) + p] = st.fresh[p] ? 1.0f : 0.0f;
    set(buffers_[kHistory + cur_], all.data(), all.size() * sizeof(float));
    frame ref;
    ref.depth = {st.ref_depth.data(), width_, height_};
    if (st.reference_has_ids) ref.object_id = {st.ref_ids.data(), width_, height_};
    frames_[1 - frame_]->upload(
        ref, st.reference_has_ids ? frame_view::depth | frame_view::object_id : frame_view::depth);
    ref_ids_ = st.reference_has_ids;
  }

  void download(void* host) override {
    auto& st = *static_cast<hush::detail::coherent_state<float>*>(host);
    const std::size_t n = st.pixels();
    std::vector<float> all(n * (channels_ + 1));
    get(buffers_[kHistory + cur_], all.data(), all.size() * sizeof(float));
    st.history.assign(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(n * channels_));
    st.fresh.resize(n);
    for (std::size_t p = 0; p < n; ++p) st.fresh[p] = all[n * channels_ + p] != 0.0f ? 1u : 0u;
    if (st.has_reference) {
      st.ref_depth.resize(n);
      get(frames_[1 - frame_]->buffer(frame_view::depth), st.ref_depth.data(), n * sizeof(float));
      st.reference_has_ids = ref_ids_;
      if (ref_ids_) {
        st.ref_ids.resize(n);
        get(frames_[1 - frame_]->buffer(frame_view::object_id), st.ref_ids.data(), n * 4);
      } else {
        st.ref_ids.clear();
      }
    }
  }

  // One pass step (see coherent_glsl_step).
  void step(hush::detail::coherent_state<float>& st, const hush::detail::coherent_step<float>& s) {
    namespace c = hush::detail::constants;
    const coherent_params& prm = *s.prm;
    const frame& f = *s.f;
    const std::size_t n = st.pixels();
    const frame_view motion_view = s.backward ? frame_view::forward_velocity : frame_view::velocity;
    const bool ids = f.object_id.data != nullptr;
    frame_upload& cur = *frames_[frame_];
    cur.upload(f, ids ? frame_view::depth | motion_view | frame_view::object_id
                      : frame_view::depth | motion_view);
    // Fields: white keys, band-pass lattice tables, or the caller's planes.
    std::vector<std::uint32_t> planes;
    gl_uint key[kCoherentFieldSlots] = {}, offset[kCoherentFieldSlots] = {};
    const bool bandpass = prm.input == coherent_input::bandpass && !s.input;
    const coherent_field_mode input_mode = s.input    ? coherent_field_mode::plane
                                           : bandpass ? coherent_field_mode::bandpass
                                                      : coherent_field_mode::white;
    const coherent_field_mode refill_mode =
        bandpass ? coherent_field_mode::bandpass : coherent_field_mode::white;
    const unsigned fx = s.backward ? c::kCoherentFieldBackRefillX : c::kCoherentFieldRefillX;
    const unsigned fy = s.backward ? c::kCoherentFieldBackRefillY : c::kCoherentFieldRefillY;
    for (int ch = 0; ch < prm.channels; ++ch) {
      const unsigned roles[kCoherentFieldUniforms] = {c::kCoherentFieldInput, fx, fy};
      for (unsigned k = 0; k < kCoherentFieldUniforms; ++k) {
        const std::size_t i = kCoherentFieldUniforms * static_cast<unsigned>(ch) + k;
        const std::uint32_t fk = hush::detail::coherent_frame_key(
            prm.seed, static_cast<unsigned>(ch), roles[k], st.next_frame);
        key[i] = fk;
        if (k == 0 && s.input) {
          offset[i] = static_cast<gl_uint>(planes.size());
          const image_view<const float>& in = s.input[ch];
          for (std::size_t y = 0; y < in.height; ++y)
            for (std::size_t x = 0; x < in.width; ++x) {
              std::uint32_t bits;
              std::memcpy(&bits, &in(x, y), 4);
              planes.push_back(bits);
            }
        } else if (bandpass) {
          key[i] = seed_key(fk);  // hush::perlin<2>(fk)'s key
          offset[i] = static_cast<gl_uint>(planes.size());
          const hush::detail::coherent_bandpass bp(fk, prm.bandpass_pixels, width_ + 1,
                                                   height_ + 1);
          for (int axis = 0; axis < 2; ++axis)
            for (std::size_t j = 0; j < bp.g.size[static_cast<std::size_t>(axis)]; ++j) {
              const lattice_coord<float> lc = lattice_split<float>(
                  bp.g.coordinate(axis, j), 0u);
              std::uint32_t bits;
              std::memcpy(&bits, &lc.f, 4);
              planes.insert(planes.end(), {lc.i0, lc.i1, bits});
            }
        }
      }
    }
    if (planes.empty()) planes.push_back(0u);  // a valid binding
    require(planes.size() * 4, "the input planes");
    set(buffers_[kPlanes], planes.data(), planes.size() * 4);
    history_bytes(n);
    // Bindings.
    cur.bind(frame_view::depth, 0);
    cur.bind(ids ? frame_view::object_id : frame_view::depth, 1);
    const frame_upload& ref = *frames_[1 - frame_];
    ref.bind(frame_view::depth, 2);
    ref.bind(ref_ids_ ? frame_view::object_id : frame_view::depth, 3);
    cur.bind(motion_view, 4);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 5, buffers_[kHistory + cur_]);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 6, buffers_[kHistory + 1 - cur_]);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 7, buffers_[kPlanes]);
    // Uniforms: the float parameters as the CPU forms them (coherent_cpu_step).
    const gl_uint prog = program(input_mode, refill_mode);
    gl_int previous = 0;
    gl_.GetIntegerv(kGlCurrentProgram, &previous);
    gl_.UseProgram(prog);
    const double alpha = hush::detail::coherent_alpha<float>(prm.alpha);
    auto u = [&](const char* name, gl_uint v) {
      gl_.Uniform1ui(gl_.GetUniformLocation(prog, name), v);
    };
    auto uf = [&](const char* name, float v) {
      gl_uint b;
      std::memcpy(&b, &v, 4);
      u(name, b);
    };
    u("hush_count", static_cast<gl_uint>(n));
    gl_.Uniform2ui(gl_.GetUniformLocation(prog, "hush_size"), width_, height_);
    u("hush_flags", (st.has_reference ? 1u : 0u) | (ids && ref_ids_ && st.has_reference ? 2u : 0u) |
                        (prm.filter == coherent_filter::stationary ? 4u : 0u));
    u("hush_channels", static_cast<gl_uint>(prm.channels));
    uf("hush_sign", s.backward ? -1.0f : 1.0f);
    uf("hush_eps_rel", hush::detail::coherent_float_parameter(prm.epsilon));
    uf("hush_eps_abs", hush::detail::coherent_float_parameter(prm.epsilon_absolute));
    uf("hush_alpha", static_cast<float>(alpha));
    uf("hush_beta", static_cast<float>(1.0 - alpha));
    uf("hush_k", static_cast<float>(coherent_k(alpha)));
    uf("hush_scale", hush::detail::coherent_bandpass_scale());
    const auto slots = static_cast<gl_sizei>(kCoherentFieldSlots);
    gl_.Uniform1uiv(gl_.GetUniformLocation(prog, "hush_field_key"), slots, key);
    gl_.Uniform1uiv(gl_.GetUniformLocation(prog, "hush_field_offset"), slots, offset);
    const gl_int first = gl_.GetUniformLocation(prog, "hush_first");
    const std::size_t groups = (n + kLocalSize - 1) / kLocalSize;
    for (std::size_t g0 = 0; g0 < groups; g0 += dev_.max_groups_per_dispatch()) {
      gl_.Uniform1ui(first, static_cast<gl_uint>(g0 * kLocalSize));
      gl_.DispatchCompute(
          static_cast<gl_uint>(std::min(dev_.max_groups_per_dispatch(), groups - g0)), 1u, 1u);
    }
    gl_.MemoryBarrier(kGlShaderStorageBarrierBit | kGlBufferUpdateBarrierBit);
    gl_.UseProgram(static_cast<gl_uint>(previous));
    gl_.check("hush::glsl::coherent: running a pass");
    // The new history is current; this frame becomes the reference.
    cur_ = 1 - cur_;
    frame_ = 1 - frame_;
    ref_ids_ = ids;
    // The output: gain * history, formed on the CPU as the CPU pass forms it.
    if (s.out_count) {
      out_.resize(n * static_cast<std::size_t>(prm.channels));
      get(buffers_[kHistory + cur_], out_.data(), out_.size() * sizeof(float));
      for (std::size_t ch = 0; ch < s.out_count; ++ch)
        for (std::size_t y = 0; y < height_; ++y)
          for (std::size_t x = 0; x < width_; ++x)
            s.out[ch](x, y) = s.gain * out_[ch * n + y * width_ + x];
    }
  }

  // The program for these field sources, compiled on first use.
  gl_uint program(coherent_field_mode input, coherent_field_mode refill) {
    auto it = programs_.find({input, refill});
    if (it == programs_.end())
      it = programs_
               .emplace(std::make_pair(input, refill),
                        link_program(gl_, {{kGlComputeShader, coherent_source(input, refill)}}))
               .first;
    return it->second.id();
  }

  // Throws hush::invalid_argument when `bytes` exceed one storage block.
  void require(std::size_t bytes, const char* what) const {
    if (bytes > dev_.max_buffer_bytes())
      hush::detail::throw_out_of_range("hush::glsl::coherent", what, bytes,
                                       ("at most " + std::to_string(dev_.max_buffer_bytes()) +
                                        " bytes (GL_MAX_SHADER_STORAGE_BLOCK_SIZE)")
                                           .c_str());
  }

 private:
  enum : int { kHistory = 0, kPlanes = 2 };  // buffers_: history[2], planes

  // Both history buffers sized for n pixels (channels planes and the fresh flags).
  void history_bytes(std::size_t n) {
    const std::size_t bytes = n * (static_cast<std::size_t>(channels_) + 1) * sizeof(float);
    require(bytes, "the history (pixels * (channels + 1) * 4 bytes)");
    if (allocated_ == bytes) return;
    for (int k = 0; k < 2; ++k) set(buffers_[kHistory + k], nullptr, bytes);
    allocated_ = bytes;
  }
  void set(gl_uint buffer, const void* data, std::size_t bytes) {
    gl_.BindBuffer(kGlShaderStorageBuffer, buffer);
    gl_.BufferData(kGlShaderStorageBuffer, static_cast<gl_sizeiptr>(bytes), data, kGlDynamicRead);
  }
  void get(gl_uint buffer, void* data, std::size_t bytes) {
    gl_.BindBuffer(kGlShaderStorageBuffer, buffer);
    gl_.GetBufferSubData(kGlShaderStorageBuffer, 0, static_cast<gl_sizeiptr>(bytes), data);
    gl_.check("hush::glsl::coherent: reading a buffer");
  }

  glsl::device& dev_;
  const gl_api& gl_;
  std::uint32_t width_, height_;
  int channels_;
  std::unique_ptr<frame_upload> frames_[2];
  gl_uint buffers_[3] = {};
  std::map<std::pair<coherent_field_mode, coherent_field_mode>, gl_program> programs_;
  int cur_ = 0;    // history buffer holding the current history
  int frame_ = 0;  // frame_upload the next frame goes to (the other holds the reference)
  bool ref_ids_ = false;
  std::size_t allocated_ = 0;
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
