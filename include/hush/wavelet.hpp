// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Wavelet noise (Robert L. Cook and Tony DeRose, "Wavelet Noise", SIGGRAPH 2005),
// 2D and 3D: band-limited noise from a tile of quadratic B-spline coefficients
// with the coarser half of its spectrum projected out (wavelet/tile.hpp), summed
// over octave bands, anti-aliased by the sample's footprint, and, in 3D,
// projectable onto a surface so that the band limit survives texturing a
// surface with a 3D noise.
//
//   hush::wavelet<2>::params prm;            // one band, 128^2 tile, seed 0
//   prm.weights = {1, 0.5, 0.25};            // bands 0, 1, 2 (frequencies 1, 2, 4)
//   hush::wavelet<2> w{prm};
//   float v = w(hush::vec2{x, y});                               // all bands
//   float a = w.sample(hush::vec2{x, y}, hush::footprint<2>::from_derivatives(dpdx, dpdy));
//   hush::wavelet<3> s{7};
//   float b = s.sample(hush::vec3{x, y, z}, normal, fp);         // projected onto the surface
//
// Definitions (paper symbols in brackets). A band is
//   N(y) = sum_i n_i B(y - i)                    [eq. 27, 29]
// over the tile's coefficients n_i (periodic, period n = tile_size) with the
// centred quadratic B-spline B; it holds frequencies between 1/4 and 1/2 cycle
// per coefficient. Band b of the noise is N at y = 2^b x + o_b (frequency 2^b,
// decorrelating offset o_b), so band 0 has one coefficient per unit, like
// Perlin noise has one lattice cell per unit. The noise is
//   M(x) = K sum_b w_b N(2^b x + o_b)            [eq. 1]
// with K = 1 / sqrt(sigma_N^2 sum_b w_b^2)      [eq. 39]
// so that M has variance 1 (sigma_N^2 is computed by hush from its own tile:
// wavelet_tile<D>::variance()), followed by the distribution remapping
// (sec. 4.2): a Gaussian scale, erf to the uniform distribution on (-1, 1), or
// a user table of the inverse CDF.
//
// Footprints (n.sample(p, footprint); core/footprint.hpp; paper sec. 3.1, 3.5):
// with w the footprint's largest width (noise units per pixel), band b's
// coefficients are c = 2^b w pixels apart. The band is fully representable for
// c <= 1 (its highest frequency, 2^(b-1), is at most the Nyquist frequency
// 1 / (2w)), and entirely above Nyquist for c >= 2 (the paper's j >= 0, which the
// renderer's B-spline pixel filter removes exactly, eq. 6). hush keeps the band
// with weight s(1 - log2 c) (s = the quintic fade of constants.hpp, clamped to
// [0, 1]): 1 below c = 1, 0 from c = 2 on, C2 in between, so a continuous zoom
// never pops and bands with weight 0 cost nothing. K is not renormalised: the
// filtered noise has less variance, as the pixel's average of the noise has.
// Why the largest width: a band is kept only where it is representable along
// every direction of the pixel, which excludes aliasing; along the footprint's
// short axis this loses detail (anisotropic filtering would need anisotropic
// noise, hush::anisotropic). A NaN, infinite or wider-than-2^32 footprint
// ("everything", core/footprint.hpp) gives the mean, 0, in every mode.
//
// Basis widening (params::widen, paper sec. 4.1): for renderers that take one
// sample per pixel, each kept band is interpolated with B widened along tile
// axis a by s_a = sqrt(1 + max(0, c_a^2 - c0^2)) (c_a the pixel's extent along
// axis a in band coefficients, c0 = 1/2), so that the basis' variance grows
// like that of B convolved with the Gaussian pixel filter (sigma = 1/2 pixel,
// kPixelFilterSigma) from the paper's j = -2 on. The widened weights are
// normalised to sum to 1. With a surface normal, the footprint is first
// projected onto the tangent plane.
//
// Infinite noise (params::relative_weights, paper sec. 5.4): weights[k] is the
// weight of the band k octaves below the finest representable one, i.e. band b
// gets W(o) with o = -(b + log2 w), linearly... (quintic) interpolated between
// integer o, faded in over o in [-1, 0] (the anti-aliasing fade above) and out
// over o in [K - 1, K], and the sum is normalised per sample by
// 1 / sqrt(sigma^2 sum W^2): zooming never changes the look, low octaves fade out
// as fine ones fade in. Bands b run over [first_band, first_band + relative_bands).
// Point evaluation (no footprint) uses w = 1.
//
// Projection (3D, n.sample(p, normal, fp); paper sec. 3.7, 4.1, eq. 32-36): the
// band is averaged along the unit normal u with the B-spline at half its
// resolution, B2(t) = B(t / 2) / 2:
//   N_u(y) = integral N(y + t u) B2(t) dt.
// For an axis-aligned u this is sum_i n_i B(.)B(.) beta(.) with the exact
// quintic beta = B * B2 along the normal (9 coefficients wide, eq. 36).
// projection::exact evaluates N_u exactly for any u: separably with beta when u
// is axis-aligned, otherwise by splitting the line integral where its
// polynomial pieces change and integrating each piece with 5-point
// Gauss-Legendre quadrature (exact: degree <= 8; with basis widening, over B2's
// three pieces only, docs/wavelet.md). projection::approximate is
// the paper's: B2 in place of beta along the normal (6 coefficients wide), and
// for any u the tensor B-spline at the coefficient moved halfway towards the
// position along u (Appendix 2), normalised to weights summing to 1. The
// approximation's error against the exact projection is measured in
// docs/wavelet.md. The normal may have any length (it is normalised); a zero,
// NaN or infinite normal gives the unprojected 3D noise (a point not on a
// surface). The projected noise is normalised by its own variance
// (tile.projected_variance along axis a; for other u, sum_a u_a^2 sigma_a^2, times
// detail::wavelet_oblique_variance_ratio(u) for the exact projection: the basis' own
// variance along u, up to 4 % below the axes').
//
// No repetition (params::variant_overlap > 0, paper sec. 4.3): the tile is laid
// out in cells of variants with blended overlaps (wavelet_blend_tile); the
// noise then does not repeat (cells are hashed over 2^32 coefficients per
// axis, where the global coefficient index wraps).
//
// Contract (D = 2, 3; float and double from one template):
//  - mean 0; variance 1 over space for the point noise (exactly over a whole
//    tile period with one band; the tests measure it within +-3 %), less where a
//    footprint filters bands out; then the distribution's (gaussian_scale^2, 1/3
//    for uniform).
//  - range: |M| <= bound() (analytic: K sum|w_b| max_i |n_i|, every kernel being
//    an average of coefficients); uniform: (-1, 1); table: its range.
//  - C1 in position (the quadratic B-spline); gradient() and sample_gradient()
//    return the exact derivative of what is evaluated (footprint held fixed).
//  - periodic with period tile_size / 2^first_band along every axis when every
//    band's offset is a multiple of... (offsets are exact multiples of 2^-24, so
//    M(x + n / 2^b0) == M(x) wherever the band positions are exact in double,
//    |2^b x| < 2^28), unless variant_overlap > 0.
//  - float evaluation is within float_budget() of the double reference.
//  - domain: every finite coordinate; a band coordinate 2^b x that overflows a
//    double is taken as 0 (like hush::fractal). NaN or +-Inf in a coordinate
//    gives NaN (value and gradient). Evaluation never throws.
#ifndef HUSH_WAVELET_HPP
#define HUSH_WAVELET_HPP

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "hush/config.hpp"
#include "hush/core/bspline.hpp"
#include "hush/core/error.hpp"
#include "hush/core/footprint.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/lattice.hpp"
#include "hush/core/samples.hpp"
#include "hush/core/vec.hpp"
#include "hush/detail/constants.hpp"
#include "hush/perlin.hpp"  // detail::fade, the quintic fade shared by every noise
#include "hush/wavelet/tile.hpp"

