// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The kernels of wavelet noise (Cook & DeRose 2005), all uniform B-splines, and
// their exact piecewise-polynomial forms, derived at compile time.
//
// Every kernel here is the density of a sum of independent centred uniform
// variables of integer widths c_1 ... c_m, i.e. the convolution of boxes:
//   B     = box1 * box1 * box1                 the quadratic B-spline (support 3)
//   B2    = box2 * box2 * box2                 B stretched by 2: B2(u) = B(u / 2) / 2
//   beta  = B * B2 (six boxes)                 the exact projection kernel, a quintic
//                                               (Cook & DeRose eq. 36, support 9)
//   g     = B * B, gb = B2 * B2, gbeta = beta * beta   their autocorrelations
// Such a density is (Schoenberg's truncated-power formula)
//   f(x) = sum over subsets e of the widths (-1)^|e| (u - sum e)_+^(m-1) / ((m-1)! prod c),
// with u = x + (sum c) / 2. On each unit piece u in [k, k + 1] it is one polynomial
// in t = u - k, whose coefficients are integer sums divided once by (m-1)! prod c:
// exact to the last bit of a double. The widths are the only input
// (constants.hpp: kBsplineUniforms, kWaveletProjectionStretch); no polynomial
// coefficient is typed anywhere, and the tests re-derive each kernel's defining
// property (partition of unity, refinement, convolution, integral).
//
// Conventions: kernels are centred (symmetric about 0) and arguments are
// distances d = y - i from a coefficient i to the position y, in coefficient
// units. Outside the support every kernel is 0.
#ifndef HUSH_CORE_BSPLINE_HPP
#define HUSH_CORE_BSPLINE_HPP

#include <array>
#include <cmath>
#include <cstdint>

#include "hush/config.hpp"
#include "hush/detail/constants.hpp"

