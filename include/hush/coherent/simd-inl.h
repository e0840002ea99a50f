// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Highway kernel of coherent noise (include/hush/coherent.hpp): one pass of
// the recursive filter over a frame, a vector of pixels of a row at a time.
// Compiled once per SIMD target (the "-inl.h" convention: toggle include
// guard, no normal guard); reached through hush/simd/dispatch.hpp.
//
// It repeats detail::coherent_pass_scalar (hush/coherent/kernel.hpp)
// operation by operation: the reprojection in float with separate multiplies
// and adds (never fused, so the visibility decisions equal the scalar ones on
// every target), the hashed fields in 32-bit lanes, the taps gathered, the
// bilinear history and the blend in the scalar order. Under HUSH_STRICT_FP
// every output, history value and fresh flag equals the scalar pass bit for
// bit (tests/coherent/coherent_simd_test.cpp, every compiled target); otherwise
// the value blends fuse multiply-adds and differ from scalar by float
// rounding (a few ulp of the values, the decisions unchanged). A row's last
// (width mod lanes) pixels run the scalar code itself; lanes of pixels that
// are not visible read the reference frame at index 0, never out of bounds.

#if defined(HUSH_COHERENT_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_COHERENT_SIMD_INL_H_
#undef HUSH_COHERENT_SIMD_INL_H_
#else
#define HUSH_COHERENT_SIMD_INL_H_
#endif

#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <hwy/highway.h>

#include "hush/config.hpp"
#include "hush/coherent/kernel.hpp"
#include "hush/detail/constants.hpp"
#include "hush/simd/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace coherent_simd {

// Generic lane maths: simd/lanes-inl.h. mul_add is used for the value blends
// only.
using namespace lanes::types;

using lanes::hash32;
using lanes::mul_add;

// detail::coherent_white of pixels `x` (lanes) of a row.
HWY_INLINE VF white(std::uint32_t row_key, VU x) {
  namespace c = detail::constants;
  const DF df;
  const DU du;
  const DI di;
  const VU h =
      hash32(hn::Xor(hn::Set(du, row_key), hn::Mul(x, hn::Set(du, c::kCoherentPixelPrime))));
  // 2 (h >> 8) < 2^25 is even, so exact in float, and exact as an int32.
  const VU twice = hn::ShiftLeft<1>(hn::ShiftRight<c::kCoherentWhiteShift>(h));
  const VF centred = hn::Sub(hn::ConvertTo(df, hn::BitCast(di, twice)),
                             hn::Set(df, static_cast<float>(c::kCoherentWhiteCentre)));
  return hn::Mul(centred, hn::Set(df, static_cast<float>(c::kCoherentWhiteScale)));
}

HWY_INLINE MF is_finite(VF v) {
  const DF df;
  const VF big = hn::Set(df, std::numeric_limits<float>::max());
  return hn::And(hn::Ge(v, hn::Neg(big)), hn::Le(v, big));
}
HWY_INLINE MF is_surface(VF d) {
  const DF df;
  return hn::And(hn::Ge(d, hn::Set(df, std::numeric_limits<float>::min())),
                 hn::Le(d, hn::Set(df, std::numeric_limits<float>::max())));
}

// detail::coherent_flush / coherent_flush_value: |v| below the smallest normal -> 0 (NaN
// stays NaN).
HWY_INLINE VF flush(VF v) {
  const DF df;
  return hn::IfThenZeroElse(hn::Lt(hn::Abs(v), hn::Set(df, std::numeric_limits<float>::min())), v);
}

// detail::coherent_field_value for pixels x (+ dx) of row y.
HWY_INLINE VF field(const detail::coherent_field& f, std::uint32_t row_key, std::uint32_t x,
                    std::uint32_t dx, std::uint32_t y) {
  const DF df;
  const DU du;
  if (!f.plane) return white(row_key, hn::Iota(du, x + dx));
  const VF v = hn::LoadU(df, f.plane + static_cast<std::size_t>(y) * f.stride + x + dx);
  return hn::IfThenElseZero(is_finite(v), v);
}

// The refill fields' values of rows y and y + 1 when they are hashed white noise: each
// value is used by four pixels (x, x - 1 and the rows y - 1, y), so a row is hashed once
// into a buffer and read by both rows (null: the field is a plane, read directly).
struct refill_rows {
  const float* x0[detail::constants::kCoherentMaxChannels] = {};  // X, row y (width + 1)
  const float* x1[detail::constants::kCoherentMaxChannels] = {};  // X, row y + 1
  const float* y0[detail::constants::kCoherentMaxChannels] = {};  // Y, row y (width)
  const float* y1[detail::constants::kCoherentMaxChannels] = {};  // Y, row y + 1
};

