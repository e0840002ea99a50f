// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Anisotropic noise (Goldberg, Zwicker & Durand, "Anisotropic Noise",
// SIGGRAPH 2008): 2D texture-space noise built from oriented subband tiles,
// with distortion compensation (sec. 3.1) and anisotropic filtering (sec. 4),
// evaluated per sample as
//
//   n(u) = sum_k f_k( sum_{i,s} gamma_{k,i,s} lambda_{i,s} n_{i,s}(u) )      (sec. 5)
//
//  - n_{i,s}: subband tile i (orientation theta_i = pi i / K, filter D_{i,s}
//    of anisotropic/steerable.hpp) looked up bilinearly at scale s, whose centre frequency
//    is f_s = frequency 2^(s - base_scale) cycles per texture unit. One tile
//    per orientation serves every scale (the paper's single 256^2 RGBA
//    texture for K = 4): scale s reads it at u f_s / kAnisoTileBand texels,
//    offset per scale so the scales do not coincide at the origin.
//  - lambda_{i,s}: the sample's pixel filter, H(J^T w) = exp(-2 pi^2 sigma^2
//    w^T S w) with S = J J^T the footprint (core/footprint.hpp), sigma =
//    kPixelFilterSigma, fitted by params::filtering (anisotropic/subband_fit.hpp rules:
//    centre = the paper's heuristic, three_point = its sec. 5 variant,
//    least_squares = its eq. 5 fit, CPU only). A point footprint gives 1.
//  - gamma_{k,i,s}: octave k's target, the isotropic band B of scale
//    base_scale + k in surface space, moved to texture space by the sample's
//    surface map T (core/surface_map.hpp): sqrt|det T| B(log2(|T^T w| /
//    f_{base_scale + k})), fitted by params::compensation, times
//    2^(s - base_scale - k): every scale's tiles have unit variance rather
//    than the paper's common white spectrum, so a subband's amplitude is its
//    filter over f_s (docs/anisotropic.md, "Distortion compensation"). Without
//    a map (the identity) gamma_{k,i,s} = 1 for s = base_scale + k, else 0.
//    The heuristic rules cap each gamma at sqrt(2 pi / A_K), the weight at
//    which one subband alone carries all of the octave's variance (A_K =
//    integral of G_i^2): strongly anisotropic maps otherwise blow the centre
//    rule up.
//  - f_k: fbm, f_k(t) = gain^k t (linear: the octave weights are summed
//    first, the paper's "optimized" form, one lookup per subband); or
//    turbulence, f_k(t) = gain^k |t| (one sum per octave, the "unoptimized" form).
// The output is divided by sqrt(sum_k gain^2k).
//
// Contract (float and double from one template; double is the reference):
//  - domain: every finite texture position; NaN or +-Inf gives NaN. The noise
//    is periodic: scale s repeats every tile_size * kAnisoTileBand / f_s units.
//  - mean 0; without a map and filter, variance 1 (fbm): each scale's tile
//    set is normalised so that the sum of its orientations, bilinearly
//    interpolated, has spatial variance exactly 1 over the continuous plane,
//    and octaves are independent up to the tiles' finite size (measured in
//    tests/anisotropic/anisotropic_test.cpp). Filtering lowers it (that is the point).
//  - range: |n| <= bound() without maps (lambda <= 1); bound_with_maps() with
//    maps and the heuristic rules; least-squares weights have no a-priori bound.
//  - float evaluation is within float_budget() of the double reference.
//  - footprints: NaN, Inf or huge give lambda = 0 everywhere: the mean, 0
//    (HARD_CASES row 12); zero, rank 1 or tiny ones filter accordingly; an
//    indefinite one (a near-singular S rounded to float) as its singular limit
//    (filter_form clamps d^T S d at 0).
//  - surface maps: det T = 0 (zero UV area, or zero 3D area through
//    surface_map::from_triangle) gives gamma = 0: the mean, 0; mirrored UVs
//    (det < 0) use |det T|; a map with a non-finite entry counts as the zero map.
//  - gradients: d n / d u of the bilinear lookups (the weights held fixed):
//    exact inside texels, one-sided at texel edges, where the noise is C0.
// Tiles: built once per (seed, orientations, tile_size) and shared
// (tile_cache(), memory reported there), each orientation a real image
// IFFT(F D_i), F a Hermitian complex Gaussian white spectrum drawn from
// hush::rng, D_i the bank's scale at kAnisoTileBand cycles per texel.
// Construction costs K FFTs of tile_size^2 (about 40 ms for K = 4 at 256^2 here).
#ifndef HUSH_ANISOTROPIC_HPP
#define HUSH_ANISOTROPIC_HPP

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "hush/core/error.hpp"
#include "hush/core/footprint.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/lattice.hpp"
#include "hush/core/rng.hpp"
#include "hush/core/samples.hpp"
#include "hush/core/surface_map.hpp"
#include "hush/core/tile_cache.hpp"
#include "hush/core/vec.hpp"
#include "hush/detail/approx_math.hpp"
#include "hush/detail/constants.hpp"
#include "hush/detail/fft.hpp"
#include "hush/fractal.hpp"  // fractal_kind
#include "hush/anisotropic/steerable.hpp"
#include "hush/anisotropic/subband_fit.hpp"

