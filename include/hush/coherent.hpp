// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Coherent noise (Michael Kass and Davide Pesare, "Coherent Noise for
// Non-Photorealistic Rendering", SIGGRAPH 2011): screen-space noise that moves
// with the surfaces of an animated scene. Each frame alone looks like white
// (or band-pass) noise; from frame to frame the noise follows the motion given
// by the renderer's depth and velocity, so it is neither flickering white
// noise nor a "shower door" pattern fixed to the screen. A scene-driven noise
// (hush::frame, core/frame.hpp): it reads per-pixel depth and velocity, and
// object ids when given.
//
//   hush::coherent_params prm;                 // alpha 0.98, stationary filter, 1 channel
//   hush::coherent_stream stream{prm};         // the history, owned by the caller
//   for (each frame) {
//     hush::frame f;                           // views of the renderer's G-buffer
//     f.depth = {depth, w, h};  f.velocity = {velocity, w, h};  f.object_id = {ids, w, h};
//     stream.advance(hush::exec::simd, f, hush::image_view<float>{out, w, h});
//   }
//   // Offline, time-symmetric (needs forward velocity too):
//   hush::coherent_symmetric(hush::exec::simd, prm, frames, outputs);
//
// The filters (docs/coherent.md derives every claim below):
//  - causal, paper: Kass & Pesare eq. 7. c_0 = k(alpha) w_0 (eq. 6); then per pixel
//    c_i = alpha c_{i-1}(x', y') + (1 - alpha) w_i where the surface point was visible in
//    frame i-1 at (x', y') (bilinear), else k(alpha) w_i (disocclusion, sec. 3.2).
//    Stationary for still scenes; under sub-pixel motion the bilinear resampling of
//    c_{i-1} averages neighbours, so moving surfaces lose variance and sharpness frame
//    after frame (HARD_CASES row 13).
//  - causal, stationary (the default): the same plus a refill term, fresh noise shaped
//    like exactly what bilinear resampling removed (its spectrum 1 - |H|^2): the output
//    keeps the variance and spectrum of the input on moving surfaces as on still ones
//    (exactly for translation, to second order in the motion's gradient otherwise).
//  - time-symmetric (sec. 3.3): forward and backward causal passes over the same w,
//    summed, minus (1 - alpha) w_i: impulse response (1 - alpha) alpha^|i|. With the
//    k(alpha) start of both passes every frame, the first and last included, has the
//    same variance.
// Contract:
//  - output: per channel, variance 1 for white input (the filters' variance is divided
//    out: gain 1 / k(alpha) causal, 1 / sqrt((1 - alpha)(1 + alpha^2) / (1 + alpha))
//    symmetric), mean 0; stationary filter: on still and moving surfaces alike.
//    Channels are independent fields sharing the reprojection.
//  - input w_i: white (a hash of seed, channel, frame index and pixel: deterministic,
//    independent per frame, uniform with variance 1), band-pass (Perlin noise in screen
//    space, cells of bandpass_pixels pixels, per-frame seed and lattice offset, scaled to
//    variance 1), or the caller's images (advance's `input`; NaN/Inf read as 0).
//  - disocclusion: a pixel takes fresh noise k(alpha) w_i (the stationary variance) when
//    its depth or motion is not finite, its depth is not positive, its reprojection leaves
//    the reference frame's outer pixel centres, a bilinear tap shows no surface or (with
//    object ids in both frames) another object, or the interpolated depth differs from
//    the expected one by more than epsilon * depth + epsilon_absolute (both ways: the paper
//    tests only "farther"; a nearer one means the footprint straddles an edge).
//  - robust: NaN/Inf/negative depth or velocity never reach the history, which holds
//    finite values only (tested, also after deserialisation); denormal motion reads as 0
//    and values below the smallest normal are stored as 0, so no denormal arithmetic
//    follows at any alpha in [0, 1) (alpha 0.999 and decaying zero input tested).
//  - float vs the double reference (basic_coherent_stream<double>): the reprojection is
//    the same float computation; values differ by rounding only, a recursion contracting
//    by alpha: within (12 / (1 - alpha) + 1) 2^-24 M for outputs of magnitude <= M
//    (tests/coherent/coherent_test.cpp; measured 2.4e-6 at alpha 0.98 against a budget of 1.4e-4).
//  - backends: exec::scalar is the reference; exec::simd equals it bit for bit under
//    HUSH_STRICT_FP (hush/coherent/simd-inl.h); exec::glsl{device} (include
//    hush/glsl/coherent.hpp) keeps the history on the GPU; tolerance there.
#ifndef HUSH_COHERENT_HPP
#define HUSH_COHERENT_HPP

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "hush/coherent/simd_kernel.hpp"
#include "hush/config.hpp"
#include "hush/core/error.hpp"
#include "hush/core/frame.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/views.hpp"
#include "hush/coherent/kernel.hpp"
#include "hush/detail/constants.hpp"
#include "hush/exec.hpp"
#include "hush/perlin.hpp"