namespace hush {

// How 3D wavelet noise is projected onto a surface (see wavelet.hpp).
enum class wavelet_projection { exact, approximate };
// The output distribution (paper sec. 4.2).
enum class wavelet_distribution { gaussian, uniform, table };

namespace detail {

// One band's kernel along one axis: taps at cells i0 + first ... i0 + first + count - 1.
template <class T>
struct wavelet_axis {
  int first = 0;
  int count = 0;
  T w[kWaveletMaxTaps] = {};
  T dw[kWaveletMaxTaps] = {};  // d w / d y (y the position in coefficient units)
};

// The plain quadratic B-spline: taps 0, 1, 2 (core/bspline.hpp).
template <class T, bool G>
HUSH_INLINE void wavelet_axis_plain(T f, wavelet_axis<T>& ax) {
  ax.first = 0;
  ax.count = 3;
  for (int j = 0; j < 3; ++j) ax.w[j] = piece_value(kBspline, 2 - j, f);
  if constexpr (G)
    for (int j = 0; j < 3; ++j) ax.dw[j] = piece_value(kBsplineDerivative, 2 - j, f);
}

// A fixed kernel k of support P (beta or B2, along the normal) at fraction f: tap
// j sits at distance f + 1/2 - j; taps j = floor(1/2 - P/2) + 1 ... ceil(3/2 + P/2) - 1
// cover every f in [0, 1) (some are 0).
template <class T, bool G, int P, int O>
HUSH_INLINE void wavelet_axis_fixed(T f, const piecewise_kernel<P, O>& k,
                                    const piecewise_kernel<P, O - 1>& dk, wavelet_axis<T>& ax) {
  constexpr int kFirst = fixed_kernel_first_tap<P>();
  static_assert(fixed_kernel_taps<P>() <= kWaveletMaxTaps, "taps fit");
  ax.first = kFirst;
  ax.count = fixed_kernel_taps<P>();
  for (int j = 0; j < ax.count; ++j) {
    const T d = f + T(constants::kWaveletCellOffset) - T(kFirst + j);
    ax.w[j] = kernel_at(k, d);
    if constexpr (G) ax.dw[j] = kernel_at(dk, d);
  }
}

// The quadratic B-spline widened by s >= 1 (B(d / s), weights normalised to sum
// 1) at relative position y (coefficient k sits at k): taps k in (y - 3s/2, y + 3s/2).
template <class T, bool G>
HUSH_INLINE void wavelet_axis_widened(T y, T s, wavelet_axis<T>& ax) {
  const T half = T(kBspline.half_support()) * s;
  ax.first = static_cast<int>(std::floor(y - half)) + 1;
  ax.count = std::min(static_cast<int>(std::ceil(y + half)) - ax.first, kWaveletMaxTaps);
  const T inv = T(1) / s;
  T sum = 0, dsum = 0;
  for (int j = 0; j < ax.count; ++j) {
    const T u = (y - T(ax.first + j)) * inv;
    ax.w[j] = kernel_at(kBspline, u);
    sum += ax.w[j];
    if constexpr (G) {
      ax.dw[j] = kernel_at(kBsplineDerivative, u) * inv;
      dsum += ax.dw[j];
    }
  }
  const T norm = T(1) / sum;
  for (int j = 0; j < ax.count; ++j) {
    if constexpr (G) ax.dw[j] = (ax.dw[j] - ax.w[j] * norm * dsum) * norm;
    ax.w[j] *= norm;
  }
}

// The plain B-spline at relative position y (any real): taps floor(y - 1/2) ... + 2.
template <class T, bool G>
HUSH_INLINE void wavelet_axis_at(T y, wavelet_axis<T>& ax) {
  const T c = std::floor(y - T(constants::kWaveletCellOffset));
  wavelet_axis_plain<T, G>(y - T(constants::kWaveletCellOffset) - c, ax);
  ax.first = static_cast<int>(c);
}

// Coefficients of the periodic tile around cell i0 (relative offsets k).
template <int D>
struct wavelet_periodic_access {
  const float* c;  // wavelet_tile::coefficients()
  int n, m;        // tile size and row length (wavelet_tile::row_length())
  std::uint32_t i0[3];
  HUSH_INLINE int wrap(long long x) const {
    long long r = x % n;
    return static_cast<int>(r < 0 ? r + n : r);
  }
  HUSH_INLINE std::size_t index(int a, int k) const {
    const std::size_t stride =
        a == 0 ? 1 : static_cast<std::size_t>(m) * (a == 2 ? static_cast<std::size_t>(n) : 1);
    return static_cast<std::size_t>(wrap(static_cast<long long>(i0[a]) + k)) * stride;
  }
  HUSH_INLINE float at(const int (&k)[std::size_t{D}]) const {
    std::size_t i = 0;
    for (int a = 0; a < D; ++a) i += index(a, k[a]);
    return c[i];
  }
};

// Coefficients of the hashed tile variants (wavelet_blend_tile): the sum over the
// (at most 2^D) overlapping cells that cover a global coefficient index. The
// global index of tap 0 is the band cell modulo 2^32 (period 0); cell T and
// offset l of i0 + k follow from i0 = T0 L + r0 with 32-bit unsigned arithmetic
// (T = T0 + carry, the carry from r0 + k), as the GPU computes them.
template <int D>
struct wavelet_variant_access {
  const float* c;
  int n, cell;  // tile size and cell pitch L = n - overlap
  std::uint32_t key;
  std::uint32_t i0[3];
  HUSH_INLINE float at(const int (&k)[std::size_t{D}]) const {
    std::uint32_t t[3][2] = {};
    int l[3][2] = {}, count[3] = {};
    const auto pitch = static_cast<std::uint32_t>(cell);
    for (int a = 0; a < D; ++a) {
      int r = static_cast<int>(i0[a] % pitch) + k[a];  // |k| < L: at most one carry
      const int carry = r < 0 ? -1 : (r >= cell ? 1 : 0);
      r -= carry * cell;
      t[a][0] = i0[a] / pitch + static_cast<std::uint32_t>(carry);
      l[a][0] = r;
      t[a][1] = t[a][0] - 1u;  // the previous cell covers r + L when that is inside it
      l[a][1] = r + cell;
      count[a] = r + cell < n ? 2 : 1;
    }
    float sum = 0;
    for (int m = 0; m < (1 << D); ++m) {
      int pick[3] = {0, 0, 0};
      bool ok = true;
      for (int a = 0; a < D; ++a) {
        pick[a] = (m >> a) & 1;
        ok = ok && pick[a] < count[a];
      }
      if (!ok) continue;
      std::uint32_t h;
      if constexpr (D == 2)
        h = lattice_hash(key, t[0][pick[0]], t[1][pick[1]]);
      else
        h = lattice_hash(key, t[0][pick[0]], t[1][pick[1]], t[2][pick[2]]);
      int local[3] = {0, 0, 0};
      for (int a = 0; a < D; ++a) local[a] = l[a][pick[a]];
      sum += c[variant_index(h, local)];
    }
    return sum;
  }
  // Storage index of local coordinates (world axes) under variant h: the permutation
  // of lexicographic rank p = ((h >> s) D!) >> s (storage axis a reads world axis
  // src[a]), then storage axis a reflected (n - 1 - l) when bit a of h is set.
  HUSH_INLINE std::size_t variant_index(std::uint32_t h, const int (&local)[3]) const {
    constexpr unsigned kShift = constants::kWaveletVariantShift;
    const std::uint32_t p = ((h >> kShift) * wavelet_permutations(D)) >> kShift;
    int src[3] = {0, 1, 2};
    if constexpr (D == 2) {
      src[0] = static_cast<int>(p);
      src[1] = 1 - src[0];
    } else {
      const int first = static_cast<int>(p / 2), lo = first == 0 ? 1 : 0, hi = first == 2 ? 1 : 2;
      src[0] = first;
      src[1] = (p & 1u) != 0 ? hi : lo;
      src[2] = (p & 1u) != 0 ? lo : hi;
    }
    std::size_t idx = 0, stride = 1;
    for (int a = 0; a < D; ++a, stride *= static_cast<std::size_t>(n)) {
      int v = local[src[a]];
      if ((h >> a) & 1u) v = n - 1 - v;
      idx += static_cast<std::size_t>(v) * stride;
    }
    return idx;
  }
};

// Sum over separable taps: the value and the gradient in coefficient units, z
// innermost (value = sum_a wx (sum_b wy (sum_c wz n))), the order every backend uses.
// (N, the array's extent, equals D: a std::size_t parameter, deduced, so the bound needs no
// conversion and the periodic overload below stays the more specialised one.)
template <class T, bool G, int D, class Access, std::size_t N>
HUSH_INLINE value_gradient<T, D> wavelet_separable(const wavelet_axis<T> (&ax)[N],
                                                   const Access& acc) {
  static_assert(N == D, "one axis per dimension");
  value_gradient<T, D> r{T(0), {}};
  int k[std::size_t{D}];
  if constexpr (D == 2) {
    for (int a = 0; a < ax[0].count; ++a) {
      k[0] = ax[0].first + a;
      T s = 0, sy = 0;
      for (int b = 0; b < ax[1].count; ++b) {
        k[1] = ax[1].first + b;
        const T c = T(acc.at(k));
        s += ax[1].w[b] * c;
        if constexpr (G) sy += ax[1].dw[b] * c;
      }
      r.value += ax[0].w[a] * s;
      if constexpr (G) {
        r.gradient[0] += ax[0].dw[a] * s;
        r.gradient[1] += ax[0].w[a] * sy;
      }
    }
  } else {
    for (int a = 0; a < ax[0].count; ++a) {
      k[0] = ax[0].first + a;
      T t = 0, ty = 0, tz = 0;
      for (int b = 0; b < ax[1].count; ++b) {
        k[1] = ax[1].first + b;
        T s = 0, sz = 0;
        for (int c = 0; c < ax[2].count; ++c) {
          k[2] = ax[2].first + c;
          const T v = T(acc.at(k));
          s += ax[2].w[c] * v;
          if constexpr (G) sz += ax[2].dw[c] * v;
        }
        t += ax[1].w[b] * s;
        if constexpr (G) {
          ty += ax[1].dw[b] * s;
          tz += ax[1].w[b] * sz;
        }
      }
      r.value += ax[0].w[a] * t;
      if constexpr (G) {
        r.gradient[0] += ax[0].dw[a] * t;
        r.gradient[1] += ax[0].w[a] * ty;
        r.gradient[2] += ax[0].w[a] * tz;
      }
    }
  }
  return r;
}

// The same over the periodic tile, with the wrapped, stride-scaled index of
// every tap precomputed per axis (the sums are the generic ones, operation by operation).
template <class T, bool G, int D, std::size_t N>
HUSH_INLINE value_gradient<T, D> wavelet_separable(const wavelet_axis<T> (&ax)[N],
                                                   const wavelet_periodic_access<D>& acc) {
  static_assert(N == D, "one axis per dimension");
  std::size_t off[std::size_t{D}][kWaveletMaxTaps];
  for (int a = 0; a < D; ++a)
    for (int j = 0; j < ax[a].count; ++j) off[a][j] = acc.index(a, ax[a].first + j);
  struct table_access {
    const float* c;
    const std::size_t (*off)[kWaveletMaxTaps];
    const wavelet_axis<T>* ax;
    HUSH_INLINE float at(const int (&k)[std::size_t{D}]) const {
      std::size_t i = 0;
      for (int a = 0; a < D; ++a) i += off[a][k[a] - ax[a].first];
      return c[i];
    }
  };
  return wavelet_separable<T, G, D>(ax, table_access{acc.c, off, ax});
}

// The paper's approximate projection along a normal that is not axis-aligned
// (Appendix 2, WProjectedNoise): the tensor B-spline at the offset d = y - k moved
// halfway along the unit normal u, e_a = (d_a - u_a (u . d) / 2) / s_a (s_a the
// widening), with weights normalised to sum 1. y: position relative to the
// cell (coefficient offset k sits at k). Coefficients are visited per column
// along the normal's dominant axis, over the interval where all three factors
// are non-zero (a few extra zero-weight taps at the ends are harmless).
template <class T, bool G, class Access>
value_gradient<T, 3> wavelet_general_approx(const T (&y)[3], const T (&u)[3], const T (&s)[3],
                                            const Access& acc) {
  int w = 0;
  for (int a = 1; a < 3; ++a)
    if (std::fabs(u[a]) > std::fabs(u[w])) w = a;
  const int ax_u = w == 0 ? 1 : 0, ax_v = w == 2 ? 1 : 2;
  const T half = T(kBspline.half_support());
  T l1 = 0;
  for (int a = 0; a < 3; ++a) l1 += std::fabs(u[a]) * s[a];
  T reach[3];
  for (int a = 0; a < 3; ++a) reach[a] = half * (s[a] + std::fabs(u[a]) * l1);
  const T stretch = T(1) / T(constants::kWaveletProjectionStretch);
  T sw = 0, sv = 0, sdw[3] = {0, 0, 0}, sg[3] = {0, 0, 0};
  const int u_lo = static_cast<int>(std::ceil(y[ax_u] - reach[ax_u]));
  const int u_hi = static_cast<int>(std::floor(y[ax_u] + reach[ax_u]));
  const int v_lo = static_cast<int>(std::ceil(y[ax_v] - reach[ax_v]));
  const int v_hi = static_cast<int>(std::floor(y[ax_v] + reach[ax_v]));
  int k[3];
  T d[3];
  for (int ku = u_lo; ku <= u_hi; ++ku) {
    k[ax_u] = ku;
    d[ax_u] = y[ax_u] - T(ku);
    for (int kv = v_lo; kv <= v_hi; ++kv) {
      k[ax_v] = kv;
      d[ax_v] = y[ax_v] - T(kv);
      // e_a = A_a + C_a d_w with d_u, d_v fixed; |e_a| < half.
      const T p = u[ax_u] * d[ax_u] + u[ax_v] * d[ax_v];
      T lo = -std::numeric_limits<T>::infinity(), hi = std::numeric_limits<T>::infinity();
      bool empty = false;
      for (int a = 0; a < 3; ++a) {
        const T A = ((a == w ? T(0) : d[a]) - u[a] * p * stretch) / s[a];
        const T C = ((a == w ? T(1) : T(0)) - u[a] * u[w] * stretch) / s[a];
        if (C == T(0)) {
          empty = empty || !(std::fabs(A) < half);
          continue;
        }
        T e0 = (-half - A) / C, e1 = (half - A) / C;
        if (e0 > e1) std::swap(e0, e1);
        lo = std::max(lo, e0);
        hi = std::min(hi, e1);
      }
      if (empty || !(lo < hi)) continue;
      const int w_lo = static_cast<int>(std::floor(y[w] - hi));
      const int w_hi = static_cast<int>(std::ceil(y[w] - lo));
      for (int kw = w_lo; kw <= w_hi; ++kw) {
        k[w] = kw;
        d[w] = y[w] - T(kw);
        const T ud = u[0] * d[0] + u[1] * d[1] + u[2] * d[2];
        T e[3], b[3];
        for (int a = 0; a < 3; ++a) {
          e[a] = (d[a] - u[a] * ud * stretch) / s[a];
          b[a] = kernel_at(kBspline, e[a]);
        }
        const T weight = b[0] * b[1] * b[2];
        if (weight == T(0)) continue;
        const T c = T(acc.at(k));
        sw += weight;
        sv += weight * c;
        if constexpr (G) {
          T q[3];
          for (int a = 0; a < 3; ++a)
            q[a] = kernel_at(kBsplineDerivative, e[a]) * b[(a + 1) % 3] * b[(a + 2) % 3] / s[a];
          const T uq = u[0] * q[0] + u[1] * q[1] + u[2] * q[2];
          for (int a = 0; a < 3; ++a) {
            const T gw = q[a] - u[a] * uq * stretch;  // d weight / d y_a
            sdw[a] += gw;
            sg[a] += gw * c;
          }
        }
      }
    }
  }
  value_gradient<T, 3> r{T(0), {}};
  if (!(sw > T(0))) return r;
  const T inv = T(1) / sw;
  r.value = sv * inv;
  if constexpr (G)
    for (int a = 0; a < 3; ++a) r.gradient[a] = (sg[a] - r.value * sdw[a]) * inv;
  return r;
}

// The knots of the exact projection's line integral (below), sorted, into
// knots[0, return value): B2's knots and the crossings of N's knot planes. Shared
// by the scalar and SIMD kernels (wavelet/simd-inl.h computes them per lane).
template <class T>
int wavelet_exact_knots(const T (&y)[3], const T (&u)[3], const T (&s)[3],
                        T (&knots)[constants::kWaveletMaxKnots]) {
  constexpr int kMaxKnots = constants::kWaveletMaxKnots;
  const T reach = T(kBspline2.half_support());
  int nk = 0;
  for (int j = 0; j <= kBspline2.pieces;
       j += static_cast<int>(constants::kWaveletProjectionStretch))
    knots[nk++] = T(j) - reach;  // B2's knots: -3, -1, 1, 3
  const T half = T(kBspline.half_support());
  const bool plain = s[0] == T(1) && s[1] == T(1) && s[2] == T(1);
  for (int a = 0; a < 3; ++a) {
    // Widened, only B2's pieces (5 nodes each): the widened basis' own knots would
    // need 4 families per axis and up to 7^3 taps per node (the GPU's loop budget,
    // hush/glsl/wavelet_glsl.hpp); widening is an approximation of the pixel filter.
    if (u[a] == T(0) || !plain) continue;
    const T span = reach * std::fabs(u[a]);
    // Knot offsets of the widened B-spline about its centre, as fractions of a coefficient.
    T deltas[4];
    int nd = 0;
    for (int m = 0; m < 4; ++m) {
      const T delta = (T(m) - half) * s[a];  // -3/2, -1/2, 1/2, 3/2 times s
      const T frac = delta - std::floor(delta);
      bool seen = false;
      for (int q = 0; q < nd; ++q) seen = seen || deltas[q] == frac;
      if (!seen) deltas[nd++] = frac;
    }
    for (int q = 0; q < nd; ++q) {
      const int lo = static_cast<int>(std::ceil(y[a] - span - deltas[q]));
      const int hi = static_cast<int>(std::floor(y[a] + span - deltas[q]));
      for (int k = lo; k <= hi && nk < kMaxKnots; ++k) {
        const T t = (T(k) + deltas[q] - y[a]) / u[a];
        if (t > -reach && t < reach) knots[nk++] = t;
      }
    }
  }
  std::sort(knots, knots + nk);
  return nk;
}

// The exact projection along any unit normal u: integral N(y + t u) B2(t) dt over
// t in [-3, 3]. The integrand is one polynomial between consecutive knots: those
// of B2 (t = -3, -1, 1, 3) and the crossings of the knot planes of N along each
// axis (y_a + t u_a = k + 1/2, k an integer); each piece gets 5-point
// Gauss-Legendre quadrature, exact for its degree (<= 8). With a widened basis
// N_s (s != 1) the line integral is taken over B2's three pieces only (15 nodes,
// not exact: widening itself approximates the pixel filter); the widened knot
// families would cost up to 7^3 taps at each of ~250 nodes.
template <class T, bool G, class Access>
value_gradient<T, 3> wavelet_general_exact(const T (&y)[3], const T (&u)[3], const T (&s)[3],
                                           const Access& acc) {
  T knots[constants::kWaveletMaxKnots];
  const int nk = wavelet_exact_knots<T>(y, u, s, knots);
  const bool plain = s[0] == T(1) && s[1] == T(1) && s[2] == T(1);
  value_gradient<T, 3> r{T(0), {}};
  for (int i = 0; i + 1 < nk; ++i) {
    const T t0 = knots[i], t1 = knots[i + 1];
    if (!(t1 > t0)) continue;
    const T mid = (t0 + t1) / T(2), h = (t1 - t0) / T(2);
    for (int q = 0; q < constants::kGaussLegendreOrder; ++q) {
      const T t = mid + h * T(constants::kGaussLegendreNode[q]);
      const T wq = h * T(constants::kGaussLegendreWeight[q]) * kernel_at(kBspline2, t);
      wavelet_axis<T> ax[3];
      for (int a = 0; a < 3; ++a) {
        const T ya = y[a] + t * u[a];
        if (plain)
          wavelet_axis_at<T, G>(ya, ax[a]);
        else
          wavelet_axis_widened<T, G>(ya, s[a], ax[a]);
      }
      const value_gradient<T, 3> n = wavelet_separable<T, G, 3>(ax, acc);
      r.value += wq * n.value;
      if constexpr (G)
        for (int a = 0; a < 3; ++a) r.gradient[a] += wq * n.gradient[a];
    }
  }
  return r;
}

// The exact projection's variance along a unit normal u relative to its variance along a
// tile axis, g(u) = sigma_u^2 / sigma_axis^2 (expected over seeds). The line integral
// N_u = integral N(y + t u) B2(t) dt has, averaged over y, the variance
//   sigma_u^2 = integral Q(r) C(r u) dr,   Q = B2 * B2 (B2's autocorrelation, [-6, 6]),
// C(x) = sum_L R(L) P(x - L) the noise's autocovariance (R the coefficients' covariance at
// lag L, P the tensor quintic B * B). The coefficients are (I - Qx Qy Qz) r plus the
// even/odd copy (wavelet/tile.hpp), so the expected R is a sum of four tensor products of 1D
// lag sequences and sigma_u^2 a 1D integral of products of 1D splines. g is 1 along an axis
// and falls to 0.964 at (1, 1, 0), 0.959 at (1, 1, 1) and 0.967 at (1, 2, 3): the cubic
// lattice is not isotropic, so interpolating the axes' variances (sum u_a^2 sigma_a^2)
// overstates an oblique normal's by up to 4 %. With the cubic invariants
// s2 = ux^2 uy^2 + uy^2 uz^2 + uz^2 ux^2 and s3 = ux^2 uy^2 uz^2,
//   g(u) = 1 + c2 s2 + c3 s3,
// c2, c3 the least-squares fit of the integral (64^3 tiles; the same within 1e-6 from 16^3
// on) over 150 random normals; the fit is within 7e-4 of the integral at 150 others. The
// per-seed scatter of a 64^3 tile's variance is about 0.6 %.
constexpr double kWaveletObliqueS2 = -0.14070926;
constexpr double kWaveletObliqueS3 = 0.15736712;
template <class T>
T wavelet_oblique_variance_ratio(const T (&u)[3]) {
  const T x = u[0] * u[0], y = u[1] * u[1], z = u[2] * u[2];
  return T(1) + T(kWaveletObliqueS2) * (x * y + y * z + z * x) + T(kWaveletObliqueS3) * (x * y * z);
}

}  // namespace detail

template <int D>
class wavelet : public sample_noise<wavelet<D>, D> {
  static_assert(D == 2 || D == 3, "hush::wavelet is 2D or 3D");

