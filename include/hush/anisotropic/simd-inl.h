// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Highway kernels for anisotropic noise (hush/anisotropic.hpp): batches of
// samples (positions with optional footprints and surface maps), points and
// uniform grids; values, and gradients on request (weights held fixed).
// Compiled once per SIMD target (toggle include guard); reached through
// hush/simd/dispatch.hpp, never included directly by users.
//
// A block of kBlock samples goes through two phases:
//  1. weights and tile coordinates, lanes = samples: the filter weights
//     lambda (pixel filter per subband: exp2 polynomial of approx_math.hpp),
//     the compensation weights gamma (log2 and band-profile polynomials), the
//     octave sums, and per scale the lattice split of the tile coordinate
//     p f_s / band + offset, in double lanes (exactly lattice_split<float>,
//     lane by lane through core/lattice.hpp beyond 2^31 texels);
//  2. lookups, lanes = channels (orientations): per sample and scale, the
//     four texels of the bilinear footprint are two runs of 2 * channels
//     floats; the blend and the weighted accumulation run on 4-channel
//     chunks, the final channel sum in anisotropic.hpp's tree order.
// Every operation repeats anisotropic.hpp's float algorithm in the same
// order, so under HUSH_STRICT_FP the results are bit for bit the scalar ones
// (tests/anisotropic/anisotropic_simd_test.cpp, every compiled target); otherwise
// multiply-adds are fused and results stay within the noise's float budget.
// Least-squares weight rules take the scalar weight code per sample
// (phase 1) and the vector lookups (phase 2): the same bits as well.
// Gradients go through the general per-sample lookup, which also forms the
// slopes of each bilinear lookup (anisotropic.hpp's accumulate).

// Toggle guard: included once per target by foreach_target.h.
#if defined(HUSH_ANISOTROPIC_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_ANISOTROPIC_SIMD_INL_H_
#undef HUSH_ANISOTROPIC_SIMD_INL_H_
#else
#define HUSH_ANISOTROPIC_SIMD_INL_H_
#endif

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <hwy/highway.h>

#include "hush/config.hpp"
#include "hush/core/lattice.hpp"
#include "hush/core/samples.hpp"
#include "hush/core/views.hpp"
#include "hush/detail/approx_math.hpp"
#include "hush/detail/constants.hpp"
#include "hush/simd/lanes-inl.h"

