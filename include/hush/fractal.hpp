// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Fractal sums of a base noise over octaves ("bands"): fBm and turbulence.
//
//   fbm(x)        = (1/K) sum_i w_i n_i(f_i x + o_i)
//   turbulence(x) = (1/K) sum_i w_i |n_i(f_i x + o_i)|
//
// with f_i = frequency * lacunarity^i, per-band weights w_i (gain^i by default,
// or given explicitly), and per-band independent fields n_i: band i uses seed
// hash32(seed, i) and a lattice offset o_i in [0, 1)^D derived from it, so
// bands are uncorrelated and their lattices do not all meet at the origin.
//
// Variance (Perlin base, over space and seeds; docs/design.md):
//   Var[sum_i w_i n_i] = sigma^2 sum_i w_i^2,  sigma^2 = Noise::variance(),
// because independent bands have zero covariance. The normalisation K makes
// the output
//   - normalization::unit_variance (fBm only): variance exactly 1, mean 0;
//     |fbm| <= sum|w_i| / (sigma sqrt(sum w_i^2)) (bound(), analytic);
//   - normalization::unit_range: |output| <= 1 (K = sum |w_i| * Noise::bound());
//     turbulence with non-negative weights then lies in [0, 1];
//   - normalization::none: K = 1, the raw sum.
// Periodic: with period[a] = p > 0 band i uses period p * lacunarity^i, so the
// sum repeats every p / frequency along axis a (lacunarity must be an integer).
// Domain: as the base noise; every finite input gives a finite output, and a
// NaN or infinite coordinate gives NaN.
#ifndef HUSH_FRACTAL_HPP
#define HUSH_FRACTAL_HPP

#include <algorithm>
#include <array>
#include <climits>
#include <cstddef>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "hush/core/error.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/point_noise.hpp"
#include "hush/core/views.hpp"
#include "hush/core/vec.hpp"

namespace hush {

enum class fractal_kind { fbm, turbulence };
enum class normalization { unit_variance, unit_range, none };

template <class Noise>
class fractal : public point_noise<fractal<Noise>, Noise::dimension> {
  static constexpr int D = Noise::dimension;

 public:
  static constexpr int kMaxOctaves = 32;

  struct params {
    std::uint32_t seed = 0;
    fractal_kind kind = fractal_kind::fbm;
    int octaves = 5;              // 1 ... 32
    double frequency = 1.0;       // of band 0, > 0 and finite
    double lacunarity = 2.0;      // frequency ratio between bands, 1 < l <= 16
    double gain = 0.5;            // w_i = gain^i when weights is empty; finite, > 0
    std::vector<double> weights;  // explicit band weights: empty, or `octaves` finite values
    normalization norm = normalization::unit_variance;
    // Per axis, in band-0 lattice units; 0 = not periodic.
    std::array<int, std::size_t{D}> period{};
  };

  fractal() : fractal(params{}) {}  // 5 octaves of fBm, unit variance, seed 0
  // Throws hush::invalid_argument naming the first parameter out of range.
  explicit fractal(const params& prm) : prm_(prm) {
    validate();
    double sum_sq = 0, sum_abs = 0;
    // Powers by repeated multiplication, not std::pow: IEEE multiplication is
    // the same everywhere, libm's pow is not (determinism across platforms).
    double gain_i = 1.0, lac_i = 1.0;
    for (int i = 0; i < prm_.octaves; ++i, gain_i *= prm_.gain, lac_i *= prm_.lacunarity) {
      const double w = prm_.weights.empty() ? gain_i : prm_.weights[static_cast<std::size_t>(i)];
      const std::uint32_t band_seed = hash32(prm_.seed, static_cast<std::uint32_t>(i));
      typename Noise::params np{};
      np.seed = band_seed;
      for (std::size_t a = 0; a < D; ++a)
        np.period[a] = prm_.period[a] == 0 ? 0 : static_cast<int>(prm_.period[a] * lac_i);
      vec<double, D> offset;
      for (int a = 0; a < D; ++a)  // 24 hash bits: an exact fraction in [0, 1)
        offset[a] = (hash32(band_seed, static_cast<std::uint32_t>(a)) >> 8) * 0x1p-24;
      bands_.push_back({Noise(np), prm_.frequency * lac_i, w, offset});
      sum_sq += w * w;
      sum_abs += std::fabs(w);
    }
    // Every weight (explicit or gain^i) within the band weights' range (detail/constants.hpp),
    // so the sums, the normalisation and the bound are finite and non-zero.
    double largest = 0;
    for (std::size_t i = 0; i < bands_.size(); ++i) {
      const double w = std::fabs(bands_[i].weight);
      if (!(w <= detail::constants::kMaxBandWeight))
        detail::throw_out_of_range(
            "hush::fractal", prm_.weights.empty() ? std::string("gain") : "weights[" + std::to_string(i) + "]",
            prm_.weights.empty() ? prm_.gain : prm_.weights[i],
            prm_.weights.empty() ? "a gain whose powers gain^i (i < octaves) stay <= 1e30"
                                 : "|w| <= 1e30");
      largest = std::max(largest, w);
    }
    if (!(largest >= detail::constants::kMinLargestBandWeight))
      hush::detail::raise_error(
          "hush::fractal: every band weight is below 1e-30 in magnitude; valid: the largest "
          "|w| in 1e-30 ... 1e30 (only the weights' ratios matter under normalisation)");
    switch (prm_.norm) {
      case normalization::unit_variance:
        scale_ = 1.0 / std::sqrt(Noise::variance() * sum_sq);
        break;
      case normalization::unit_range:
        scale_ = 1.0 / (sum_abs * Noise::bound());
        break;
      case normalization::none:
        scale_ = 1.0;
        break;
    }
    bound_ = scale_ * sum_abs * Noise::bound();
    variance_ = prm_.kind == fractal_kind::fbm ? scale_ * scale_ * Noise::variance() * sum_sq : -1;
  }

