// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Coherent noise (include/hush/coherent.hpp; Kass & Pesare 2011) from the caller's own
// G-buffer on the GPU, resident: the frame comes in as GL textures the caller owns, the noise
// goes out into R32F textures the caller owns, the history stays in the stream's storage
// buffers between frames. Per frame the host sets uniforms and dispatches one compute pass:
// no read-back, no per-pixel host work (with band-pass input, O(width + height) host work
// per frame for the lattice tables, see below).
//
//   hush::glsl::coherent_gl_stream noise(gpu.device, prm, width, height);
//   hush::glsl::coherent_gl_frame f{depth_tex, velocity_tex, ids_tex, width, height};
//   noise.advance(f, out_tex);                     // each frame; out_tex: R32F, width x height
//
// The textures (level 0 is read, with texelFetch, through the stream's own sampler object
// (GL_NEAREST), so the textures' own filters and mipmaps do not matter); texel (x, y) is pixel
// (x, y) of hush::frame (core/frame.hpp), row 0 first (GL's texel row 0):
//   depth     GL_R32F       linear view depth (hush::frame::depth; > 0 and finite on surfaces)
//   velocity  GL_RGB32F or GL_RGBA32F: (dx, dy, dz) in .xyz (hush::frame::velocity, backward:
//             the point seen at p was at p - (dx, dy) with depth depth - dz the frame before)
//   ids       GL_R32UI      object ids (hush::frame::object_id), or 0: none
//   outputs   GL_R32F       one per channel (up to coherent_params::channels), written with
//             imageStore: gain() times the history, as hush::coherent_stream's out
// Other float formats read too (the values are whatever texelFetch returns); the results equal
// the CPU-image path (exec::glsl, which uploads into such textures and runs this pass) bit for
// bit only for the 32-bit float and integer formats above. Textures the caller wrote with
// imageStore need the caller's glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT) first; after the
// pass the stream issues glMemoryBarrier(GL_ALL_BARRIER_BITS), so the outputs can be sampled,
// attached, read or copied at once.
//
// State: the history (channels planes and the fresh flags, float, width x height each) and the
// reference frame (depth bits and ids) in two ping-pong pairs of shader storage buffers the
// stream owns. reset() forgets the history (the next frame starts afresh, Kass & Pesare eq. 6)
// without touching GL; copy() duplicates the state on the GPU (glCopyBufferSubData, no
// read-back); to_stream() reads the state back into a hush::coherent_stream (continuing on the
// CPU or serialising), and the constructor from a coherent_stream uploads one.
//
// Error against the double reference and exec::scalar: hush/glsl/coherent/renderer.hpp's
// contract (the same pass). Not available here: output smoothing (coherent_params::smoothing
// must be 0: smooth in your own pass), the caller's input images (coherent_stream::advance's
// `input`), the time-symmetric filter (coherent_symmetric). Band-pass input fills, per frame and
// channel, three lattice tables of (width + 1) + (height + 1) triples on the host (the
// CPU-split Perlin coordinates, hush/glsl/library.hpp) and uploads them: host time O(width +
// height); white input: O(1).
//
// GL state: rebinds the textures of units 0 - 2 (its sampler object is bound there during the
// pass only), image units 0 - 3, the indexed shader-storage bindings 2 - 7 and
// GL_SHADER_STORAGE_BUFFER; restores the current program and active texture unit. Throws
// std::runtime_error for GL errors, hush::invalid_argument for a frame whose size differs from the
// stream's, a missing depth or velocity texture, more outputs than channels, smoothing, or buffers
// beyond GL_MAX_SHADER_STORAGE_BLOCK_SIZE. Not thread-safe; destroy it while its context is alive.
#ifndef HUSH_GLSL_COHERENT_FRAME_HPP
#define HUSH_GLSL_COHERENT_FRAME_HPP

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "hush/coherent.hpp"
#include "hush/core/lattice.hpp"
#include "hush/glsl/coherent/glsl.hpp"
#include "hush/glsl/compute_source.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/detail/gl_resident.hpp"
#include "hush/glsl/device.hpp"