 public:
  static constexpr bool takes_footprint = true;
  static constexpr bool takes_normal = D == 3;
  static constexpr int kMaxBands = detail::constants::kWaveletMaxBands;

  struct params {
    std::uint32_t seed = 0;
    // Coefficients per tile side: even, 16 ... 2048 (2D) / 128 (3D) (wavelet/tile.hpp).
    int tile_size = D == 2 ? 128 : 64;
    // Band i has frequency 2^(first_band + i); first_band in [-32, 32].
    int first_band = 0;
    // Band weights w_i (1 ... 32 values, |w_i| <= 1e30, the largest |w_i| >= 1e-30, so that
    // the sums and the normalisation are finite in float); one band by default.
    // With relative_weights: the weight k octaves below the finest representable band.
    std::vector<double> weights = {1.0};
    // Per-band decorrelating offsets (sec. 3, footnote 1), in coefficient units:
    // empty = derived from the seed (independent per band and axis), or one per band.
    std::vector<vec<double, D>> offsets;
    bool even_odd_fix = true;  // the paper's even/odd variance correction (sec. 4.3)
    wavelet_distribution distribution = wavelet_distribution::gaussian;
    double gaussian_scale = 1.0;  // standard deviation of the gaussian output; 0 < s <= 1e30
    // The inverse CDF of the wanted distribution at u = 0, 1/(m-1), ..., 1 (2 ... 65536
    // values, |v| <= 1e30), for wavelet_distribution::table.
    std::vector<double> table;
    wavelet_projection projection = wavelet_projection::exact;  // 3D with a normal
    bool widen = false;             // basis widening for one sample per pixel (sec. 4.1)
    bool relative_weights = false;  // infinite noise (sec. 5.4)
    int relative_bands = 16;        // with relative_weights: bands first_band ... + this - 1
    // 0: the tile repeats (period tile_size); 1 ... tile_size / 4: hashed tile
    // variants blended over this many coefficients (sec. 4.3), no repetition.
    int variant_overlap = 0;
  };

