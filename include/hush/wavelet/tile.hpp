// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::wavelet_tile<D>: the periodic tile of noise coefficients of wavelet noise
// (Cook & DeRose, "Wavelet Noise", SIGGRAPH 2005, sec. 3.4, 3.6, 4.2, 4.3,
// Appendix 1), 2D or 3D, built once per (size, seed, even/odd correction) and
// shared (core/tile_cache.hpp).
//
// Construction (n = size, the tile is periodic with period n on every axis):
//  1. R: n^D independent standard Gaussians r_i from hush::rng (seed, stream D),
//     read in index order (x fastest). R(y) = sum_i r_i B(y - i) lies in the
//     full-resolution space S^1 of the quadratic B-spline B (core/bspline.hpp).
//  2. Along every axis in turn, each line is projected onto the half-resolution
//     space S^0 spanned by B((y - 1/2)/2 - m), m = 0 ... n/2 - 1: the analysis
//     (least-squares) filter c_m = sum_k a_(k - 2m) x_k (eq. 16), then refined
//     back to S^1 by u_k = sum_m p_(k - 2m) c_m (eq. 12, p = constants.hpp
//     kWaveletRefine). After all D axes this is the projection Q of R onto the
//     coarse tensor space (S^0)^D.
//  3. N = R - Q R (eq. 20, 26): the band, orthogonal to (S^0)^D (eq. 30, 31).
//  4. The even/odd correction (sec. 4.3, Appendix 1): the analysis and
//     refinement treat even and odd coefficients differently, so the variance of
//     N(y) is periodic with period 2, not 1 (in 2D the cells [2m, 2m + 1) between
//     coefficients, inside a coarse basis function, have 16 to 18 % less variance
//     than their neighbours). Adding a copy of N shifted by an odd number of
//     coefficients o (n/2, or n/2 + 1 when that is even) along every axis makes
//     it 1-periodic (equal within 1 %; tests/wavelet/wavelet_tile_test.cpp). The copy
//     lies in a shifted wavelet space whose components near the coarse Nyquist
//     frequency are no longer cancelled by the coarse basis, so the corrected
//     tile is not orthogonal to (S^0)^D any more: 11 % of its energy projects
//     onto it (2D, measured there), against 1e-15 without the correction. The
//     spectrum, what a renderer sees, is unchanged by shifts. even_odd_fix =
//     false keeps the exact orthogonality and the period-2 variance.
//
// The analysis filter (eq. 16). Let g(d) = <B(. - i), B(. - i - d)> be the
// B-spline Gram entries (66, 26, 1 / 120 for d = 0, 1, 2; core/bspline.hpp) and
// h_d = sum_i p_i g(i - d). The normal equations of the least-squares problem
// min || sum_k x_k B(y - k) - sum_m c_m B((y - 1/2)/2 - m) ||^2 read
//   2 sum_j g(m - j) c_j = sum_k h_(k - 2m) x_k,
// so a_d = (1/2) sum_l G^-1(l) h_(d + 2l), with G^-1 the inverse of the Toeplitz
// Gram matrix. Its symbol is 120 z^2 / Q(z), Q(z) = z^4 + 26 z^3 + 66 z^2 + 26 z
// + 1, whose roots inside the unit circle are lambda = 2 / (w - sqrt(w^2 - 4)),
// w = -13 +- sqrt(105) (Q / z^2 = w^2 + 26 w + 64, w = z + 1/z). By residues,
//   G^-1(l) = 120 sum_lambda lambda^(|l| + 1) / Q'(lambda),
// which converges to the last bit of a double; |a_d| decays as 0.656^|d|
// (sqrt of the larger root) and is kept for |d| <= kWaveletAnalysisRadius (tail
// below 2e-18). a is symmetric about 1/2 and sums to 1 (even and odd taps to 1/2
// each); a composed with the refinement is the identity on S^0 (tested).
// Against the paper's 6-digit table (Appendix 1, symmetric about -1/2 in its
// indexing): every tap agrees within 8e-6 except the outermost pair, where the
// table has 0.000334 and the exact value is -0.000173 (and the appendix's loop
// over k = 2i - 16 ... 2i + 16 reads a 33rd tap past the end of its 32-entry
// array); the table's 0.003546 against 0.003545 (exact 0.0035446) breaks its
// symmetry. Effect, measured on 1D bands (mean of 20
// seeds, n = 256; tests/wavelet/wavelet_tile_test.cpp): the band keeps 4.7e-6 of its
// energy in S^0 with the table, 2.8e-6 with the exact taps cut to the same 32,
// and 1e-29 with hush's.
//
// Periodic tiles use the filter periodised to n (taps d and d + n summed), which
// is the exact least-squares projection for periodic coefficient sequences.
//
// Statistics: the coefficients are Gaussian (linear in the r_i). variance() is
// sigma_N^2, the spatial average of N(y)^2 over the whole tile, computed exactly
// from the stored float coefficients: (1/n^D) sum_i n_i (G n)_i with G the
// tensor Gram matrix. projected_variance(axis, exact) is the same for the noise
// projected along that axis (beta or the double-width B-spline along it).
// Expected values over seeds (n -> infinity) are in docs/wavelet.md beside the
// paper's 0.265 (2D), 0.210 (3D), 0.296 (projected).
#ifndef HUSH_WAVELET_TILE_HPP
#define HUSH_WAVELET_TILE_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hush/core/bspline.hpp"
#include "hush/core/error.hpp"
#include "hush/core/rng.hpp"
#include "hush/core/tile_cache.hpp"
#include "hush/detail/constants.hpp"

