// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Highway kernel of NPR Gabor noise's stage 2 (hush/npr_gabor.hpp,
// hush/npr_gabor/splat.hpp): the splat records added into a float
// image. Compiled once per SIMD target (the "-inl.h" convention: toggle include
// guard below); reached through hush/simd/dispatch.hpp.
//
// How: the image is cut into tiles of 32 x 32 pixels; every record is
// binned (counting sort, so each tile keeps its records in record order) to
// every tile its pixel range touches. Per tile, its G-buffer views are copied
// into padded tile buffers and its sums kept in a tile accumulator; per
// (record, tile) the kernel's x factors (gabor/kernel.hpp's separable form) are
// computed once per tile column in lanes, its y factors once per tile row, and
// per pixel only their product, the taper and the tests, lanes along x: the
// object and triangle tests in 32-bit lanes, the depth test in double lanes as
// the scalar code computes it (pixel depth times the plane's 1/z, relative
// tolerance, soft band). A record touches tiles whose own ids and depths show
// it cannot pass a test anywhere in them (tile_summary): those pairs are
// skipped, which changes nothing (every fragment there fails).
//
// Agreement with detail::npr_gabor_splat_scalar: the same offsets (in double,
// rounded to float), hush's own exp and sin/cos in lanes (lanes-inl.h), the
// same products and taper, and per pixel the same records in the same order;
// a fragment that fails a test adds +0 (or vis 0 times the kernel, +-0), which
// leaves the sum as it is (it starts at +0 and a round-to-nearest sum is -0
// only when both terms are). Under HUSH_STRICT_FP every pixel equals the
// scalar result bit for bit (tests/npr_gabor/npr_gabor_simd_test.cpp, every
// compiled target); otherwise products may fuse with sums on either side,
// within the kernel's float budget, and a depth decision may flip where the
// relative difference is within an ulp of the tolerance.

#if defined(HUSH_NPR_GABOR_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_NPR_GABOR_SIMD_INL_H_
#undef HUSH_NPR_GABOR_SIMD_INL_H_
#else
#define HUSH_NPR_GABOR_SIMD_INL_H_
#endif

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <hwy/highway.h>

#include "hush/config.hpp"
#include "hush/core/views.hpp"
#include "hush/detail/constants.hpp"
#include "hush/npr_gabor/splat.hpp"
#include "hush/gabor/kernel-inl.h"
#include "hush/simd/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace npr_gabor_simd {

// Generic lane types: simd/lanes-inl.h; the Gabor kernel's factors and pair
// products: gabor_simd (gabor/kernel-inl.h).
using namespace lanes::types;
using DD = hn::ScalableTag<double>;
using DFD = hn::Rebind<float, DD>;  // as many floats as DD has doubles
using VD = hn::Vec<DD>;

// Tile height; the width is max(32, lanes), a whole number of vectors (32 x 32 measured
// fastest of 16 x 16, 32 x 16, 64 x 16 and 32 x 32 on the dense scene, AVX3).
constexpr std::size_t kTileH = 32;
constexpr std::size_t kMaxTileW = lanes::kMaxLanes;
constexpr std::size_t kMaxTile = kMaxTileW * kTileH;

// A tile's copy of the G-buffer (padded with zeros past the image) and its sums.
struct tile {
  std::size_t x0 = 0, y0 = 0, w = 0, h = 0;  // pixels covered (w, h < tile size at the edges)
  alignas(64) double depth[kMaxTile];  // NaN where the depth test fails whatever the plane
  alignas(64) std::uint32_t object[kMaxTile];
  alignas(64) std::uint32_t triangle[kMaxTile];
  alignas(64) float acc[kMaxTile];
  // Per record: the x factors of the tile's columns, the plane's column part, visibility.
  alignas(64) float dx[kMaxTileW], cd2[kMaxTileW], ce[kMaxTileW], cs[kMaxTileW], cc[kMaxTileW];
  alignas(64) float dy[kTileH > kMaxTileW ? kTileH : kMaxTileW];
  alignas(64) float rd2[kMaxTileW], re[kMaxTileW], rs[kMaxTileW], rc[kMaxTileW];
  alignas(64) double pc[kMaxTileW];
  // What can pass: the ids present (one bit per id mod 64) and the depth range.
  std::uint64_t objects = 0, triangles = 0;
  double zmin = 0, zmax = 0;
  bool any_depth = false;
};

// The job's constants as the scalar code rounds them: T(-A), T(1 / (1 - s0)), and the
// depth test's limit (tol, or 2 tol with the soft band).
struct consts {
  float neg_a = 0, taper_k = 0;
  double limit = 0;
};
inline consts consts_of(const detail::npr_gabor_splat_job& j) {
  consts c;
  c.neg_a = static_cast<float>(-j.envelope_exponent);
  c.taper_k = static_cast<float>(1.0 / (1.0 - detail::constants::kGaborTaperStart));
  c.limit = j.soft_depth ? 2.0 * j.depth_tolerance : j.depth_tolerance;
  return c;
}