  wavelet() : wavelet(params{}) {}
  explicit wavelet(std::uint32_t seed) : wavelet(make_params(seed)) {}
  // Throws hush::invalid_argument naming the first parameter out of range.
  explicit wavelet(const params& prm) : prm_(prm) {
    validate();
    tile_ = wavelet_tile<D>::get({prm_.tile_size, prm_.seed, prm_.even_odd_fix});
    if (prm_.distribution == wavelet_distribution::table) {
      auto t = std::make_shared<std::vector<float>>();
      for (double v : prm_.table) t->push_back(static_cast<float>(v));
      table_ = std::move(t);
    }
    if (prm_.variant_overlap > 0)
      blend_ = wavelet_blend_tile<D>::get(
          {{prm_.tile_size, prm_.seed, prm_.even_odd_fix}, prm_.variant_overlap});
    const int nb = band_count();
    double sum_sq = 0, sum_abs = 0;
    for (int i = 0; i < nb; ++i) {
      band b;
      b.index = prm_.first_band + i;
      b.frequency = std::ldexp(1.0, b.index);
      b.weight = prm_.relative_weights ? 0.0 : prm_.weights[static_cast<std::size_t>(i)];
      const std::uint32_t band_seed = hash32(prm_.seed, static_cast<std::uint32_t>(b.index));
      for (int a = 0; a < D; ++a) {
        double o;
        if (prm_.offsets.empty()) {
          // A whole cell in [0, n) plus an exact 24-bit fraction.
          const std::uint32_t h = hash32(band_seed, static_cast<std::uint32_t>(a));
          o = static_cast<double>(hash32(h) % static_cast<std::uint32_t>(prm_.tile_size)) +
              static_cast<double>(h >> 8) * 0x1p-24;
        } else {
          o = prm_.offsets[static_cast<std::size_t>(i)][a];
        }
        // The tap-0 cell of y is floor(y - 1/2): fold the half into the offset.
        b.offset[a] = o - detail::constants::kWaveletCellOffset;
      }
      bands_.push_back(b);
      sum_sq += b.weight * b.weight;
      sum_abs += std::fabs(b.weight);
    }
    key_ = seed_key(prm_.seed);
    // The smallest kernel variance (3D: projected noise has less) bounds every scale.
    double smallest = tile_->variance();
    if constexpr (D == 3)
      for (int a = 0; a < 3; ++a)
        for (bool exact : {true, false})
          smallest = std::min(smallest, tile_->projected_variance(a, exact));
    if (!prm_.relative_weights) {
      scale_ = 1.0 / std::sqrt(tile_->variance() * sum_sq);
      bound_ = sum_abs * tile_->max_abs() / std::sqrt(smallest * sum_sq);
    } else {
      // Per sample K = 1 / sqrt(sigma^2 sum W^2); at most K + 1 bands have W != 0
      // (octaves o in (-1, K)), so sum |W| <= sqrt(K + 1) sqrt(sum W^2) (Cauchy-Schwarz).
      scale_ = 1.0;
      bound_ =
          std::sqrt((static_cast<double>(prm_.weights.size()) + 1.0) / smallest) * tile_->max_abs();
    }
    pre_bound_ = bound_;
    switch (prm_.distribution) {
      case wavelet_distribution::gaussian:
        slope_ = prm_.gaussian_scale;
        bound_ *= prm_.gaussian_scale;
        break;
      case wavelet_distribution::uniform:
        slope_ = 2 * detail::constants::kInvSqrt2Pi;  // erf(v / sqrt 2)' <= sqrt(2 / pi)
        bound_ = 1.0;
        break;
      case wavelet_distribution::table: {
        double steepest = 0;
        bound_ = 0;
        for (std::size_t i = 0; i < prm_.table.size(); ++i) {
          bound_ = std::max(bound_, std::fabs(prm_.table[i]));
          if (i + 1 < prm_.table.size())
            steepest = std::max(steepest, std::fabs(prm_.table[i + 1] - prm_.table[i]));
        }
        // Phi'(v) <= 1 / sqrt(2 pi); the table's slope in u is steepest * (m - 1).
        slope_ =
            steepest * static_cast<double>(prm_.table.size() - 1) * detail::constants::kInvSqrt2Pi;
        break;
      }
    }
  }