namespace hush {
namespace detail {

// G^-1(l): the inverse of the B-spline Gram matrix (Toeplitz, entries g(d)), by
// the residue formula in the file comment.
inline double bspline_gram_inverse(int l) {
  const double q0 = bspline_gram(0), q1 = bspline_gram(1), q2 = bspline_gram(2);
  // Q(z) = (q2 z^4 + q1 z^3 + q0 z^2 + q1 z + q2) / q2; Q / z^2 = w^2 + (q1/q2) w + q0/q2 - 2.
  const double b = q1 / q2, c = q0 / q2 - 2.0;
  const double disc = std::sqrt(b * b - 4.0 * c);
  double sum = 0;
  for (const double w : {(-b + disc) / 2.0, (-b - disc) / 2.0}) {
    const double lambda = 2.0 / (w - std::sqrt(w * w - 4.0));  // the root inside |z| < 1
    const double dq = 4.0 * lambda * lambda * lambda + 3.0 * b * lambda * lambda +
                      2.0 * (q0 / q2) * lambda + b;  // Q'(lambda)
    sum += std::pow(lambda, std::abs(l) + 1) / (q2 * dq);
  }
  return sum;
}

// The analysis filter a_d for d in [1 - R, R] (R = kWaveletAnalysisRadius), index d - 1 + R.
inline const std::vector<double>& wavelet_analysis_filter() {
  static const std::vector<double> taps = [] {
    constexpr int R = constants::kWaveletAnalysisRadius;
    constexpr int kFirst = constants::kWaveletRefineFirst;
    auto h = [](int d) {
      double s = 0;
      for (int i = 0; i < 4; ++i) {
        const int k = kFirst + i, lag = std::abs(k - d);
        if (lag < kBsplineGramReach) s += constants::kWaveletRefine[i] * bspline_gram(lag);
      }
      return s;
    };
    std::vector<double> a(static_cast<std::size_t>(2 * R));
    for (int d = 1 - R; d <= R; ++d) {
      double s = 0;
      // h is non-zero for |d - 1/2| < 4: the terms with |l| > R + 4 are below 1e-40.
      for (int l = -R - 4; l <= R + 4; ++l) s += bspline_gram_inverse(l) * h(d + 2 * l);
      a[static_cast<std::size_t>(d + R) - 1] = 0.5 * s;
    }
    return a;
  }();
  return taps;
}

inline int wavelet_mod(long long x, int n) {
  const long long r = x % n;
  return static_cast<int>(r < 0 ? r + n : r);
}

// Projects every line of `x` along one axis (stride, n coefficients, period n)
// onto S^0 and back: x <- P A x, line by line.
inline void wavelet_down_up(std::vector<double>& x, int n, std::size_t stride) {
  const std::vector<double>& a = wavelet_analysis_filter();
  constexpr int R = constants::kWaveletAnalysisRadius;
  // The filter periodised to n: taps (offset mod n, weight), merged.
  std::vector<double> per(static_cast<std::size_t>(n), 0.0);
  for (int d = 1 - R; d <= R; ++d)
    per[static_cast<std::size_t>(wavelet_mod(d, n))] += a[static_cast<std::size_t>(d + R) - 1];
  std::vector<int> off;
  std::vector<double> wt;
  for (int j = 0; j < n; ++j)
    if (per[static_cast<std::size_t>(j)] != 0.0) {
      off.push_back(j);
      wt.push_back(per[static_cast<std::size_t>(j)]);
    }
  const int half = n / 2;
  std::vector<double> line(static_cast<std::size_t>(n)), coarse(static_cast<std::size_t>(half));
  const std::size_t count = x.size();
  for (std::size_t base = 0; base < count; ++base) {
    if ((base / stride) % static_cast<std::size_t>(n) != 0) continue;  // not a line start
    for (int k = 0; k < n; ++k)
      line[static_cast<std::size_t>(k)] = x[base + static_cast<std::size_t>(k) * stride];
    for (int m = 0; m < half; ++m) {  // c_m = sum_j per_j x_(2m + j)
      double s = 0;
      for (std::size_t t = 0; t < off.size(); ++t) {
        int k = 2 * m + off[t];
        if (k >= n) k -= n;
        s += wt[t] * line[static_cast<std::size_t>(k)];
      }
      coarse[static_cast<std::size_t>(m)] = s;
    }
    for (int k = 0; k < n; ++k) {  // u_k = sum_t p_t c_((k - t) / 2), k - t even
      double s = 0;
      for (int i = 0; i < 4; ++i) {
        const int t = constants::kWaveletRefineFirst + i;
        if (((k - t) & 1) != 0) continue;
        s += constants::kWaveletRefine[i] *
             coarse[static_cast<std::size_t>(wavelet_mod((k - t) / 2, half))];
      }
      x[base + static_cast<std::size_t>(k) * stride] = s;
    }
  }
}

// Applies the circulant kernel k(d), |d| < reach, along one axis of the periodic array x.
template <class Kernel>
void wavelet_convolve_axis(std::vector<double>& x, int n, std::size_t stride, int reach, Kernel k) {
  std::vector<double> line(static_cast<std::size_t>(n)), kd(static_cast<std::size_t>(reach));
  for (int d = 0; d < reach; ++d) kd[static_cast<std::size_t>(d)] = k(d);
  for (std::size_t base = 0; base < x.size(); ++base) {
    if ((base / stride) % static_cast<std::size_t>(n) != 0) continue;
    for (int i = 0; i < n; ++i)
      line[static_cast<std::size_t>(i)] = x[base + static_cast<std::size_t>(i) * stride];
    for (int i = 0; i < n; ++i) {
      double s = 0;
      for (int d = 1 - reach; d < reach; ++d)
        s += kd[static_cast<std::size_t>(std::abs(d))] *
             line[static_cast<std::size_t>(wavelet_mod(i + d, n))];
      x[base + static_cast<std::size_t>(i) * stride] = s;
    }
  }
}

}  // namespace detail

template <int D>
class wavelet_tile {
  static_assert(D == 2 || D == 3, "hush::wavelet_tile is 2D or 3D");