namespace hush {

// The subband tiles of one (seed, orientations, tile_size): K real N x N
// images, interleaved per texel into `channels` floats (4 for K <= 4, else 8,
// unused channels 0: one or two RGBA textures on the GPU), stored with one
// wrapped extra row and column so that a bilinear lookup reads texels (x, y)
// and (x + 1, y) as one run of 2 * channels floats.
class anisotropic_tile {
 public:
  struct key {
    std::uint32_t seed;
    int orientations;
    int size;
    friend bool operator<(const key& a, const key& b) {
      return std::tie(a.seed, a.orientations, a.size) < std::tie(b.seed, b.orientations, b.size);
    }
  };

  explicit anisotropic_tile(const key& k)
      : size_(k.size), orientations_(k.orientations), channels_(k.orientations <= 4 ? 4 : 8) {
    build(k.seed);
  }

  int size() const { return size_; }
  int orientations() const { return orientations_; }
  int channels() const { return channels_; }
  // Texel (x, y), x and y in 0 ... size() (size() wraps to 0): `channels()` floats.
  const float* texel(std::uint32_t x, std::uint32_t y) const {
    return texels_.data() +
           (static_cast<std::size_t>(y) * static_cast<std::size_t>(size_ + 1) + x) *
               static_cast<std::size_t>(channels_);
  }
  // Floats between the starts of two texel rows.
  std::size_t row_stride() const {
    return static_cast<std::size_t>(size_ + 1) * static_cast<std::size_t>(channels_);
  }
  const std::vector<float>& texels() const { return texels_; }
  // Largest |value| of orientation i's tile, and largest difference between
  // neighbouring texels (bilinear weight precision on GPUs scales with it).
  float max_abs(int i) const { return max_abs_[static_cast<std::size_t>(i)]; }
  float max_step(int i) const { return max_step_[static_cast<std::size_t>(i)]; }
  // The size() x size() RGBA texture of channels 4t ... 4t + 3 (t = 0 or 1), row-major.
  std::vector<float> rgba(int t) const {
    const auto n = static_cast<std::size_t>(size_), first = 4 * static_cast<std::size_t>(t);
    std::vector<float> out(n * n * 4);
    for (std::size_t y = 0; y < n; ++y)
      for (std::size_t x = 0; x < n; ++x)
        for (std::size_t c = 0; c < 4; ++c)
          out[(y * n + x) * 4 + c] =
              texel(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y))[first + c];
    return out;
  }
  // Memory held, in bytes.
  std::size_t bytes() const {
    return texels_.size() * sizeof(float) + (max_abs_.size() + max_step_.size()) * sizeof(float);
  }

