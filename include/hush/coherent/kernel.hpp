// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The per-frame work of coherent noise (include/hush/coherent.hpp), as plain
// data and one scalar loop: what a recursive-filter pass does for every pixel
// of one frame. The SIMD kernel (hush/coherent/simd-inl.h) and the GLSL
// program (backends/glsl, hush/glsl/coherent.hpp) repeat it operation by
// operation; include hush/coherent.hpp, not this.
//
// One pass step, frame i against its reference frame r (i - 1 for the causal
// filter, i + 1 for the backward pass of the time-symmetric one), for pixel
// p = (x, y) (Kass & Pesare 2011, sec. 3.2; the refill term is hush's):
//   reprojection, in float (identical in every backend):
//     u = x - s m_x, v = y - s m_y      (m = velocity, s = +1; forward velocity, s = -1)
//     e = depth - s m_z                 (the point's expected depth in frame r)
//     i0 = min(floor(u), W - 2), tx = u - i0 (likewise j0, ty): bilinear taps and weights
//   visible when: the pixel has a surface (finite depth >= FLT_MIN, finite motion), (u, v)
//     lies within the outer pixel centres of frame r, every tap with a non-zero weight shows
//     a surface (and, when both frames carry object ids, the same id), e >= FLT_MIN, and the
//     bilinear depth d' of frame r satisfies |d' - e| <= eps_rel e + eps_abs;
//   value, per channel, in T (float, or double for the reference):
//     visible, paper filter:       c = alpha h + (1 - alpha) w         (eq. 7)
//     visible, stationary filter:  c = alpha (h + d) + (1 - alpha) w   (docs/coherent.md)
//     otherwise (disoccluded):     c = k(alpha) w                      (eq. 6)
//   with h the bilinear history of frame r at (u, v), w the input noise at p, and d the
//   refill: k (sqrt(tx (1 - tx)) ((1 - ty) D_x(p) + ty D_x(p + e_y)) + sqrt(ty (1 - ty)) D_y(p)),
//   D_x(q) = X(q) - X(q + e_x), D_y(q) = Y(q) - Y(q + e_y), X and Y two more fields drawn
//   like the input (independent). The output is gain * c.
#ifndef HUSH_COHERENT_KERNEL_HPP
#define HUSH_COHERENT_KERNEL_HPP

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "hush/config.hpp"
#include "hush/core/hash.hpp"
#include "hush/detail/constants.hpp"