  const params& parameters() const { return prm_; }
  // |output| <= bound() for every input (see the file comment).
  double bound() const { return bound_; }
  // The shared tile and the memory this noise holds (tiles shared with other noises count
  // once per holder).
  const wavelet_tile<D>& tile() const { return *tile_; }
  std::shared_ptr<const wavelet_tile<D>> tile_ptr() const { return tile_; }
  std::shared_ptr<const wavelet_blend_tile<D>> blend_tile_ptr() const { return blend_; }
  // The distribution table in float (the float path's T(table[i])), shared with the GPU
  // backend; null unless distribution == table.
  std::shared_ptr<const std::vector<float>> table_floats() const { return table_; }
  std::size_t memory_bytes() const {
    return sizeof(*this) + tile_->bytes() + (blend_ ? blend_->bytes() : 0) +
           bands_.capacity() * sizeof(band);
  }

  // The bands as evaluated, for the SIMD and GLSL backends: band i's index b
  // (frequency 2^b), its raw weight (0 under relative_weights), and the
  // position of tap 0 of p, 2^b p + o_b - 1/2 (double; component a depends on p[a] only).
  int band_count() const {
    return prm_.relative_weights ? prm_.relative_bands : static_cast<int>(prm_.weights.size());
  }
  int band_index(int i) const { return bands_[static_cast<std::size_t>(i)].index; }
  double band_frequency(int i) const { return bands_[static_cast<std::size_t>(i)].frequency; }
  double band_raw_weight(int i) const { return bands_[static_cast<std::size_t>(i)].weight; }
  vec<double, D> band_position(int i, const vec<double, D>& p) const {
    return bands_[static_cast<std::size_t>(i)].position(p);
  }
  // Tile variants: the key hashing band i's cells (hash32(seed_key, b)).
  std::uint32_t variant_key(int i) const {
    return hash32(key_, static_cast<std::uint32_t>(bands_[static_cast<std::size_t>(i)].index));
  }
  // The normalisation K of the point noise (1 under relative_weights: per sample).
  double scale() const { return scale_; }
  // The lattice period a backend splits band positions with: the tile size, or 0
  // (2^32) with tile variants, which need the global coefficient index.
  std::uint32_t split_period() const {
    return prm_.variant_overlap > 0 ? 0u : static_cast<std::uint32_t>(prm_.tile_size);
  }