 private:
  void build(std::uint32_t seed) {
    using cd = std::complex<double>;
    const auto n = static_cast<std::size_t>(size_);
    // F: Hermitian complex Gaussian white noise, F(k) = (g(k) + conj g(-k)) / sqrt 2
    // with g i.i.d. complex Gaussian of unit power: E|F(k)|^2 = 1 on every bin.
    std::vector<cd> g(n * n);
    rng gen(seed, 0x7a11e5u);  // the tiles' own stream of the seed
    for (cd& v : g) {
      const double re = gen.gaussian<double>(), im = gen.gaussian<double>();
      v = cd(re, im) * std::sqrt(0.5);
    }
    std::vector<cd> f(n * n);
    for (std::size_t y = 0; y < n; ++y)
      for (std::size_t x = 0; x < n; ++x) {
        const std::size_t my = (n - y) % n, mx = (n - x) % n;
        f[y * n + x] = (g[y * n + x] + std::conj(g[my * n + mx])) * std::sqrt(0.5);
      }
    steerable_bank::params bp;
    bp.orientations = orientations_;
    bp.scales = 1;
    bp.base_frequency = detail::constants::kAnisoTileBand;
    const steerable_bank bank(bp);
    // Per bin: the radial band B (shared by the orientations) and cos(theta -
    // theta_i) for each orientation; D_i = G(cos) B, as steerable_bank::subband.
    const std::size_t kk = static_cast<std::size_t>(orientations_);
    std::vector<double> filter(n * n * kk, 0.0);
    for (std::size_t y = 0; y < n; ++y)
      for (std::size_t x = 0; x < n; ++x) {
        const dvec2 w{detail::bin_frequency(x, n), detail::bin_frequency(y, n)};
        const double b = bank.scale_band(0, w);
        if (b == 0.0) continue;
        const double r = std::hypot(w.x, w.y);
        for (std::size_t i = 0; i < kk; ++i) {
          const dvec2& d = bank.direction(static_cast<int>(i));
          filter[(y * n + x) * kk + i] =
              steerable_bank::angular(orientations_, (w.x * d.x + w.y * d.y) / r) * b;
        }
      }
    // Normalisation: the continuous-plane variance of the bilinear interpolant
    // of s = sum_i n_i is (1/N^4) sum_k |S(k)|^2 a(k_x) a(k_y) with
    // a(k) = (2 + cos(2 pi k / N)) / 3 (the mean of |(1 - t) + t e^{i w}|^2 over t).
    std::vector<double> a1(n);
    for (std::size_t x = 0; x < n; ++x)
      a1[x] = (2.0 + std::cos(2.0 * detail::constants::kPi * detail::bin_frequency(x, n))) / 3.0;
    double var = 0;
    for (std::size_t y = 0; y < n; ++y)
      for (std::size_t x = 0; x < n; ++x) {
        double d = 0;
        for (std::size_t i = 0; i < kk; ++i) d += filter[(y * n + x) * kk + i];
        if (d != 0.0) var += std::norm(f[y * n + x] * d) * a1[x] * a1[y];
      }
    const double nn = static_cast<double>(n * n);
    var /= nn * nn;
    const double scale = var > 0 ? 1.0 / (std::sqrt(var) * nn) : 0.0;  // with the IFFT's 1/N^2
    const std::size_t stride = (n + 1) * static_cast<std::size_t>(channels_);
    texels_.assign((n + 1) * stride, 0.0f);
    max_abs_.assign(kk, 0.0f);
    max_step_.assign(kk, 0.0f);
    std::vector<cd> a(n * n);
    for (std::size_t i = 0; i < kk; ++i) {
      for (std::size_t q = 0; q < n * n; ++q) a[q] = f[q] * filter[q * kk + i];
      detail::fft2(a.data(), n, +1);
      for (std::size_t y = 0; y <= n; ++y)
        for (std::size_t x = 0; x <= n; ++x)
          texels_[y * stride + x * static_cast<std::size_t>(channels_) + i] =
              static_cast<float>(a[(y % n) * n + (x % n)].real() * scale);
      float m = 0, step = 0;
      for (std::size_t y = 0; y < n; ++y)
        for (std::size_t x = 0; x < n; ++x) {
          const auto ux = static_cast<std::uint32_t>(x), uy = static_cast<std::uint32_t>(y);
          const float v = texel(ux, uy)[i];
          m = std::max(m, std::fabs(v));
          step = std::max(
              {step, std::fabs(texel(ux + 1, uy)[i] - v), std::fabs(texel(ux, uy + 1)[i] - v)});
        }
      max_abs_[i] = m;
      max_step_[i] = step;
    }
  }

  int size_, orientations_, channels_;
  std::vector<float> texels_;
  std::vector<float> max_abs_, max_step_;
};

class anisotropic : public sample_noise<anisotropic, 2> {
 public:
  static constexpr bool takes_footprint = true;
  static constexpr bool takes_surface_map = true;
  static constexpr int kMaxChannels = 8;

  struct params {
    std::uint32_t seed = 0;
    int orientations = 4;  // K: 2 ... 8
    int scales = 3;        // S: 1 ... 12, subband scales of the bank
    int base_scale = 0;    // scale of octave 0: 0 ... S - 1 (scales below it
                           // serve surface maps that stretch the texture)
    int octaves = 3;       // 1 ... S - base_scale
    double gain = 0.5;     // amplitude ratio between octaves: finite, > 0
    fractal_kind kind = fractal_kind::fbm;
    double frequency = 1.0;  // octave 0's centre frequency, cycles per unit: finite, > 0
    int tile_size = 256;     // N: a power of two, 16 ... 2048
    weight_rule filtering = weight_rule::centre;     // lambda from footprints
    weight_rule compensation = weight_rule::centre;  // gamma from surface maps
  };