namespace hush {

// The recursive filter's resampling (see the file comment).
enum class coherent_filter {
  paper,       // Kass & Pesare eq. 7 exactly: bilinear history, fades under motion
  stationary,  // hush: eq. 7 plus the refill of what bilinear resampling removed
};
// The input noise w_i.
enum class coherent_input {
  white,     // hashed per pixel and frame
  bandpass,  // Perlin in screen space, bandpass_pixels per cell, per-frame seed and offset
};

struct coherent_params {
  std::uint32_t seed = 0;
  // Recursive filter weight, in [0, 1): the noise renews over about 1 / (1 - alpha) frames.
  double alpha = detail::constants::kCoherentDefaultAlpha;
  // Disocclusion tolerance: relative to the expected depth, plus an absolute one (depth
  // units); both >= 0 and finite. Relative alone works at every depth scale.
  double epsilon = detail::constants::kCoherentDefaultEpsilon;
  double epsilon_absolute = 0.0;
  coherent_filter filter = coherent_filter::stationary;
  coherent_input input = coherent_input::white;
  double bandpass_pixels = detail::constants::kCoherentDefaultBandpassPixels;  // 1 ... 1024
  // Output smoothing: Gaussian standard deviation in pixels, 0 (off) ... 2, renormalised so
  // white noise keeps variance 1; smooths across object boundaries (paper sec. 3.4).
  double smoothing = 0.0;
  int channels = 1;  // 1 ... 4 independent fields from one call
};

// Throws hush::invalid_argument naming the first parameter outside its range.
inline void validate(const coherent_params& p) {
  namespace c = detail::constants;
  const char* where = "hush::coherent";
  if (!(p.alpha >= 0.0 && p.alpha < 1.0))
    detail::throw_out_of_range(where, "alpha", p.alpha, "0 <= alpha < 1");
  if (!(p.epsilon >= 0.0) || !std::isfinite(p.epsilon))
    detail::throw_out_of_range(where, "epsilon", p.epsilon, "a finite number >= 0");
  if (!(p.epsilon_absolute >= 0.0) || !std::isfinite(p.epsilon_absolute))
    detail::throw_out_of_range(where, "epsilon_absolute", p.epsilon_absolute,
                               "a finite number >= 0");
  if (p.filter != coherent_filter::paper && p.filter != coherent_filter::stationary)
    detail::throw_out_of_range(where, "filter", static_cast<int>(p.filter),
                               "coherent_filter::paper or coherent_filter::stationary");
  if (p.input != coherent_input::white && p.input != coherent_input::bandpass)
    detail::throw_out_of_range(where, "input", static_cast<int>(p.input),
                               "coherent_input::white or coherent_input::bandpass");
  detail::require_in_range(where, "bandpass_pixels", p.bandpass_pixels, 1.0,
                           c::kCoherentMaxBandpassPixels, "1 ... 1024");
  detail::require_in_range(where, "smoothing", p.smoothing, 0.0, c::kCoherentMaxSmoothing,
                           "0 (off) ... 2 pixels");
  detail::require_in_range(where, "channels", p.channels, 1, c::kCoherentMaxChannels, "1 ... 4");
}

// k(alpha) = sqrt((1 - alpha) / (1 + alpha)), Kass & Pesare eq. 6: the standard deviation
// of the stationary causal output for unit-variance input.
inline double coherent_k(double alpha) { return std::sqrt((1.0 - alpha) / (1.0 + alpha)); }
// Standard deviation of the time-symmetric sum for unit-variance input:
// sqrt((1 - alpha)(1 + alpha^2) / (1 + alpha)) (docs/coherent.md).
inline double coherent_symmetric_sd(double alpha) {
  return std::sqrt((1.0 - alpha) * (1.0 + alpha * alpha) / (1.0 + alpha));
}

// The white input noise w_i at pixel (x, y) of frame `frame`, channel `channel`: what the
// filters read for coherent_input::white (unit variance, mean 0). For tests and tools.
inline float coherent_white_noise(std::uint32_t seed, int channel, std::uint32_t frame,
                                  std::uint32_t x, std::uint32_t y) {
  const std::uint32_t key = detail::coherent_frame_key(
      seed, static_cast<unsigned>(channel), detail::constants::kCoherentFieldInput, frame);
  return detail::coherent_white(detail::coherent_row_key(key, y), x);
}

namespace detail {

// The part of a stream's state a GPU backend keeps between frames (hush/glsl/coherent.hpp).
// The stream calls download() before any CPU access when the device holds newer data.
class coherent_device_state {
 public:
  virtual ~coherent_device_state() = default;
  virtual const void* device() const = 0;  // which device holds it
  // Writes the device's history, reference depth/ids and fresh flags into the host state.
  virtual void download(void* host_state) = 0;
};

// Everything a pass carries from frame to frame: the history c_{i-1} and the reference
// frame's depth and ids (copied, since the caller's views need not outlive a call).
template <class T>
struct coherent_state {
  std::uint32_t width = 0, height = 0;
  std::uint32_t next_frame = 0;  // frame index of the next advance (seeds the input)
  bool has_reference = false;    // false: the next frame starts afresh (c = k w)
  bool reference_has_ids = false;
  std::vector<float> ref_depth;
  std::vector<std::uint32_t> ref_ids;
  std::vector<float> next_depth;  // scratch: this frame's depth, the next reference
  std::vector<std::uint32_t> next_ids;
  std::vector<T> history;           // channels planes, packed
  std::vector<T> next;              // scratch: the history being written
  std::vector<std::uint8_t> fresh;  // last frame: 1 where fresh noise was taken
  // GPU residency: when `device` is set and host_current is false, the device holds the
  // newer state.
  std::shared_ptr<coherent_device_state> device;
  bool host_current = true;