 public:
  // What determines a tile: its size, its seed and whether the even/odd
  // correction is applied.
  struct key {
    int size = 0;
    std::uint32_t seed = 0;
    bool even_odd_fix = true;
    friend bool operator<(const key& a, const key& b) {
      if (a.size != b.size) return a.size < b.size;
      if (a.seed != b.seed) return a.seed < b.seed;
      return a.even_odd_fix < b.even_odd_fix;
    }
  };

  // The largest tile size of this dimension.
  static constexpr int max_size() {
    return D == 2 ? detail::constants::kWaveletMaxTile2 : detail::constants::kWaveletMaxTile3;
  }
  // Throws hush::invalid_argument (naming `where` and `name`) unless n is an even
  // number in [kWaveletMinTile, max_size()] (HARD_CASES row 14).
  static void validate_size(const char* where, const char* name, int n) {
    const std::string valid = "an even number from " +
                              std::to_string(detail::constants::kWaveletMinTile) + " to " +
                              std::to_string(max_size()) +
                              " (the tile must be even, Cook & DeRose footnote 4, and at least "
                              "16 coefficients, wider than the widest kernel's reach)";
    if (n < detail::constants::kWaveletMinTile || n > max_size() || n % 2 != 0)
      detail::throw_out_of_range(where, name, n, valid.c_str());
  }