  anisotropic() : anisotropic(params{}) {}
  // Throws hush::invalid_argument naming the first parameter out of range.
  explicit anisotropic(const params& prm) : prm_(prm) {
    validate();
    namespace c = detail::constants;
    steerable_bank::params bp;
    bp.orientations = prm_.orientations;
    bp.scales = prm_.scales;
    bp.base_frequency = std::ldexp(prm_.frequency, -prm_.base_scale);
    bank_ = steerable_bank(bp);
    tile_ =
        tile_cache().get(anisotropic_tile::key{prm_.seed, prm_.orientations, prm_.tile_size}, [&] {
          return anisotropic_tile(
              anisotropic_tile::key{prm_.seed, prm_.orientations, prm_.tile_size});
        });
    channels_ = tile_->channels();
    double g = 1.0, sum_sq = 0.0;
    for (int k = 0; k < prm_.octaves; ++k, g *= prm_.gain) {
      octave_gain_[k] = g;
      sum_sq += g * g;
    }
    norm_ = 1.0 / std::sqrt(sum_sq);
    // Pixel filter exponent per scale, in powers of two: lambda = 2^-(kappa_s q),
    // kappa_s = 2 pi^2 sigma^2 f_s^2 log2(e).
    const double sigma = c::kPixelFilterSigma;
    for (int s = 0; s < prm_.scales; ++s) {
      const double f = bank_.centre_frequency(s);
      kappa_[s] = 2.0 * c::kPi * c::kPi * sigma * sigma * f * f * c::kLog2E;
      texels_per_unit_[s] = f / c::kAnisoTileBand;
      rng r(prm_.seed, 0x0ff5e7u + static_cast<std::uint32_t>(s));
      offset_[s] = {r.uniform<double>() * prm_.tile_size, r.uniform<double>() * prm_.tile_size};
    }
    for (int i = 0; i < prm_.orientations; ++i) {
      const dvec2 d = bank_.direction(i);
      dir_[i] = d;
      dxx_[i] = d.x * d.x;
      dyy_[i] = d.y * d.y;
      dxy2_[i] = 2.0 * d.x * d.y;
    }
    // Cap of the heuristic compensation weights: one subband (variance
    // A_K / 2 pi, unit-variance tiles) carrying all of an octave's unit
    // variance has gamma = sqrt(2 pi / A_K), A_K = integral of G_i^2 over the
    // circle = alpha_K^4 2 pi C(4K - 4, 2K - 2) / 4^(2K - 2) (docs/anisotropic.md).
    const int kk = prm_.orientations;
    double binom = 1.0;  // C(4K - 4, 2K - 2) / 4^(2K - 2), as a running product
    for (int m = 1; m <= 2 * kk - 2; ++m)
      binom *= static_cast<double>(2 * kk - 2 + m) / (4.0 * static_cast<double>(m));
    const double a2 = steerable_bank::alpha(kk) * steerable_bank::alpha(kk);
    const double area = a2 * a2 * 2.0 * c::kPi * binom;
    cap_unit_ = std::sqrt(2.0 * c::kPi / area);
    if (prm_.filtering == weight_rule::least_squares ||
        prm_.compensation == weight_rule::least_squares)
      fit_ = std::make_shared<const subband_fit>(bank_);
  }

  const params& parameters() const { return prm_; }
  const steerable_bank& bank() const { return bank_; }
  const anisotropic_tile& tile() const { return *tile_; }
  // The shared tile itself (the GLSL backend keeps its textures while it lives).
  const std::shared_ptr<const anisotropic_tile>& tile_ptr() const { return tile_; }
  int channels() const { return channels_; }

  // The process-wide cache of tiles (memory: tile_cache().live_bytes()).
  static hush::tile_cache<anisotropic_tile::key, anisotropic_tile>& tile_cache() {
    static hush::tile_cache<anisotropic_tile::key, anisotropic_tile> cache;
    return cache;
  }

  // Position of sample p in scale s's tile, in texels (double): p f_s / band
  // + offset; a product beyond double range is a multiple of the tile (cell 0).
  double band_coordinate(int s, int axis, double p) const {
    double q = p * texels_per_unit_[s];
    if (std::isinf(q) && std::isfinite(p)) q = 0.0;  // NaN and Inf positions stay non-finite
    return q + offset_[s][static_cast<std::size_t>(axis)];
  }