  void sync_host() {
    if (device && !host_current) {
      device->download(this);
      host_current = true;
    }
  }
  std::size_t pixels() const { return std::size_t(width) * height; }
};

// What one pass step reads besides the state: the frame, the direction, the fields.
template <class T>
struct coherent_step {
  const coherent_params* prm = nullptr;
  const frame* f = nullptr;
  bool backward = false;  // reads forward_velocity, refill fields of the backward pass
  const image_view<const float>* input = nullptr;  // per channel, or null: prm->input
  const image_view<T>* out = nullptr;              // per channel, or null: not written
  std::size_t out_count = 0;                       // views in out (the channel count)
  T gain = 0;
};

// alpha as the filter uses it in T: rounded to T, and kept below 1 (an alpha that rounds to
// 1 would never forget); k(alpha) and 1 - alpha are then formed from this value, so the
// stationarity condition holds for the recursion actually computed.
template <class T>
double coherent_alpha(double alpha) {
  const T a = static_cast<T>(alpha);
  return static_cast<double>(a < T(1) ? a : std::nextafter(T(1), T(0)));
}
// A tolerance as a float, below the smallest normal float read as 0 (no denormal operand).
inline float coherent_float_parameter(double v) {
  const float f = static_cast<float>(v);
  return f >= std::numeric_limits<float>::min() ? f : 0.0f;
}

// Band-pass input: Perlin noise with the frame key as seed, its lattice shifted by an offset
// in [0, 1)^2 cells taken from the key (so the variance, zero at lattice points, is
// stationary in expectation), scaled to unit variance. Sample (x, y) of the plane is at
// pixel centre (x + 0.5, y + 0.5).
inline float coherent_bandpass_scale() {
  return static_cast<float>(1.0 / std::sqrt(perlin<2>::variance()));
}
struct coherent_bandpass {
  perlin<2> noise;
  grid<2> g;
  float scale;
  coherent_bandpass(std::uint32_t key, double pixels, std::size_t nx, std::size_t ny)
      : noise(key), scale(coherent_bandpass_scale()) {
    const double ox = static_cast<double>(hash32(key, 1u) >> 8) * 0x1p-24;
    const double oy = static_cast<double>(hash32(key, 2u) >> 8) * 0x1p-24;
    g.origin = {0.5 / pixels + ox, 0.5 / pixels + oy};
    g.step = {1.0 / pixels, 1.0 / pixels};
    g.size = {nx, ny};
  }
};

template <class Exec>
void coherent_fill_bandpass(const Exec& ex, const coherent_bandpass& b, std::vector<float>& plane) {
  plane.resize(b.g.count());
  if constexpr (std::is_same<Exec, exec::scalar_t>::value ||
                std::is_same<Exec, exec::simd_t>::value)
    evaluate_grid(b.noise, ex, b.g, span<float>(plane));
  else
    evaluate_grid(b.noise, exec::scalar, b.g, span<float>(plane));
  for (float& v : plane) v *= b.scale;
}

template <class T, class Exec>
void coherent_run_pass(const Exec& ex, const coherent_pass_job<T>& job) {
  if constexpr (std::is_same<Exec, exec::simd_t>::value && std::is_same<T, float>::value) {
#if HUSH_CONFIG_SIMD
    simd::coherent_pass(job);
#else
    coherent_pass_scalar(job);
#endif
  } else {
    (void)ex;
    coherent_pass_scalar(job);
  }
}

// The frame's depth and ids become the next step's reference: the pass wrote their copies
// into next_depth / next_ids (the caller's views need not outlive the call).
template <class T>
void coherent_keep_reference(coherent_state<T>& st, bool has_ids) {
  std::swap(st.ref_depth, st.next_depth);
  st.reference_has_ids = has_ids;
  if (has_ids)
    std::swap(st.ref_ids, st.next_ids);
  else
    st.ref_ids.clear();
  st.has_reference = true;
}

// Gaussian smoothing of one output plane in place (separable, clamp-to-edge), weights
// normalised to unit sum of squares per axis so that white noise keeps its variance.
template <class T>
void coherent_smooth(const image_view<T>& img, double sigma) {
  if (!(sigma > 0.0)) return;
  const int radius =
      static_cast<int>(std::ceil(detail::constants::kCoherentSmoothingRadius * sigma));
  std::vector<T> weight(static_cast<std::size_t>(2 * radius + 1));
  double sum_sq = 0.0;
  std::vector<double> wd(weight.size());
  for (std::size_t i = 0; i < wd.size(); ++i) {
    // (k / sigma)^2, not k^2 / sigma^2: a subnormal sigma squares to 0 (0 / 0 at the centre);
    // k / sigma is 0 there and infinite elsewhere, so the kernel is the identity it tends to.
    const double t = (static_cast<double>(i) - radius) / sigma;
    wd[i] = std::exp(-0.5 * t * t);
    sum_sq += wd[i] * wd[i];
  }
  for (std::size_t i = 0; i < wd.size(); ++i) weight[i] = T(wd[i] / std::sqrt(sum_sq));
  const std::size_t w = img.width, h = img.height;
  std::vector<T> line(std::max(w, h)), tmp(std::max(w, h));
  auto clamp_index = [](long i, std::size_t n) {
    return static_cast<std::size_t>(std::min<long>(std::max<long>(i, 0), long(n) - 1));
  };
  for (std::size_t y = 0; y < h; ++y) {  // rows
    T* row = img.row(y);
    std::copy(row, row + w, line.begin());
    for (std::size_t x = 0; x < w; ++x) {
      T s = T(0);
      for (std::size_t i = 0; i < weight.size(); ++i)
        s += weight[i] * line[clamp_index(long(x) + long(i) - radius, w)];
      row[x] = s;
    }
  }
  for (std::size_t x = 0; x < w; ++x) {  // columns
    for (std::size_t y = 0; y < h; ++y) line[y] = img(x, y);
    for (std::size_t y = 0; y < h; ++y) {
      T s = T(0);
      for (std::size_t i = 0; i < weight.size(); ++i)
        s += weight[i] * line[clamp_index(long(y) + long(i) - radius, h)];
      tmp[y] = s;
    }
    for (std::size_t y = 0; y < h; ++y) img(x, y) = tmp[y];
  }
}

// Checks the per-channel views of a call: `count` views, each frame-sized with data.
template <class V>
void coherent_check_views(const char* where, const char* name, const V* views, std::size_t given,
                          std::size_t want, std::size_t width, std::size_t height) {
  if (given != want)
    throw_out_of_range(where, std::string(name) + ".size()", given,
                       ("exactly " + std::to_string(want) + " (one view per channel)").c_str());
  for (std::size_t c = 0; c < given; ++c) {
    const V& v = views[c];
    const std::string n = std::string(name) + "[" + std::to_string(c) + "]";
    if (!v.data) hush::detail::raise_error(std::string(where) + ": " + n + " has null data");
    if (v.width != width || v.height != height)
      throw_out_of_range(
          where, n + " size", std::to_string(v.width) + "x" + std::to_string(v.height),
          ("the frame's size, " + std::to_string(width) + "x" + std::to_string(height)).c_str());
    if (v.stride < v.width)
      throw_out_of_range(where, n + ".stride", v.stride, "at least its width");
  }
}

// One step of a pass on a CPU backend: builds the job (fields, planes) and runs it.
template <class T, class Exec>
void coherent_cpu_step(const Exec& ex, coherent_state<T>& st, const coherent_step<T>& s) {
  namespace c = constants;
  const coherent_params& prm = *s.prm;
  const frame& f = *s.f;
  st.sync_host();
  const std::size_t w = st.width, h = st.height, n = w * h;
  const int nc = prm.channels;
  st.history.resize(n * static_cast<std::size_t>(nc));
  st.next.resize(n * static_cast<std::size_t>(nc));
  st.fresh.resize(n);
  st.next_depth.resize(n);
  st.next_ids.resize(f.object_id.data ? n : 0);
  coherent_pass_job<T> job;
  job.width = st.width;
  job.height = st.height;
  job.depth = f.depth.data;
  job.depth_stride = f.depth.stride;
  const image_view<const vec3>& motion = s.backward ? f.forward_velocity : f.velocity;
  job.motion = reinterpret_cast<const float*>(motion.data);
  job.motion_stride = motion.stride;
  job.motion_sign = s.backward ? -1.0f : 1.0f;
  job.ids = f.object_id.data;
  job.ids_stride = f.object_id.stride;
  if (st.has_reference) {
    job.ref_depth = st.ref_depth.data();
    job.ref_ids = st.reference_has_ids ? st.ref_ids.data() : nullptr;
  }
  job.eps_rel = coherent_float_parameter(prm.epsilon);
  job.eps_abs = coherent_float_parameter(prm.epsilon_absolute);
  const double alpha = coherent_alpha<T>(prm.alpha);
  job.alpha = T(alpha);
  job.beta = T(1.0 - alpha);  // exact: alpha is a T
  job.k = T(coherent_k(alpha));
  job.gain = s.gain;
  job.stationary = prm.filter == coherent_filter::stationary;
  job.channels = nc;
  job.fresh = st.fresh.data();
  job.depth_copy = st.next_depth.data();
  job.ids_copy = f.object_id.data ? st.next_ids.data() : nullptr;
  // Band-pass planes live for the step.
  std::vector<float> planes[c::kCoherentMaxChannels][3];
  const unsigned fx = s.backward ? c::kCoherentFieldBackRefillX : c::kCoherentFieldRefillX;
  const unsigned fy = s.backward ? c::kCoherentFieldBackRefillY : c::kCoherentFieldRefillY;
  for (int ch = 0; ch < nc; ++ch) {
    const unsigned uc = static_cast<unsigned>(ch);
    const std::uint32_t ki =
        coherent_frame_key(prm.seed, uc, c::kCoherentFieldInput, st.next_frame);
    const std::uint32_t kx = coherent_frame_key(prm.seed, uc, fx, st.next_frame);
    const std::uint32_t ky = coherent_frame_key(prm.seed, uc, fy, st.next_frame);
    job.input[ch].key = ki;
    job.refill_x[ch].key = kx;
    job.refill_y[ch].key = ky;
    if (s.input) {  // the caller's input; the refill stays white (the caller's spectrum is unknown)
      job.input[ch].plane = s.input[ch].data;
      job.input[ch].stride = s.input[ch].stride;
    } else if (prm.input == coherent_input::bandpass) {
      auto& p = planes[ch];
      coherent_fill_bandpass(ex, coherent_bandpass(ki, prm.bandpass_pixels, w, h), p[0]);
      job.input[ch] = {ki, p[0].data(), w};
      if (job.stationary) {
        coherent_fill_bandpass(ex, coherent_bandpass(kx, prm.bandpass_pixels, w + 1, h + 1), p[1]);
        coherent_fill_bandpass(ex, coherent_bandpass(ky, prm.bandpass_pixels, w, h + 1), p[2]);
        job.refill_x[ch] = {kx, p[1].data(), w + 1};
        job.refill_y[ch] = {ky, p[2].data(), w};
      }
    }
    job.ref_history[ch] = st.history.data() + n * uc;
    job.history[ch] = st.next.data() + n * uc;
    job.out[ch] = uc < s.out_count ? s.out[ch].data : nullptr;
  }
  // Output views share one stride in the job; give each its own when they differ.
  job.out_stride = s.out_count ? s.out[0].stride : 0;
  bool same_stride = true;
  for (std::size_t ch = 1; ch < s.out_count; ++ch)
    same_stride = same_stride && s.out[ch].stride == job.out_stride;
  if (!same_stride)
    for (int ch = 0; ch < nc; ++ch) job.out[ch] = nullptr;
  coherent_run_pass(ex, job);
  std::swap(st.history, st.next);
  if (s.out_count && !same_stride)
    for (std::size_t ch = 0; ch < s.out_count; ++ch)
      for (std::size_t y = 0; y < h; ++y)
        for (std::size_t x = 0; x < w; ++x)
          s.out[ch](x, y) = s.gain * st.history[n * static_cast<std::size_t>(ch) + y * w + x];
  coherent_keep_reference(st, f.object_id.data != nullptr);
  ++st.next_frame;
}

}  // namespace detail

// A coherent-noise stream (causal filter): the state the caller owns and advances frame by
// frame. A regular value type: copy it to branch, reset() it at a cut, serialise it to save
// a game. T = float, or double for the reference.
template <class T>
class basic_coherent_stream {
  static_assert(std::is_same<T, float>::value || std::is_same<T, double>::value,
                "hush::basic_coherent_stream<T>: T is float or double");