namespace hush {
namespace detail {

// A kernel as Pieces unit polynomial pieces of Order coefficients (degree
// Order - 1), ascending powers of the local variable t in [0, 1]; piece k
// covers d in [k - Pieces / 2, k + 1 - Pieces / 2].
template <int Pieces, int Order>
struct piecewise_kernel {
  static constexpr int pieces = Pieces;
  static constexpr int order = Order;
  std::array<std::array<double, std::size_t{Order}>, std::size_t{Pieces}> c{};
  static constexpr double half_support() { return Pieces / 2.0; }
};

// n choose k, for the small n used here.
constexpr std::int64_t binomial(int n, int k) {
  std::int64_t r = 1;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}
constexpr std::int64_t ipow(std::int64_t b, int e) {
  std::int64_t r = 1;
  for (int i = 0; i < e; ++i) r *= b;
  return r;
}

// The pieces of the density of a sum of M centred uniforms of integer widths w.
template <int M, int S>
constexpr piecewise_kernel<S, M> uniform_sum_kernel(const std::array<int, std::size_t{M}>& w) {
  piecewise_kernel<S, M> r{};
  std::int64_t denom = 1;
  for (int i = 1; i < M; ++i) denom *= i;  // (M - 1)!
  for (std::size_t i = 0; i < M; ++i) denom *= w[i];
  for (int k = 0; k < S; ++k) {
    std::int64_t num[std::size_t{M}] = {};
    for (unsigned e = 0; e < (1u << M); ++e) {
      int s = 0, sign = 1;
      for (int i = 0; i < M; ++i)
        if (e >> i & 1u) {
          s += w[static_cast<std::size_t>(i)];
          sign = -sign;
        }
      if (s > k) continue;  // (u - s)_+ vanishes on this piece
      // (t + k - s)^(M-1) = sum_j binom(M-1, j) t^j (k - s)^(M-1-j)
      for (int j = 0; j < M; ++j) num[j] += sign * binomial(M - 1, j) * ipow(k - s, M - 1 - j);
    }
    for (int j = 0; j < M; ++j)
      r.c[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)] =
          static_cast<double>(num[j]) / static_cast<double>(denom);
  }
  return r;
}

// The density of that sum where u = x + S / 2 is the integer `u`, exactly:
// f = sum_e (-1)^|e| (u - s_e)_+^(M-1) / ((M-1)! prod w). Every term is an
// integer below 2^47 for the kernels here, so the sum is exact in int64.
template <int M>
constexpr double uniform_sum_density_at(const std::array<int, std::size_t{M}>& w, int u) {
  std::int64_t num = 0, denom = 1;
  for (int i = 1; i < M; ++i) denom *= i;
  for (std::size_t i = 0; i < M; ++i) denom *= w[i];
  for (unsigned e = 0; e < (1u << M); ++e) {
    int s = 0, sign = 1;
    for (int i = 0; i < M; ++i)
      if (e >> i & 1u) {
        s += w[static_cast<std::size_t>(i)];
        sign = -sign;
      }
    if (u > s) num += sign * ipow(u - s, M - 1);
  }
  return static_cast<double>(num) / static_cast<double>(denom);
}

namespace bspline_widths {
constexpr int kN = constants::kBsplineUniforms;
constexpr int kStretch = static_cast<int>(constants::kWaveletProjectionStretch);
static_assert(kStretch == constants::kWaveletProjectionStretch, "an integer stretch");
template <int M>
constexpr std::array<int, std::size_t{M}> boxes(int width) {
  std::array<int, std::size_t{M}> r{};
  for (std::size_t i = 0; i < M; ++i) r[i] = width;
  return r;
}
template <int A, int B>
constexpr std::array<int, std::size_t{A + B}> concat(const std::array<int, std::size_t{A}>& a,
                                                     const std::array<int, std::size_t{B}>& b) {
  std::array<int, std::size_t{A + B}> r{};
  for (std::size_t i = 0; i < A; ++i) r[i] = a[i];
  for (std::size_t i = 0; i < B; ++i) r[std::size_t{A} + i] = b[i];
  return r;
}
constexpr auto kB = boxes<kN>(1);                              // B
constexpr auto kB2 = boxes<kN>(kStretch);                      // B2 = B(u / 2) / 2
constexpr auto kBeta = concat<kN, kN>(kB, kB2);                // beta = B * B2
constexpr auto kG = concat<kN, kN>(kB, kB);                    // B * B
constexpr auto kGb2 = concat<kN, kN>(kB2, kB2);                // B2 * B2
constexpr auto kGbeta = concat<2 * kN, 2 * kN>(kBeta, kBeta);  // beta * beta
}  // namespace bspline_widths

// The quadratic B-spline B (3 pieces), B2 (6 pieces) and the quintic beta (9 pieces).
inline constexpr auto kBspline =
    uniform_sum_kernel<bspline_widths::kN, bspline_widths::kN>(bspline_widths::kB);
inline constexpr auto kBspline2 =
    uniform_sum_kernel<bspline_widths::kN, bspline_widths::kN * bspline_widths::kStretch>(
        bspline_widths::kB2);
inline constexpr auto kBeta =
    uniform_sum_kernel<2 * bspline_widths::kN, bspline_widths::kN*(1 + bspline_widths::kStretch)>(
        bspline_widths::kBeta);

// Autocorrelations at integer lags d (0 <= d < support): the Gram entries of the
// basis (g), and of the two projection kernels along the normal (for variances).
constexpr double bspline_gram(int d) {
  return uniform_sum_density_at<2 * bspline_widths::kN>(bspline_widths::kG, d + bspline_widths::kN);
}
constexpr double bspline2_gram(int d) {
  return uniform_sum_density_at<2 * bspline_widths::kN>(
      bspline_widths::kGb2, d + bspline_widths::kN * bspline_widths::kStretch);
}
constexpr double beta_gram(int d) {
  return uniform_sum_density_at<4 * bspline_widths::kN>(
      bspline_widths::kGbeta, d + bspline_widths::kN * (1 + bspline_widths::kStretch));
}
// Lags where they are non-zero: |d| < reach.
constexpr int kBsplineGramReach = bspline_widths::kN;                                // 3
constexpr int kBspline2GramReach = bspline_widths::kN * bspline_widths::kStretch;    // 6
constexpr int kBetaGramReach = bspline_widths::kN * (1 + bspline_widths::kStretch);  // 9

// The derivative's pieces (coefficients j c_j, shifted down one power).
template <int P, int O>
constexpr piecewise_kernel<P, O - 1> derivative(const piecewise_kernel<P, O>& k) {
  piecewise_kernel<P, O - 1> r{};
  for (int p = 0; p < P; ++p)
    for (std::size_t j = 1; j < O; ++j)
      r.c[static_cast<std::size_t>(p)][j - 1] = k.c[static_cast<std::size_t>(p)][j] * double(j);
  return r;
}
inline constexpr auto kBsplineDerivative = derivative(kBspline);
inline constexpr auto kBspline2Derivative = derivative(kBspline2);
inline constexpr auto kBetaDerivative = derivative(kBeta);

// Piece p of kernel k at local t, Horner form (highest power first), in T.
template <class T, int P, int O>
HUSH_INLINE T piece_value(const piecewise_kernel<P, O>& k, int p, T t) {
  const auto& c = k.c[static_cast<std::size_t>(p)];
  T r = T(c.back());
  for (int j = O - 2; j >= 0; --j) r = r * t + T(c[static_cast<std::size_t>(j)]);
  return r;
}

// Kernel k at distance d (0 outside its support), in T.
template <class T, int P, int O>
HUSH_INLINE T kernel_at(const piecewise_kernel<P, O>& k, T d) {
  const T u = d + T(P / 2.0);
  if (!(u > T(0) && u < T(P))) return T(0);  // also 0 for NaN
  const int p = static_cast<int>(std::floor(u));
  return piece_value(k, p, u - T(p));
}

// A fixed kernel of support P (B2: 6, beta: 9) read at fraction f in [0, 1): tap j sits
// at distance f + 1/2 - j, and the taps j = floor(1/2 - P/2) + 1 ... ceil(3/2 + P/2) - 1
// (-2 ... 4 for B2, -3 ... 5 for beta) cover every f (some weights are 0).
template <int P>
constexpr int fixed_kernel_first_tap() {
  return P % 2 == 0 ? 1 - P / 2 : (3 - P) / 2;
}
template <int P>
constexpr int fixed_kernel_taps() {
  return (P + 2) / 2 - fixed_kernel_first_tap<P>() + 1;
}
// The most taps any kernel has along one axis (beta's 9; the widened B-spline is
// limited to it).
constexpr int kWaveletMaxTaps = fixed_kernel_taps<kBeta.pieces>();

// The number of axis permutations of a D-dimensional tile (D!: 2 or 6), for the
// hashed tile variants of wavelet noise.
constexpr std::uint32_t wavelet_permutations(int d) { return d == 2 ? 2u : 6u; }

// The plain 3-tap weights of B at fraction f in [0, 1): the position y lies at
// distance f + 1/2 - j from coefficient i0 + j, j = 0, 1, 2 (i0 = floor(y - 1/2),
// f = y - 1/2 - i0), so tap j reads piece 2 - j at t = f.
template <class T>
HUSH_INLINE void bspline_weights(T f, T (&w)[3]) {
  for (int j = 0; j < 3; ++j) w[j] = piece_value(kBspline, 2 - j, f);
}
template <class T>
HUSH_INLINE void bspline_derivative_weights(T f, T (&w)[3]) {
  for (int j = 0; j < 3; ++j) w[j] = piece_value(kBsplineDerivative, 2 - j, f);
}

}  // namespace detail
}  // namespace hush

#endif  // HUSH_CORE_BSPLINE_HPP