  // ---- Per-scale and per-orientation constants (the SIMD and GLSL paths read them).
  double texels_per_unit(int s) const { return texels_per_unit_[s]; }
  const dvec2& offset(int s) const { return offset_[s]; }
  double kappa(int s) const { return kappa_[s]; }
  const dvec2& direction(int i) const { return dir_[i]; }
  // q_i = d_i^T S d_i of footprint fp, orientation i in 0 ... K-1, in double:
  // at grazing angles S is nearly singular with entries of 1e4 and more, and
  // the terms cancel. Range [0, 2 W^2] (W = the footprint's width cap): S rounded
  // to float may be slightly indefinite (q < 0 by ulps of its entries, and
  // 2^-(kappa q) would overflow), so q is clamped at 0, S's singular limit.
  double filter_form(const footprint<2>& fp, int i) const {
    const double sxx = fp.covariance(0, 0), sxy = fp.covariance(0, 1), syy = fp.covariance(1, 1);
    return std::max((sxx * dxx_[i] + sxy * dxy2_[i]) + syy * dyy_[i], 0.0);
  }
  double octave_weight(int k) const { return norm_ * octave_gain_[k]; }
  double normalization() const { return norm_; }
  // Cap of a heuristic compensation weight.
  double gamma_cap() const { return cap_unit_; }

  // Variance without map and filter (fbm): 1.
  static constexpr double variance() { return 1.0; }
  // |n| <= bound() without surface maps, for every footprint (lambda <= 1).
  double bound() const {
    double t = 0;
    for (int i = 0; i < prm_.orientations; ++i) t += tile_->max_abs(i);
    double g = 0;
    for (int k = 0; k < prm_.octaves; ++k) g += octave_weight(k);
    return t * g;
  }
  // |n| <= bound_with_maps() for every surface map under the heuristic rules:
  // per octave and orientation at most 3 scales have a weight (2 for the
  // centre rule), each at most gamma_cap().
  double bound_with_maps() const {
    double t = 0;
    for (int i = 0; i < prm_.orientations; ++i) t += tile_->max_abs(i);
    double g = 0;
    for (int k = 0; k < prm_.octaves; ++k) g += octave_weight(k);
    return t * g * std::min(prm_.scales, 3) * cap_unit_;
  }
  // |float - double| at the same input is within float_budget() (no map,
  // heuristic rules): the float weights' relative error (2^-20: the
  // approximations of approx_math.hpp plus the products forming them) on
  // bound(), plus the lookups' rounding: 8 float operations per subband on
  // values up to bound() (docs/anisotropic.md, "Float error").
  double float_budget() const {
    const int subbands = prm_.scales * channels_;
    return bound() * (std::ldexp(1.0, -20) + (8.0 + subbands) * std::ldexp(1.0, -24));
  }

  // ---- Evaluation (core/point_noise.hpp and core/samples.hpp give the public overloads).
  template <class T>
  T value(const vec<double, 2>& p) const {
    return sample_value<T>(sample_input<2>{p, {}, {}, false, {}, false});
  }
  template <class T>
  value_gradient<T, 2> value_and_gradient(const vec<double, 2>& p) const {
    return sample_value_and_gradient<T>(sample_input<2>{p, {}, {}, false, {}, false});
  }
  template <class T>
  T sample_value(const sample_input<2>& in) const {
    return eval<T, false>(in).value;
  }
  template <class T>
  value_gradient<T, 2> sample_value_and_gradient(const sample_input<2>& in) const {
    return eval<T, true>(in);
  }

  // The combined weights of a sample (fbm; turbulence: octave 0's... see
  // octave_weights): w[i + channels() s] = sum_k gamma_{k,i,s} lambda_{i,s}
  // times the octave weights, 0 for padding channels.
  template <class T>
  void weights(const sample_input<2>& in, T* w) const {
    T lambda[detail::constants::kAnisoMaxScales * kMaxChannels];
    filter_weights<T>(in.fp, lambda);
    combine<T>(in, lambda, -1, w);
  }
  // The weights of octave k alone (turbulence), gain^k not included.
  template <class T>
  void octave_weights(const sample_input<2>& in, int k, T* w) const {
    T lambda[detail::constants::kAnisoMaxScales * kMaxChannels];
    filter_weights<T>(in.fp, lambda);
    combine<T>(in, lambda, k, w);
  }

  // lambda_{i,s} into lam[i + channels() s].
  template <class T>
  void filter_weights(const footprint<2>& fp, T* lam) const {
    namespace c = detail::constants;
    const int kc = channels_;
    std::fill(lam, lam + prm_.scales * kc, T(0));
    if (fp.is_point()) {
      for (int s = 0; s < prm_.scales; ++s)
        for (int i = 0; i < prm_.orientations; ++i) lam[i + kc * s] = T(1);
      return;
    }
    if (prm_.filtering == weight_rule::least_squares) {
      const double sxx = fp.covariance(0, 0), sxy = fp.covariance(0, 1), syy = fp.covariance(1, 1);
      const double k2 = 2.0 * c::kPi * c::kPi * c::kPixelFilterSigma * c::kPixelFilterSigma;
      std::vector<double> w = fit_->fit(weight_rule::least_squares, [&](const dvec2& x) {
        // Clamped like the centre rule's q: an indefinite S would give exp(+huge).
        return std::exp(
            -k2 * std::max(sxx * x.x * x.x + 2.0 * sxy * x.x * x.y + syy * x.y * x.y, 0.0));
      });
      for (int s = 0; s < prm_.scales; ++s)
        for (int i = 0; i < prm_.orientations; ++i)
          lam[i + kc * s] = static_cast<T>(w[detail::index(i + prm_.orientations * s)]);
      return;
    }
    const T cut = T(c::kAnisoWeightCutoff * c::kLog2E);
    const bool three = prm_.filtering == weight_rule::three_point;
    for (int i = 0; i < prm_.orientations; ++i) {
      const double q = filter_form(fp, i);
      for (int s = 0; s < prm_.scales; ++s) {
        const T z = T(kappa_[s] * q);
        lam[i + kc * s] = three ? lambda3(z, cut) : lambda1(z, cut);
      }
    }
  }