// The noise class comes first, not from here: hush/anisotropic.hpp includes these
// kernels at its end (hush/anisotropic/simd_kernel.hpp), as src/simd/anisotropic.cpp does.
HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace aniso_simd {

using namespace lanes::types;
using DD = hn::ScalableTag<double>;
using VD = hn::Vec<DD>;
using DFH = hn::Rebind<float, DD>;     // as many floats as DD has doubles
using DIH = hn::Rebind<int32_t, DD>;   // ... and int32
using DUH = hn::Rebind<uint32_t, DD>;  // ... and uint32
using D4 = hn::CappedTag<float, 4>;    // one chunk of channels (1 lane on HWY_SCALAR)
using V4 = hn::Vec<D4>;

namespace c = detail::constants;

// Samples per block: a multiple of every target's lane count (AVX-512: 16
// floats; SVE at most 64) and small enough for the block buffers to stay in L1/L2.
constexpr std::size_t kBlock = 64;
constexpr int kMaxScales = c::kAnisoMaxScales;
constexpr int kMaxChannels = anisotropic::kMaxChannels;

// Generic lane maths: simd/lanes-inl.h (mul_add for float and double
// vectors of any width; exp2 and log2 as detail/approx_math.hpp).
using lanes::exp2_nonpositive;
using lanes::horner;
using lanes::log2_positive;
using lanes::mul_add;

constexpr auto kSinPi = lanes::to_float(c::kAnisoSeries.sinpi);

// detail::band_profile: cos^2(pi x / 2) for |x| < 1, else 0 (x is never NaN here).
HWY_INLINE VF band_profile(VF x) {
  const DF df;
  const VF ax = hn::Abs(x);
  const VF z = hn::Sub(ax, hn::Set(df, 0.5f));
  const VF p = horner(kSinPi, hn::Mul(z, z));
  const VF half = hn::Set(df, 0.5f);
  const VF v = hn::Sub(half, hn::Mul(half, hn::Mul(p, z)));
  return hn::IfThenElseZero(hn::Lt(ax, hn::Set(df, 1.0f)), v);
}

// The noise's constants in float, once per call.
struct config {
  int k = 4, kc = 4, scales = 3, base = 0, octaves = 3;
  bool fbm = true, lsq = false;
  weight_rule filtering = weight_rule::centre, compensation = weight_rule::centre;
  std::uint32_t n = 256;
  std::size_t stride = 0;
  const float* texels = nullptr;
  double dxx[kMaxChannels] = {}, dyy[kMaxChannels] = {}, dxy2[kMaxChannels] = {};
  double dx[kMaxChannels] = {}, dy[kMaxChannels] = {}, kappa[kMaxScales] = {};
  float ow[kMaxScales] = {}, gain[kMaxScales] = {};
  float norm = 1, cap = 1, cut = 0;
  // pow4: kappa_s = 4^s kappa_0 exactly (the scales' frequencies are f_0 2^s), so
  // float(kappa_s q) = 4^s float(kappa_0 q): scaling by a power of two commutes with
  // rounding, overflow included; below float's normal range (z < 2^-126) the two may
  // differ, but exp2's polynomial then returns its constant term for both: the same
  // lambda. Checked here rather than assumed.
  bool pow4 = true;
  float four_s[kMaxScales] = {};
  double tpu[kMaxScales] = {}, off[kMaxScales][2] = {};

  explicit config(const anisotropic& a) {
    const auto& p = a.parameters();
    k = p.orientations;
    kc = a.channels();
    scales = p.scales;
    base = p.base_scale;
    octaves = p.octaves;
    fbm = p.kind == fractal_kind::fbm;
    filtering = p.filtering;
    compensation = p.compensation;
    lsq = filtering == weight_rule::least_squares || compensation == weight_rule::least_squares;
    n = static_cast<std::uint32_t>(p.tile_size);
    stride = a.tile().row_stride();
    texels = a.tile().texels().data();
    for (int i = 0; i < k; ++i) {
      const dvec2 d = a.direction(i);
      dxx[i] = d.x * d.x;
      dyy[i] = d.y * d.y;
      dxy2[i] = 2.0 * d.x * d.y;
      dx[i] = d.x;
      dy[i] = d.y;
    }
    for (int s = 0; s < scales; ++s) {
      kappa[s] = a.kappa(s);
      tpu[s] = a.texels_per_unit(s);
      off[s][0] = a.offset(s).x;
      off[s][1] = a.offset(s).y;
    }
    for (int s = 0; s < scales; ++s) {
      four_s[s] = std::ldexp(1.0f, 2 * s);
      pow4 = pow4 && kappa[s] == std::ldexp(kappa[0], 2 * s);
    }
    double g = 1.0;
    for (int o = 0; o < octaves; ++o, g *= p.gain) {
      ow[o] = float(a.octave_weight(o));
      gain[o] = float(g);
    }
    norm = float(a.normalization());
    cap = float(a.gamma_cap());
    cut = float(c::kAnisoWeightCutoff * c::kLog2E);
  }
  // Octave passes of phase 2: 1 for fbm (octaves summed into the weights).
  int passes() const { return fbm ? 1 : octaves; }
};

// One block's phase-1 results.
struct block {
  // w[((pass * scales + s) * chunks + h) * kBlock * 4 + sample * 4 + q]:
  // channel 4h + q of the weights of scale s in octave pass `pass`.
  std::vector<float> w;
  // Per scale and sample: the offset of texel (x0, y0) in the tile's float
  // array, and the fractions.
  HWY_ALIGN std::uint32_t offset[kMaxScales][kBlock];
  HWY_ALIGN float fx[kMaxScales][kBlock];
  HWY_ALIGN float fy[kMaxScales][kBlock];
  // active[s][j] != 0: some weight of scale s (any pass) is not 0 for sample j.
  HWY_ALIGN std::uint32_t active[kMaxScales][kBlock];
  bool bad[kBlock];
  // The samples' coordinates in double (x, y).
  HWY_ALIGN double x[kBlock], y[kBlock];
  // Phase 1's double-precision parts, rounded to float: the filter exponents
  // z[(s * kc + i) * kBlock + j], |T^T w_i|^2 in m2[i * kBlock + j], |det T| in det[j].
  std::vector<float> z, m2;
  HWY_ALIGN float det[kBlock];
  explicit block(const config& cf)
      : w(static_cast<std::size_t>(cf.passes() * cf.scales * cf.kc) * kBlock, 0.0f),
        z(static_cast<std::size_t>(cf.scales * cf.kc) * kBlock, 0.0f),
        m2(static_cast<std::size_t>(cf.kc) * kBlock, 0.0f) {}
  float* weights(const config& cf, int pass, int s, int h) {
    return w.data() + index(cf, pass, s, h);
  }
  const float* weights(const config& cf, int pass, int s, int h) const {
    return w.data() + index(cf, pass, s, h);
  }
  static std::size_t index(const config& cf, int pass, int s, int h) {
    return static_cast<std::size_t>((pass * cf.scales + s) * (cf.kc / 4) + h) * kBlock * 4;
  }
};

// The scalar algorithm's lambda for z = kappa_s q: 0 beyond the cutoff.
HWY_INLINE VF lambda1(VF z, VF cut) {
  return hn::IfThenZeroElse(hn::Gt(z, cut), exp2_nonpositive(hn::Neg(z)));
}
HWY_INLINE VF lambda(VF z, VF cut, bool three) {
  const DF df;
  // Beyond the cutoff in every lane, also at the three-point rule's lowest
  // radius (a far scale): 0, as lane by lane.
  if (hn::AllTrue(df, hn::Gt(three ? hn::Mul(z, hn::Set(df, 0.5f)) : z, cut))) return hn::Zero(df);
  if (!three) return lambda1(z, cut);
  const VF lo = lambda1(hn::Mul(z, hn::Set(df, 0.5f)), cut);
  const VF mid = lambda1(z, cut);
  const VF hi = lambda1(hn::Mul(z, hn::Set(df, 2.0f)), cut);
  const VF side = hn::Set(df, float(c::kAnisoThreePointSide));
  return mul_add(side, hi,
                 mul_add(side, lo, hn::Mul(hn::Set(df, float(c::kAnisoThreePointCentre)), mid)));
}

// Stores channel vectors ch[0 ... kc-1] (lanes = samples first ... first +
// lanes - 1) into the block's interleaved weight rows of (pass, s).
HWY_INLINE void store_weights(const config& cf, block& b, int pass, int s, std::size_t first,
                              const VF* ch) {
  const DF df;
  for (int h = 0; h < cf.kc / 4; ++h) {
    const VF* c4 = ch + static_cast<std::size_t>(4 * h);
    hn::StoreInterleaved4(c4[0], c4[1], c4[2], c4[3], df, b.weights(cf, pass, s, h) + first * 4);
  }
}

// Phase 1, weights, for samples [first, first + lanes) of the block; fp and
// map point at the block's first sample (null when not given).
HWY_INLINE void weights_vector(const config& cf, block& b, std::size_t first, const float* fp,
                               const float* map) {
  const DF df;
  const DD dd;
  const DFH dfh;
  const VF zero = hn::Zero(df);
  // The quadratic forms and the determinant in double (anisotropic.hpp: they
  // cancel at grazing angles and for nearly singular maps), rounded to float.
  for (std::size_t h = first; h < first + hn::Lanes(df); h += hn::Lanes(dd)) {
    if (fp) {
      hn::Vec<DFH> a, bb, cc;
      hn::LoadInterleaved3(dfh, fp + h * 3, a, bb, cc);
      const VD sxx = hn::PromoteTo(dd, a), sxy = hn::PromoteTo(dd, bb), syy = hn::PromoteTo(dd, cc);
      for (int i = 0; i < cf.k; ++i) {
        // anisotropic::filter_form: clamped at 0 (S rounded to float may be indefinite).
        const VD q = hn::Max(
            mul_add(syy, hn::Set(dd, cf.dyy[i]),
                    mul_add(sxy, hn::Set(dd, cf.dxy2[i]), hn::Mul(sxx, hn::Set(dd, cf.dxx[i])))),
            hn::Zero(dd));
        for (int s = 0; s < cf.scales; ++s)
          hn::StoreU(hn::DemoteTo(dfh, hn::Mul(hn::Set(dd, cf.kappa[s]), q)), dfh,
                     b.z.data() + static_cast<std::size_t>(s * cf.kc + i) * kBlock + h);
      }
    }
    if (map) {
      hn::Vec<DFH> a00, a01, a10, a11;
      hn::LoadInterleaved4(dfh, map + h * 4, a00, a01, a10, a11);
      VD m00 = hn::PromoteTo(dd, a00), m01 = hn::PromoteTo(dd, a01);
      VD m10 = hn::PromoteTo(dd, a10), m11 = hn::PromoteTo(dd, a11);
      // A map with a non-finite entry counts as the zero map.
      const auto ok = hn::And(hn::And(hn::IsFinite(m00), hn::IsFinite(m01)),
                              hn::And(hn::IsFinite(m10), hn::IsFinite(m11)));
      m00 = hn::IfThenElseZero(ok, m00);
      m01 = hn::IfThenElseZero(ok, m01);
      m10 = hn::IfThenElseZero(ok, m10);
      m11 = hn::IfThenElseZero(ok, m11);
      hn::StoreU(hn::DemoteTo(dfh, hn::Abs(hn::Sub(hn::Mul(m00, m11), hn::Mul(m01, m10)))), dfh,
                 b.det + h);
      for (int i = 0; i < cf.k; ++i) {
        const VD dxv = hn::Set(dd, cf.dx[i]), dyv = hn::Set(dd, cf.dy[i]);
        const VD tu = mul_add(m10, dyv, hn::Mul(m00, dxv));
        const VD tv = mul_add(m11, dyv, hn::Mul(m01, dxv));
        hn::StoreU(hn::DemoteTo(dfh, mul_add(tv, tv, hn::Mul(tu, tu))), dfh,
                   b.m2.data() + static_cast<std::size_t>(i) * kBlock + h);
      }
    }
  }
  VF half_log[kMaxChannels], sd = zero;
  if (map) {
    sd = hn::Sqrt(hn::LoadU(df, b.det + first));
    for (int i = 0; i < cf.k; ++i)
      half_log[i] = hn::Mul(
          hn::Set(df, 0.5f),
          log2_positive(hn::LoadU(df, b.m2.data() + static_cast<std::size_t>(i) * kBlock + first)));
  }
  const VF cut = hn::Set(df, cf.cut), cap = hn::Set(df, cf.cap);
  const bool three_l = cf.filtering == weight_rule::three_point;
  const bool three_c = cf.compensation == weight_rule::three_point;
  const VF side = hn::Set(df, float(c::kAnisoThreePointSide));
  const VF centre = hn::Set(df, float(c::kAnisoThreePointCentre));
  const VF halfv = hn::Set(df, 0.5f);
  const DU du;
  const VU magnitude = hn::Set(du, 0x7fffffffu);
  for (int s = 0; s < cf.scales; ++s) {
    VU any = hn::Zero(du);
    VF lam[kMaxChannels];
    for (int i = 0; i < cf.k; ++i)
      lam[i] =
          fp ? lambda(hn::LoadU(df, b.z.data() + static_cast<std::size_t>(s * cf.kc + i) * kBlock +
                                        first),
                      cut, three_l)
             : hn::Set(df, 1.0f);
    for (int pass = 0; pass < cf.passes(); ++pass) {
      VF ch[kMaxChannels];
      for (int i = 0; i < cf.kc; ++i) ch[i] = zero;
      const int k0 = cf.fbm ? 0 : pass, k1 = cf.fbm ? cf.octaves : pass + 1;
      for (int i = 0; i < cf.k; ++i) {
        if (!map) {
          const int o = s - cf.base;
          if (o >= k0 && o < k1) ch[i] = hn::Mul(hn::Set(df, cf.fbm ? cf.ow[o] : cf.norm), lam[i]);
          continue;
        }
        VF acc = zero;
        for (int o = k0; o < k1; ++o) {
          const VF x = hn::Add(hn::Set(df, float(s - cf.base - o)), half_log[i]);
          const VF prof = three_c ? mul_add(side, band_profile(hn::Add(x, halfv)),
                                            mul_add(side, band_profile(hn::Sub(x, halfv)),
                                                    hn::Mul(centre, band_profile(x))))
                                  : band_profile(x);
          const VF g = hn::Min(
              hn::Mul(hn::Set(df, float(std::ldexp(1.0, s - cf.base - o))), hn::Mul(sd, prof)),
              cap);
          const VF gamma = hn::IfThenElseZero(hn::Gt(prof, zero), g);
          acc = mul_add(hn::Set(df, cf.fbm ? cf.ow[o] : cf.norm), gamma, acc);
        }
        ch[i] = hn::Mul(acc, lam[i]);
      }
      for (int i = 0; i < cf.k; ++i) any = hn::Or(any, hn::And(hn::BitCast(du, ch[i]), magnitude));
      store_weights(cf, b, pass, s, first, ch);
    }
    hn::StoreU(any, du, b.active[s] + first);
  }
}

#if !HWY_HAVE_SCALABLE && HWY_TARGET != HWY_SCALAR
// Phase 1, weights, in the most frequent case (fbm, footprints, no surface
// maps, centre filtering: the bench frame, hush render without --scene): the
// operations of weights_vector in the same order, without its map and
// octave-pass machinery. Lanes = samples; the double quadratic forms of the
// two halves are demoted and joined in registers rather than through b.z.
HWY_INLINE void weights_filter(const config& cf, block& b, std::size_t first, const float* fp) {
  const DF df;
  const DD dd;
  const DFH dfh;
  const DU du;
  const std::size_t half = hn::Lanes(dd);
  static_assert(hn::MaxLanes(DF()) == 2 * hn::MaxLanes(DD()), "two double halves per float vector");
  hn::Vec<DFH> a0, b0, c0, a1, b1, c1;
  hn::LoadInterleaved3(dfh, fp + first * 3, a0, b0, c0);
  hn::LoadInterleaved3(dfh, fp + (first + half) * 3, a1, b1, c1);
  const VD sxx0 = hn::PromoteTo(dd, a0), sxy0 = hn::PromoteTo(dd, b0), syy0 = hn::PromoteTo(dd, c0);
  const VD sxx1 = hn::PromoteTo(dd, a1), sxy1 = hn::PromoteTo(dd, b1), syy1 = hn::PromoteTo(dd, c1);
  VD q0[kMaxChannels], q1[kMaxChannels];
  for (int i = 0; i < cf.k; ++i) {
    const VD dxx = hn::Set(dd, cf.dxx[i]), dxy2 = hn::Set(dd, cf.dxy2[i]),
             dyy = hn::Set(dd, cf.dyy[i]);
    q0[i] = hn::Max(mul_add(syy0, dyy, mul_add(sxy0, dxy2, hn::Mul(sxx0, dxx))), hn::Zero(dd));
    q1[i] = hn::Max(mul_add(syy1, dyy, mul_add(sxy1, dxy2, hn::Mul(sxx1, dxx))), hn::Zero(dd));
  }
  // The filter exponents of scale 0; the others are 4^s times them (config::pow4).
  VF z0[kMaxChannels];
  if (cf.pow4) {
    const VD kappa = hn::Set(dd, cf.kappa[0]);
    for (int i = 0; i < cf.k; ++i)
      z0[i] = hn::Combine(df, hn::DemoteTo(dfh, hn::Mul(kappa, q1[i])),
                          hn::DemoteTo(dfh, hn::Mul(kappa, q0[i])));
  }
  const VF cut = hn::Set(df, cf.cut);
  const VU magnitude = hn::Set(du, 0x7fffffffu);
  for (int s = 0; s < cf.scales; ++s) {
    VF ch[kMaxChannels];
    for (int i = 0; i < cf.kc; ++i) ch[i] = hn::Zero(df);
    VU any = hn::Zero(du);
    const int o = s - cf.base;
    if (o >= 0 && o < cf.octaves) {
      const VD kappa = hn::Set(dd, cf.kappa[s]);
      const VF four_s = hn::Set(df, cf.four_s[s]);
      const VF ow = hn::Set(df, cf.ow[o]);
      for (int i = 0; i < cf.k; ++i) {
        const VF z = cf.pow4 ? hn::Mul(z0[i], four_s)
                             : hn::Combine(df, hn::DemoteTo(dfh, hn::Mul(kappa, q1[i])),
                                           hn::DemoteTo(dfh, hn::Mul(kappa, q0[i])));
        ch[i] = hn::Mul(ow, lambda(z, cut, false));
        any = hn::Or(any, hn::And(hn::BitCast(du, ch[i]), magnitude));
      }
    }
    store_weights(cf, b, 0, s, first, ch);
    hn::StoreU(any, du, b.active[s] + first);
  }
}
#endif

// Phase 1, tile coordinates of scale s for the block's `count` samples (the
// coordinates b.x, b.y, padded to whole vectors): lattice_split<float>(p tpu + off, n).
HWY_INLINE void split_scale(const config& cf, block& b, int s, std::size_t count) {
  const DD dd;
  const DFH dfh;
  const DIH dih;
  const DUH duh;
  const std::size_t lanes = hn::Lanes(dd);
  const VD tpu = hn::Set(dd, cf.tpu[s]);
  const VD limit = hn::Set(dd, 2147483648.0);
  const auto ulp = hn::Set(dfh, detail::one_minus_ulp<float>());
  const auto mask = hn::Set(duh, cf.n - 1u);
  HWY_ALIGN std::uint32_t cells[2][kBlock];
  for (int axis = 0; axis < 2; ++axis) {
    std::uint32_t* cell = cells[axis];
    float* frac = axis == 0 ? b.fx[s] : b.fy[s];
    const double* coord = axis == 0 ? b.x : b.y;
    const VD off = hn::Set(dd, cf.off[s][axis]);
    for (std::size_t j = 0; j < count; j += lanes) {
      VD qv = hn::Mul(hn::Load(dd, coord + j), tpu);
      qv = hn::Add(hn::IfThenElseZero(hn::IsFinite(qv), qv), off);
      const VD fl = hn::Floor(qv);
      if (HWY_LIKELY(hn::AllTrue(dd, hn::Lt(hn::Abs(fl), limit)))) {
        hn::StoreU(hn::Min(hn::DemoteTo(dfh, hn::Sub(qv, fl)), ulp), dfh, frac + j);
        hn::StoreU(hn::And(hn::BitCast(duh, hn::DemoteTo(dih, fl)), mask), duh, cell + j);
      } else {
        HWY_ALIGN double qs[kBlock];
        hn::Store(qv, dd, qs);
        for (std::size_t l = 0; l < lanes; ++l) {
          // NaN positions (bad samples) land here too: cell 0, never read.
          const lattice_coord<float> lc = lattice_split<float>(qs[l], cf.n);
          cell[j + l] = std::isfinite(qs[l]) ? lc.i0 : 0u;
          frac[j + l] = std::isfinite(qs[l]) ? lc.f : 0.0f;
        }
      }
    }
  }
  const DU du;
  const VU stride = hn::Set(du, static_cast<std::uint32_t>(cf.stride));
  const VU kc = hn::Set(du, static_cast<std::uint32_t>(cf.kc));
  for (std::size_t j = 0; j < count; j += hn::Lanes(du))
    hn::StoreU(hn::Add(hn::Mul(hn::LoadU(du, cells[1] + j), stride),
                       hn::Mul(hn::LoadU(du, cells[0] + j), kc)),
               du, b.offset[s] + j);
}

// Phase 2 for one sample: the weighted bilinear lookups of every scale
// (general: any channel count and octave passes, 4-channel chunks). With
// Gradient, also the gradient into g[0], g[1]: the bilinear lookups' slopes
// times the scale's texels per unit, weights held fixed (anisotropic.hpp's
// accumulate, the same operations in the same order).
template <bool Gradient>
HWY_INLINE float lookup_sample(const config& cf, const block& b, std::size_t j, float* g) {
  const D4 d4;
  const std::size_t n4 = hn::Lanes(d4);
  const int passes = cf.passes();
  // Accumulators of octave pass p start at row(p) (size_t: no int products as offsets).
  const auto row = [&](int p) {
    return static_cast<std::size_t>(p) * static_cast<std::size_t>(cf.kc);
  };
  HWY_ALIGN float acc[kMaxScales * kMaxChannels];
  HWY_ALIGN float gx[Gradient ? kMaxScales * kMaxChannels : 1];
  HWY_ALIGN float gy[Gradient ? kMaxScales * kMaxChannels : 1];
  std::fill(acc, acc + row(passes), 0.0f);
  if constexpr (Gradient) {
    std::fill(gx, gx + row(passes), 0.0f);
    std::fill(gy, gy + row(passes), 0.0f);
  }
  for (int s = 0; s < cf.scales; ++s) {
    if (!b.active[s][j]) continue;
    const float* t00 = cf.texels + b.offset[s][j];
    const float* t01 = t00 + cf.stride;
    const V4 fx = hn::Set(d4, b.fx[s][j]), fy = hn::Set(d4, b.fy[s][j]);
    const V4 scale = hn::Set(d4, float(cf.tpu[s]));
    for (int cc = 0; cc < cf.kc; cc += static_cast<int>(n4)) {
      const V4 c00 = hn::LoadU(d4, t00 + cc), c10 = hn::LoadU(d4, t00 + cf.kc + cc);
      const V4 c01 = hn::LoadU(d4, t01 + cc), c11 = hn::LoadU(d4, t01 + cf.kc + cc);
      const V4 d0 = hn::Sub(c01, c00), d1 = hn::Sub(c11, c10);
      const V4 r0 = mul_add(fy, d0, c00);
      const V4 r1 = mul_add(fy, d1, c10);
      const V4 v = mul_add(fx, hn::Sub(r1, r0), r0);
      V4 sx, sy;
      if constexpr (Gradient) {
        sx = hn::Mul(scale, hn::Sub(r1, r0));
        sy = hn::Mul(scale, mul_add(fx, hn::Sub(d1, d0), d0));
      }
      for (int pass = 0; pass < passes; ++pass) {
        const V4 w = hn::LoadU(d4, b.weights(cf, pass, s, cc / 4) + j * 4 + cc % 4);
        const std::size_t at = row(pass) + static_cast<std::size_t>(cc);
        hn::Store(mul_add(w, v, hn::Load(d4, acc + at)), d4, acc + at);
        if constexpr (Gradient) {
          hn::Store(mul_add(w, sx, hn::Load(d4, gx + at)), d4, gx + at);
          hn::Store(mul_add(w, sy, hn::Load(d4, gy + at)), d4, gy + at);
        }
      }
    }
  }
  auto tree = [&](const float* a) {
    const float s4 = (a[0] + a[1]) + (a[2] + a[3]);
    return cf.kc == 4 ? s4 : s4 + ((a[4] + a[5]) + (a[6] + a[7]));
  };
  if (cf.fbm) {
    if constexpr (Gradient) {
      g[0] = tree(gx);
      g[1] = tree(gy);
    }
    return tree(acc);
  }
  float r = 0.0f, rx = 0.0f, ry = 0.0f;
  for (int pass = 0; pass < passes; ++pass) {
    const float v = tree(acc + row(pass));
    r = r + cf.gain[pass] * std::fabs(v);
    if constexpr (Gradient) {
      const float gs = cf.gain[pass] * (v < 0.0f ? -1.0f : 1.0f);
      rx = rx + gs * tree(gx + row(pass));
      ry = ry + gs * tree(gy + row(pass));
    }
  }
  if constexpr (Gradient) {
    g[0] = rx;
    g[1] = ry;
  }
  return r;
}

#if !HWY_HAVE_SCALABLE && HWY_TARGET != HWY_SCALAR && HWY_MAX_BYTES >= 32
// Phase 2 for fbm with KC channels on targets whose vectors hold two texels
// (2 KC floats): each row of the bilinear footprint is one load, blended in
// y across both texels at once, then in x between the halves. Same
// operations as lookup_sample, fewer instructions.
template <int KC>
HWY_INLINE void lookup_block_pairs(const config& cf, const block& b, std::size_t count,
                                   float* out) {
  const hn::FixedTag<float, 2 * KC> dp;
  const hn::FixedTag<float, KC> dk;
  using VK = hn::Vec<decltype(dk)>;
  const int scales = cf.scales;
  const std::size_t stride = cf.stride;
  for (std::size_t j = 0; j < count; ++j) {
    if (b.bad[j]) {
      out[j] = std::numeric_limits<float>::quiet_NaN();
      continue;
    }
    VK acc = hn::Zero(dk);
    for (int s = 0; s < scales; ++s) {
      if (!b.active[s][j]) continue;
      const float* t00 = cf.texels + b.offset[s][j];
      const auto row0 = hn::LoadU(dp, t00), row1 = hn::LoadU(dp, t00 + stride);
      const auto r = mul_add(hn::Set(dp, b.fy[s][j]), hn::Sub(row1, row0), row0);
      const VK r0 = hn::LowerHalf(dk, r), r1 = hn::UpperHalf(dk, r);
      const VK v = mul_add(hn::Set(dk, b.fx[s][j]), hn::Sub(r1, r0), r0);
      const float* w = b.w.data() + (static_cast<std::size_t>(s) * (KC / 4) * kBlock) * 4;
      VK wk;
      if constexpr (KC == 4) {
        wk = hn::LoadU(dk, w + j * 4);
      } else {
        // Channels 0-3 and 4-7 sit in two interleaved rows of the block.
        const hn::FixedTag<float, 4> d4f;
        wk = hn::Combine(dk, hn::LoadU(d4f, w + kBlock * 4 + j * 4), hn::LoadU(d4f, w + j * 4));
      }
      acc = mul_add(wk, v, acc);
    }
    HWY_ALIGN float a[KC];
    hn::Store(acc, dk, a);
    const float s4 = (a[0] + a[1]) + (a[2] + a[3]);
    if constexpr (KC == 4)
      out[j] = s4;
    else
      out[j] = s4 + ((a[4] + a[5]) + (a[6] + a[7]));
  }
}
#endif

#if !HWY_HAVE_SCALABLE && HWY_TARGET != HWY_SCALAR && HWY_MAX_BYTES >= 32
// Phase 2 for fbm with 8 channels where a vector holds one texel (AVX2):
// four loads per scale, the blend on whole texels.
HWY_INLINE void lookup_block_texels8(const config& cf, const block& b, std::size_t count,
                                     float* out) {
  const hn::FixedTag<float, 8> d8;
  const hn::FixedTag<float, 4> d4f;
  using V8 = hn::Vec<decltype(d8)>;
  const std::size_t stride = cf.stride;
  for (std::size_t j = 0; j < count; ++j) {
    if (b.bad[j]) {
      out[j] = std::numeric_limits<float>::quiet_NaN();
      continue;
    }
    V8 acc = hn::Zero(d8);
    for (int s = 0; s < cf.scales; ++s) {
      if (!b.active[s][j]) continue;
      const float* t00 = cf.texels + b.offset[s][j];
      const float* t01 = t00 + stride;
      const V8 fy = hn::Set(d8, b.fy[s][j]);
      const V8 c00 = hn::LoadU(d8, t00), c10 = hn::LoadU(d8, t00 + 8);
      const V8 r0 = mul_add(fy, hn::Sub(hn::LoadU(d8, t01), c00), c00);
      const V8 r1 = mul_add(fy, hn::Sub(hn::LoadU(d8, t01 + 8), c10), c10);
      const V8 v = mul_add(hn::Set(d8, b.fx[s][j]), hn::Sub(r1, r0), r0);
      const float* w = b.w.data() + static_cast<std::size_t>(s) * 2 * kBlock * 4;
      const V8 wk =
          hn::Combine(d8, hn::LoadU(d4f, w + kBlock * 4 + j * 4), hn::LoadU(d4f, w + j * 4));
      acc = mul_add(wk, v, acc);
    }
    HWY_ALIGN float a[8];
    hn::Store(acc, d8, a);
    out[j] = ((a[0] + a[1]) + (a[2] + a[3])) + ((a[4] + a[5]) + (a[6] + a[7]));
  }
}
#endif

// Phase 2 for a block: with gradients (grad: interleaved x, y) per sample;
// values only through the paired fast path where the target allows, else per sample.
HWY_INLINE void lookup_block(const config& cf, const block& b, std::size_t count, float* out,
                             float* grad) {
  if (grad) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (std::size_t j = 0; j < count; ++j) {
      if (b.bad[j]) {
        out[j] = grad[2 * j] = grad[2 * j + 1] = nan;
        continue;
      }
      out[j] = lookup_sample<true>(cf, b, j, grad + 2 * j);
    }
    return;
  }
#if !HWY_HAVE_SCALABLE && HWY_TARGET != HWY_SCALAR && HWY_MAX_BYTES >= 32
  if (cf.fbm && cf.kc == 4) return lookup_block_pairs<4>(cf, b, count, out);
#if HWY_MAX_BYTES >= 64
  if (cf.fbm && cf.kc == 8) return lookup_block_pairs<8>(cf, b, count, out);
#else
  if (cf.fbm && cf.kc == 8) return lookup_block_texels8(cf, b, count, out);
#endif
#endif
  for (std::size_t j = 0; j < count; ++j)
    out[j] = b.bad[j] ? std::numeric_limits<float>::quiet_NaN()
                      : lookup_sample<false>(cf, b, j, nullptr);
}