  const params& parameters() const { return prm_; }
  // |output| <= bound() for every input (analytic, from |n_i| <= Noise::bound()).
  double bound() const { return bound_; }
  // Variance over space and seeds of fBm (1 under unit_variance); turbulence: -1 (not derived).
  double variance() const { return variance_; }
  // The weight and frequency of band i, after normalisation.
  double band_weight(int i) const { return bands_[static_cast<std::size_t>(i)].weight * scale_; }
  double band_frequency(int i) const { return bands_[static_cast<std::size_t>(i)].frequency; }

  // The bands as evaluated, for backends that run them themselves (hush/simd):
  // band i's noise, its raw weight w_i (before the normalisation scale()),
  // its frequency, and its position f_i x + o_i in double, exactly as value()
  // forms it.
  int band_count() const { return static_cast<int>(bands_.size()); }
  const Noise& band_noise(int i) const { return bands_[static_cast<std::size_t>(i)].noise; }
  double band_raw_weight(int i) const { return bands_[static_cast<std::size_t>(i)].weight; }
  vec<double, D> band_position(int i, const vec<double, D>& p) const {
    return bands_[static_cast<std::size_t>(i)].position(p);
  }
  // The normalisation factor K applied to the weighted sum.
  double scale() const { return scale_; }

  // Band positions f_i x + o_i are formed in double; each band evaluates in T.
  template <class T>
  T value(const vec<double, D>& p) const {
    T sum = 0;
    for (const band& b : bands_) add_value(b, b.noise.template value<T>(b.position(p)), sum);
    return T(scale_) * sum;
  }
  // Gradient of the sum. For turbulence, |n| is not differentiable where n = 0;
  // there the gradient of +n is returned.
  template <class T>
  value_gradient<T, D> value_and_gradient(const vec<double, D>& p) const {
    value_gradient<T, D> r{T(0), {}};
    for (const band& b : bands_)
      add_value_gradient(b, b.noise.template value_and_gradient<T>(b.position(p)), r);
    scale_value_gradient(r);
    return r;
  }