// Values of a white field in row y, pixels 0 ... count - 1 (count rounded up to lanes).
HWY_INLINE void white_row(std::uint32_t row_key, std::size_t count, float* out) {
  const DF df;
  const DU du;
  const std::size_t lanes = hn::Lanes(df);
  for (std::size_t x = 0; x < count; x += lanes)
    hn::StoreU(white(row_key, hn::Iota(du, static_cast<std::uint32_t>(x))), df, out + x);
}

// Pixels x ... x + lanes - 1 of row y (all inside the row).
HWY_INLINE void pixels(const detail::coherent_pass_job<float>& j,
                       const detail::coherent_row_keys& keys, const refill_rows& rows,
                       std::uint32_t x, std::uint32_t y) {
  const DF df;
  const DU du;
  const DI di;
  const std::size_t p = static_cast<std::size_t>(y) * j.width + x;
  // ---- Reprojection (coherent_reproject), in float, never fused.
  const VF depth = hn::LoadU(df, j.depth + static_cast<std::size_t>(y) * j.depth_stride + x);
  if (j.depth_copy) hn::StoreU(depth, df, j.depth_copy + p);
  VF mx, my, mz;
  hn::LoadInterleaved3(df, j.motion + 3 * (static_cast<std::size_t>(y) * j.motion_stride + x), mx,
                       my, mz);
  const VF sign = hn::Set(df, j.motion_sign);
  mx = flush(hn::Mul(sign, mx));
  my = flush(hn::Mul(sign, my));
  mz = flush(hn::Mul(sign, mz));
  const VF u = hn::Sub(hn::Iota(df, static_cast<float>(x)), mx);  // x + lane: exact
  const VF v = hn::Sub(hn::Set(df, static_cast<float>(y)), my);
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f);
  MF ok = hn::And(hn::And(is_surface(depth), is_finite(mx)), hn::And(is_finite(my), is_finite(mz)));
  ok = hn::And(ok, hn::And(hn::And(hn::Ge(u, zero), hn::Le(u, hn::Set(df, float(j.width - 1)))),
                           hn::And(hn::Ge(v, zero), hn::Le(v, hn::Set(df, float(j.height - 1))))));
  const VF i0 = hn::Min(hn::Floor(u), hn::Set(df, float(j.width > 1 ? j.width - 2 : 0)));
  const VF j0 = hn::Min(hn::Floor(v), hn::Set(df, float(j.height > 1 ? j.height - 2 : 0)));
  const VF tx = hn::Sub(u, i0), ty = hn::Sub(v, j0);
  const VF a = hn::Sub(one, tx), b = hn::Sub(one, ty);
  const VF w[4] = {hn::Mul(a, b), hn::Mul(tx, b), hn::Mul(a, ty), hn::Mul(tx, ty)};
  // Tap indices (int32: frames are at most 16384^2 pixels); lanes that are not ok read 0.
  const auto ok_i = hn::RebindMask(di, ok);
  const VI i0i = hn::IfThenElseZero(ok_i, hn::ConvertTo(di, hn::IfThenElseZero(ok, i0)));
  const VI j0i = hn::IfThenElseZero(ok_i, hn::ConvertTo(di, hn::IfThenElseZero(ok, j0)));
  const VI sx = hn::IfThenElseZero(ok_i, hn::Set(di, j.width > 1 ? 1 : 0));
  const VI sy = hn::IfThenElseZero(ok_i, hn::Set(di, j.height > 1 ? int(j.width) : 0));
  VI t[4];
  t[0] = hn::Add(hn::Mul(j0i, hn::Set(di, static_cast<std::int32_t>(j.width))), i0i);
  t[1] = hn::Add(t[0], sx);
  t[2] = hn::Add(t[0], sy);
  t[3] = hn::Add(t[2], sx);
  // The taps of most vectors are contiguous: every lane's cell is its neighbour's plus one
  // column, in one row (smooth motion moves neighbouring pixels alike). Then each tap is one
  // unaligned load instead of a gather; the values are the same.
  const std::int32_t i_first = hn::GetLane(i0i), j_first = hn::GetLane(j0i);
  const bool contiguous =
      hn::AllTrue(di, ok_i) &&
      hn::AllTrue(di, hn::Eq(hn::Sub(i0i, hn::Iota(di, 0)), hn::Set(di, i_first))) &&
      hn::AllTrue(di, hn::Eq(j0i, hn::Set(di, j_first)));
  const std::size_t base =
      static_cast<std::size_t>(j_first) * j.width + static_cast<std::size_t>(i_first);
  const std::size_t offset[4] = {0, j.width > 1 ? 1u : 0u, j.height > 1 ? j.width : 0u,
                                 (j.height > 1 ? j.width : 0u) + (j.width > 1 ? 1u : 0u)};
  auto tap = [&](auto d, const auto* plane, int k) {
    return contiguous ? hn::LoadU(d, plane + base + offset[k]) : hn::GatherIndex(d, plane, t[k]);
  };
  const bool use_ids = j.ids && j.ref_ids;
  VU id = hn::Zero(du);
  if (j.ids) {
    id = hn::LoadU(du, j.ids + static_cast<std::size_t>(y) * j.ids_stride + x);
    if (j.ids_copy) hn::StoreU(id, du, j.ids_copy + p);
  }
  VF interpolated = zero;
  for (int k = 0; k < 4; ++k) {
    const MF used = hn::Ne(w[k], zero);
    const VF d = tap(df, j.ref_depth, k);
    MF tap_ok = is_surface(d);
    if (use_ids) tap_ok = hn::And(tap_ok, hn::RebindMask(df, hn::Eq(tap(du, j.ref_ids, k), id)));
    ok = hn::And(ok, hn::Or(hn::Not(used), tap_ok));
    interpolated = hn::IfThenElse(used, hn::Add(interpolated, hn::Mul(w[k], d)), interpolated);
  }
  const VF expected = hn::Sub(depth, mz);
  const VF tolerance = hn::Add(hn::Mul(hn::Set(df, j.eps_rel), expected), hn::Set(df, j.eps_abs));
  const MF visible = hn::And(hn::And(ok, is_surface(expected)),
                             hn::Le(hn::Abs(hn::Sub(interpolated, expected)), tolerance));
  if (j.fresh) {
    const VI flag = hn::IfThenZeroElse(hn::RebindMask(di, visible), hn::Set(di, 1));
    hn::StoreU(hn::DemoteTo(hn::Rebind<std::uint8_t, DI>(), flag), hn::Rebind<std::uint8_t, DI>(),
               j.fresh + p);
  }
  // ---- Values, per channel.
  const VF alpha = hn::Set(df, j.alpha), beta = hn::Set(df, j.beta), kk = hn::Set(df, j.k);
  const VF sqx = hn::Sqrt(hn::Mul(tx, a)), sqy = hn::Sqrt(hn::Mul(ty, b));
  for (int c = 0; c < j.channels; ++c) {
    const VF wv = field(j.input[c], keys.input[c], x, 0, y);
    const float* hist = j.ref_history[c];
    const VF h = mul_add(w[3], tap(df, hist, 3),
                         mul_add(w[2], tap(df, hist, 2),
                                 mul_add(w[1], tap(df, hist, 1), hn::Mul(w[0], tap(df, hist, 0)))));
    VF value;
    if (!j.stationary) {
      value = mul_add(alpha, h, hn::Mul(beta, wv));
    } else {
      VF x00, x10, x01, x11, y00, y01;
      if (rows.x0[c]) {
        x00 = hn::LoadU(df, rows.x0[c] + x);
        x10 = hn::LoadU(df, rows.x0[c] + x + 1);
        x01 = hn::LoadU(df, rows.x1[c] + x);
        x11 = hn::LoadU(df, rows.x1[c] + x + 1);
      } else {
        x00 = field(j.refill_x[c], keys.x0[c], x, 0, y);
        x10 = field(j.refill_x[c], keys.x0[c], x, 1, y);
        x01 = field(j.refill_x[c], keys.x1[c], x, 0, y + 1);
        x11 = field(j.refill_x[c], keys.x1[c], x, 1, y + 1);
      }
      if (rows.y0[c]) {
        y00 = hn::LoadU(df, rows.y0[c] + x);
        y01 = hn::LoadU(df, rows.y1[c] + x);
      } else {
        y00 = field(j.refill_y[c], keys.y0[c], x, 0, y);
        y01 = field(j.refill_y[c], keys.y1[c], x, 0, y + 1);
      }
      const VF dx = mul_add(ty, hn::Sub(x01, x11), hn::Mul(b, hn::Sub(x00, x10)));
      const VF d = hn::Mul(kk, mul_add(sqy, hn::Sub(y00, y01), hn::Mul(sqx, dx)));
      value = mul_add(alpha, hn::Add(h, d), hn::Mul(beta, wv));
    }
    value = flush(hn::IfThenElse(visible, value, hn::Mul(kk, wv)));
    hn::StoreU(value, df, j.history[c] + p);
    if (j.out[c])
      hn::StoreU(hn::Mul(hn::Set(df, j.gain), value), df,
                 j.out[c] + static_cast<std::size_t>(y) * j.out_stride + x);
  }
}