 public:
  using params = coherent_params;

  // Throws hush::invalid_argument for parameters outside their ranges (validate()).
  explicit basic_coherent_stream(const params& prm = params{}) : prm_(prm) { validate(prm_); }
  basic_coherent_stream(const basic_coherent_stream& o) : prm_(o.prm_), st_(o.host_state()) {
    st_.device.reset();
    st_.host_current = true;
  }
  basic_coherent_stream& operator=(const basic_coherent_stream& o) {
    if (this != &o) {
      prm_ = o.prm_;
      st_ = o.host_state();
      st_.device.reset();
      st_.host_current = true;
    }
    return *this;
  }
  basic_coherent_stream(basic_coherent_stream&&) noexcept = default;
  basic_coherent_stream& operator=(basic_coherent_stream&&) noexcept = default;
  ~basic_coherent_stream() = default;

  const params& parameters() const { return prm_; }
  // The frame index the next advance() uses (it seeds the input noise), and the size of the
  // history (0 x 0 before the first frame and after reset()).
  std::uint32_t frame_index() const { return st_.next_frame; }
  std::size_t width() const { return st_.has_reference ? st_.width : 0; }
  std::size_t height() const { return st_.has_reference ? st_.height : 0; }
  // Output gain: the output is gain() * c, c in the paper's units (variance k(alpha)^2 for
  // unit-variance input), so the output has variance 1.
  double gain() const { return 1.0 / coherent_k(detail::coherent_alpha<T>(prm_.alpha)); }