  // The samples of `g` with slowest-axis index in [first, first + count), as
  // exec::scalar asks for them (exec.hpp), when the bands evaluate grids of
  // positions themselves (perlin's grid_rows_at): each band runs its grid
  // path over the band positions f_i x + o_i (formed per axis as value()
  // forms them) and the bands are summed in order with value() /
  // value_and_gradient()'s operations. So values and gradients are point
  // evaluation's except where the band's grid path says otherwise (Perlin
  // 3D gradients on rows with shared cells: the affine-in-x form,
  // docs/design.md); hush/simd's fractal grids compute the same.
  template <class N = Noise, class = decltype(&N::template grid_rows_at<double (*)(std::size_t),
                                                                        double (*)(std::size_t),
                                                                        double (*)(std::size_t)>)>
  void grid_values(const grid<D>& g, std::size_t first, std::size_t count, float* out,
                   vec<float, D>* grad) const {
    const std::size_t nx = g.size[0];
    const std::size_t j0 = D == 2 ? first : 0, j1 = D == 2 ? first + count : g.size[1];
    const std::size_t k0 = D == 3 ? first : 0, k1 = D == 3 ? first + count : 1;
    const std::size_t n = nx * (j1 - j0) * (k1 - k0);
    std::vector<float> bv(n);
    std::vector<vec<float, D>> bg(grad ? n : 0);
    std::vector<value_gradient<float, D>> sum(grad ? n : 0, value_gradient<float, D>{0.0f, {}});
    std::fill(out, out + n, 0.0f);
    for (const band& b : bands_) {
      // Band position along axis a of grid index `index`: f_i x + o_i.
      auto at = [&](int a) {
        return [&, a](std::size_t index) {
          vec<double, D> p{};
          p[a] = g.coordinate(a, index);
          return b.position(p)[a];
        };
      };
      b.noise.grid_rows_at(nx, at(0), j0, j1, at(1), k0, k1, at(D - 1), bv.data(),
                           grad ? bg.data() : nullptr);
      for (std::size_t i = 0; i < n; ++i) {
        if (grad)
          add_value_gradient(b, value_gradient<float, D>{bv[i], bg[i]}, sum[i]);
        else
          add_value(b, bv[i], out[i]);
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (grad) {
        scale_value_gradient(sum[i]);
        out[i] = sum[i].value;
        grad[i] = sum[i].gradient;
      } else {
        out[i] *= float(scale_);
      }
    }
  }

 private:
  struct band {
    Noise noise;
    double frequency;
    double weight;
    vec<double, D> offset;
    // f x + o in double. Where a finite x overflows (|x f| > DBL_MAX), the
    // exact product is a multiple of 2^32, i.e. lattice cell 0 with fraction
    // 0 under the 2^32-cell wrap (core/lattice.hpp), so 0 is the exact band
    // coordinate, and a finite input keeps giving a finite output.
    vec<double, D> position(const vec<double, D>& p) const {
      vec<double, D> q;
      for (int a = 0; a < D; ++a) {
        q[a] = p[a] * frequency + offset[a];
        if (!std::isfinite(q[a]) && std::isfinite(p[a])) q[a] = 0.0;
      }
      return q;
    }
  };

  // One band's term of the sums in value() and value_and_gradient().
  template <class T>
  void add_value(const band& b, T n, T& sum) const {
    sum += T(b.weight) * (prm_.kind == fractal_kind::fbm ? n : std::fabs(n));
  }
  template <class T>
  void add_value_gradient(const band& b, const value_gradient<T, D>& ng,
                          value_gradient<T, D>& r) const {
    T sign = T(1);
    if (prm_.kind == fractal_kind::turbulence && ng.value < T(0)) sign = T(-1);
    r.value += T(b.weight) * sign * ng.value;
    const T chain = T(b.weight * b.frequency) * sign;  // d(f x + o)/dx = f
    for (int a = 0; a < D; ++a) r.gradient[a] += chain * ng.gradient[a];
  }
  template <class T>
  void scale_value_gradient(value_gradient<T, D>& r) const {
    r.value *= T(scale_);
    for (int a = 0; a < D; ++a) r.gradient[a] *= T(scale_);
  }

  void validate() const {
    const char* where = "hush::fractal";
    detail::require_in_range(where, "octaves", prm_.octaves, 1, kMaxOctaves, "1 ... 32");
    if (!(std::isfinite(prm_.frequency) && prm_.frequency > 0))
      detail::throw_out_of_range(where, "frequency", prm_.frequency, "finite and > 0");
    if (!(prm_.lacunarity > 1.0 && prm_.lacunarity <= 16.0))
      detail::throw_out_of_range(where, "lacunarity", prm_.lacunarity, "1 < lacunarity <= 16");
    if (prm_.weights.empty()) {
      if (!(std::isfinite(prm_.gain) && prm_.gain > 0))
        detail::throw_out_of_range(where, "gain", prm_.gain, "finite and > 0");
      // gain^(octaves-1) must stay a normal double for the weights to mean anything.
      const double smallest = std::pow(prm_.gain, prm_.octaves - 1);
      if (!(std::isfinite(smallest) && smallest >= 1e-300))
        detail::throw_out_of_range(where, "gain", prm_.gain,
                                   "gain^(octaves-1) finite and >= 1e-300");
    } else {
      if (prm_.weights.size() != static_cast<std::size_t>(prm_.octaves))
        detail::throw_out_of_range(where, "weights.size()", prm_.weights.size(),
                                   "empty (use gain) or equal to octaves");
      bool any = false;
      for (std::size_t i = 0; i < prm_.weights.size(); ++i) {
        if (!std::isfinite(prm_.weights[i]))
          detail::throw_out_of_range(where, "weights[" + std::to_string(i) + "]", prm_.weights[i],
                                     "a finite number");
        any = any || prm_.weights[i] != 0.0;
      }
      if (!any)
        hush::detail::raise_error(
            "hush::fractal: weights are all zero; valid: at least one non-zero weight");
    }
    if (prm_.kind == fractal_kind::turbulence && prm_.norm == normalization::unit_variance)
      hush::detail::raise_error(
          "hush::fractal: norm = unit_variance is not available for turbulence; valid: "
          "unit_range or none");
    for (std::size_t a = 0; a < D; ++a) {
      const std::string name = "period[" + std::to_string(a) + "]";
      if (prm_.period[a] < 0)
        detail::throw_out_of_range(where, name, prm_.period[a], "0 (not periodic) or >= 1");
      if (prm_.period[a] == 0) continue;
      if (prm_.lacunarity != std::floor(prm_.lacunarity))
        detail::throw_out_of_range(where, "lacunarity", prm_.lacunarity,
                                   "an integer (2 ... 16) when a period is set");
      const double top = prm_.period[a] * std::pow(prm_.lacunarity, prm_.octaves - 1);
      if (top > INT_MAX)
        detail::throw_out_of_range(where, name, prm_.period[a],
                                   "period * lacunarity^(octaves-1) <= 2147483647");
    }
  }

  params prm_;
  std::vector<band> bands_;
  double scale_ = 1, bound_ = 1, variance_ = 1;
};

}  // namespace hush

// The SIMD backend's entry points and exec::simd binding, after the class they use.
#include "hush/fractal/simd_kernel.hpp"  // IWYU pragma: export

#endif  // HUSH_FRACTAL_HPP