// The same when there is no reference frame (the first frame): every pixel fresh.
HWY_INLINE void fresh_pixels(const detail::coherent_pass_job<float>& j,
                             const detail::coherent_row_keys& keys, std::uint32_t x,
                             std::uint32_t y) {
  const DF df;
  const DU du;
  const std::size_t p = static_cast<std::size_t>(y) * j.width + x;
  if (j.fresh) {
    const hn::Rebind<std::uint8_t, DF> d8;
    hn::StoreU(hn::Set(d8, std::uint8_t{1}), d8, j.fresh + p);
  }
  if (j.depth_copy)
    hn::StoreU(hn::LoadU(df, j.depth + static_cast<std::size_t>(y) * j.depth_stride + x), df,
               j.depth_copy + p);
  if (j.ids_copy)
    hn::StoreU(hn::LoadU(du, j.ids + static_cast<std::size_t>(y) * j.ids_stride + x), du,
               j.ids_copy + p);
  for (int c = 0; c < j.channels; ++c) {
    const VF value = flush(hn::Mul(hn::Set(df, j.k), field(j.input[c], keys.input[c], x, 0, y)));
    hn::StoreU(value, df, j.history[c] + p);
    if (j.out[c])
      hn::StoreU(hn::Mul(hn::Set(df, j.gain), value), df,
                 j.out[c] + static_cast<std::size_t>(y) * j.out_stride + x);
  }
}

}  // namespace coherent_simd