  // Forgets the history: the next frame starts afresh (c = k(alpha) w, Kass & Pesare
  // eq. 6) at any size, with frame index `next_frame`.
  void reset(std::uint32_t next_frame = 0) {
    std::shared_ptr<detail::coherent_device_state> device = std::move(st_.device);
    st_ = detail::coherent_state<T>{};
    st_.next_frame = next_frame;
    st_.device = std::move(device);  // a GPU backend's buffers and program are kept
  }

  // Filters the next frame: `out` holds one view per channel (parameters().channels), each
  // the frame's size. `f` needs depth and velocity; object_id is used when present (in
  // this frame and the previous one). `input`, when given (one view per channel), replaces
  // the input noise w_i (unit variance expected; NaN/Inf read as 0). Throws
  // hush::invalid_argument (before anything changes) for missing or mismatched views, or
  // a frame whose size differs from the history's: call reset() at a change of resolution.
  // Evaluation itself never throws.
  template <class Exec>
  void advance(const Exec& ex, const frame& f, span<const image_view<T>> out,
               span<const image_view<const float>> input = {}) {
    check(f, out, input);
    begin_frame(f);
    detail::coherent_step<T> s;
    s.prm = &prm_;
    s.f = &f;
    s.input = input.empty() ? nullptr : input.data();
    s.out = out.data();
    s.out_count = out.size();
    s.gain = T(gain());
    step(ex, s);
    for (std::size_t c = 0; c < out.size(); ++c) detail::coherent_smooth(out[c], prm_.smoothing);
  }
  // One channel.
  template <class Exec>
  void advance(const Exec& ex, const frame& f, const image_view<T>& out) {
    advance(ex, f, span<const image_view<T>>(&out, 1));
  }

  // Pixels of the last frame that took fresh noise (disocclusions, the first frame): 1,
  // else 0; width() x height(), row-major. Empty before the first frame.
  const std::vector<std::uint8_t>& fresh() const { return host_state().fresh; }
  // The history c_i of channel c (paper units), width() x height(), row-major.
  span<const T> history(int channel) const {
    const auto& st = host_state();
    const std::size_t n = st.pixels();
    if (!st.has_reference || channel < 0 || channel >= prm_.channels) return {};
    return span<const T>(st.history.data() + n * static_cast<std::size_t>(channel), n);
  }

  // The whole state as bytes (little-endian; parameters, frame index, history, reference
  // depth and ids), and back. deserialize() throws hush::invalid_argument for data that
  // is not such a state (wrong magic, version, float type, truncated, parameters out of
  // range, or a non-finite history value: a stream never holds NaN).
  std::vector<std::uint8_t> serialize() const;
  static basic_coherent_stream deserialize(span<const std::uint8_t> bytes);

  // For backends (hush/glsl/coherent.hpp): the state.
  detail::coherent_state<T>& state() { return st_; }

 private:
  static constexpr const char* kWhere = "hush::coherent_stream::advance";

  const detail::coherent_state<T>& host_state() const {
    const_cast<detail::coherent_state<T>&>(st_).sync_host();
    return st_;
  }

  void check(const frame& f, span<const image_view<T>> out,
             span<const image_view<const float>> input) const {
    f.validate(kWhere, frame_view::depth | frame_view::velocity,
               detail::constants::kCoherentMaxSide);
    const std::size_t nc = static_cast<std::size_t>(prm_.channels);
    detail::coherent_check_views(kWhere, "out", out.data(), out.size(), nc, f.width(), f.height());
    if (!input.empty())
      detail::coherent_check_views(kWhere, "input", input.data(), input.size(), nc, f.width(),
                                   f.height());
    if (st_.has_reference && (f.width() != st_.width || f.height() != st_.height))
      detail::throw_out_of_range(
          kWhere, "frame size", std::to_string(f.width()) + "x" + std::to_string(f.height()),
          ("the history's size, " + std::to_string(st_.width) + "x" + std::to_string(st_.height) +
           " (call reset() at a change of resolution)")
              .c_str());
  }

  void begin_frame(const frame& f) {
    st_.width = static_cast<std::uint32_t>(f.width());
    st_.height = static_cast<std::uint32_t>(f.height());
  }

  template <class Exec>
  void step(const Exec& ex, const detail::coherent_step<T>& s) {
    if constexpr (std::is_same<Exec, exec::scalar_t>::value ||
                  std::is_same<Exec, exec::simd_t>::value) {
      detail::coherent_cpu_step(ex, st_, s);
    } else {
      // exec::glsl{device}: hush/glsl/coherent.hpp (found by argument-dependent lookup).
      coherent_glsl_step(ex.device, st_, s);
    }
  }