// Least-squares rules: phase-1 weights of sample j from the scalar code.
inline void scalar_weights(const anisotropic& a, const config& cf, block& b, std::size_t j,
                           const sample_input<2>& in) {
  float w[kMaxScales * kMaxChannels];
  for (int pass = 0; pass < cf.passes(); ++pass) {
    if (cf.fbm)
      a.weights<float>(in, w);
    else
      a.octave_weights<float>(in, pass, w);
    for (int s = 0; s < cf.scales; ++s)
      for (int h = 0; h < cf.kc / 4; ++h)
        std::memcpy(b.weights(cf, pass, s, h) + j * 4,
                    w + static_cast<std::size_t>(s * cf.kc + 4 * h), 4 * sizeof(float));
  }
}

// A block of `count` <= kBlock samples whose coordinates are in b.x, b.y
// (padded to whole vectors), with footprints fp and maps (null: not given) at
// the block's first sample; gradients into grad (interleaved x, y) unless null.
inline void run_block(const anisotropic& a, const config& cf, block& b, std::size_t count,
                      const float* fp, const float* map, float* out, float* grad) {
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  const std::size_t padded = (count + lanes - 1) / lanes * lanes;
  // Pad the block's inputs to whole vectors (copies of the last sample).
  HWY_ALIGN float fpb[kBlock * 3], mapb[kBlock * 4];
  if (padded > count) {
    if (fp) {
      for (std::size_t j = 0; j < padded; ++j)
        std::memcpy(fpb + 3 * j, fp + 3 * std::min(j, count - 1), 3 * sizeof(float));
      fp = fpb;
    }
    if (map) {
      for (std::size_t j = 0; j < padded; ++j)
        std::memcpy(mapb + 4 * j, map + 4 * std::min(j, count - 1), 4 * sizeof(float));
      map = mapb;
    }
  }
  for (std::size_t j = count; j < padded; ++j) {
    b.x[j] = b.x[count - 1];
    b.y[j] = b.y[count - 1];
  }
  for (std::size_t j = 0; j < count; ++j)
    b.bad[j] = !(std::isfinite(b.x[j]) && std::isfinite(b.y[j]));
  if (!cf.lsq) {
#if !HWY_HAVE_SCALABLE && HWY_TARGET != HWY_SCALAR
    if (cf.fbm && fp && !map && cf.filtering == weight_rule::centre) {
      for (std::size_t j = 0; j < padded; j += lanes) weights_filter(cf, b, j, fp);
    } else
#endif
      for (std::size_t j = 0; j < padded; j += lanes) weights_vector(cf, b, j, fp, map);
  } else {
    for (std::size_t j = 0; j < count; ++j) {
      sample_input<2> in;
      in.position = {b.x[j], b.y[j]};
      if (fp) {
        const float u[3] = {fp[3 * j], fp[3 * j + 1], fp[3 * j + 2]};
        in.fp = footprint<2>::from_covariance(u);
      }
      if (map) {
        in.map = {map[4 * j], map[4 * j + 1], map[4 * j + 2], map[4 * j + 3]};
        in.has_map = true;
      }
      scalar_weights(a, cf, b, j, in);
      for (int s = 0; s < cf.scales; ++s) b.active[s][j] = 1;
    }
  }
  // Tile coordinates only for scales some sample reads (far from the
  // camera, the pixel filter zeroes the fine scales of whole blocks).
  for (int s = 0; s < cf.scales; ++s)
    if (std::any_of(b.active[s], b.active[s] + count, [](std::uint32_t v) { return v != 0; }))
      split_scale(cf, b, s, padded);
  lookup_block(cf, b, count, out, grad);
}

}  // namespace aniso_simd