namespace hush {
namespace glsl {

// The caller's G-buffer of one frame, as GL texture names (formats above).
struct coherent_gl_frame {
  detail::gl_uint depth = 0;     // GL_R32F
  detail::gl_uint velocity = 0;  // GL_RGB32F / GL_RGBA32F, (dx, dy, dz) in .xyz
  detail::gl_uint ids = 0;       // GL_R32UI, or 0: no object ids
  std::uint32_t width = 0, height = 0;
};

namespace detail {

// The pass writes channel c into image unit c (hush_out0 ... hush_out3 in glsl.hpp).
static_assert(hush::detail::constants::kCoherentMaxChannels == 4,
              "one image binding per channel in the pass");

// What one pass reads besides the state (coherent_gl_pass::run).
struct coherent_pass_args {
  const coherent_params* prm = nullptr;
  std::uint32_t frame_index = 0;           // seeds the fields (coherent_state::next_frame)
  bool has_reference = false;              // false: start afresh
  bool backward = false;                   // forward velocity, the backward pass's refill fields
  gl_uint depth = 0, motion = 0, ids = 0;  // textures (ids 0: none)
  const image_view<const float>* input = nullptr;  // per channel, or null: prm->input
  const gl_uint* outputs = nullptr;                // R32F textures, or none
  std::size_t output_count = 0;
  float gain = 0.0f;
};

// The pass of hush/glsl/coherent/glsl.hpp and the state it carries: history and reference in
// ping-pong storage buffers, the field planes, the programs, the sampler. Both the CPU-image
// path (renderer.hpp) and coherent_gl_stream run frames through run().
class coherent_gl_pass {
 public:
  coherent_gl_pass(glsl::device& dev, std::uint32_t width, std::uint32_t height, int channels)
      : dev_(dev),
        gl_(dev.gl()),
        gr_(dev.gl().loader),
        width_(width),
        height_(height),
        channels_(channels) {
    const std::size_t n = pixels();
    require(n * (static_cast<std::size_t>(channels) + 1) * 4,
            "the history (pixels * (channels + 1) * 4 bytes)");
    require(2 * n * 4, "the reference frame (pixels * 8 bytes)");
    gl_.GenBuffers(kBuffers, buffers_);
    for (int k = 0; k < 2; ++k) {
      set(buffers_[kHistory + k], nullptr, history_bytes());
      set(buffers_[kReference + k], nullptr, reference_bytes());
    }
    const std::uint32_t none = 0;
    set(buffers_[kPlanes], &none, 4);
    sampler_ = gr_.nearest_sampler();
    gl_.check("hush::glsl::coherent: setting up");
  }
  coherent_gl_pass(const coherent_gl_pass&) = delete;
  coherent_gl_pass& operator=(const coherent_gl_pass&) = delete;
  ~coherent_gl_pass() {
    gr_.DeleteSamplers(1, &sampler_);
    gl_.DeleteBuffers(kBuffers, buffers_);
  }

  glsl::device& device() const { return dev_; }
  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  int channels() const { return channels_; }
  std::size_t pixels() const { return std::size_t(width_) * height_; }
  bool reference_has_ids() const { return ref_ids_; }
  // The buffers holding the state after the last run: the history (channels planes, then the
  // fresh flags, float) and the reference (depth bits, then ids, uint).
  gl_uint history_buffer() const { return buffers_[kHistory + cur_]; }
  gl_uint reference_buffer() const { return buffers_[kReference + cur_]; }
  std::size_t history_bytes() const {
    return pixels() * (static_cast<std::size_t>(channels_) + 1) * sizeof(float);
  }
  std::size_t reference_bytes() const { return 2 * pixels() * sizeof(std::uint32_t); }