  params prm_;
  detail::coherent_state<T> st_;
};

using coherent_stream = basic_coherent_stream<float>;

// ---- Serialisation.
namespace detail {

constexpr char kCoherentMagic[8] = {'H', 'U', 'S', 'H', 'C', 'O', 'H', '1'};

class byte_writer {
 public:
  void raw(const void* p, std::size_t n) {
    const auto* b = static_cast<const std::uint8_t*>(p);
    bytes.insert(bytes.end(), b, b + n);
  }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void f64(double v) {
    std::uint64_t u = 0;
    std::memcpy(&u, &v, sizeof u);
    u64(u);
  }
  template <class V>
  void values(const std::vector<V>& v) {
    for (const V& x : v) {
      if constexpr (sizeof(V) == 1) {
        bytes.push_back(static_cast<std::uint8_t>(x));
      } else if constexpr (sizeof(V) == 4) {
        std::uint32_t u = 0;
        std::memcpy(&u, &x, 4);
        u32(u);
      } else {
        std::uint64_t u = 0;
        std::memcpy(&u, &x, 8);
        u64(u);
      }
    }
  }
  std::vector<std::uint8_t> bytes;
};

class byte_reader {
 public:
  explicit byte_reader(span<const std::uint8_t> b) : b_(b) {}
  void need(std::size_t n) const {
    if (b_.size() - pos_ < n)
      hush::detail::raise_error(
          "hush::coherent_stream::deserialize: the data is truncated (a state of " +
          std::to_string(b_.size()) + " bytes ends early)");
  }
  std::uint32_t u32() {
    need(4);
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= std::uint32_t(b_[pos_++]) << (8 * i);
    return v;
  }
  std::uint64_t u64() {
    need(8);
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= std::uint64_t(b_[pos_++]) << (8 * i);
    return v;
  }
  double f64() {
    const std::uint64_t u = u64();
    double v = 0;
    std::memcpy(&v, &u, sizeof v);
    return v;
  }
  template <class V>
  void values(std::vector<V>& v, std::size_t n) {
    need(n * sizeof(V));
    v.resize(n);
    for (V& x : v) {
      if constexpr (sizeof(V) == 1) {
        x = static_cast<V>(b_[pos_++]);
      } else if constexpr (sizeof(V) == 4) {
        const std::uint32_t u = u32();
        std::memcpy(&x, &u, 4);
      } else {
        const std::uint64_t u = u64();
        std::memcpy(&x, &u, 8);
      }
    }
  }
  bool done() const { return pos_ == b_.size(); }
  std::size_t position() const { return pos_; }