 private:
  void validate() const {
    namespace c = detail::constants;
    const char* w = "hush::anisotropic";
    detail::require_in_range(w, "orientations", prm_.orientations, c::kAnisoMinOrientations,
                             c::kAnisoMaxOrientations, "2 ... 8");
    detail::require_in_range(w, "scales", prm_.scales, 1, c::kAnisoMaxScales, "1 ... 12");
    detail::require_in_range(w, "base_scale", prm_.base_scale, 0, prm_.scales - 1,
                             ("0 ... scales - 1 = " + std::to_string(prm_.scales - 1)).c_str());
    detail::require_in_range(
        w, "octaves", prm_.octaves, 1, prm_.scales - prm_.base_scale,
        ("1 ... scales - base_scale = " + std::to_string(prm_.scales - prm_.base_scale)).c_str());
    if (!(prm_.gain > 0.0 && prm_.gain <= 1e6))
      detail::throw_out_of_range(w, "gain", prm_.gain, "a number in (0, 1e6]");
    if (!(prm_.frequency > 0.0 && prm_.frequency <= 1e12))
      detail::throw_out_of_range(w, "frequency", prm_.frequency,
                                 "a number in (0, 1e12] (cycles per unit)");
    const int n = prm_.tile_size;
    if (n < c::kAnisoMinTileSize || n > c::kAnisoMaxTileSize || (n & (n - 1)) != 0)
      detail::throw_out_of_range(w, "tile_size", n, "a power of two, 16 ... 2048");
    if (prm_.kind != fractal_kind::fbm && prm_.kind != fractal_kind::turbulence)
      hush::detail::raise_error(std::string(w) + ": kind is not fbm or turbulence");
  }

  // Least-squares compensation weights of octaves [k0, k1) for map m (each
  // 2^(s - b - k) gamma_{k,i,s}, octave after octave), cached per distinct map:
  // a batch over a mesh solves once per triangle. The cache (the last
  // kLsqCacheSize maps) is shared by copies of the noise and locked; lookups copy.
  std::vector<double> lsq_gamma(const surface_map& m, int k0, int k1) const {
    lsq_cache& cache = *lsq_cache_;
    {
      const std::lock_guard<std::mutex> lock(cache.mutex);
      for (const auto& e : cache.entries)
        if (e.map == m && e.k0 == k0 && e.k1 == k1) return e.gamma;
    }
    const int b = prm_.base_scale;
    const double sd = std::sqrt(std::fabs(m.determinant()));
    std::vector<double> gamma;
    for (int k = k0; k < k1; ++k) {
      const double fk = bank_.centre_frequency(b + k);
      std::vector<double> g = fit_->fit(weight_rule::least_squares, [&](const dvec2& x) {
        const double tu = double(m.m00) * x.x + double(m.m10) * x.y;
        const double tv = double(m.m01) * x.x + double(m.m11) * x.y;
        const double r = std::sqrt(tu * tu + tv * tv);
        return r > 0 ? sd * steerable_bank::radial(std::log2(r / fk)) : 0.0;
      });
      for (int s = 0; s < prm_.scales; ++s)
        for (int i = 0; i < prm_.orientations; ++i) {
          double& v = g[detail::index(i + prm_.orientations * s)];
          v = std::ldexp(v, s - b - k);
        }
      gamma.insert(gamma.end(), g.begin(), g.end());
    }
    const std::lock_guard<std::mutex> lock(cache.mutex);
    if (cache.entries.size() < kLsqCacheSize) {
      cache.entries.push_back({m, k0, k1, gamma});
    } else {
      cache.entries[cache.next] = {m, k0, k1, gamma};
      cache.next = (cache.next + 1) % kLsqCacheSize;
    }
    return gamma;
  }