  // The host state into the buffers (a stream that ran on the CPU continues here).
  void upload(const hush::detail::coherent_state<float>& st) {
    if (!st.has_reference) return;  // the pass will not read a history
    const std::size_t n = pixels();
    std::vector<float> all(n * (static_cast<std::size_t>(channels_) + 1));
    std::copy(st.history.begin(), st.history.end(), all.begin());
    for (std::size_t p = 0; p < st.fresh.size(); ++p)
      all[n * static_cast<std::size_t>(channels_) + p] = st.fresh[p] ? 1.0f : 0.0f;
    set(buffers_[kHistory + cur_], all.data(), history_bytes());
    std::vector<std::uint32_t> ref(2 * n, 0u);
    std::memcpy(ref.data(), st.ref_depth.data(), n * 4);
    if (st.reference_has_ids)
      std::copy(st.ref_ids.begin(), st.ref_ids.end(), ref.begin() + static_cast<std::ptrdiff_t>(n));
    set(buffers_[kReference + cur_], ref.data(), reference_bytes());
    ref_ids_ = st.reference_has_ids;
  }

  // The buffers into the host state (reads back; `has_reference` and the frame index are the
  // caller's).
  void download(hush::detail::coherent_state<float>& st) const {
    const std::size_t n = pixels(), nc = static_cast<std::size_t>(channels_);
    std::vector<float> all(n * (nc + 1));
    get(buffers_[kHistory + cur_], all.data(), history_bytes());
    st.history.assign(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(n * nc));
    st.fresh.resize(n);
    for (std::size_t p = 0; p < n; ++p) st.fresh[p] = all[n * nc + p] != 0.0f ? 1u : 0u;
    if (st.has_reference) {
      std::vector<std::uint32_t> ref(2 * n);
      get(buffers_[kReference + cur_], ref.data(), reference_bytes());
      st.ref_depth.resize(n);
      std::memcpy(st.ref_depth.data(), ref.data(), n * 4);
      st.reference_has_ids = ref_ids_;
      if (ref_ids_)
        st.ref_ids.assign(ref.begin() + static_cast<std::ptrdiff_t>(n), ref.end());
      else
        st.ref_ids.clear();
    }
  }

  // Copies o's state (same size and channels) into this pass's buffers on the GPU.
  void copy_from(const coherent_gl_pass& o) {
    copy(o.buffers_[kHistory + o.cur_], buffers_[kHistory + cur_], history_bytes());
    copy(o.buffers_[kReference + o.cur_], buffers_[kReference + cur_], reference_bytes());
    ref_ids_ = o.ref_ids_;
    gl_.check("hush::glsl::coherent: copying a state");
  }