 private:
  span<const std::uint8_t> b_;
  std::size_t pos_ = 0;
};

}  // namespace detail

template <class T>
std::vector<std::uint8_t> basic_coherent_stream<T>::serialize() const {
  const detail::coherent_state<T>& st = host_state();
  detail::byte_writer w;
  w.raw(detail::kCoherentMagic, sizeof detail::kCoherentMagic);
  w.u32(static_cast<std::uint32_t>(sizeof(T)));
  w.u32(prm_.seed);
  w.f64(prm_.alpha);
  w.f64(prm_.epsilon);
  w.f64(prm_.epsilon_absolute);
  w.u32(static_cast<std::uint32_t>(prm_.filter));
  w.u32(static_cast<std::uint32_t>(prm_.input));
  w.f64(prm_.bandpass_pixels);
  w.f64(prm_.smoothing);
  w.u32(static_cast<std::uint32_t>(prm_.channels));
  w.u32(st.next_frame);
  w.u32(st.has_reference ? 1u : 0u);
  if (st.has_reference) {
    w.u32(st.width);
    w.u32(st.height);
    w.u32(st.reference_has_ids ? 1u : 0u);
    w.values(st.ref_depth);
    if (st.reference_has_ids) w.values(st.ref_ids);
    w.values(st.fresh);
    w.values(st.history);
  }
  return std::move(w.bytes);
}

template <class T>
basic_coherent_stream<T> basic_coherent_stream<T>::deserialize(span<const std::uint8_t> bytes) {
  const char* where = "hush::coherent_stream::deserialize";
  detail::byte_reader r(bytes);
  r.need(sizeof detail::kCoherentMagic);
  if (std::memcmp(bytes.data(), detail::kCoherentMagic, sizeof detail::kCoherentMagic) != 0)
    hush::detail::raise_error(std::string(where) +
                                 ": not a coherent-noise state (no HUSHCOH1 header)");
  std::vector<std::uint8_t> skip;
  r.values(skip, sizeof detail::kCoherentMagic);
  const std::uint32_t size = r.u32();
  if (size != sizeof(T))
    hush::detail::raise_error(std::string(where) + ": the state holds " +
                                 std::to_string(8 * size) + "-bit values; this stream holds " +
                                 std::to_string(8 * sizeof(T)) + "-bit values");
  params p;
  p.seed = r.u32();
  p.alpha = r.f64();
  p.epsilon = r.f64();
  p.epsilon_absolute = r.f64();
  p.filter = static_cast<coherent_filter>(r.u32());
  p.input = static_cast<coherent_input>(r.u32());
  p.bandpass_pixels = r.f64();
  p.smoothing = r.f64();
  p.channels = static_cast<int>(r.u32());
  basic_coherent_stream s(p);  // validates the parameters
  detail::coherent_state<T>& st = s.st_;
  st.next_frame = r.u32();
  const std::uint32_t has = r.u32();
  if (has > 1u) hush::detail::raise_error(std::string(where) + ": corrupt history flag");
  if (has) {
    st.width = r.u32();
    st.height = r.u32();
    if (st.width == 0 || st.height == 0 || st.width > detail::constants::kCoherentMaxSide ||
        st.height > detail::constants::kCoherentMaxSide)
      detail::throw_out_of_range(where, "size",
                                 std::to_string(st.width) + "x" + std::to_string(st.height),
                                 "1 ... 16384 pixels per side");
    const std::uint32_t ids = r.u32();
    if (ids > 1u) hush::detail::raise_error(std::string(where) + ": corrupt id flag");
    const std::size_t n = st.pixels();
    r.values(st.ref_depth, n);
    st.reference_has_ids = ids != 0;
    if (st.reference_has_ids) r.values(st.ref_ids, n);
    r.values(st.fresh, n);
    r.values(st.history, n * static_cast<std::size_t>(p.channels));
    for (const T& v : st.history)
      if (!std::isfinite(v))
        hush::detail::raise_error(std::string(where) + ": the history holds a non-finite value");
    st.has_reference = true;
  }
  if (!r.done())
    hush::detail::raise_error(std::string(where) + ": " +
                                 std::to_string(bytes.size() - r.position()) +
                                 " bytes follow the state");
  return s;
}

// ---- The time-symmetric filter (Kass & Pesare sec. 3.3), over a whole sequence.

// How coherent_symmetric reads a sequence and hands back its result, one frame at a time,
// so that no more than two frames' worth of data need be in memory:
//  - frame_at(i) gives frame i's views (depth, velocity, forward_velocity; object_id when
//    available), valid until the next call. It is called for i = 0 ... n-1 (forward pass),
//    then for i = n-1 ... 0 (backward pass).
//  - input_at(i), when set, gives the input noise of frame i, one view per channel (see
//    basic_coherent_stream::advance), valid until the next call; the same images both times.
//  - write(i, out) receives the result of frame i, one view per channel (in the backward
//    pass, i = n-1 ... 0).
//  - keep(i, bytes) / recall(i, bytes): where the forward pass's result of frame i (record_bytes
//    bytes each) waits for the backward pass; when unset, in memory (n records).
template <class T>
struct coherent_sequence {
  std::size_t frames = 0;
  std::uint32_t first_frame = 0;  // frame index of frame 0 (seeds the input noise)
  std::function<frame(std::size_t)> frame_at;
  std::function<std::vector<image_view<const float>>(std::size_t)> input_at;
  std::function<void(std::size_t, span<const image_view<T>>)> write;
  std::function<void(std::size_t, span<const std::uint8_t>)> keep;
  std::function<void(std::size_t, span<std::uint8_t>)> recall;
};

// Bytes of one kept forward record for frames of w x h pixels: the channels' forward
// history (T) and one byte of fresh flags per pixel.
template <class T>
std::size_t coherent_record_bytes(const coherent_params& p, std::size_t w, std::size_t h) {
  return w * h * (static_cast<std::size_t>(p.channels) * sizeof(T) + 1);
}

namespace detail {

// Combines frame i: C = c_fwd + c_bwd - (1 - alpha) w (eq. 11), or, where both passes took
// fresh noise (a pixel seen in this frame only), C = s w with s the symmetric standard
// deviation; the output is gain * C.
template <class T, class Exec>
void coherent_combine(const Exec& ex, const coherent_params& prm, std::uint32_t frame_index,
                      std::size_t w, std::size_t h, const T* fwd, const std::uint8_t* fwd_fresh,
                      const T* bwd, const std::uint8_t* bwd_fresh,
                      const image_view<const float>* input, const image_view<T>* out) {
  namespace c = constants;
  const std::size_t n = w * h;
  const double alpha = coherent_alpha<T>(prm.alpha);
  const T beta = T(1.0 - alpha), gain = T(1.0 / coherent_symmetric_sd(alpha));
  const T both = T(coherent_symmetric_sd(alpha));
  for (int ch = 0; ch < prm.channels; ++ch) {
    const std::size_t off = n * static_cast<std::size_t>(ch);
    const std::uint32_t key = coherent_frame_key(prm.seed, static_cast<unsigned>(ch),
                                                 c::kCoherentFieldInput, frame_index);
    std::vector<float> plane;
    const float* pl = nullptr;
    std::size_t stride = w;
    if (input) {
      pl = input[ch].data;
      stride = input[ch].stride;
    } else if (prm.input == coherent_input::bandpass) {
      coherent_fill_bandpass(ex, coherent_bandpass(key, prm.bandpass_pixels, w, h), plane);
      pl = plane.data();
    }
    const coherent_field field{key, pl, stride};
    std::vector<float> row_values(w);
    for (std::size_t y = 0; y < h; ++y) {
      const std::uint32_t row = coherent_row_key(key, static_cast<std::uint32_t>(y));
      for (std::size_t x = 0; x < w; ++x)
        row_values[x] = coherent_field_value(field, row, static_cast<std::uint32_t>(x),
                                             static_cast<std::uint32_t>(y));
      T* dst = out[ch].row(y);
      const std::size_t p0 = y * w;
      for (std::size_t x = 0; x < w; ++x) {
        const std::size_t p = p0 + x;
        const T wv = T(row_values[x]);
        const T sum =
            (fwd_fresh[p] && bwd_fresh[p]) ? both * wv : fwd[off + p] + bwd[off + p] - beta * wv;
        dst[x] = gain * sum;
      }
    }
  }
}

}  // namespace detail

// The time-symmetric coherent noise of a whole sequence (frames first_frame ... + n - 1),
// streamed through `io` (see coherent_sequence). The result has unit variance per channel
// for unit-variance input, at every frame including the first and the last; it equals the
// sum of a forward causal pass and a backward one (over forward_velocity) minus
// (1 - alpha) w_i (Kass & Pesare eq. 11), times 1 / coherent_symmetric_sd(alpha).
// Throws hush::invalid_argument for invalid parameters, n = 0, missing callbacks, or a frame
// whose views are missing, mismatched or of another size than frame 0's.
template <class T, class Exec>
void coherent_symmetric(const Exec& ex, const coherent_params& prm,
                        const coherent_sequence<T>& io) {
  const char* where = "hush::coherent_symmetric";
  validate(prm);
  if (io.frames == 0) detail::throw_out_of_range(where, "frames", 0, "at least 1");
  if (!io.frame_at || !io.write)
    hush::detail::raise_error(std::string(where) + ": frame_at and write are required");
  if (static_cast<bool>(io.keep) != static_cast<bool>(io.recall))
    hush::detail::raise_error(std::string(where) + ": set both keep and recall, or neither");
  const frame_view needs = frame_view::depth | frame_view::velocity | frame_view::forward_velocity;
  const std::size_t nc = static_cast<std::size_t>(prm.channels);
  std::size_t w = 0, h = 0;
  basic_coherent_stream<T> pass(prm);
  std::vector<std::uint8_t> record;
  std::vector<image_view<const float>> input;
  auto load = [&](std::size_t i) {
    const frame f = io.frame_at(i);
    f.validate(where, needs, detail::constants::kCoherentMaxSide);
    if (w == 0) {
      w = f.width();
      h = f.height();
    } else if (f.width() != w || f.height() != h) {
      detail::throw_out_of_range(
          where, "frame " + std::to_string(i) + " size",
          std::to_string(f.width()) + "x" + std::to_string(f.height()),
          ("frame 0's size, " + std::to_string(w) + "x" + std::to_string(h)).c_str());
    }
    if (io.input_at) {
      input = io.input_at(i);
      detail::coherent_check_views(where, "input", input.data(), input.size(), nc, w, h);
    }
    return f;
  };
  auto step = [&](const frame& f, bool backward, std::uint32_t index) {
    auto& st = pass.state();
    st.next_frame = index;
    st.width = static_cast<std::uint32_t>(f.width());
    st.height = static_cast<std::uint32_t>(f.height());
    detail::coherent_step<T> s;
    s.prm = &prm;
    s.f = &f;
    s.backward = backward;
    s.input = io.input_at ? input.data() : nullptr;
    s.out = nullptr;
    s.gain = T(1);
    if constexpr (std::is_same<Exec, exec::scalar_t>::value ||
                  std::is_same<Exec, exec::simd_t>::value)
      detail::coherent_cpu_step(ex, st, s);
    else
      coherent_glsl_step(ex.device, st, s);
    st.sync_host();
  };
  // Forward pass: keep each frame's history and fresh flags (in memory, or through keep()).
  std::vector<std::vector<T>> kept_values(io.keep ? 0 : io.frames);
  std::vector<std::vector<std::uint8_t>> kept_fresh(io.keep ? 0 : io.frames);
  for (std::size_t i = 0; i < io.frames; ++i) {
    const frame f = load(i);
    step(f, false, io.first_frame + static_cast<std::uint32_t>(i));
    const auto& st = pass.state();
    const std::size_t n = w * h;
    if (io.keep) {
      record.resize(coherent_record_bytes<T>(prm, w, h));
      std::memcpy(record.data(), st.history.data(), n * nc * sizeof(T));
      std::memcpy(record.data() + n * nc * sizeof(T), st.fresh.data(), n);
      io.keep(i, span<const std::uint8_t>(record.data(), record.size()));
    } else {
      kept_values[i].assign(st.history.begin(), st.history.end());
      kept_fresh[i].assign(st.fresh.begin(), st.fresh.end());
    }
  }
  // Backward pass, combined frame by frame with the kept forward result.
  pass.reset();
  std::vector<T> out_planes(w * h * nc), fwd;
  std::vector<std::uint8_t> fwd_fresh;
  std::vector<image_view<T>> out(nc);
  for (std::size_t c = 0; c < nc; ++c) out[c] = image_view<T>(out_planes.data() + w * h * c, w, h);
  for (std::size_t r = io.frames; r-- > 0;) {
    const frame f = load(r);
    const std::uint32_t index = io.first_frame + static_cast<std::uint32_t>(r);
    step(f, true, index);
    const std::size_t n = w * h;
    const T* forward = nullptr;
    const std::uint8_t* forward_fresh = nullptr;
    if (io.recall) {
      record.resize(coherent_record_bytes<T>(prm, w, h));
      io.recall(r, span<std::uint8_t>(record.data(), record.size()));
      fwd.resize(n * nc);
      fwd_fresh.resize(n);
      std::memcpy(fwd.data(), record.data(), n * nc * sizeof(T));
      std::memcpy(fwd_fresh.data(), record.data() + n * nc * sizeof(T), n);
      forward = fwd.data();
      forward_fresh = fwd_fresh.data();
    } else {
      forward = kept_values[r].data();
      forward_fresh = kept_fresh[r].data();
    }
    const auto& st = pass.state();
    detail::coherent_combine(ex, prm, index, w, h, forward, forward_fresh, st.history.data(),
                             st.fresh.data(), io.input_at ? input.data() : nullptr, out.data());
    if (!io.recall) {  // frame r's record has served: free it
      std::vector<T>().swap(kept_values[r]);
      std::vector<std::uint8_t>().swap(kept_fresh[r]);
    }
    for (std::size_t c = 0; c < nc; ++c) detail::coherent_smooth(out[c], prm.smoothing);
    io.write(r, span<const image_view<T>>(out.data(), out.size()));
  }
}

// The same over frames and outputs in memory: out holds frames.size() * channels views,
// frame-major (out[i * channels + c] is channel c of frame i).
template <class T, class Exec>
void coherent_symmetric(const Exec& ex, const coherent_params& prm, span<const frame> frames,
                        span<const image_view<T>> out) {
  const char* where = "hush::coherent_symmetric";
  validate(prm);
  const std::size_t nc = static_cast<std::size_t>(prm.channels);
  if (out.size() != frames.size() * nc)
    detail::throw_out_of_range(
        where, "out.size()", out.size(),
        ("frames.size() * channels = " + std::to_string(frames.size() * nc)).c_str());
  for (std::size_t i = 0; i < frames.size(); ++i)
    detail::coherent_check_views(where, "out", out.data() + i * nc, nc, nc, frames[i].width(),
                                 frames[i].height());
  coherent_sequence<T> io;
  io.frames = frames.size();
  io.frame_at = [&](std::size_t i) { return frames[i]; };
  io.write = [&](std::size_t i, span<const image_view<T>> result) {
    for (std::size_t c = 0; c < nc; ++c) {
      const image_view<T>& dst = out[i * nc + c];
      for (std::size_t y = 0; y < dst.height; ++y)
        std::copy(result[c].row(y), result[c].row(y) + dst.width, dst.row(y));
    }
  };
  coherent_symmetric(ex, prm, io);
}

}  // namespace hush

#endif  // HUSH_COHERENT_HPP