// Anisotropic noise at n samples: positions xy (interleaved), footprints fp
// (3 floats each: the stored upper triangle; null = points) and surface
// maps (4 floats each; null = none); values into `value`, gradients
// (interleaved x, y, weights held fixed as in anisotropic.hpp) into grad
// unless null.
inline void anisotropic_samples(const anisotropic& a, const float* xy, const float* fp,
                                const float* map, std::size_t n, float* value, float* grad) {
  using namespace aniso_simd;
  const config cf(a);
  block b(cf);
  for (std::size_t first = 0; first < n; first += kBlock) {
    const std::size_t count = std::min(kBlock, n - first);
    const float* p = xy + 2 * first;
    for (std::size_t j = 0; j < count; ++j) {
      b.x[j] = double(p[2 * j]);
      b.y[j] = double(p[2 * j + 1]);
    }
    run_block(a, cf, b, count, fp ? fp + 3 * first : nullptr, map ? map + 4 * first : nullptr,
              value + first, grad ? grad + 2 * first : nullptr);
  }
}

// Anisotropic noise on a uniform 2D grid (C order, i fastest); positions
// g.coordinate() per axis in double, as the scalar grid path forms them;
// gradients (interleaved x, y) into grad unless null.
inline void anisotropic_grid(const anisotropic& a, const grid<2>& g, float* value, float* grad) {
  using namespace aniso_simd;
  const config cf(a);
  block b(cf);
  const std::size_t nx = g.size[0], ny = g.size[1];
  for (std::size_t j = 0; j < ny; ++j) {
    const double y = g.coordinate(1, j);
    for (std::size_t first = 0; first < nx; first += kBlock) {
      const std::size_t count = std::min(kBlock, nx - first);
      for (std::size_t i = 0; i < count; ++i) {
        b.x[i] = g.coordinate(0, first + i);
        b.y[i] = y;
      }
      run_block(a, cf, b, count, nullptr, nullptr, value + j * nx + first,
                grad ? grad + 2 * (j * nx + first) : nullptr);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_ANISOTROPIC_SIMD_INL_H_ toggle