  // The float budget: |float - double| at any position (forward error analysis,
  // docs/wavelet.md). A plain band is an average of coefficients (|n| <= max_abs)
  // whose weights come from a degree-2 Horner step (error <= 6 u each, u = 2^-24)
  // and whose D nested sums of 3 terms add 3 u each level on top of the weights'
  // error: at most 21 D u max_abs per band. Summing nb bands and scaling adds
  // nb + 2 roundings of the result, so |error| <= (21 D + nb + 2) u bound().
  // Kernels with more taps and higher degree (projection, widening) get the
  // loose constant 512 in place of 21 D (beta alone: 9 taps of degree 5).
  double float_budget(bool plain_kernel = true) const {
    const double per_band = plain_kernel ? 21.0 * D : 512.0;
    // The remap multiplies the error by at most its slope and adds 8 roundings of its own
    // (erf, erfc and exp are within a few ulp in float).
    const double u = std::ldexp(1.0, -24);
    return (per_band + static_cast<double>(band_count()) + 2.0) * u * pre_bound_ * slope_ +
           8.0 * u * bound_;
  }

  // The same for the gradient: the derivative weights of a tap triple sum to at most 2
  // in magnitude (|f - 1| + |1 - 2f| + |f|), and band b's gradient is multiplied by
  // 2^b, so the bound is the value's with max_abs replaced by 2 max_abs 2^b per band.
  double float_gradient_budget(bool plain_kernel = true) const {
    double wf = 0, w = 0;
    for (const band& b : bands_) {
      wf += std::fabs(b.weight) * b.frequency;
      w += std::fabs(b.weight);
    }
    if (prm_.relative_weights) {  // at most K + 1 bands, each up to the top frequency
      wf = (static_cast<double>(prm_.weights.size()) + 1.0) * bands_.back().frequency;
      w = static_cast<double>(prm_.weights.size()) + 1.0;
    }
    return 2.0 * float_budget(plain_kernel) * wf / std::max(w, 1e-300);
  }

  // ---- Evaluation (core/point_noise.hpp, core/samples.hpp give the public overloads).
  template <class T>
  T value(const vec<double, D>& p) const {
    return eval<T, false>(point_input(p)).value;
  }
  template <class T>
  value_gradient<T, D> value_and_gradient(const vec<double, D>& p) const {
    return eval<T, true>(point_input(p));
  }
  template <class T>
  T sample_value(const sample_input<D>& s) const {
    return eval<T, false>(s).value;
  }
  template <class T>
  value_gradient<T, D> sample_value_and_gradient(const sample_input<D>& s) const {
    return eval<T, true>(s);
  }

  // ---- The per-sample plan, shared with the backends: what eval() does for one
  // sample, as data. `weight[i]` is band i's weight in the sum (0: skipped),
  // `scale` the normalisation (after the sum), `everything` a footprint that
  // filters everything (output 0), and the kernel: the normal (unit, double;
  // projected when `project`), its axis when axis-aligned (-1 otherwise), and
  // the per-band widening factors.
  struct plan {
    double weight[kMaxBands] = {};
    double scale = 0;
    double sum_sq = 0;  // sum of weight^2
    bool everything = false;
    bool project = false;
    int normal_axis = -1;
    vec<double, 3> normal{};
    double widen[kMaxBands][3] = {};
  };
  plan make_plan(const sample_input<D>& s) const {
    plan pl;
    const int nb = band_count();
    // Footprint width: the largest extent (file comment).
    double log2w = -std::numeric_limits<double>::infinity();
    const double wmax = s.fp.max_width();
    if (!(wmax < detail::constants::kFootprintMaxWidth)) {
      pl.everything = true;
      return pl;
    }
    if (wmax > 0) log2w = std::log2(wmax);
    plan_normal(s, pl);
    const double variance = plan_variance(pl);
    // Tangent-plane extents per tile axis, for widening: (P S P)_aa, P = I - u u^T.
    double extent2[3] = {0, 0, 0};
    if (prm_.widen) {
      for (int a = 0; a < D; ++a) {
        double pa[std::size_t{D}];
        for (int c = 0; c < D; ++c) pa[c] = (c == a ? 1.0 : 0.0);
        if constexpr (D == 3)
          if (pl.project)
            for (int c = 0; c < 3; ++c) pa[c] -= pl.normal[c] * pl.normal[a];
        double q = 0;
        for (int r = 0; r < D; ++r)
          for (int c = 0; c < D; ++c)
            q += pa[r] * static_cast<double>(s.fp.covariance(r, c)) * pa[c];
        extent2[a] = std::max(q, 0.0);
      }
    }
    double sum_sq = 0;
    for (int i = 0; i < nb; ++i) {
      const band& b = bands_[static_cast<std::size_t>(i)];
      const double level = static_cast<double>(b.index) + log2w;  // log2 of c = 2^b w
      double w;
      if (prm_.relative_weights)
        w = relative_weight(wmax > 0 ? level : static_cast<double>(b.index));
      else
        w = b.weight * fade_weight(level);
      pl.weight[i] = w;
      sum_sq += w * w;
      for (int a = 0; a < 3; ++a) pl.widen[i][a] = 1.0;
      if (prm_.widen && w != 0.0) {
        const double c0 = detail::constants::kWaveletWidenStart;
        const double c1 = detail::constants::kWaveletWidenEnd;  // where the fade reaches 0
        const double smax2 = 1.0 + c1 * c1 - c0 * c0;
        for (int a = 0; a < D; ++a) {
          const double c2 = extent2[a] * b.frequency * b.frequency;
          const double s2 = std::min(1.0 + std::max(0.0, c2 - c0 * c0), smax2);
          pl.widen[i][a] = std::sqrt(s2);
        }
      }
    }
    pl.sum_sq = sum_sq;
    pl.scale = plan_scale(pl, variance);
    return pl;
  }
  // The plan's surface part (3D): project, the unit normal (normalised in double)
  // and its axis when axis-aligned, from the sample's normal (a zero, NaN or
  // infinite normal: no projection). make_plan's; a backend whose samples have no
  // footprint reuses the bands' part and redoes only this, plan_variance and
  // plan_scale per sample.
  void plan_normal(const sample_input<D>& s, plan& pl) const {
    pl.project = false;
    pl.normal_axis = -1;
    pl.normal = {};
    if constexpr (D == 3) {
      if (s.has_normal) {
        double m = 0;
        bool finite = true;
        for (int a = 0; a < 3; ++a) {
          finite = finite && std::isfinite(s.normal[a]);
          m = std::max(m, std::fabs(s.normal[a]));
        }
        if (finite && m > 0) {
          double len = 0;
          for (int a = 0; a < 3; ++a) {
            pl.normal[a] = s.normal[a] / m;
            len += pl.normal[a] * pl.normal[a];
          }
          len = std::sqrt(len);
          int zeros = 0, axis = 0;
          for (int a = 0; a < 3; ++a) {
            pl.normal[a] /= len;
            if (pl.normal[a] == 0.0)
              ++zeros;
            else
              axis = a;
          }
          pl.project = true;
          if (zeros == 2) {
            pl.normal_axis = axis;
            pl.normal = {};
            pl.normal[axis] = 1.0;
          }
        }
      }
    }
  }
  // The variance of one unit-weight band of the plan's kernel (projected or not).
  double plan_variance(const plan& pl) const {
    double variance = tile_->variance();
    if constexpr (D == 3) {
      if (pl.project) {
        const bool exact = prm_.projection == wavelet_projection::exact;
        variance = 0;
        for (int a = 0; a < 3; ++a)
          variance += pl.normal[a] * pl.normal[a] * tile_->projected_variance(a, exact);
        // An oblique normal's exact projection has less variance than the axes' interpolation
        // (detail::wavelet_oblique_variance_ratio; 1 along an axis).
        if (exact) {
          const double u[3] = {pl.normal[0], pl.normal[1], pl.normal[2]};
          variance *= detail::wavelet_oblique_variance_ratio(u);
        }
      }
    }
    return variance;
  }
  // The normalisation after the band sum (pl.sum_sq set).
  double plan_scale(const plan& pl, double variance) const {
    if (prm_.relative_weights)
      return pl.sum_sq > 0 ? 1.0 / std::sqrt(variance * pl.sum_sq) : 0.0;
    return scale_ * std::sqrt(tile_->variance() / variance);
  }