  // exp(-x) for z = x log2(e) >= 0, 0 beyond the cutoff.
  template <class T>
  static T lambda1(T z, T cut) {
    return z > cut ? T(0) : detail::exp2_nonpositive(-z);
  }
  // The 3-radial-point rule: 1/4 exp(-x/2) + 1/2 exp(-x) + 1/4 exp(-2x).
  template <class T>
  static T lambda3(T z, T cut) {
    namespace c = detail::constants;
    const T lo = lambda1(z * T(0.5), cut), mid = lambda1(z, cut), hi = lambda1(z * T(2), cut);
    return (T(c::kAnisoThreePointSide) * lo + T(c::kAnisoThreePointCentre) * mid) +
           T(c::kAnisoThreePointSide) * hi;
  }

  // Combines gamma (from the map) with lam into w: all octaves with their
  // weights (octave < 0, fbm) or one octave without its gain.
  template <class T>
  void combine(const sample_input<2>& in, const T* lam, int octave, T* w) const {
    namespace c = detail::constants;
    const int kc = channels_, b = prm_.base_scale;
    std::fill(w, w + prm_.scales * kc, T(0));
    const int k0 = octave < 0 ? 0 : octave, k1 = octave < 0 ? prm_.octaves : octave + 1;
    auto ow = [&](int k) { return T(octave < 0 ? octave_weight(k) : norm_); };
    if (!in.has_map) {
      for (int k = k0; k < k1; ++k)
        for (int i = 0; i < prm_.orientations; ++i)
          w[i + kc * (b + k)] = ow(k) * lam[i + kc * (b + k)];
      return;
    }
    const surface_map m = in.map.finite() ? in.map : surface_map::zero();
    if (prm_.compensation == weight_rule::least_squares) {
      const std::vector<double> g = lsq_gamma(m, k0, k1);
      for (int k = k0; k < k1; ++k)
        for (int s = 0; s < prm_.scales; ++s)
          for (int i = 0; i < prm_.orientations; ++i)
            w[i + kc * s] +=
                ow(k) *
                T(g[detail::index((k - k0) * bank_.subbands() + i + prm_.orientations * s)]) *
                lam[i + kc * s];
      return;
    }
    const bool three = prm_.compensation == weight_rule::three_point;
    const T cap = T(cap_unit_);
    // det T and |T^T w|^2 in double (they cancel for nearly singular maps),
    // the transcendental functions in T.
    const double m00 = m.m00, m01 = m.m01, m10 = m.m10, m11 = m.m11;
    const T sd = std::sqrt(T(std::fabs(m00 * m11 - m01 * m10)));
    for (int i = 0; i < prm_.orientations; ++i) {
      const double tu = m00 * dir_[i].x + m10 * dir_[i].y, tv = m01 * dir_[i].x + m11 * dir_[i].y;
      const T half_log = T(0.5) * detail::log2_positive(T(tu * tu + tv * tv));
      for (int s = 0; s < prm_.scales; ++s) {
        T acc = T(0);
        for (int k = k0; k < k1; ++k) {
          const T x = T(s - b - k) + half_log;
          const T prof = three ? (T(c::kAnisoThreePointSide) * detail::band_profile(x - T(0.5)) +
                                  T(c::kAnisoThreePointCentre) * detail::band_profile(x)) +
                                     T(c::kAnisoThreePointSide) * detail::band_profile(x + T(0.5))
                               : detail::band_profile(x);
          // 2^(s - b - k) sqrt|det T| prof, capped (exact power of two in T).
          const T gamma =
              prof > T(0) ? std::min(T(std::ldexp(1.0, s - b - k)) * (sd * prof), cap) : T(0);
          acc = acc + ow(k) * gamma;
        }
        w[i + kc * s] = acc * lam[i + kc * s];
      }
    }
  }