  // One frame: the pass reads the textures in `a` and the state, writes the new state (and the
  // outputs); ping-pong. Host work: uniforms and one dispatch (band-pass: the lattice tables;
  // input images: their upload).
  void run(const coherent_pass_args& a) {
    namespace c = hush::detail::constants;
    const coherent_params& prm = *a.prm;
    const std::size_t n = pixels();
    const bool ids = a.ids != 0u;
    // Fields: white keys, band-pass lattice tables, or the caller's planes.
    planes_.clear();
    gl_uint key[kCoherentFieldSlots] = {}, offset[kCoherentFieldSlots] = {};
    const bool bandpass = prm.input == coherent_input::bandpass && !a.input;
    const coherent_field_mode input_mode = a.input    ? coherent_field_mode::plane
                                           : bandpass ? coherent_field_mode::bandpass
                                                      : coherent_field_mode::white;
    const coherent_field_mode refill_mode =
        bandpass ? coherent_field_mode::bandpass : coherent_field_mode::white;
    const unsigned fx = a.backward ? c::kCoherentFieldBackRefillX : c::kCoherentFieldRefillX;
    const unsigned fy = a.backward ? c::kCoherentFieldBackRefillY : c::kCoherentFieldRefillY;
    for (int ch = 0; ch < prm.channels; ++ch) {
      const unsigned roles[kCoherentFieldUniforms] = {c::kCoherentFieldInput, fx, fy};
      for (unsigned k = 0; k < kCoherentFieldUniforms; ++k) {
        const std::size_t i = kCoherentFieldUniforms * static_cast<unsigned>(ch) + k;
        const std::uint32_t fk = hush::detail::coherent_frame_key(
            prm.seed, static_cast<unsigned>(ch), roles[k], a.frame_index);
        key[i] = fk;
        if (k == 0 && a.input) {
          offset[i] = static_cast<gl_uint>(planes_.size());
          const image_view<const float>& in = a.input[ch];
          for (std::size_t y = 0; y < in.height; ++y)
            for (std::size_t x = 0; x < in.width; ++x) {
              std::uint32_t bits;
              std::memcpy(&bits, &in(x, y), 4);
              planes_.push_back(bits);
            }
        } else if (bandpass) {
          key[i] = seed_key(fk);  // hush::perlin<2>(fk)'s key
          offset[i] = static_cast<gl_uint>(planes_.size());
          const hush::detail::coherent_bandpass bp(fk, prm.bandpass_pixels, width_ + 1,
                                                   height_ + 1);
          for (int axis = 0; axis < 2; ++axis)
            for (std::size_t j = 0; j < bp.g.size[static_cast<std::size_t>(axis)]; ++j) {
              const lattice_coord<float> lc = lattice_split<float>(
                  bp.g.coordinate(axis, j), 0u);
              std::uint32_t bits;
              std::memcpy(&bits, &lc.f, 4);
              planes_.insert(planes_.end(), {lc.i0, lc.i1, bits});
            }
        }
      }
    }
    if (!planes_.empty()) {
      require(planes_.size() * 4, "the input planes");
      set(buffers_[kPlanes], planes_.data(), planes_.size() * 4);
    }
    // Bindings: the frame's textures through the sampler, the state, the outputs.
    const gl_uint textures[3] = {a.depth, a.ids, a.motion};
    gl_int active = 0;
    gl_.GetIntegerv(kGlActiveTexture, &active);
    for (gl_uint u = 0; u < 3; ++u) {
      gl_.ActiveTexture(kGlTexture0 + u);
      gl_.BindTexture(kGlTexture2d, textures[u]);
      gr_.BindSampler(u, sampler_);
    }
    gl_.ActiveTexture(static_cast<gl_enum>(active));
    gl_.BindBufferBase(kGlShaderStorageBuffer, 2, buffers_[kReference + cur_]);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 3, buffers_[kReference + 1 - cur_]);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 5, buffers_[kHistory + cur_]);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 6, buffers_[kHistory + 1 - cur_]);
    gl_.BindBufferBase(kGlShaderStorageBuffer, 7, buffers_[kPlanes]);
    for (std::size_t k = 0; k < a.output_count; ++k)
      gr_.BindImageTexture(static_cast<gl_uint>(k), a.outputs[k], 0, 0, 0, kGlWriteOnly,
                           kGlR32fFormat);
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
    u("hush_flags", (a.has_reference ? 1u : 0u) | (ids && ref_ids_ && a.has_reference ? 2u : 0u) |
                        (prm.filter == coherent_filter::stationary ? 4u : 0u));
    u("hush_frame_ids", ids ? 1u : 0u);
    u("hush_channels", static_cast<gl_uint>(prm.channels));
    u("hush_outputs", static_cast<gl_uint>(a.output_count));
    uf("hush_gain", a.gain);
    uf("hush_sign", a.backward ? -1.0f : 1.0f);
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
    gl_.MemoryBarrier(kGlAllBarrierBits);
    gl_.UseProgram(static_cast<gl_uint>(previous));
    for (gl_uint unit = 0; unit < 3; ++unit) gr_.BindSampler(unit, 0);  // the caller's filtering
    gl_.check("hush::glsl::coherent: running a pass");
    // The new history is current; this frame is the reference.
    cur_ = 1 - cur_;
    ref_ids_ = ids;
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
  // buffers_: history[2], reference[2], planes.
  enum : int { kHistory = 0, kReference = 2, kPlanes = 4, kBuffers = 5 };

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
  void set(gl_uint buffer, const void* data, std::size_t bytes) const {
    gl_.BindBuffer(kGlShaderStorageBuffer, buffer);
    gl_.BufferData(kGlShaderStorageBuffer, static_cast<gl_sizeiptr>(bytes), data, kGlDynamicRead);
  }
  void get(gl_uint buffer, void* data, std::size_t bytes) const {
    gl_.BindBuffer(kGlShaderStorageBuffer, buffer);
    gl_.GetBufferSubData(kGlShaderStorageBuffer, 0, static_cast<gl_sizeiptr>(bytes), data);
    gl_.check("hush::glsl::coherent: reading a buffer");
  }
  void copy(gl_uint from, gl_uint to, std::size_t bytes) const {
    gl_.BindBuffer(kGlCopyReadBuffer, from);
    gl_.BindBuffer(kGlCopyWriteBuffer, to);
    gr_.CopyBufferSubData(kGlCopyReadBuffer, kGlCopyWriteBuffer, 0, 0,
                          static_cast<gl_sizeiptr>(bytes));
  }