namespace hush {
namespace detail {

// ---- The hashed white-noise fields.

// Key of field `field` of channel `channel` in frame `frame`, for noise seed `seed`.
HUSH_INLINE constexpr std::uint32_t coherent_frame_key(std::uint32_t seed, unsigned channel,
                                                       unsigned field, std::uint32_t frame) {
  return hash32(hash32(seed_key(seed), channel * constants::kCoherentFields + field), frame);
}
// Per-row key of a field: hash32(frame_key, y).
HUSH_INLINE constexpr std::uint32_t coherent_row_key(std::uint32_t frame_key, std::uint32_t y) {
  return hash32(frame_key, y);
}
// The white value of pixel x in a row: unit variance, mean 0, odd multiples of
// sqrt(3) 2^-24 (constants.hpp). Every operation is exact but the last multiply.
HUSH_INLINE float coherent_white(std::uint32_t row_key, std::uint32_t x) {
  namespace c = constants;
  const std::uint32_t h = hash32(row_key ^ (x * c::kCoherentPixelPrime));
  const float centred = static_cast<float>(2u * (h >> c::kCoherentWhiteShift)) -
                        static_cast<float>(c::kCoherentWhiteCentre);  // 2n + 1 - 2^24, exact
  return centred * static_cast<float>(c::kCoherentWhiteScale);
}

// Where one field's values come from: hashed white noise of `key` (a frame key), or a
// plane of floats (band-pass noise, or the caller's input) where value (x, y) is
// plane[y * stride + x]. Planes of the refill fields cover (width + 1) x (height + 1)
// values (X) and width x (height + 1) values (Y).
struct coherent_field {
  std::uint32_t key = 0;
  const float* plane = nullptr;
  std::size_t stride = 0;
};

// One pass over one frame: every pointer the loop reads or writes. Planes the
// stream owns are packed (row stride = width); the caller's views keep their strides
// (in elements; the motion view's in vec3 elements, i.e. 3 floats each).
template <class T>
struct coherent_pass_job {
  std::uint32_t width = 0, height = 0;
  // This frame.
  const float* depth = nullptr;
  std::size_t depth_stride = 0;
  const float* motion = nullptr;  // 3 floats per pixel: velocity, or forward velocity
  std::size_t motion_stride = 0;  // in pixels
  float motion_sign = 1.0f;       // +1: velocity (causal); -1: forward velocity (backward pass)
  const std::uint32_t* ids = nullptr;  // null: no id test
  std::size_t ids_stride = 0;
  // The reference frame (stored by the stream, packed); null depth: no reference, all fresh.
  const float* ref_depth = nullptr;
  const std::uint32_t* ref_ids = nullptr;
  // Parameters.
  float eps_rel = 0, eps_abs = 0;
  T alpha = 0, beta = 0, k = 0, gain = 0;  // beta = 1 - alpha, k = k(alpha)
  bool stationary = true;
  int channels = 1;
  coherent_field input[constants::kCoherentMaxChannels];
  coherent_field refill_x[constants::kCoherentMaxChannels];
  coherent_field refill_y[constants::kCoherentMaxChannels];
  const T* ref_history[constants::kCoherentMaxChannels] = {};  // packed planes (with ref_depth)
  T* history[constants::kCoherentMaxChannels] = {};            // packed planes, written
  T* out[constants::kCoherentMaxChannels] = {};                // null: not written
  std::size_t out_stride = 0;
  std::uint8_t* fresh = nullptr;  // packed: 1 where the pixel took fresh noise, else 0
  // Packed copies of this frame's depth and ids (the next frame's reference), or null.
  float* depth_copy = nullptr;
  std::uint32_t* ids_copy = nullptr;
};

// ---- The reprojection, in float: the same operations in every backend.

struct coherent_taps {
  bool visible = false;
  std::uint32_t t00 = 0, t10 = 0, t01 = 0, t11 = 0;  // pixel indices in the reference frame
  float w00 = 0, w10 = 0, w01 = 0, w11 = 0;          // bilinear weights
  float tx = 0, ty = 0;                              // fractions of the bilinear cell
};

// A depth is a surface when finite and at least the smallest normal float (denormal,
// zero, negative, NaN and infinite depths are not: no denormal arithmetic follows).
HUSH_INLINE bool coherent_surface(float d) {
  return d >= std::numeric_limits<float>::min() && d <= std::numeric_limits<float>::max();
}
HUSH_INLINE bool coherent_finite(float v) {
  return v >= -std::numeric_limits<float>::max() && v <= std::numeric_limits<float>::max();
}

// Motion components below the smallest normal float are read as 0 (no denormal arithmetic);
// NaN stays NaN (the pixel is then not visible).
HUSH_INLINE float coherent_flush(float v) {
  return std::fabs(v) < std::numeric_limits<float>::min() ? 0.0f : v;
}
// History values below the smallest normal T are stored as 0: with an input of zeros (the
// caller's) the history decays as alpha^i and would otherwise go denormal.
template <class T>
HUSH_INLINE T coherent_flush_value(T v) {
  return std::fabs(v) < std::numeric_limits<T>::min() ? T(0) : v;
}

template <class T>
HUSH_INLINE coherent_taps coherent_reproject(const coherent_pass_job<T>& j, std::uint32_t x,
                                             std::uint32_t y) {
  coherent_taps r;
  if (!j.ref_depth) return r;
  const float depth = j.depth[y * j.depth_stride + x];
  const float* m = j.motion + 3 * (y * j.motion_stride + x);
  const float mx = coherent_flush(j.motion_sign * m[0]), my = coherent_flush(j.motion_sign * m[1]),
              mz = coherent_flush(j.motion_sign * m[2]);
  if (!coherent_surface(depth) || !coherent_finite(mx) || !coherent_finite(my) ||
      !coherent_finite(mz))
    return r;
  const float u = static_cast<float>(x) - mx, v = static_cast<float>(y) - my;
  const float max_u = static_cast<float>(j.width - 1), max_v = static_cast<float>(j.height - 1);
  if (!(u >= 0.0f && u <= max_u && v >= 0.0f && v <= max_v)) return r;
  // The cell's lower corner; on the last row/column the cell before it, with the upper
  // taps weighted 1. A 1-pixel-wide frame has one column: both taps are it, tx = 0.
  const float i0 = std::fmin(std::floor(u), static_cast<float>(j.width > 1 ? j.width - 2 : 0));
  const float j0 = std::fmin(std::floor(v), static_cast<float>(j.height > 1 ? j.height - 2 : 0));
  r.tx = u - i0;  // exact
  r.ty = v - j0;
  const float a = 1.0f - r.tx, b = 1.0f - r.ty;
  r.w00 = a * b;
  r.w10 = r.tx * b;
  r.w01 = a * r.ty;
  r.w11 = r.tx * r.ty;
  const std::uint32_t step_x = j.width > 1 ? 1u : 0u, step_y = j.height > 1 ? j.width : 0u;
  r.t00 = static_cast<std::uint32_t>(j0) * j.width + static_cast<std::uint32_t>(i0);
  r.t10 = r.t00 + step_x;
  r.t01 = r.t00 + step_y;
  r.t11 = r.t01 + step_x;
  const std::uint32_t id = j.ids ? j.ids[y * j.ids_stride + x] : 0u;
  const bool use_ids = j.ids && j.ref_ids;
  const std::uint32_t taps[4] = {r.t00, r.t10, r.t01, r.t11};
  const float weights[4] = {r.w00, r.w10, r.w01, r.w11};
  float interpolated = 0.0f;
  for (int k = 0; k < 4; ++k) {
    if (weights[k] == 0.0f) continue;  // never read: a background tap must not matter
    const float d = j.ref_depth[taps[k]];
    if (!coherent_surface(d) || (use_ids && j.ref_ids[taps[k]] != id)) return r;
    interpolated = interpolated + weights[k] * d;
  }
  const float expected = depth - mz;
  if (!coherent_surface(expected)) return r;
  const float tolerance = j.eps_rel * expected + j.eps_abs;
  r.visible = std::fabs(interpolated - expected) <= tolerance;
  return r;
}

// Value of a field at (x, y): the hash, or the plane (a non-finite plane value reads as 0,
// so no NaN can enter the history).
HUSH_INLINE float coherent_field_value(const coherent_field& f, std::uint32_t row_key,
                                       std::uint32_t x, std::uint32_t y) {
  if (!f.plane) return coherent_white(row_key, x);
  const float v = f.plane[y * f.stride + x];
  return coherent_finite(v) ? v : 0.0f;
}

// ---- The scalar pass: the reference every other backend is tested against.

// Row keys of every field of every channel for row y (and y + 1 for the refill fields).
struct coherent_row_keys {
  std::uint32_t input[constants::kCoherentMaxChannels];
  std::uint32_t x0[constants::kCoherentMaxChannels], x1[constants::kCoherentMaxChannels];
  std::uint32_t y0[constants::kCoherentMaxChannels], y1[constants::kCoherentMaxChannels];
};
template <class T>
HUSH_INLINE coherent_row_keys coherent_keys(const coherent_pass_job<T>& j, std::uint32_t y) {
  coherent_row_keys k{};
  for (int c = 0; c < j.channels; ++c) {
    k.input[c] = coherent_row_key(j.input[c].key, y);
    k.x0[c] = coherent_row_key(j.refill_x[c].key, y);
    k.x1[c] = coherent_row_key(j.refill_x[c].key, y + 1);
    k.y0[c] = coherent_row_key(j.refill_y[c].key, y);
    k.y1[c] = coherent_row_key(j.refill_y[c].key, y + 1);
  }
  return k;
}

// Pixel (x, y) of a pass: fresh flag, history and output of every channel.
template <class T>
HUSH_INLINE void coherent_pixel(const coherent_pass_job<T>& j, const coherent_row_keys& keys,
                                std::uint32_t x, std::uint32_t y) {
  const coherent_taps g = coherent_reproject(j, x, y);
  const std::size_t p = static_cast<std::size_t>(y) * j.width + x;
  if (j.fresh) j.fresh[p] = g.visible ? 0u : 1u;
  if (j.depth_copy) j.depth_copy[p] = j.depth[y * j.depth_stride + x];
  if (j.ids_copy) j.ids_copy[p] = j.ids[y * j.ids_stride + x];
  for (int c = 0; c < j.channels; ++c) {
    const T w = T(coherent_field_value(j.input[c], keys.input[c], x, y));
    T value;
    if (!g.visible) {
      value = j.k * w;
    } else {
      const T* hist = j.ref_history[c];
      const T h = T(g.w00) * hist[g.t00] + T(g.w10) * hist[g.t10] + T(g.w01) * hist[g.t01] +
                  T(g.w11) * hist[g.t11];
      if (!j.stationary) {
        value = j.alpha * h + j.beta * w;
      } else {
        const T tx = T(g.tx), ty = T(g.ty);
        const T sx = std::sqrt(tx * (T(1) - tx)), sy = std::sqrt(ty * (T(1) - ty));
        const T x00 = T(coherent_field_value(j.refill_x[c], keys.x0[c], x, y));
        const T x10 = T(coherent_field_value(j.refill_x[c], keys.x0[c], x + 1, y));
        const T x01 = T(coherent_field_value(j.refill_x[c], keys.x1[c], x, y + 1));
        const T x11 = T(coherent_field_value(j.refill_x[c], keys.x1[c], x + 1, y + 1));
        const T y00 = T(coherent_field_value(j.refill_y[c], keys.y0[c], x, y));
        const T y01 = T(coherent_field_value(j.refill_y[c], keys.y1[c], x, y + 1));
        const T dx = (T(1) - ty) * (x00 - x10) + ty * (x01 - x11);
        // The refill has the history's scale: k(alpha) (the fields have unit variance).
        const T d = j.k * (sx * dx + sy * (y00 - y01));
        value = j.alpha * (h + d) + j.beta * w;
      }
    }
    value = coherent_flush_value(value);
    j.history[c][p] = value;
    if (j.out[c]) j.out[c][static_cast<std::size_t>(y) * j.out_stride + x] = j.gain * value;
  }
}

template <class T>
void coherent_pass_scalar(const coherent_pass_job<T>& j) {
  for (std::uint32_t y = 0; y < j.height; ++y) {
    const coherent_row_keys keys = coherent_keys(j, y);
    for (std::uint32_t x = 0; x < j.width; ++x) coherent_pixel(j, keys, x, y);
  }
}

}  // namespace detail
}  // namespace hush

#endif  // HUSH_COHERENT_KERNEL_HPP