  template <class T, bool WithGradient>
  value_gradient<T, 2> eval(const sample_input<2>& in) const {
    value_gradient<T, 2> r{T(0), {T(0), T(0)}};
    if (!std::isfinite(in.position.x) || !std::isfinite(in.position.y)) {
      const T nan = std::numeric_limits<T>::quiet_NaN();
      return {nan, {nan, nan}};
    }
    const int kc = channels_;
    T lam[detail::constants::kAnisoMaxScales * kMaxChannels];
    T w[detail::constants::kAnisoMaxScales * kMaxChannels];
    filter_weights<T>(in.fp, lam);
    if (prm_.kind == fractal_kind::fbm) {
      combine<T>(in, lam, -1, w);
      T acc[kMaxChannels] = {}, gx[kMaxChannels] = {}, gy[kMaxChannels] = {};
      for (int s = 0; s < prm_.scales; ++s)
        accumulate<T, WithGradient>(in.position, s, w + kc * s, acc, gx, gy);
      r.value = channel_sum(acc);
      if constexpr (WithGradient) r.gradient = {channel_sum(gx), channel_sum(gy)};
      return r;
    }
    for (int k = 0; k < prm_.octaves; ++k) {
      combine<T>(in, lam, k, w);
      T acc[kMaxChannels] = {}, gx[kMaxChannels] = {}, gy[kMaxChannels] = {};
      for (int s = 0; s < prm_.scales; ++s)
        accumulate<T, WithGradient>(in.position, s, w + kc * s, acc, gx, gy);
      const T v = channel_sum(acc), g = T(octave_gain_[k]);
      const T sign = v < T(0) ? T(-1) : T(1);
      r.value = r.value + g * std::fabs(v);
      if constexpr (WithGradient)
        r.gradient = {r.gradient.x + g * sign * channel_sum(gx),
                      r.gradient.y + g * sign * channel_sum(gy)};
    }
    return r;
  }

  // acc[c] += w[c] * bilinear(tile channel c at scale s); skipped when every w[c] is 0.
  template <class T, bool WithGradient>
  void accumulate(const vec<double, 2>& p, int s, const T* w, T* acc, T* gx, T* gy) const {
    const int kc = channels_;
    bool any = false;
    for (int c = 0; c < kc; ++c) any = any || w[c] != T(0);
    if (!any) return;
    const auto n = static_cast<std::uint32_t>(prm_.tile_size);
    const lattice_coord<T> cx = lattice_split<T>(band_coordinate(s, 0, p.x), n);
    const lattice_coord<T> cy = lattice_split<T>(band_coordinate(s, 1, p.y), n);
    const float* t00 = tile_->texel(cx.i0, cy.i0);
    const float* t01 = t00 + tile_->row_stride();
    const T fx = cx.f, fy = cy.f;
    for (int c = 0; c < kc; ++c) {
      const T c00 = T(t00[c]), c10 = T(t00[kc + c]), c01 = T(t01[c]), c11 = T(t01[kc + c]);
      const T r0 = c00 + fy * (c01 - c00), r1 = c10 + fy * (c11 - c10);
      const T v = r0 + fx * (r1 - r0);
      acc[c] = acc[c] + w[c] * v;
      if constexpr (WithGradient) {
        const T scale = T(texels_per_unit_[s]);
        const T dx = r1 - r0;
        const T dy = (c01 - c00) + fx * ((c11 - c10) - (c01 - c00));
        gx[c] = gx[c] + w[c] * (scale * dx);
        gy[c] = gy[c] + w[c] * (scale * dy);
      }
    }
  }

  // Sum of the channels in a fixed tree order (the SIMD kernel's).
  template <class T>
  T channel_sum(const T* a) const {
    const T s4 = (a[0] + a[1]) + (a[2] + a[3]);
    if (channels_ == 4) return s4;
    return s4 + ((a[4] + a[5]) + (a[6] + a[7]));
  }

  params prm_;
  steerable_bank bank_;
  std::shared_ptr<const anisotropic_tile> tile_;
  std::shared_ptr<const subband_fit> fit_;  // least-squares rules only
  static constexpr std::size_t kLsqCacheSize = 256;
  struct lsq_cache {
    struct entry {
      surface_map map;
      int k0, k1;
      std::vector<double> gamma;
    };
    std::mutex mutex;
    std::vector<entry> entries;  // at most kLsqCacheSize, then overwritten oldest first
    std::size_t next = 0;
    lsq_cache() { entries.reserve(kLsqCacheSize); }
  };
  std::shared_ptr<lsq_cache> lsq_cache_ = std::make_shared<lsq_cache>();
  int channels_ = 4;
  double norm_ = 1.0, cap_unit_ = 1.0;
  double octave_gain_[detail::constants::kAnisoMaxScales] = {};
  double kappa_[detail::constants::kAnisoMaxScales] = {};
  double texels_per_unit_[detail::constants::kAnisoMaxScales] = {};
  dvec2 offset_[detail::constants::kAnisoMaxScales] = {};
  dvec2 dir_[detail::constants::kAnisoMaxOrientations] = {};
  double dxx_[detail::constants::kAnisoMaxOrientations] = {};
  double dyy_[detail::constants::kAnisoMaxOrientations] = {};
  double dxy2_[detail::constants::kAnisoMaxOrientations] = {};
};

}  // namespace hush

// The SIMD backend's entry points and exec::simd binding, after the class they use.
#include "hush/anisotropic/simd_kernel.hpp"  // IWYU pragma: export

#endif  // HUSH_ANISOTROPIC_HPP