  glsl::device& dev_;
  const gl_api& gl_;
  gl_resident_api gr_;
  std::uint32_t width_, height_;
  int channels_;
  gl_uint buffers_[kBuffers] = {};
  gl_uint sampler_ = 0;
  std::map<std::pair<coherent_field_mode, coherent_field_mode>, gl_program> programs_;
  int cur_ = 0;  // the pair member holding the current history and reference
  bool ref_ids_ = false;
  std::vector<std::uint32_t> planes_;
};

}  // namespace detail

// A coherent-noise stream on the GPU, resident: see the contract at the top of this file.
class coherent_gl_stream {
 public:
  // Throws hush::invalid_argument for parameters out of range (coherent_stream's validate()),
  // smoothing, a size of 0 or above kCoherentMaxSide, or state beyond one storage block.
  coherent_gl_stream(device& dev, const coherent_params& prm, std::uint32_t width,
                     std::uint32_t height)
      : prm_(checked(prm, width, height)),
        pass_(std::make_unique<detail::coherent_gl_pass>(dev, width, height, prm.channels)) {}
  // Continues `s` (its parameters, frame index and state; uploaded): `s` must have run at
  // width x height or be fresh.
  coherent_gl_stream(device& dev, const coherent_stream& s, std::uint32_t width,
                     std::uint32_t height)
      : coherent_gl_stream(dev, s.parameters(), width, height) {
    const hush::detail::coherent_state<float>& st = state_of(s);
    next_frame_ = st.next_frame;
    if (st.has_reference) {
      if (st.width != width || st.height != height)
        hush::detail::throw_out_of_range(
            kWhere, "stream size", std::to_string(st.width) + "x" + std::to_string(st.height),
            ("the GL stream's size, " + std::to_string(width) + "x" + std::to_string(height))
                .c_str());
      pass_->upload(st);
      has_reference_ = true;
    }
  }
  coherent_gl_stream(const coherent_gl_stream&) = delete;
  coherent_gl_stream& operator=(const coherent_gl_stream&) = delete;
  coherent_gl_stream(coherent_gl_stream&&) noexcept = default;
  coherent_gl_stream& operator=(coherent_gl_stream&&) noexcept = default;
  ~coherent_gl_stream() = default;

  const coherent_params& parameters() const { return prm_; }
  std::uint32_t width() const { return pass_->width(); }
  std::uint32_t height() const { return pass_->height(); }
  // The frame index the next advance() uses (it seeds the input noise).
  std::uint32_t frame_index() const { return next_frame_; }
  // Whether the next frame blends with a history (false before the first and after reset()).
  bool has_history() const { return has_reference_; }
  // The output gain (coherent_stream::gain()).
  double gain() const { return 1.0 / coherent_k(hush::detail::coherent_alpha<float>(prm_.alpha)); }