  // The distribution remapping of a unit-variance value v (and d/dv), in T.
  template <class T>
  void remap(T& v, T* dv) const {
    switch (prm_.distribution) {
      case wavelet_distribution::gaussian:
        v *= T(prm_.gaussian_scale);
        if (dv) *dv = T(prm_.gaussian_scale);
        return;
      case wavelet_distribution::uniform: {
        const T x = v * T(detail::constants::kInvSqrt2);
        if (dv) *dv = T(2 * detail::constants::kInvSqrt2Pi) * std::exp(-x * x);
        v = std::erf(x);
        return;
      }
      case wavelet_distribution::table: {
        const T x = v * T(detail::constants::kInvSqrt2);
        const T u = std::erfc(-x) / T(2);  // Phi(v)
        const std::size_t m = prm_.table.size();
        if (!(u >= T(0) && u <= T(1))) {  // NaN
          if (dv) *dv = u;
          v = u;
          return;
        }
        const T pos = u * T(static_cast<double>(m - 1));
        std::size_t i = static_cast<std::size_t>(pos);
        if (i > m - 2) i = m - 2;
        const T t = pos - T(static_cast<double>(i));
        const T a = T(prm_.table[i]), b = T(prm_.table[i + 1]);
        if (dv)
          *dv = (b - a) * T(static_cast<double>(m - 1)) * T(detail::constants::kInvSqrt2Pi) *
                std::exp(-x * x);
        v = a + t * (b - a);
        return;
      }
    }
  }

 private:
  struct band {
    int index = 0;
    double frequency = 1;
    double weight = 0;
    vec<double, D> offset{};
    // 2^b p + o_b - 1/2 in double (exact products); a coordinate whose product
    // overflows is taken as 0 (file comment).
    vec<double, D> position(const vec<double, D>& p) const {
      vec<double, D> q;
      for (int a = 0; a < D; ++a) {
        double x = p[a] * frequency;
        if (!std::isfinite(x) && std::isfinite(p[a])) x = 0.0;
        q[a] = x + offset[a];
      }
      return q;
    }
  };

  static params make_params(std::uint32_t seed) {
    params p;
    p.seed = seed;
    return p;
  }
  static sample_input<D> point_input(const vec<double, D>& p) {
    sample_input<D> s;
    s.position = p;
    return s;
  }

  // The anti-aliasing fade of a band whose coefficients are 2^level pixels apart.
  static double fade_weight(double level) {
    if (!(level > 0)) return 1.0;  // also for -inf (a point footprint)
    if (level >= 1) return 0.0;
    return detail::fade(1.0 - level);
  }
  // Infinite noise: the weight of a band `level` = log2(2^b w) (octave -level
  // below the finest representable band).
  double relative_weight(double level) const {
    const double o = -level;
    const int k = static_cast<int>(prm_.weights.size());
    if (!(o > -1.0) || !(o < static_cast<double>(k))) return 0.0;
    if (o < 0) return prm_.weights[0] * detail::fade(o + 1.0);
    if (o > k - 1) return prm_.weights[static_cast<std::size_t>(k - 1)] * detail::fade(k - o);
    const int i = static_cast<int>(std::floor(o));
    if (i >= k - 1) return prm_.weights[static_cast<std::size_t>(k - 1)];
    const double t = detail::fade(o - i);
    const double a = prm_.weights[static_cast<std::size_t>(i)];
    const double b = prm_.weights[static_cast<std::size_t>(i) + 1];
    return a + t * (b - a);
  }

  // One band at tile-coordinate position q (tap 0 at floor(q)), in coefficient units.
  template <class T, bool G, class Access>
  value_gradient<T, D> band_kernel(const lattice_coord<T> (&c)[std::size_t{D}], const plan& pl,
                                   int i, const Access& acc) const {
    detail::wavelet_axis<T> ax[std::size_t{D}];
    bool widened = false;
    for (int a = 0; a < D; ++a) widened = widened || pl.widen[i][a] != 1.0;
    if constexpr (D == 3) {
      if (pl.project && pl.normal_axis < 0) {
        T y[3], u[3], s[3];
        for (int a = 0; a < 3; ++a) {
          y[a] = c[a].f + T(detail::constants::kWaveletCellOffset);
          u[a] = T(pl.normal[a]);
          s[a] = T(pl.widen[i][a]);
        }
        if (prm_.projection == wavelet_projection::exact)
          return detail::wavelet_general_exact<T, G>(y, u, s, acc);
        return detail::wavelet_general_approx<T, G>(y, u, s, acc);
      }
    }
    for (int a = 0; a < D; ++a) {
      if (D == 3 && pl.project && a == pl.normal_axis) {
        if (prm_.projection == wavelet_projection::exact)
          detail::wavelet_axis_fixed<T, G>(c[a].f, detail::kBeta, detail::kBetaDerivative, ax[a]);
        else
          detail::wavelet_axis_fixed<T, G>(c[a].f, detail::kBspline2, detail::kBspline2Derivative,
                                           ax[a]);
      } else if (widened && pl.widen[i][a] != 1.0) {
        detail::wavelet_axis_widened<T, G>(c[a].f + T(detail::constants::kWaveletCellOffset),
                                           T(pl.widen[i][a]), ax[a]);
      } else {
        detail::wavelet_axis_plain<T, G>(c[a].f, ax[a]);
      }
    }
    return detail::wavelet_separable<T, G, D>(ax, acc);
  }