  // Builds the tile (see the file comment). Throws hush::invalid_argument for a bad size.
  explicit wavelet_tile(const key& k) : key_(k) {
    validate_size("hush::wavelet_tile", "size", k.size);
    const int n = k.size;
    std::size_t count = 1;
    for (int a = 0; a < D; ++a) count *= static_cast<std::size_t>(n);
    std::vector<double> r(count);
    rng gen(k.seed, static_cast<std::uint32_t>(D));
    for (double& v : r) v = gen.gaussian<double>();
    std::vector<double> q = r;
    std::size_t stride = 1;
    for (int a = 0; a < D; ++a, stride *= static_cast<std::size_t>(n))
      detail::wavelet_down_up(q, n, stride);
    for (std::size_t i = 0; i < count; ++i) q[i] = r[i] - q[i];  // N = R - Q R
    r.clear();
    r.shrink_to_fit();
    const auto un = static_cast<std::size_t>(n), m = static_cast<std::size_t>(row_length());
    coef_.resize(count / un * m);
    int offset = n / 2;
    if (offset % 2 == 0) ++offset;
    for (std::size_t i = 0; i < count; ++i) {
      double v = q[i];
      if (k.even_odd_fix) {
        std::size_t j = 0, s = 1, rest = i;
        for (int a = 0; a < D; ++a, s *= static_cast<std::size_t>(n)) {
          const std::size_t c = rest % static_cast<std::size_t>(n);
          rest /= static_cast<std::size_t>(n);
          j += ((c + static_cast<std::size_t>(offset)) % static_cast<std::size_t>(n)) * s;
        }
        v += q[j];
      }
      // Row i / n, column i % n; a padded row repeats its first columns after n.
      const auto f = static_cast<float>(v);
      for (std::size_t x = i % un; x < m; x += un) coef_[i / un * m + x] = f;
      max_abs_ = std::max(max_abs_, std::fabs(static_cast<double>(f)));
    }
    variance_ = quadratic_form(-1, false);
    if constexpr (D == 3)
      for (int a = 0; a < 3; ++a) {
        projected_[a][0] = quadratic_form(a, true);
        projected_[a][1] = quadratic_form(a, false);
      }
  }

  // The shared tile of `k` (built on first use; core/tile_cache.hpp).
  static std::shared_ptr<const wavelet_tile> get(const key& k) {
    return cache().get(k, [&] { return wavelet_tile(k); });
  }
  static tile_cache<key, wavelet_tile>& cache() {
    static tile_cache<key, wavelet_tile> c;
    return c;
  }

  const key& id() const { return key_; }
  int size() const { return key_.size; }
  // Coefficients per stored x row: n, plus kWaveletRowPad in 3D (see coefficients()).
  int row_length() const { return key_.size + kRowPad; }
  // The index step of tile axis `axis` in coefficients(): 1, row_length(),
  // row_length() n.
  int stride(int axis) const { return axis == 0 ? 1 : row_length() * (axis == 2 ? size() : 1); }
  // The coefficients, the only copy: n^(D-1) x rows of row_length() floats,
  // coefficient (i_x, i_y[, i_z]) at i_x + row_length() (i_y + n i_z), i_x < n. In 3D
  // every row is followed by a repeat of its first kWaveletRowPad coefficients, so
  // that the three x taps of any cell i_x < n and one float more are four adjacent
  // floats: one unaligned 128-bit load in the SIMD kernels instead of three gathers
  // (2D tiles are not padded: the largest, 2048^2, fills the 16 MiB a GPU buffer is
  // guaranteed to hold). storage_size() floats.
  const float* coefficients() const { return coef_.data(); }
  std::size_t storage_size() const { return coef_.size(); }
  // n^D: the number of distinct coefficients.
  std::size_t count() const { return coef_.size() / static_cast<std::size_t>(row_length()) *
                                     static_cast<std::size_t>(size()); }
  // Coefficient i in the unpadded order, i = i_x + n (i_y + n i_z), i < count().
  float coefficient(std::size_t i) const {
    const auto n = static_cast<std::size_t>(size());
    return coef_[i / n * static_cast<std::size_t>(row_length()) + i % n];
  }
  // max |n_i|: |N(y)| never exceeds it (every kernel is an average of coefficients).
  double max_abs() const { return max_abs_; }
  // sigma_N^2: the mean of N(y)^2 over the tile (file comment).
  double variance() const { return variance_; }
  // The same for the noise projected along tile axis `axis` (3D): with the exact
  // kernel beta (exact = true) or the double-width B-spline.
  double projected_variance(int axis, bool exact) const { return projected_[axis][exact ? 0 : 1]; }
  // Memory held, in bytes.
  std::size_t bytes() const { return sizeof(*this) + coef_.capacity() * sizeof(float); }