  // Filters the next frame into `outputs` (R32F textures of the frame's size, the first
  // outputs.size() channels; none: only the state advances). Host work independent of the
  // pixel count (white input). Throws hush::invalid_argument (before anything changes) for a
  // missing depth or velocity texture, a size other than the stream's, too many outputs.
  void advance(const coherent_gl_frame& f, span<const detail::gl_uint> outputs) {
    if (f.depth == 0u || f.velocity == 0u)
      hush::detail::throw_out_of_range(kWhere, "frame", f.depth == 0u ? "depth 0" : "velocity 0",
                                       "GL texture names of the depth and velocity");
    if (f.width != width() || f.height != height())
      hush::detail::throw_out_of_range(
          kWhere, "frame size", std::to_string(f.width) + "x" + std::to_string(f.height),
          ("the stream's size, " + std::to_string(width()) + "x" + std::to_string(height()))
              .c_str());
    if (outputs.size() > static_cast<std::size_t>(prm_.channels))
      hush::detail::throw_out_of_range(kWhere, "outputs", outputs.size(),
                                       "at most parameters().channels textures");
    detail::coherent_pass_args a;
    a.prm = &prm_;
    a.frame_index = next_frame_;
    a.has_reference = has_reference_;
    a.depth = f.depth;
    a.motion = f.velocity;
    a.ids = f.ids;
    a.outputs = outputs.data();
    a.output_count = outputs.size();
    a.gain = static_cast<float>(gain());
    pass_->run(a);
    has_reference_ = true;
    ++next_frame_;
  }
  // One output texture (channel 0).
  void advance(const coherent_gl_frame& f, detail::gl_uint output) {
    advance(f, span<const detail::gl_uint>(&output, 1));
  }

  // Forgets the history: the next frame starts afresh, with frame index `next_frame`. No GL.
  void reset(std::uint32_t next_frame = 0) {
    has_reference_ = false;
    next_frame_ = next_frame;
  }
  // A stream continuing like this one, its state copied on the GPU (no read-back).
  coherent_gl_stream copy() const {
    coherent_gl_stream c(pass_->device(), prm_, width(), height());
    c.next_frame_ = next_frame_;
    c.has_reference_ = has_reference_;
    if (has_reference_) c.pass_->copy_from(*pass_);
    return c;
  }
  // The state read back into a CPU stream (reads back; for tests, serialisation, CPU work).
  coherent_stream to_stream() const {
    coherent_stream s(prm_);
    s.reset(next_frame_);
    if (!has_reference_) return s;
    hush::detail::coherent_state<float>& st = s.state();
    st.width = width();
    st.height = height();
    st.has_reference = true;
    pass_->download(st);
    return s;
  }

  // The storage buffers holding the state (valid until the next advance): the history,
  // channels planes of width x height floats then the fresh flags (1.0 fresh, 0.0 blended);
  // the reference frame, width x height depth bits then as many object ids.
  detail::gl_uint history_buffer() const { return pass_->history_buffer(); }
  detail::gl_uint reference_buffer() const { return pass_->reference_buffer(); }

 private:
  static constexpr const char* kWhere = "hush::glsl::coherent_gl_stream";

  static const coherent_params& checked(const coherent_params& prm, std::uint32_t w,
                                        std::uint32_t h) {
    coherent_stream probe(prm);  // validates the parameters
    if (prm.smoothing != 0.0)
      hush::detail::throw_out_of_range(kWhere, "smoothing", prm.smoothing,
                                       "0 (smooth the output in your own pass)");
    const std::uint32_t most = hush::detail::constants::kCoherentMaxSide;
    if (w == 0 || h == 0 || w > most || h > most)
      hush::detail::throw_out_of_range(kWhere, "size", std::to_string(w) + "x" + std::to_string(h),
                                       ("sides 1 ... " + std::to_string(most)).c_str());
    return prm;
  }
  static const hush::detail::coherent_state<float>& state_of(const coherent_stream& s) {
    // history() syncs a GPU-held state to the host; state() is the non-const accessor.
    (void)s.fresh();
    return const_cast<coherent_stream&>(s).state();
  }

  coherent_params prm_;
  std::unique_ptr<detail::coherent_gl_pass> pass_;
  std::uint32_t next_frame_ = 0;
  bool has_reference_ = false;
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_COHERENT_FRAME_HPP