inline std::uint64_t id_bit(std::uint32_t id) { return std::uint64_t{1} << (id & 63u); }

inline void load_tile(const detail::npr_gabor_splat_job& j, std::size_t tw, tile& t) {
  std::fill(t.depth, t.depth + tw * kTileH, std::numeric_limits<double>::quiet_NaN());
  std::fill(t.object, t.object + tw * kTileH, 0u);
  std::fill(t.triangle, t.triangle + tw * kTileH, 0u);
  std::fill(t.acc, t.acc + tw * kTileH, 0.0f);
  t.objects = t.triangles = 0;
  t.zmin = std::numeric_limits<double>::infinity();
  t.zmax = 0;
  t.any_depth = false;
  for (std::size_t r = 0; r < t.h; ++r) {
    const std::size_t y = t.y0 + r;
    for (std::size_t i = 0; i < t.w; ++i) {
      const std::size_t x = t.x0 + i;
      if (j.depth_test) {
        const float z = j.depth(x, y);
        // Pixels that can pass: depth > 0 and finite (else NaN: every comparison fails).
        if (z > 0.0f && z <= std::numeric_limits<float>::max()) {
          t.depth[r * tw + i] = static_cast<double>(z);
          t.zmin = std::min(t.zmin, static_cast<double>(z));
          t.zmax = std::max(t.zmax, static_cast<double>(z));
          t.any_depth = true;
        }
      }
      if (j.object_test) {
        t.object[r * tw + i] = j.object_id(x, y);
        t.objects |= id_bit(t.object[r * tw + i]);
      }
      if (j.triangle_test) {
        t.triangle[r * tw + i] = j.triangle_id(x, y);
        t.triangles |= id_bit(t.triangle[r * tw + i]);
      }
    }
  }
}

// False when no fragment of record s in tile t can pass the tests: its ids are
// absent, or every pixel's relative depth difference to the plane exceeds the
// limit with a margin far above the rounding of the per-pixel test (1e-6).
inline bool may_pass(const detail::npr_gabor_splat_job& j, const consts& info,
              const hush::npr_gabor_splat& s, const tile& t) {
  if (j.object_test && !(t.objects & id_bit(s.object))) return false;
  if (j.triangle_test && !(t.triangles & id_bit(s.triangle))) return false;
  if (!j.depth_test) return true;
  if (!t.any_depth) return false;
  // The plane's 1/z over the tile's pixel centres: affine, extremes at the corners.
  const double xa = static_cast<double>(t.x0) + 0.5, xb = xa + static_cast<double>(t.w - 1);
  const double ya = static_cast<double>(t.y0) + 0.5, yb = ya + static_cast<double>(t.h - 1);
  const double p00 = s.q0 + s.qx * xa + s.qy * ya, p10 = s.q0 + s.qx * xb + s.qy * ya;
  const double p01 = s.q0 + s.qx * xa + s.qy * yb, p11 = s.q0 + s.qx * xb + s.qy * yb;
  const double pmin = std::min(std::min(p00, p10), std::min(p01, p11));
  const double pmax = std::max(std::max(p00, p10), std::max(p01, p11));
  if (!(pmin > 0.0) || !(pmax < std::numeric_limits<double>::infinity())) return true;
  // zp plane ranges over [zmin pmin, zmax pmax] (all positive).
  const double lo = t.zmin * pmin, hi = t.zmax * pmax, lim = info.limit + 1e-6;
  return !(lo - 1.0 > lim || 1.0 - hi > lim);
}

// npr_gabor_visibility of one vector of pixels (depth: the tile's doubles, NaN where no
// plane can pass; pc: the plane's column part q0 + qx x; qy: its row part), in double
// lanes as the scalar code computes it, rounded to float once.
HWY_INLINE VD visibility_d(const detail::npr_gabor_splat_job& j, const consts& info,
                           const double* depth, const double* pc, VD qy) {
  const DD dd;
  const VD one = hn::Set(dd, 1.0);
  const VD rel = hn::Abs(hn::Sub(hn::Mul(hn::LoadU(dd, depth), hn::Add(hn::LoadU(dd, pc), qy)), one));
  VD v = one;
  if (j.soft_depth) {
    const VD tol = hn::Set(dd, j.depth_tolerance);
    v = hn::IfThenElse(hn::Gt(rel, tol), hn::Sub(hn::Set(dd, 2.0), hn::Div(rel, tol)), one);
  }
  return hn::IfThenElseZero(hn::Le(rel, hn::Set(dd, info.limit)), v);
}
HWY_INLINE VF visibility(const detail::npr_gabor_splat_job& j, const consts& info,
                         const double* depth, const double* pc, VD qy) {
  const DF df;
#if HWY_TARGET == HWY_SCALAR
  return hn::Set(df, static_cast<float>(hn::GetLane(visibility_d(j, info, depth, pc, qy))));
#else
  // Two double vectors per float vector: demoted halves, combined in registers.
  const hn::Half<DF> dh;
  const std::size_t nd = hn::Lanes(DD());
  const auto lo = hn::DemoteTo(dh, visibility_d(j, info, depth, pc, qy));
  const auto hi = hn::DemoteTo(dh, visibility_d(j, info, depth + nd, pc + nd, qy));
  return hn::Combine(df, hi, lo);
#endif
}