 private:
  // (1/n^D) sum_i n_i (K n)_i with K the tensor product of the Gram kernel along
  // every axis except `along`, where it is beta's (exact) or B2's autocorrelation.
  double quadratic_form(int along, bool exact) const {
    const int n = key_.size;
    std::vector<double> x(count());
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = coefficient(i);
    std::size_t stride = 1;
    for (int a = 0; a < D; ++a, stride *= static_cast<std::size_t>(n)) {
      if (a != along)
        detail::wavelet_convolve_axis(x, n, stride, detail::kBsplineGramReach,
                                      detail::bspline_gram);
      else if (exact)
        detail::wavelet_convolve_axis(x, n, stride, detail::kBetaGramReach, detail::beta_gram);
      else
        detail::wavelet_convolve_axis(x, n, stride, detail::kBspline2GramReach,
                                      detail::bspline2_gram);
    }
    double s = 0;
    for (std::size_t i = 0; i < x.size(); ++i) s += static_cast<double>(coefficient(i)) * x[i];
    return s / static_cast<double>(x.size());
  }

  static constexpr int kRowPad = D == 3 ? detail::constants::kWaveletRowPad : 0;

  key key_;
  std::vector<float> coef_;
  double max_abs_ = 0;
  double variance_ = 0;
  double projected_[3][2] = {};
};

// hush::wavelet_blend_tile<D>: the tile of wavelet_tile<D> prepared for hashed
// tile variants without visible repetition (Cook & DeRose sec. 4.3).
//
// Space is covered by tile cells of L = n - m coefficients per axis (m = the
// overlap); cell T holds a copy of the tile, transformed by its own variant (an
// axis permutation and per-axis reflection chosen by a hash of T: 8 variants in
// 2D, 48 in 3D), covering the global coefficients [T L, T L + n). Neighbouring
// copies overlap by m coefficients and are cross-faded there with weights
// sin(theta), cos(theta), theta = (j + 1/2) / m * pi / 2 for the j-th overlapping
// coefficient, so the squared weights sum to 1 and the blend keeps the variance
// (the paper divides an alpha / (1 - alpha) blend by sqrt(alpha^2 + (1 -
// alpha)^2) for the same effect). As the paper suggests, the weights are
// multiplied into the coefficients here, once: the profile is the same on every
// axis and symmetric under reflection, so one premultiplied tile serves every
// variant. Outside [0, n) a copy is 0.
template <int D>
class wavelet_blend_tile {
 public:
  struct key {
    typename wavelet_tile<D>::key tile;
    int overlap = 0;
    friend bool operator<(const key& a, const key& b) {
      if (a.tile < b.tile) return true;
      if (b.tile < a.tile) return false;
      return a.overlap < b.overlap;
    }
  };
  // Throws hush::invalid_argument unless 1 <= overlap <= size / 4.
  static void validate_overlap(const char* where, const char* name, int size, int overlap) {
    if (overlap < 1 || overlap > size / 4)
      detail::throw_out_of_range(
          where, name, overlap,
          ("0 (no variants) or 1 ... tile_size / 4 = " + std::to_string(size / 4)).c_str());
  }

  explicit wavelet_blend_tile(const key& k) : key_(k) {
    const std::shared_ptr<const wavelet_tile<D>> base = wavelet_tile<D>::get(k.tile);
    const int n = base->size(), m = k.overlap;
    validate_overlap("hush::wavelet_blend_tile", "overlap", n, m);
    std::vector<double> alpha(static_cast<std::size_t>(n), 1.0);
    constexpr double kQuarterTurn = 1.5707963267948966192;  // pi / 2
    for (int j = 0; j < m; ++j) {
      const double theta = (j + 0.5) / m * kQuarterTurn;
      alpha[static_cast<std::size_t>(j)] = std::sin(theta);
      alpha[static_cast<std::size_t>(n - m) + static_cast<std::size_t>(j)] = std::cos(theta);
    }
    coef_.resize(base->count());
    for (std::size_t i = 0; i < coef_.size(); ++i) {
      double w = 1;
      std::size_t rest = i;
      for (int a = 0; a < D; ++a) {
        w *= alpha[rest % static_cast<std::size_t>(n)];
        rest /= static_cast<std::size_t>(n);
      }
      coef_[i] = static_cast<float>(w * static_cast<double>(base->coefficient(i)));
    }
  }

  static std::shared_ptr<const wavelet_blend_tile> get(const key& k) {
    return cache().get(k, [&] { return wavelet_blend_tile(k); });
  }
  static tile_cache<key, wavelet_blend_tile>& cache() {
    static tile_cache<key, wavelet_blend_tile> c;
    return c;
  }

  int size() const { return key_.tile.size; }
  int overlap() const { return key_.overlap; }
  const float* coefficients() const { return coef_.data(); }
  std::size_t count() const { return coef_.size(); }
  std::size_t bytes() const { return sizeof(*this) + coef_.capacity() * sizeof(float); }

 private:
  key key_;
  std::vector<float> coef_;
};

}  // namespace hush

#endif  // HUSH_WAVELET_TILE_HPP