  // One band of the sample: the cells of its position, then the kernel on the
  // periodic tile or on the hashed variants.
  template <class T, bool G>
  value_gradient<T, D> band_value(const vec<double, D>& p, const plan& pl, int i) const {
    const band& b = bands_[static_cast<std::size_t>(i)];
    const vec<double, D> q = b.position(p);
    lattice_coord<T> c[std::size_t{D}];
    const std::uint32_t period = split_period();
    for (int a = 0; a < D; ++a) c[a] = lattice_split<T>(q[a], period);
    if (prm_.variant_overlap == 0) {
      detail::wavelet_periodic_access<D> acc{tile_->coefficients(), prm_.tile_size,
                                             tile_->row_length(), {0, 0, 0}};
      for (int a = 0; a < D; ++a) acc.i0[a] = c[a].i0;
      return band_kernel<T, G>(c, pl, i, acc);
    }
    detail::wavelet_variant_access<D> acc{blend_->coefficients(),
                                          prm_.tile_size,
                                          prm_.tile_size - prm_.variant_overlap,
                                          variant_key(i),
                                          {0, 0, 0}};
    for (int a = 0; a < D; ++a) acc.i0[a] = c[a].i0;
    return band_kernel<T, G>(c, pl, i, acc);
  }

  template <class T, bool G>
  value_gradient<T, D> eval(const sample_input<D>& s) const {
    value_gradient<T, D> r{T(0), {}};
    for (int a = 0; a < D; ++a)
      if (!std::isfinite(s.position[a])) {
        r.value = std::numeric_limits<T>::quiet_NaN();
        for (int c = 0; c < D; ++c) r.gradient[c] = r.value;
        return r;
      }
    const plan pl = make_plan(s);
    if (pl.everything) {  // filtered to the mean: 0 before the remapping, constant after
      remap<T>(r.value, nullptr);
      return r;
    }
    const int nb = band_count();
    for (int i = 0; i < nb; ++i) {
      if (pl.weight[i] == 0.0) continue;
      const value_gradient<T, D> n = band_value<T, G>(s.position, pl, i);
      r.value += T(pl.weight[i]) * n.value;
      if constexpr (G) {
        const T chain = T(pl.weight[i] * bands_[static_cast<std::size_t>(i)].frequency);
        for (int a = 0; a < D; ++a) r.gradient[a] += chain * n.gradient[a];
      }
    }
    r.value *= T(pl.scale);
    if constexpr (G) {
      for (int a = 0; a < D; ++a) r.gradient[a] *= T(pl.scale);
      T dv = T(1);
      remap<T>(r.value, &dv);
      for (int a = 0; a < D; ++a) r.gradient[a] *= dv;
    } else {
      remap<T>(r.value, nullptr);
    }
    return r;
  }

  void validate() const {
    const char* where = "hush::wavelet";
    wavelet_tile<D>::validate_size(where, "tile_size", prm_.tile_size);
    namespace c = detail::constants;
    const std::string band_range =
        std::to_string(c::kWaveletMinBand) + " ... " + std::to_string(c::kWaveletMaxBand);
    detail::require_in_range(where, "first_band", prm_.first_band, c::kWaveletMinBand,
                             c::kWaveletMaxBand, band_range.c_str());
    const std::size_t nw = prm_.weights.size();
    if (nw < 1 || nw > static_cast<std::size_t>(kMaxBands))
      detail::throw_out_of_range(where, "weights.size()", nw, "1 ... 32");
    // K = 1 / sqrt(sigma^2 sum w^2) and every weight must be finite non-zero numbers in float
    // (detail/constants.hpp kMaxBandWeight, kMinLargestBandWeight).
    constexpr double kMaxWeight = c::kMaxBandWeight, kMinLargestWeight = c::kMinLargestBandWeight;
    const char* valid = "a finite number, |w| <= 1e30";
    double largest = 0;
    for (std::size_t i = 0; i < nw; ++i) {
      if (!(std::fabs(prm_.weights[i]) <= kMaxWeight))
        detail::throw_out_of_range(where, "weights[" + std::to_string(i) + "]", prm_.weights[i],
                                   valid);
      largest = std::max(largest, std::fabs(prm_.weights[i]));
    }
    if (largest == 0.0)
      hush::detail::raise_error(
          "hush::wavelet: weights are all zero; valid: at least one non-zero weight");
    if (largest < kMinLargestWeight)
      hush::detail::raise_error(
          "hush::wavelet: weights are all below 1e-30 in magnitude; valid: the largest |w| in "
          "1e-30 ... 1e30 (only the weights' ratios matter)");
    if (prm_.relative_weights)
      detail::require_in_range(where, "relative_bands", prm_.relative_bands, 1, kMaxBands,
                               "1 ... 32");
    const int nb = prm_.relative_weights ? prm_.relative_bands : static_cast<int>(nw);
    if (prm_.first_band + nb - 1 > c::kWaveletMaxBand)
      detail::throw_out_of_range(
          where, "first_band", prm_.first_band,
          ("first_band + bands - 1 <= " + std::to_string(c::kWaveletMaxBand)).c_str());
    if (!prm_.offsets.empty()) {
      if (prm_.offsets.size() != static_cast<std::size_t>(nb))
        detail::throw_out_of_range(where, "offsets.size()", prm_.offsets.size(),
                                   "0 (derived from the seed) or one per band");
      for (std::size_t i = 0; i < prm_.offsets.size(); ++i)
        for (int a = 0; a < D; ++a)
          if (!std::isfinite(prm_.offsets[i][a]))
            detail::throw_out_of_range(
                where, "offsets[" + std::to_string(i) + "][" + std::to_string(a) + "]",
                prm_.offsets[i][a], "a finite number");
    }
    // The output's scale stays within float's range (detail/constants.hpp kMaxOutputScale).
    if (!(prm_.gaussian_scale > 0 && prm_.gaussian_scale <= c::kMaxOutputScale))
      detail::throw_out_of_range(where, "gaussian_scale", prm_.gaussian_scale, "0 < s <= 1e30");
    if (prm_.distribution == wavelet_distribution::table) {
      if (prm_.table.size() < 2 || prm_.table.size() > 65536)
        detail::throw_out_of_range(where, "table.size()", prm_.table.size(),
                                   "2 ... 65536 values (with distribution = table)");
      for (std::size_t i = 0; i < prm_.table.size(); ++i)
        if (!(std::fabs(prm_.table[i]) <= c::kMaxOutputScale))
          detail::throw_out_of_range(where, "table[" + std::to_string(i) + "]", prm_.table[i],
                                     "|v| <= 1e30");
    }
    if (prm_.variant_overlap != 0)
      wavelet_blend_tile<D>::validate_overlap(where, "variant_overlap", prm_.tile_size,
                                              prm_.variant_overlap);
  }

  params prm_;
  std::shared_ptr<const wavelet_tile<D>> tile_;
  std::shared_ptr<const wavelet_blend_tile<D>> blend_;
  std::shared_ptr<const std::vector<float>> table_;
  std::vector<band> bands_;
  std::uint32_t key_ = 0;
  double scale_ = 1, bound_ = 1, pre_bound_ = 1, slope_ = 1;
};

}  // namespace hush

// The SIMD backend's entry points and exec::simd binding, after the class they use.
#include "hush/wavelet/simd_kernel.hpp"  // IWYU pragma: export

#endif  // HUSH_WAVELET_HPP