// Record s over the part of tile t it covers.
inline void splat_tile(const detail::npr_gabor_splat_job& j, const consts& info,
                const hush::npr_gabor_splat& s, std::size_t tw, tile& t) {
  const DF df;
  const DU du;
  const DI di;
  const DD dd;
  const DFD dfd;
  const std::size_t n = hn::Lanes(df), nd = hn::Lanes(dd);
  const std::size_t x0 = t.x0, y0 = t.y0;
  // Covered columns ia ... ib and rows ra ... rb, tile-relative.
  const std::size_t ia = static_cast<std::size_t>(s.x0) > x0 ? static_cast<std::size_t>(s.x0) - x0 : 0;
  const std::size_t ib = std::min(static_cast<std::size_t>(s.x1) - x0, t.w - 1);
  const std::size_t ra = static_cast<std::size_t>(s.y0) > y0 ? static_cast<std::size_t>(s.y0) - y0 : 0;
  const std::size_t rb = std::min(static_cast<std::size_t>(s.y1) - y0, t.h - 1);
  const std::size_t va = ia / n * n, vb = ib / n * n + n;  // vectors covering ia ... ib
  const std::size_t wa = ra / n * n, wb = rb / n * n + n;  // the same for the rows
  // The offsets of the columns and rows in radii, in double and rounded to float as the
  // scalar code does: ((x + 1/2) - s.x) / r.
  const VD inv_r = hn::Set(dd, 1.0 / s.radius), sx = hn::Set(dd, s.x), sy = hn::Set(dd, s.y);
  for (std::size_t i = va; i < vb; i += nd) {
    const VD xc = hn::Iota(dd, static_cast<double>(x0 + i) + 0.5);
    hn::StoreU(hn::DemoteTo(dfd, hn::Mul(hn::Sub(xc, sx), inv_r)), dfd, t.dx + i);
    if (j.depth_test) hn::StoreU(hn::Add(hn::Set(dd, s.q0), hn::Mul(hn::Set(dd, s.qx), xc)), dd, t.pc + i);
  }
  for (std::size_t r = wa; r < wb; r += nd) {
    const VD yc = hn::Iota(dd, static_cast<double>(y0 + r) + 0.5);
    hn::StoreU(hn::DemoteTo(dfd, hn::Mul(hn::Sub(yc, sy), inv_r)), dfd, t.dy + r);
  }
  const VF neg_a = hn::Set(df, info.neg_a), taper_k = hn::Set(df, info.taper_k);
  const VF phi_x = hn::Set(df, static_cast<float>(s.fx * s.radius));
  const VF phi_y = hn::Set(df, static_cast<float>(s.fy * s.radius));
  // Columns outside ia ... ib get d^2 = 2: s = dx^2 + dy^2 >= 1 fails there as it does
  // outside the disc, so the kernel's own test masks them.
  const VI lane = hn::Iota(di, 0);
  const VI before_first = hn::Set(di, static_cast<std::int32_t>(ia) - 1);
  const VI after_last = hn::Set(di, static_cast<std::int32_t>(ib) + 1);
  for (std::size_t i = va; i < vb; i += n) {
    const gabor_simd::axis a = gabor_simd::axis_factors(hn::LoadU(df, t.dx + i), neg_a, phi_x);
    const VI col = hn::Add(lane, hn::Set(di, static_cast<std::int32_t>(i)));
    const MF in = hn::RebindMask(df, hn::And(hn::Gt(col, before_first), hn::Lt(col, after_last)));
    hn::StoreU(hn::IfThenElse(in, a.d2, hn::Set(df, 2.0f)), df, t.cd2 + i);
    hn::StoreU(a.e, df, t.ce + i);
    hn::StoreU(a.s, df, t.cs + i);
    hn::StoreU(a.c, df, t.cc + i);
  }
  for (std::size_t r = wa; r < wb; r += n) {
    const gabor_simd::axis a = gabor_simd::axis_factors(hn::LoadU(df, t.dy + r), neg_a, phi_y);
    hn::StoreU(a.d2, df, t.rd2 + r);
    hn::StoreU(a.e, df, t.re + r);
    hn::StoreU(a.s, df, t.rs + r);
    hn::StoreU(a.c, df, t.rc + r);
  }
  const float weight = static_cast<float>(s.weight);
  const VF one = hn::Set(df, 1.0f);
  const VU object = hn::Set(du, s.object), triangle = hn::Set(du, s.triangle);
  for (std::size_t r = ra; r <= rb; ++r) {
    const gabor_simd::row row{hn::Set(df, weight * t.re[r]), hn::Set(df, t.rc[r]),
                              hn::Set(df, t.rs[r]), hn::Set(df, t.rd2[r])};
    const std::size_t base = r * tw;
    const VD qy = hn::Set(dd, s.qy * (static_cast<double>(y0 + r) + 0.5));
    for (std::size_t i = va; i < vb; i += n) {
      const gabor_simd::axis ax{hn::Zero(df), hn::LoadU(df, t.cd2 + i), hn::LoadU(df, t.ce + i),
                                hn::LoadU(df, t.cs + i), hn::LoadU(df, t.cc + i)};
      MF m = hn::Lt(hn::Add(ax.d2, row.d2), one);
      if (j.object_test)
        m = hn::And(m, hn::RebindMask(df, hn::Eq(hn::LoadU(du, t.object + base + i), object)));
      if (j.triangle_test)
        m = hn::And(m, hn::RebindMask(df, hn::Eq(hn::LoadU(du, t.triangle + base + i), triangle)));
      VF g = gabor_simd::pair(ax, row, taper_k);
      if (j.depth_test) g = hn::Mul(visibility(j, info, t.depth + base + i, t.pc + i, qy), g);
      float* acc = t.acc + base + i;
      hn::StoreU(hn::Add(hn::LoadU(df, acc), hn::IfThenElseZero(m, g)), df, acc);
    }
  }
}