// One pass over a frame (detail::coherent_pass_job): full vectors of each row in
// lanes, the rest of the row (fewer pixels than lanes) through the scalar pixel code.
inline void coherent_pass(const detail::coherent_pass_job<float>& j) {
  namespace cs = coherent_simd;
  const std::size_t lanes = hn::Lanes(cs::DF());
  const std::uint32_t full = static_cast<std::uint32_t>(j.width / lanes * lanes);
  // Row buffers of the white refill fields (stationary filter, with a reference frame).
  const std::size_t padded = (j.width + 1 + lanes - 1) / lanes * lanes;
  const bool refill = j.stationary && j.ref_depth;
  std::vector<float> buffers;
  float* rows_of[detail::constants::kCoherentMaxChannels][4] = {};  // x0, x1, y0, y1
  if (refill) {
    buffers.resize(4 * padded * static_cast<std::size_t>(j.channels));
    for (int c = 0; c < j.channels; ++c)
      for (int k = 0; k < 4; ++k)
        rows_of[c][k] = buffers.data() + (4 * static_cast<std::size_t>(c) + k) * padded;
  }
  for (std::uint32_t y = 0; y < j.height; ++y) {
    const detail::coherent_row_keys keys = detail::coherent_keys(j, y);
    cs::refill_rows rows;
    for (int c = 0; refill && c < j.channels; ++c) {
      // Row y is the previous row's y + 1 (swapped in), except on the first row.
      if (y == 0) {
        if (!j.refill_x[c].plane) cs::white_row(keys.x0[c], j.width + 1, rows_of[c][0]);
        if (!j.refill_y[c].plane) cs::white_row(keys.y0[c], j.width, rows_of[c][2]);
      } else {
        std::swap(rows_of[c][0], rows_of[c][1]);
        std::swap(rows_of[c][2], rows_of[c][3]);
      }
      if (!j.refill_x[c].plane) {
        cs::white_row(keys.x1[c], j.width + 1, rows_of[c][1]);
        rows.x0[c] = rows_of[c][0];
        rows.x1[c] = rows_of[c][1];
      }
      if (!j.refill_y[c].plane) {
        cs::white_row(keys.y1[c], j.width, rows_of[c][3]);
        rows.y0[c] = rows_of[c][2];
        rows.y1[c] = rows_of[c][3];
      }
    }
    std::uint32_t x = 0;
    for (; x < full; x += static_cast<std::uint32_t>(lanes)) {
      if (j.ref_depth)
        cs::pixels(j, keys, rows, x, y);
      else
        cs::fresh_pixels(j, keys, x, y);
    }
    for (; x < j.width; ++x) detail::coherent_pixel(j, keys, x, y);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_COHERENT_SIMD_INL_H_ toggle