inline void npr_gabor_splat(const detail::npr_gabor_splat_job& j, const image_view<float>& out) {
  const DF df;
  const std::size_t tw = std::max<std::size_t>(32, hn::Lanes(df));
  const std::size_t width = out.width, height = out.height;
  if (width == 0 || height == 0 || j.count == 0) return;
  const std::size_t ntx = (width + tw - 1) / tw, nty = (height + kTileH - 1) / kTileH;
  // Bin the records: counting sort by tile, record order kept within a tile.
  std::vector<std::uint32_t> start(ntx * nty + 1, 0);
  auto tiles_of = [&](const hush::npr_gabor_splat& s, auto&& f) {
    for (std::size_t ty = static_cast<std::size_t>(s.y0) / kTileH;
         ty <= static_cast<std::size_t>(s.y1) / kTileH; ++ty)
      for (std::size_t tx = static_cast<std::size_t>(s.x0) / tw;
           tx <= static_cast<std::size_t>(s.x1) / tw; ++tx)
        f(ty * ntx + tx);
  };
  for (std::size_t k = 0; k < j.count; ++k) tiles_of(j.splats[k], [&](std::size_t t) { ++start[t + 1]; });
  for (std::size_t t = 0; t < ntx * nty; ++t) start[t + 1] += start[t];
  std::vector<std::uint32_t> list(start.back());
  {
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < j.count; ++k)
      tiles_of(j.splats[k], [&](std::size_t t) { list[next[t]++] = static_cast<std::uint32_t>(k); });
  }
  consts info = consts_of(j);
  std::vector<tile> storage(1);  // ~40 KB: on the heap
  tile& t = storage[0];
  for (std::size_t ty = 0; ty < nty; ++ty)
    for (std::size_t tx = 0; tx < ntx; ++tx) {
      const std::size_t id = ty * ntx + tx;
      if (start[id] == start[id + 1]) continue;  // out is already 0 there
      t.x0 = tx * tw;
      t.y0 = ty * kTileH;
      t.w = std::min(tw, width - t.x0);
      t.h = std::min(kTileH, height - t.y0);
      load_tile(j, tw, t);
      for (std::uint32_t k = start[id]; k < start[id + 1]; ++k) {
        const hush::npr_gabor_splat& s = j.splats[list[k]];
        if (may_pass(j, info, s, t)) splat_tile(j, info, s, tw, t);
      }
      for (std::size_t r = 0; r < t.h; ++r)
        std::copy(t.acc + r * tw, t.acc + r * tw + t.w, out.row(t.y0 + r) + t.x0);
    }
}

}  // namespace npr_gabor_simd

inline void npr_gabor_splat(const detail::npr_gabor_splat_job& j, const image_view<float>& out) {
  npr_gabor_simd::npr_gabor_splat(j, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_NPR_GABOR_SIMD_INL_H_
