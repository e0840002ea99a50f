// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Gabor noise (Lagae, Lefebvre, Drettakis, Dutre, "Procedural noise using
// sparse Gabor convolution", SIGGRAPH 2009): a sparse convolution of Gabor
// kernels (hush/gabor/kernel.hpp) at Poisson-distributed impulses with random
// weights, in 2D, 3D (solid) and on surfaces, with exact spectral control and
// analytic anti-aliasing.
//
//   hush::gabor<2>::params prm;                  // isotropic, F0 = 1, a = 0.8, N' = 16
//   prm.kind = hush::gabor_kind::anisotropic;
//   prm.orientation = 0.25 * 3.14159;            // omega0, radians
//   hush::gabor<2> noise{prm};
//   float v = noise(hush::vec2{x, y});                              // unit variance
//   float f = noise.sample(hush::vec2{x, y},                        // filtered over a pixel
//                          hush::footprint<2>::from_derivatives(dpdx, dpdy));
//   hush::gabor<3> solid{hush::gabor<3>::params{}};
//   float s = solid.sample(p, normal, fp);       // surface noise (sec. 4.3)
//
// The noise (paper sec. 3.2, eq. 6): n(x) = scale sum_i w_i g_{F_i}(x - x_i),
//  - impulses x_i: a Poisson process of density lambda = N' / (V_D r^D), so
//    that N' kernels overlap a point on average (N' = `impulses`; V_D the
//    volume of the unit ball, r the kernel radius). Space is cut into cells of
//    side r; cell c's impulses come from its own stream
//    hush::rng(lattice_hash(key, c), kGaborSolidStream), key = seed_key(seed):
//    the count from the first word through hush::poisson_table (integer
//    comparisons, so every backend draws the same counts), then per impulse
//    16-bit halves of the next words: position in the cell, weight, then the
//    orientation and frequency its kind draws (gabor_marks below). Cells are
//    32-bit (core/lattice.hpp): any seed, any cell, period 2^32 cells.
//  - weights w_i uniform in (-1, 1) (symmetric 16-bit values, E[w^2] =
//    (1 - 2^-32) / 3), so the noise has mean 0;
//  - kinds (paper sec. 3.3): anisotropic (every F_i = F0 omega0), isotropic
//    (omega_i uniform on the circle or sphere), hybrid (omega_i uniform in an
//    orientation range around omega0 of width orientation_spread: an arc in 2D,
//    a spherical cap of that apex angle in 3D; |F_i| uniform in F0 +-
//    frequency_spread / 2).
//
// Statistics (derived in docs/gabor.md; measured in tests/gabor/gabor_test.cpp):
//  - mean 0 and variance exactly 1 over space and seeds: scale = 1 / sqrt(
//    lambda E[w^2] E[int g_F^2]) (Campbell's theorem: the zero-mean weights
//    make it independent of the count distribution beyond its mean, which is
//    the Poisson table's exact mean), with the kernel energy integrated by
//    quadrature (exact, not the paper's approximation K^2 / 4a^2).
//  - power spectrum: lambda E[w^2] E[|g^_F(f)|^2] scale^2 (paper eq. 8),
//    power_spectrum(f); isotropic noise's is a ring at |f| = F0, anisotropic
//    noise's two blobs at +-F0 omega0, hybrid noise's the arcs between.
//  - bound(): |n| <= 3^D max_count scale (every kernel is at most 1 in
//    magnitude); the observed maximum is far smaller (tests).
//  - C1: the kernels are tapered to 0 (gabor/kernel.hpp); gradient() is the
//    analytic derivative.
//  - float evaluation is within scale 2^-21 (1 + 2 pi Phi) (N' + 1) of the
//    double reference (each kernel within 2^-21 (1 + 2 pi Phi) of its double
//    value, gabor/kernel.hpp, and ~N' kernels reach a point); measured in
//    tests/gabor/gabor_test.cpp ("float evaluation stays within the stated budget").
//    The per-kernel figure is measured (gabor_kernel_test); the worst-case
//    rounding analysis exceeds it for Phi < 0.9 (up to 4.5x at Phi = 0 in 3D;
//    docs/gabor.md "Float accuracy").
//  - domain: every coordinate whose cell coordinate p / r is finite, |p| <= DBL_MAX r
//    (positions are split into cell and fraction in double, so precision does not
//    degrade far from the origin); NaN or +-Inf in a coordinate, or one beyond that,
//    gives NaN (value and gradient).
//
// Filtering (paper sec. 5): sample(p, footprint) evaluates the noise
// convolved with the Gaussian pixel filter N(0, sigma^2 S) of the footprint
// (sigma = kPixelFilterSigma pixels, core/footprint.hpp) in closed form: each
// kernel becomes the filtered Gabor kernel of gabor_filter (gabor/kernel.hpp),
// kept within the kernel's support. A point footprint gives exactly the
// unfiltered noise; every footprint (zero, rank 1, det 1e-30 or 1e30, NaN:
// HARD_CASES row 12) gives a finite result, continuous in the footprint, which
// tends to the mean 0 as the footprint grows.
//
// Surface noise (3D, paper sec. 4.3): sample(p, normal[, footprint]) evaluates
// 2D kernels in the tangent plane of the surface at p. The impulses of a
// second 3D process (stream kGaborSurfaceStream, cells of side r sqrt(3/2))
// that lie in the slab |<n, x - x_i>| < h = r / sqrt 2 contribute the 2D
// kernel of their projection onto the plane, weighted by the taper of their
// distance to it. The projection of a Poisson process in a slab is a 2D
// Poisson process, so on a plane the surface noise has exactly the 2D noise's
// spectrum and unit variance, with no slicing of a 3D spectrum. Isotropic and
// hybrid impulses carry a 3D direction whose projection (normalised) is their
// orientation in the plane (uniform on the circle for isotropic noise, for
// every normal); anisotropic noise projects omega0 without normalising
// (frequency F0 |P omega0|: the asked-for spectrum where omega0 lies in the
// tangent plane, continuous everywhere). Footprints are projected onto the
// tangent plane. A zero normal evaluates the solid noise; a non-finite normal
// gives NaN.
//
// Its parts: hush/gabor/kernel.hpp (the kernel and its filtered form), hush/gabor/marks.hpp
// (impulse kinds and marks), hush/gabor/spectrum.hpp (gabor_spectrum), and the SIMD
// kernels (hush/gabor/simd_kernel.hpp, hush/gabor/simd-inl.h).
#ifndef HUSH_GABOR_HPP
#define HUSH_GABOR_HPP

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "hush/config.hpp"
#include "hush/core/error.hpp"
#include "hush/core/footprint.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/lattice.hpp"
#include "hush/core/poisson_table.hpp"
#include "hush/core/rng.hpp"
#include "hush/core/samples.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/detail/constants.hpp"
#include "hush/detail/elementary.hpp"
#include "hush/detail/quadrature.hpp"
#include "hush/gabor/kernel.hpp"
#include "hush/gabor/marks.hpp"

namespace hush {

template <int D>
class gabor : public sample_noise<gabor<D>, D> {
  static_assert(D == 2 || D == 3, "hush::gabor is 2D or 3D");

 public:
  static constexpr bool takes_footprint = true;
  static constexpr bool takes_normal = D == 3;

  struct params {
    std::uint32_t seed = 0;
    gabor_kind kind = gabor_kind::isotropic;
    // F0: the principal frequency, cycles per noise unit, 0 ... 1e6.
    double frequency = 1.0;
    // a: the kernel's bandwidth, 1/noise units, 1e-6 ... 1e6; the radial
    // spectral width of each blob is a / (2 sqrt(pi)) (standard deviation).
    double bandwidth = 0.8;
    // omega0 (anisotropic and hybrid): azimuth in the xy plane, radians.
    double orientation = 0.0;
    // 3D: omega0's angle above the xy plane, radians.
    double elevation = 0.0;
    // hybrid: width of the orientation range around omega0, radians, 0 ...
    // 2 pi (2D: an arc; 3D: the apex angle of a spherical cap; 2 pi = all).
    double orientation_spread = 0.0;
    // hybrid: width of the frequency range around F0, 0 ... 2 F0.
    double frequency_spread = 0.0;
    // N': the mean number of kernels overlapping a point, 1e-6 ... 256.
    double impulses = 16.0;
    // t: the kernel envelope's value at its support radius, 1e-9 ... 0.5.
    double truncation = detail::constants::kGaborDefaultTruncation;
  };

  gabor() : gabor(params{}) {}
  // Throws hush::invalid_argument naming the first parameter out of range.
  explicit gabor(const params& prm) : prm_(prm), kernel_(check(prm).bandwidth, prm.truncation) {
    namespace c = detail::constants;
    key_ = seed_key(prm.seed);
    const double r = kernel_.radius();
    inv_cell_ = 1.0 / r;
    marks_ = gabor_marks<D>(prm.kind, prm.frequency * r, prm.frequency_spread * r, prm.orientation,
                            prm.elevation, prm.orientation_spread);
    // N' kernels per unit ball of radius r: N' / V_D per cell of side r.
    const double ball = D == 2 ? c::kPi : 4.0 * c::kPi / 3.0;
    table_ = std::make_shared<const poisson_table>(prm.impulses / ball);
    scale_ = 1.0 / std::sqrt(table_->exact_mean() * weight_moment() * mean_energy());
    if constexpr (D == 3) {
      // Slab of half-height h = r / sqrt 2, disk of radius r, cells of r sqrt(3/2):
      // lambda_3 = N' / (2 h pi r^2), mu = lambda_3 cell^3.
      const double cell = c::kGaborSurfaceCell;
      inv_surface_cell_ = 1.0 / (r * cell);
      surface_table_ = std::make_shared<const poisson_table>(prm.impulses * cell * cell * cell /
                                                             (2.0 * c::kGaborSurfaceSlab * c::kPi));
      surface_scale_ = 1.0 / std::sqrt(surface_table_->exact_mean() * weight_moment() *
                                       mean_energy_2d() * surface_geometry());
      for (const auto& t : {table_, surface_table_})
        if (t->max_count() > static_cast<std::uint32_t>(c::kGaborMaxThresholds))
          hush::detail::raise_error("hush::gabor: internal Poisson table too long");
    }
  }

  const params& parameters() const { return prm_; }
  const gabor_kernel<D>& kernel() const { return kernel_; }
  const gabor_marks<D>& marks() const { return marks_; }
  // The per-cell Poisson tables (solid; surface in 3D).
  const poisson_table& table() const { return *table_; }
  const poisson_table& surface_table() const {
    static_assert(D == 3, "surface noise is 3D");
    return *surface_table_;
  }
  std::uint32_t key() const { return key_; }
  // 1 / cell side (cells are r wide; surface cells r sqrt(3/2)).
  double inverse_cell() const { return inv_cell_; }
  double inverse_surface_cell() const { return inv_surface_cell_; }
  // Words one impulse takes from its cell's stream (after the count's word).
  int words_per_impulse() const { return words_for(prm_.kind); }
  // The factor that makes the variance 1 (the raw sum times scale()).
  double scale() const { return scale_; }
  double surface_scale() const { return surface_scale_; }

  // Surface noise's set-up per sample (sample_eval, surface_eval; the SIMD
  // kernel repeats it per lane). unit_normal: the unit normal of n (scaled
  // before normalising, so that tiny and huge normals both work); false for a
  // zero normal (no tangent plane: the solid noise). n must be finite.
  static bool unit_normal(const vec<double, 3>& n, vec<double, 3>& unit) {
    const double big = std::fmax(std::fabs(n.x), std::fmax(std::fabs(n.y), std::fabs(n.z)));
    if (!(big > 0.0)) return false;
    const vec<double, 3> m{n.x / big, n.y / big, n.z / big};
    const double len = std::sqrt(m.x * m.x + m.y * m.y + m.z * m.z);
    unit = {m.x / len, m.y / len, m.z / len};
    return true;
  }
  // surface_frame: the tangent frame (t, b) of unit normal n and the filter of
  // footprint fp projected onto the plane ([t b]^T S [t b], in the kernel's units).
  // The projection stays in double (entries within 3 W^2, as S's are within
  // W^2: finite, no cap needed), not rounded to a footprint<2> (float): GCC 12's
  // SLP vectorizer drops double -> float -> double round trips in code built for
  // AVX and later (the SIMD kernels inline this function), which would make scalar
  // and SIMD filters differ for ill-conditioned projections (huge footprints).
  gabor_filter<2> surface_frame(const vec<double, 3>& n, const footprint<3>& fp, vec<double, 3>& t,
                                vec<double, 3>& b) const {
    detail::orthonormal_basis(n, t, b);
    double s[2][2];
    const vec<double, 3>* axes[2] = {&t, &b};
    for (int i = 0; i < 2; ++i)
      for (int j = i; j < 2; ++j) {
        double v = 0;
        for (int r = 0; r < 3; ++r)
          for (int k = 0; k < 3; ++k)
            v += (*axes[i])[r] * static_cast<double>(fp.covariance(r, k)) * (*axes[j])[k];
        s[i][j] = s[j][i] = v;
      }
    return gabor_filter<2>(s, kernel_.envelope_exponent(), inv_cell_);
  }

  // Variance 1 and mean 0 over space and seeds (see the file comment).
  static constexpr double variance() { return 1.0; }
  // |n| <= bound() (solid noise; surface noise's bound in 3D is surface_bound()).
  double bound() const { return std::pow(3.0, D) * table_->max_count() * scale_; }
  double surface_bound() const { return 27.0 * surface_table_->max_count() * surface_scale_; }

  // E[w^2] of the 8-bit symmetric weights: (1 - 2^-16) / 3.
  static constexpr double weight_moment() { return (1.0 - 1.0 / 65536.0) / 3.0; }
  // E over the kind's frequencies of the kernel energy int g^2 in cell units.
  double mean_energy() const { return mean_energy_of<D>(); }

  // The power spectrum of the unit-variance noise at frequency f (cycles per
  // noise unit), exact: lambda E[w^2] E_F[|g^_F(f)|^2] scale^2. Quadrature of
  // the kernel transform for each call (isotropic: <= 1344 of them;
  // anisotropic: 2). Hybrid noise averages over millions of values of H (2D:
  // <= 6.6e6 in the frequency and orientation windows, <= 6.7e7 below them,
  // |Phi| <= 64; 3D: <= 1296 spheres of <= 2144 nodes, two values each: 5.6e6;
  // 1.4e7 with rim_cuts' pieces, f within ~0.22 rad of the cap's rim),
  // so it tabulates H once per call
  // (<= 1217 quadratures, up to kGaborSpectrumWindowCycles; beyond, H's
  // asymptotic term, as gabor_spectrum): within 1e-15 of H(0) up to 64 cycles
  // per cell, < 3e-8 of H(0) beyond (docs/gabor.md "Cost of the spectra").
  // gabor_spectrum tabulates the spectrum itself for images.
  double power_spectrum(const vec<double, D>& f) const {
    namespace c = detail::constants;
    const double a = kernel_.envelope_exponent();
    auto exact = [a](double k) { return detail::gabor_envelope_transform<D>(a, k); };
    if (prm_.kind != gabor_kind::hybrid) return spectrum_with(f, exact);
    const detail::chebyshev_table table = transform_table(f);
    const double top = std::fmin(transform_table_reach(f), c::kGaborSpectrumWindowCycles);
    return spectrum_with(f, [&](double k) {
      return k <= top ? table(k) : detail::gabor_envelope_transform_tail<D>(a, k);
    });
  }

  // The table power_spectrum(f) takes H from for hybrid noise (exposed for
  // its tests: calls() counts the quadratures), over [0, min(|f r| + |Phi|max,
  // kGaborSpectrumWindowCycles)] (no blob is further from f r).
  detail::chebyshev_table transform_table(const vec<double, D>& f) const {
    namespace c = detail::constants;
    const double a = kernel_.envelope_exponent();
    return detail::chebyshev_table(
        [a](double k) { return detail::gabor_envelope_transform<D>(a, k); }, 0.0,
        std::fmin(transform_table_reach(f), c::kGaborSpectrumWindowCycles),
        c::kGaborTransformTablePanel, c::kGaborTransformTableNodes);
  }

  // The same with H(k), the tapered envelope's transform at k cycles per cell,
  // supplied by the caller (gabor_spectrum passes a table of it). window
  // (cycles per cell): isotropic and hybrid noise integrate only the Phi
  // that bring a blob within `window` of f r; the default bounds every call
  // whatever F0, a and the spreads (calls of h: isotropic <= 1344; hybrid 2D
  // <= 6.6e6, 3D <= 5.6e6, 1.4e7 near the cap's rim; isotropic_mean,
  // hybrid_window_2d, frequency_window, cap_mean); infinity takes every Phi
  // (isotropic: same cost; hybrid: the full average, cost ~ |Phi|^2 in 2D,
  // ~ |Phi| |f r| in 3D).
  template <class H>
  double spectrum_with(const vec<double, D>& f, H h,
                       double window = detail::constants::kGaborSpectrumWindowCycles) const {
    const double r = kernel_.radius();
    vec<double, D> xi;
    for (int i = 0; i < D; ++i) xi[i] = f[i] * r;
    return scale_ * scale_ * table_->exact_mean() * weight_moment() * std::pow(r, D) *
           mean_kernel_spectrum(xi, h, window);
  }

  // p(vec) -> value, p.gradient(vec) (core/point_noise.hpp) and p.sample(...)
  // (core/samples.hpp) come from the base classes.
  template <class T>
  T value(const vec<double, D>& p) const {
    return eval<T, false>(p).value;
  }
  template <class T>
  value_gradient<T, D> value_and_gradient(const vec<double, D>& p) const {
    return eval<T, true>(p);
  }
  // A grid's sample at p: the separable form that every backend's grids use
  // (eval below); within the bound of docs/gabor.md "Float accuracy" of
  // value(p). Float or double.
  template <class T>
  value_gradient<T, D> grid_sample(const vec<double, D>& p) const {
    return eval<T, true, true>(p);
  }
  // exec.hpp's grid_values (the scalar grid): every sample in the grid form,
  // at the positions scalar_grid's sample loop takes (grid::position), bit for bit
  // grid_sample's values. The grid is cut into tiles of samples that share their
  // cell (at most kGridTile samples along an axis); a tile decodes its cells'
  // impulses once and forms each impulse's x factors once per column and its
  // other axes' factors once per row, so that a sample costs a product and a
  // taper per kept impulse. Tiles too small to share them evaluate sample by sample.
  void grid_values(const grid<D>& g, std::size_t first, std::size_t count, float* out,
                   vec<float, D>* grad) const {
    if (grad)
      grid_tiles<true>(g, first, count, out, grad);
    else
      grid_tiles<false>(g, first, count, out, grad);
  }
  template <class T>
  T sample_value(const sample_input<D>& s) const {
    return sample_eval<T, false>(s).value;
  }
  template <class T>
  value_gradient<T, D> sample_value_and_gradient(const sample_input<D>& s) const {
    return sample_eval<T, true>(s);
  }

  // ---- The pieces every backend repeats (hush/gabor/simd-inl.h, GLSL).

  // The impulses of solid cell `cell` (32-bit lattice indices), in stream
  // order: f(words), the impulse's words_per_impulse() stream words, whose
  // fields impulse_position() and mark_values() decode (constants.hpp,
  // "Impulse marks"): decoding only what is needed is what every backend does.
  template <class F>
  void for_each_impulse(const std::uint32_t (&cell)[std::size_t{D}], F f) const {
    rng r(cell_seed(cell), detail::constants::kGaborSolidStream);
    const std::uint32_t n = table_->count(r.next_u32());
    const int words = words_per_impulse();
    for (std::uint32_t k = 0; k < n; ++k) {
      std::uint32_t w[3] = {0, 0, 0};
      for (int i = 0; i < words; ++i) w[i] = r.next_u32();
      f(static_cast<const std::uint32_t*>(w));
    }
  }
  // The same for the surface process (3D; cells r sqrt(3/2) wide).
  template <class F>
  void for_each_surface_impulse(const std::uint32_t (&cell)[3], F f) const {
    rng r(lattice_hash(key_, cell[0], cell[1], cell[2]), detail::constants::kGaborSurfaceStream);
    const std::uint32_t n = surface_table_->count(r.next_u32());
    const int words = words_for(prm_.kind, 3);
    for (std::uint32_t k = 0; k < n; ++k) {
      std::uint32_t w[3] = {0, 0, 0};
      for (int i = 0; i < words; ++i) w[i] = r.next_u32();
      f(static_cast<const std::uint32_t*>(w));
    }
  }
  // Coordinate `axis` of an impulse's position in its cell, in (0, 1).
  template <class T>
  static T impulse_position(const std::uint32_t* words, int axis) {
    return detail::gabor_byte<T>(words[0], static_cast<unsigned>(axis));
  }
  // The values gabor_marks::draw takes, from an impulse's words (E = 2 or 3:
  // the process's dimension).
  template <class T, int E = D>
  void mark_values(const std::uint32_t* words, T* u) const {
    u[0] = detail::gabor_byte<T>(words[0], E);  // weight
    if (prm_.kind == gabor_kind::anisotropic) return;
    if constexpr (E == 2) {
      u[1] = detail::gabor_byte<T>(words[0], 3);
      if (prm_.kind == gabor_kind::hybrid) u[2] = detail::gabor_half<T>(words[1], 0);
    } else {
      u[1] = detail::gabor_half<T>(words[1], 0);
      u[2] = detail::gabor_half<T>(words[1], 1);
      if (prm_.kind == gabor_kind::hybrid) u[3] = detail::gabor_half<T>(words[2], 0);
    }
  }

  // Words per impulse of a kind in E dimensions (constants.hpp, "Impulse marks").
  static int words_for(gabor_kind kind, int e = D) {
    if (kind == gabor_kind::hybrid) return e == 2 ? 2 : 3;
    return kind == gabor_kind::isotropic && e == 3 ? 2 : 1;
  }

 private:
  // Hybrid noise's |Phi| range [phi0 - dphi / 2, phi0 + dphi / 2] (cell units) as doubles hold
  // it. Means over it divide by the held width hi - lo, not dphi: a dphi of a few ulps of phi0
  // rounds the ends; when they meet (dphi 0, or below phi0's resolution) the mean is f(phi0).
  struct phi_range {
    double lo, hi;
    bool single() const { return !(hi > lo); }
    double width() const { return hi - lo; }
  };
  phi_range frequency_range() const {
    const double p = marks_.phi0(), h = 0.5 * marks_.dphi();
    return {p - h, p + h};
  }
  static const params& check(const params& p) {
    namespace c = detail::constants;
    const char* w = "hush::gabor";
    detail::require_in_range(w, "frequency", p.frequency, 0.0, c::kGaborMaxFrequency,
                             "0 <= frequency <= 1e+06 (cycles per noise unit)");
    detail::require_in_range(w, "bandwidth", p.bandwidth, c::kGaborMinBandwidth,
                             c::kGaborMaxBandwidth, "1e-06 <= bandwidth <= 1e+06 (1/noise units)");
    detail::require_in_range(w, "truncation", p.truncation, c::kGaborMinTruncation,
                             c::kGaborMaxTruncation, "1e-09 <= truncation <= 0.5");
    detail::require_in_range(w, "impulses", p.impulses, c::kGaborMinImpulses, c::kGaborMaxImpulses,
                             "1e-06 <= impulses <= 256");
    if (!std::isfinite(p.orientation))
      detail::throw_out_of_range(w, "orientation", p.orientation, "a finite angle in radians");
    if (!std::isfinite(p.elevation))
      detail::throw_out_of_range(w, "elevation", p.elevation, "a finite angle in radians");
    detail::require_in_range(w, "orientation_spread", p.orientation_spread, 0.0, c::kTwoPi,
                             "0 <= orientation_spread <= 2 pi (radians)");
    detail::require_in_range(w, "frequency_spread", p.frequency_spread, 0.0, 2.0 * p.frequency,
                             "0 <= frequency_spread <= 2 * frequency");
    if (p.kind != gabor_kind::isotropic && p.kind != gabor_kind::anisotropic &&
        p.kind != gabor_kind::hybrid)
      detail::throw_out_of_range(w, "kind", static_cast<int>(p.kind),
                                 "isotropic, anisotropic or hybrid");
    return p;
  }

  std::uint32_t cell_seed(const std::uint32_t (&cell)[std::size_t{D}]) const {
    if constexpr (D == 2)
      return lattice_hash(key_, cell[0], cell[1]);
    else
      return lattice_hash(key_, cell[0], cell[1], cell[2]);
  }

  // The largest distance |f r| + |Phi| of a blob from f r plus 1 (cycles per
  // cell); f infinite or NaN: 1 (spectrum_with gives 0 there without H).
  double transform_table_reach(const vec<double, D>& f) const {
    double len = 0;
    for (int i = 0; i < D; ++i) len += f[i] * f[i];
    const double reach = std::sqrt(len) * kernel_.radius() + marks_.phi0() + 0.5 * marks_.dphi();
    return (reach < std::numeric_limits<double>::infinity() ? reach : 0.0) + 1.0;
  }

  // E over the kind's frequency vectors Phi of |g^_Phi(xi)|^2 (cell units), with
  // |g^_Phi(xi)| = (H(|xi - Phi|) + H(|xi + Phi|)) / 2 (gabor/kernel.hpp).
  template <class H>
  double mean_kernel_spectrum(const vec<double, D>& xi, H h, double window) const {
    namespace c = detail::constants;
    auto one = [&](const vec<double, D>& phi) {
      double lo = 0, hi = 0;
      for (int i = 0; i < D; ++i) {
        lo += (xi[i] - phi[i]) * (xi[i] - phi[i]);
        hi += (xi[i] + phi[i]) * (xi[i] + phi[i]);
      }
      const double v = 0.5 * (h(std::sqrt(lo)) + h(std::sqrt(hi)));
      return v * v;
    };
    if (prm_.kind == gabor_kind::anisotropic) return one(marks_.fixed_frequency());
    double xi_len = 0;
    for (int i = 0; i < D; ++i) xi_len += xi[i] * xi[i];
    xi_len = std::sqrt(xi_len);
    const double phi0 = marks_.phi0(), dphi = marks_.dphi();
    const bool hybrid = prm_.kind == gabor_kind::hybrid;
    if (!hybrid) return isotropic_mean(xi_len, phi0, h, window);
    // The blob centres +-Phi move by 2 pi |Phi| cycles per cell per turn, and H
    // is ~0.4 cycles per cell wide (t = 0.05): these node counts resolve it to
    // ~1e-10, less for narrower cores (the isotropic trapezoid rule with these
    // counts was at 4e-5 of the peak for t = 0.5; tests/gabor/gabor_kernel_test.cpp).
    const double reach = phi0 + 0.5 * dphi;
    // No blob within the window of xi (|xi| beyond the band by W or more,
    // infinite or NaN): 0, what the windows leave out everywhere.
    if (!(xi_len - reach < window)) return 0.0;
    // Average over |Phi| (hybrid) of f(|Phi|).
    auto over_frequency = [&](auto f) {
      const phi_range pr = frequency_range();
      if (!hybrid || pr.single()) return f(phi0);
      const int panels = 1 + static_cast<int>(std::ceil(2.0 * dphi));
      return detail::integrate(f, pr.lo, pr.hi, panels) / pr.width();
    };
    if constexpr (D == 2) {
      if (reach > window) return hybrid_window_2d(xi, h, window);
      return over_frequency([&](double ph) {
        auto at = [&](double turns) {
          const double ang = c::kTwoPi * turns;
          return one({ph * std::cos(ang), ph * std::sin(ang)});
        };
        const double spread = marks_.spread_turns(), theta0 = marks_.theta0();
        if (spread == 0.0) return at(theta0);
        const int panels = 1 + static_cast<int>(std::ceil(8.0 * reach * spread));
        return detail::integrate(at, theta0 - 0.5 * spread, theta0 + 0.5 * spread, panels) / spread;
      });
    } else {
      // Over |Phi| as hybrid 2D noise (frequency_window), on each sphere over
      // the cap (cap_mean): bounded whatever the window, F0 and the spreads.
      double cb = 1.0;  // cos of the angle between xi and the cap's axis
      if (xi_len > 0.0) {
        cb = 0.0;
        for (int i = 0; i < 3; ++i) cb += xi[i] * marks_.frame_axis()[i];
        cb = std::fmax(-1.0, std::fmin(1.0, cb / xi_len));
      }
      return frequency_window([&](double ph) { return cap_mean(xi_len, ph, cb, h, window); },
                              xi_len, window);
    }
  }

  // ((H(k_-) + H(k_+)) / 2)^2 from the squared distances k_-^2, k_+^2 to the two blobs
  // (clamped at 0 against rounding): the integrand of isotropic_mean and hybrid_window_2d.
  template <class H>
  static double blob_pair(H& h, double km2, double kp2) {
    const double v = 0.5 * (h(std::sqrt(std::fmax(km2, 0.0))) + h(std::sqrt(std::fmax(kp2, 0.0))));
    return v * v;
  }

  // Isotropic noise's E_Phi[((H(|xi - Phi|) + H(|xi + Phi|)) / 2)^2] for |xi| = x,
  // |Phi| = ph, over the orientations where the near blob is within `window`
  // of xi (all of them when window >= sqrt(x^2 + ph^2); docs/gabor.md "Cost of
  // the spectra"). With gamma the angle between xi and Phi, k_-^2 = x^2 + ph^2
  // - 2 x ph cos gamma and k_+ (cos gamma -> -cos gamma) swap under gamma ->
  // pi - gamma, so the mean is over cos gamma >= 0, where k_+ >= k_-; left out
  // is where k_- > window, both blobs in H's tail. 2D: gamma uniform,
  // u = 2 sqrt(x ph) sin(gamma / 2) gives k_-^2 = (x - ph)^2 + u^2 (smooth in u,
  // |dk/du| <= 1), d gamma = 2 du / sqrt(4 x ph - u^2), gamma = pi / 2 at
  // u^2 = 2 x ph, mean (2 / pi) int. 3D: cos gamma uniform, d cos gamma =
  // -k dk / (x ph), mean (1 / (x ph)) int k G dk. H's core (<= 1.5 cycles wide,
  // 0.26 at t = 0.5) lies within 4 of k = 0: panels 0.5 wide there, 2 wide
  // beyond (H oscillates at <= 1 cycle per unit k): at most 8 + 2 + window / 2
  // panels of 16 nodes, two calls of h each.
  // The composite 16-point rule on [lo, hi] with panels 0.5 wide within 4 of
  // `core` (where H's core, <= 1.5 cycles wide, lies), 2 wide elsewhere (H
  // oscillates at <= 1 cycle per unit there).
  template <class G>
  static double core_rule(G g, double lo, double hi, double core) {
    double sum = 0;
    const double cut[4] = {lo, std::fmin(hi, std::fmax(lo, core - 4.0)),
                           std::fmin(hi, std::fmax(lo, core + 4.0)), hi};
    for (int i = 0; i < 3; ++i) {
      if (!(cut[i + 1] > cut[i])) continue;
      const double per = i == 1 ? 2.0 : 0.5;  // panels per unit
      sum += detail::integrate(g, cut[i], cut[i + 1],
                               1 + static_cast<int>(std::ceil(per * (cut[i + 1] - cut[i]))));
    }
    return sum;
  }

  // Hybrid 2D noise's mean over |Phi| uniform in [phi0 -+ dphi / 2] and the
  // orientation uniform on the arc, for |Phi| > window somewhere: |Phi| only
  // within `window` of |xi| (k_-, k_+ >= ||xi| - |Phi||), and for each |Phi|
  // with |xi|^2 + |Phi|^2 > window^2 the orientations within the windows
  // around xi's direction (k_- < window) and the opposite one (k_+ <
  // window), clipped to the arc, in isotropic_mean's variable u on each side;
  // below, the whole arc (zero spread: omega0 alone). Outer nodes <= 1296
  // (frequency_window), inner per window <= 2 x 640: bounded, ~6.6e6 calls of h
  // at most.
  template <class H>
  double hybrid_window_2d(const vec<double, 2>& xi, H h, double window) const {
    namespace c = detail::constants;
    const double x = std::sqrt(xi[0] * xi[0] + xi[1] * xi[1]);
    const double arc = c::kTwoPi * marks_.spread_turns(), centre = c::kTwoPi * marks_.theta0();
    const double dir = std::atan2(xi[1], xi[0]);
    auto inner = [&](double ph) {  // mean over the arc at |Phi| = ph
      const double xp = x * ph, base = x * x + ph * ph, kmin = std::fabs(x - ph);
      auto pair = [&](double km2, double kp2) { return blob_pair(h, km2, kp2); };
      auto at = [&](double ang) {
        const double cross = 2.0 * xp * std::cos(ang - dir);
        return pair(base - cross, base + cross);
      };
      if (arc == 0.0) return at(centre);  // omega0 only
      if (!(base > window * window)) {    // small: the whole arc, as for |Phi| <= window
        const int panels = 1 + static_cast<int>(std::ceil(8.0 * ph * marks_.spread_turns()));
        return detail::integrate(at, centre - 0.5 * arc, centre + 0.5 * arc, panels) / arc;
      }
      if (!(kmin < window)) return 0.0;
      const double root = 2.0 * std::sqrt(xp);
      const double u_max = std::sqrt(std::fmin((window - kmin) * (window + kmin), 2.0 * xp));
      const double g_max = 2.0 * std::asin(u_max / root);  // the window's half-width in angle
      const double sum2 = (x + ph) * (x + ph);
      double sum = 0;
      for (int far = 0; far < 2; ++far) {  // around xi's direction (k_-), then opposite (k_+)
        auto g = [&](double u) {
          const double u2 = u * u, near2 = kmin * kmin + u2, other2 = sum2 - u2;
          return (far ? pair(other2, near2) : pair(near2, other2)) * 2.0 /
                 std::sqrt(root * root - u2);
        };
        // The arc relative to the window's centre, in (-pi, pi] + 2 pi m.
        const double off = std::remainder(centre - dir - (far ? c::kPi : 0.0), c::kTwoPi);
        for (int m = -1; m <= 1; ++m) {
          const double lo = std::fmax(off - 0.5 * arc + c::kTwoPi * m, -g_max);
          const double hi = std::fmin(off + 0.5 * arc + c::kTwoPi * m, g_max);
          if (!(hi > lo)) continue;
          auto to_u = [&](double gam) { return root * std::sin(0.5 * std::fabs(gam)); };
          if (hi > 0.0) sum += core_rule(g, to_u(std::fmax(lo, 0.0)), to_u(hi), 0.0);
          if (lo < 0.0) sum += core_rule(g, to_u(std::fmin(hi, 0.0)), to_u(lo), 0.0);
        }
      }
      return sum / arc;
    };
    return frequency_window(inner, x, window);
  }

  // Hybrid noise's mean over |Phi| uniform in [phi0 -+ dphi / 2] of inner(|Phi|),
  // the mean over the orientations at |Phi|: only |Phi| within `window` of
  // |xi| = x (both blobs are at least ||xi| - |Phi|| from xi; further, inner
  // leaves them out), panels 0.5 wide within 4 of x, 2 wide beyond: at most
  // 81 panels of 16 nodes, 1296 (the whole range when window = infinity).
  template <class F>
  double frequency_window(F inner, double x, double window) const {
    const phi_range pr = frequency_range();
    if (pr.single()) return inner(marks_.phi0());
    const double lo = std::fmax(pr.lo, x - window);
    const double hi = std::fmin(pr.hi, x + window);
    if (!(hi > lo)) return 0.0;
    return core_rule(inner, lo, hi, x) / pr.width();
  }

  // Hybrid 3D noise's mean of ((H(k_-) + H(k_+)) / 2)^2 over Phi uniform on the
  // cap {omega . axis >= cap} of the sphere |Phi| = ph, |xi| = x, cb = cos beta
  // (beta: xi's angle to the axis). With gamma Phi's angle to xi, k_-^2 =
  // x^2 + ph^2 - 2 x ph cos gamma, k_+ the same with -cos gamma; on the circle
  // of directions at gamma (azimuth psi around xi) omega . axis = cos gamma cb
  // + sin gamma sin beta cos psi, so the cap holds the fraction w(gamma) =
  // acos(clamp((cap - cos gamma cb) / (sin gamma sin beta))) / pi of it, and
  // the mean is int G w d cos gamma / (1 - cap) (int w d cos gamma = 1 - cap).
  // As in isotropic_mean, cos gamma >= 0 in k = k_- and cos gamma <= 0 in
  // k = k_+ (d cos gamma = -+ k dk / (x ph)), each only while k < window
  // (what is left out: both blobs in H's tail, as there). w has square-root
  // ends where the circle touches the cap's rim, gamma = beta -+ theta
  // (cos theta = cap): the rule is cut there and each piece integrated by
  // integrate_ends. Nodes per half <= 16 (1 + 2 + ceil(4 pi) + ceil(window pi
  // / 4)) = 1072 with the window (two calls of h each), plus <= 48 pieces of 32
  // nodes where a rim is near a pole (rim_cuts).
  template <class H>
  double cap_mean(double x, double ph, double cb, H& h, double window) const {
    const double cap = marks_.cos_cap();
    const double kmin = std::fabs(x - ph);
    if (!(kmin < window)) return 0.0;  // both blobs beyond the window (or xi = inf)
    const double xp = x * ph, base = x * x + ph * ph;
    if (!(xp > 1e-150)) return blob_pair(h, base, base);  // Phi = 0 or xi = 0: one value
    if (cap >= 1.0) return blob_pair(h, base - 2.0 * xp * cb, base + 2.0 * xp * cb);  // omega0
    const double sb = std::sqrt(std::fmax((1.0 - cb) * (1.0 + cb), 0.0));
    const double st = std::sqrt(std::fmax((1.0 - cap) * (1.0 + cap), 0.0));
    auto weight = [&](double cg) {
      const double num = cap - cg * cb,
                   den = std::sqrt(std::fmax((1.0 - cg) * (1.0 + cg), 0.0)) * sb;
      if (!(num < den)) return 0.0;   // the whole circle outside the cap
      if (!(num > -den)) return 1.0;  // inside
      return std::acos(num / den) / detail::constants::kPi;
    };
    const double rim[2] = {cb * cap - sb * st, cb * cap + sb * st};  // cos(beta +- theta)
    double sum = 0;
    if (xp < 1.0) {  // k moves by < 1 over cos gamma in [-1, 1]: integrate in cos gamma
      const double c_lo = std::fmax(0.0, (base - window * window) / (2.0 * xp));
      for (const double side : {1.0, -1.0}) {
        if (!(c_lo < 1.0)) break;
        auto g = [&](double c) {
          const double cg = side * c;
          return blob_pair(h, base - 2.0 * xp * cg, base + 2.0 * xp * cg) * weight(cg);
        };
        sum += cut_rule(g, c_lo, 1.0, 1.0, rim_cuts(rim, side), 1.0);
      }
      return sum / (1.0 - cap);
    }
    const double k_hi = std::fmin(window, std::sqrt(base));
    for (const double side : {1.0, -1.0}) {
      auto g = [&](double k) {
        const double k2 = k * k, far2 = 2.0 * base - k2;
        const double cg = side * (base - k2) / (2.0 * xp);
        return k * (side > 0 ? blob_pair(h, k2, far2) : blob_pair(h, far2, k2)) * weight(cg);
      };
      // k where side * cos gamma = c (c = 1, the pole: k = kmin).
      cap_cuts cuts = rim_cuts(rim, side);
      for (double& c : cuts) c = std::sqrt(std::fmax(base - 2.0 * xp * c, 0.0));
      sum += cut_rule(g, kmin, k_hi, kmin + 4.0, cuts, 0.5);
    }
    return sum / ((1.0 - cap) * xp);
  }

  // cap_mean's cuts on one side, in c = side cos gamma (the side's pole, gamma = 0
  // or pi, at c = 1): the two rims, and where a rim is within d < 0.025 of the
  // pole, cuts at c = 1 - 4^j d (j >= 1, up to 1 - 0.1). There the circle of
  // directions at gamma ~ sqrt(2 (1 - c)) is small and the rim ~sqrt(2 d) from its
  // centre, so beyond the rim w ~ acos(-sqrt(d / (1 - c))) / pi changes on the
  // scale d, with the pole's singularity d beyond the rim: one piece from the
  // rim on (the sine map resolves the rim's square root, not that) was off by
  // up to 2.3e-6 of the value at d ~ 5e-6 (xi 3e-3 rad from the rim);
  // pieces spanning a factor 4 in 1 - c (2 in gamma) keep it analytic around
  // each piece, as far from the pole as the piece is long: <= 2 x 25 cuts
  // (d >= 2^-53), 1e-11 of the value (docs/gabor.md "Cost of the spectra").
  // Unused entries repeat the first rim (empty pieces).
  static constexpr std::size_t kCapCuts = 52;  // 2 rims x (the rim, <= 24 cuts, a spare)
  using cap_cuts = std::array<double, kCapCuts>;
  static cap_cuts rim_cuts(const double (&rim)[2], double side) {
    cap_cuts cuts{};
    std::size_t n = 0;
    for (const double r : rim) {
      const double c = side * r, d = 1.0 - c;
      cuts[n++] = c;
      if (d > 0.0 && d < 0.025)
        for (double e = 4.0 * d; e < 0.1 && n < kCapCuts; e *= 4.0) cuts[n++] = 1.0 - e;
    }
    for (; n < kCapCuts; ++n) cuts[n] = cuts[0];
    return cuts;
  }

  // integrate_ends over [lo, hi] cut at `cuts` (those inside) and at `core`:
  // panels per unit 2 below core, `per` beyond (H oscillates at <= 1 cycle per
  // unit k, its core is within 4 of k = 0), pi / 2 times that for the map.
  template <class G, std::size_t N>
  static double cut_rule(G& g, double lo, double hi, double core, const std::array<double, N>& cuts,
                         double per) {
    std::array<double, N + 3> at{};
    at[0] = lo;
    at[1] = hi;
    at[2] = std::fmin(std::fmax(core, lo), hi);
    for (std::size_t i = 0; i < N; ++i) at[3 + i] = std::fmin(std::fmax(cuts[i], lo), hi);
    std::sort(at.begin(), at.end());
    double sum = 0;
    for (std::size_t i = 0; i + 1 < at.size(); ++i) {
      const double a = at[i], b = at[i + 1];
      if (!(b > a)) continue;
      const double density = b <= core ? 2.0 : per;
      sum += detail::integrate_ends(
          g, a, b,
          1 + static_cast<int>(std::ceil(density * (b - a) * 0.5 * detail::constants::kPi)));
    }
    return sum;
  }

  template <class H>
  static double isotropic_mean(double x, double ph, H h, double window) {
    const double kmin = std::fabs(x - ph);
    if (!(kmin < window)) return 0.0;  // no orientation brings a blob near xi (or xi = inf)
    const double xp = x * ph, base = x * x + ph * ph;
    auto pair = [&](double km2, double kp2) { return blob_pair(h, km2, kp2); };
    if (!(xp > 1e-150)) return pair(base, base);  // Phi = 0 or xi = 0: one orientation is all
    auto rule = [](auto g, double lo, double hi) { return core_rule(g, lo, hi, lo); };
    if constexpr (D == 2) {
      // fmin: the window may cover every gamma in [0, pi / 2].
      const double u_max = std::sqrt(std::fmin((window - kmin) * (window + kmin), 2.0 * xp));
      const double sum2 = (x + ph) * (x + ph);
      auto g = [&](double u) {
        const double u2 = u * u;
        return pair(kmin * kmin + u2, sum2 - u2) * 2.0 / std::sqrt(4.0 * xp - u2);
      };
      return rule(g, 0.0, u_max) * (2.0 / detail::constants::kPi);
    } else {
      const double c_lo = std::fmax(0.0, (base - window * window) / (2.0 * xp));
      if (xp < 1.0) {  // k moves by < 1 over cos gamma in [0, 1]: integrate in cos gamma
        auto g = [&](double cg) { return pair(base - 2.0 * xp * cg, base + 2.0 * xp * cg); };
        return detail::integrate(g, c_lo, 1.0, 2);
      }
      auto g = [&](double k) { return k * pair(k * k, 2.0 * base - k * k); };
      return rule(g, kmin, std::fmin(window, std::sqrt(base))) / xp;
    }
  }

  template <int E>
  double mean_energy_of() const {
    namespace c = detail::constants;
    const double a = kernel_.envelope_exponent(), phi = marks_.phi0();
    const phi_range pr = frequency_range();
    if (prm_.kind != gabor_kind::hybrid || pr.single()) return detail::gabor_energy<E>(a, phi);
    // |Phi| uniform over the range; the energy is smooth in it.
    return detail::integrate([&](double x) { return detail::gabor_energy<E>(a, x); }, pr.lo,
                             pr.hi, 2) /
           pr.width();
  }
  double mean_energy_2d() const { return mean_energy_of<2>(); }
  // Surface noise's variance per (table mean * E[w^2] * 2D energy): the slab
  // taper's mean square 2 int_0^1 tau(z^2)^2 dz times h r^2 / cell^3.
  static double surface_geometry() {
    namespace c = detail::constants;
    const double k = 1.0 / (1.0 - c::kGaborTaperStart);
    const double z0 = std::sqrt(c::kGaborTaperStart);
    auto tau2 = [&](double z) {
      const double t = detail::gabor_taper(z * z, k);
      return t * t;
    };
    const double j = detail::integrate(tau2, 0.0, z0, 1) + detail::integrate(tau2, z0, 1.0, 2);
    const double cell = c::kGaborSurfaceCell;
    return 2.0 * j * c::kGaborSurfaceSlab / (cell * cell * cell);
  }

  // ---- Evaluation (the scalar reference of every backend).

  // Calls pair(d, d2, s, w, phi) for every impulse of the solid process within
  // the support of x = p / r (cell units): offsets d (cell units), their
  // squares, s = |d|^2 < 1, weight and frequency vector. Cells go in raster
  // order (z, y, x from -1 to 1 around x's cell) and impulses in stream order:
  // the order the grid kernels accumulate in. False for a non-finite p.
  template <class T, class Pair>
  bool for_each_pair(const vec<double, D>& p, Pair pair) const {
    lattice_coord<T> c[std::size_t{D}];
    for (int a = 0; a < D; ++a) {
      c[a] = lattice_split<T>(p[a] * inv_cell_);
      if (std::isnan(c[a].f)) return false;
    }
    constexpr int kCells = D == 2 ? 9 : 27;
    for (int n = 0; n < kCells; ++n) {
      int o[std::size_t{D}];
      std::uint32_t cell[std::size_t{D}];
      for (int ax = 0, m = n; ax < D; ++ax, m /= 3) {
        o[ax] = m % 3 - 1;
        cell[ax] = c[ax].i0 + static_cast<std::uint32_t>(o[ax]);
      }
      for_each_impulse(cell, [&](const std::uint32_t* words) {
        T d[std::size_t{D}], d2[std::size_t{D}];
        for (int ax = 0; ax < D; ++ax) {
          d[ax] = detail::gabor_offset(c[ax].f, o[ax], impulse_position<T>(words, ax));
          d2[ax] = d[ax] * d[ax];
        }
        const T s = D == 2 ? d2[0] + d2[1] : d2[0] + (d2[1] + d2[2]);
        if (!(s < T(1))) return;
        T u[4] = {}, w;
        vec<T, D> phi;
        mark_values<T>(words, u);
        marks_.template draw<T>(u, w, phi);
        pair(d, d2, s, w, phi);
      });
    }
    return true;
  }

  // The sum of unfiltered solid noise's terms at one sample: at a point the point
  // form (gabor/kernel.hpp, gabor_point_term), on a grid's sample (Grid) the
  // separable pair, which the grid kernels share between rows and columns. Every
  // backend chooses the same way: grids always the separable form, points the point
  // form. add() takes the kept impulses in for_each_pair's order.
  template <class T, bool G, bool Grid>
  struct solid_sum {
    T neg_a, a, taper_k;
    T sum = 0, g[std::size_t{D}] = {};
    // The point form sums by fours (detail::gabor_point_sum), value and gradient alike.
    detail::gabor_point_sum<T> psum, pg_sum[std::size_t{D}];
    explicit solid_sum(const gabor& n)
        : neg_a(T(-n.kernel_.envelope_exponent())),
          a(T(n.kernel_.envelope_exponent())),
          taper_k(taper_k_<T>()) {}
    HUSH_INLINE void add(const T* d, T s, T w, const vec<T, D>& phi) {
      if constexpr (!Grid) {
        T ph[std::size_t{D}];
        for (int i = 0; i < D; ++i) ph[i] = phi[i];
        const T theta = detail::gabor_point_phase<T, D>(ph, d);
        if constexpr (G) {
          const auto pg = detail::gabor_point_term_with_gradient(w, s, theta, neg_a, taper_k, a);
          psum.add(pg.value);
          for (int i = 0; i < D; ++i) pg_sum[i].add(pg.u * d[i] - pg.v * phi[i]);
        } else {
          psum.add(detail::gabor_point_term(w, s, theta, neg_a, taper_k));
        }
        return;
      }
      detail::gabor_axis<T> ax[std::size_t{D}];
      for (int i = 0; i < D; ++i) ax[i] = detail::gabor_axis_factors(d[i], neg_a, phi[i]);
      detail::gabor_row<T> row;
      if constexpr (D == 2)
        row = detail::gabor_row_of(w, ax[1]);
      else
        row = detail::gabor_row_of(w, ax[1], ax[2]);
      if constexpr (G) {
        const auto pg = detail::gabor_pair_with_gradient(ax[0], row, taper_k, a);
        sum += pg.value;
        for (int i = 0; i < D; ++i) g[i] += pg.u * d[i] - pg.v * phi[i];
      } else {
        sum += detail::gabor_pair(ax[0], row, taper_k);
      }
    }
    value_gradient<T, D> result(const gabor& n) {
      if constexpr (!Grid) {
        sum = psum.total();
        for (int i = 0; i < D; ++i) g[i] = pg_sum[i].total();
      }
      return finish<T, G>(sum, g, T(n.scale_), T(n.scale_ * n.inv_cell_));
    }
  };

  template <class T, bool G, bool Grid = false>
  value_gradient<T, D> eval(const vec<double, D>& p) const {
    solid_sum<T, G, Grid> acc(*this);
    const bool ok = for_each_pair<T>(
        p, [&](const T* d, const T*, T s, T w, const vec<T, D>& phi) { acc.add(d, s, w, phi); });
    if (!ok) return nan_result<T>();
    return acc.result(*this);
  }

  // ---- Batches: the impulses of a block of cells decoded once for every sample in it.

  // One impulse of a block: o + u per axis (gabor_offset's exact sum, o its cell's
  // offset from the block's centre cell), weight and frequency vector.
  template <class T>
  struct block_impulse {
    T ou[std::size_t{D}];
    T w;
    vec<T, D> phi;
  };
  // The impulses of the 3^D cells around cell `centre`, in for_each_pair's order
  // (cells in raster order, impulses in stream order), all of them: a sample of
  // the centre cell keeps those with s < 1.
  // An impulse a point keeps: its offsets, s = |d|^2 and its block entry.
  struct kept_impulse {
    float d[std::size_t{D}], s;
    const block_impulse<float>* b;
  };
  template <class T>
  void fill_block(const std::uint32_t (&centre)[std::size_t{D}],
                  std::vector<block_impulse<T>>& out) const;

 public:
  // exec.hpp's point_values (scalar points): exactly noise(p) and noise.gradient(p)
  // per point, the decoded impulses of a point's 3^D cells reused by the following
  // points while they stay in the same cell (points in raster or scanline order
  // decode each block once per run of points in it).
  void point_values(const vec<float, D>* pts, std::size_t count, float* out,
                    vec<float, D>* grad) const;

 private:
  // The kept impulses first (s < 1, a branch-free compaction: which impulses a point
  // keeps is random, a branch on it mispredicted about one time in three), then their
  // terms in the same order.
  template <bool G>
  value_gradient<float, D> block_eval(const std::vector<block_impulse<float>>& block,
                                      const lattice_coord<float>* c,
                                      std::vector<kept_impulse>& kept) const;

  // ---- The scalar grid's tiles (grid_values).

  static constexpr std::size_t kGridTile = 64;
  // A run of consecutive sample indices along one axis in one cell (or one sample
  // whose coordinate is not finite: nan).
  struct grid_run {
    std::size_t begin, end;
    bool nan;
  };
  // The x factors of one impulse at one column, and the other axes' at one row
  // (gabor_axis_factors, gabor_row_of), with the products gabor_pair_of_products
  // takes; d2 >= 1 leaves the rest unset (no sample keeps the impulse there).
  struct grid_column {
    float d, d2, ec, es;
  };
  struct grid_row {
    float d[std::size_t{D} - 1], d2, b, q;
  };

  template <bool G>
  void grid_tiles(const grid<D>& g, std::size_t first, std::size_t count, float* out,
                  vec<float, D>* grad) const;

  template <bool G, class Put>
  void grid_tile(const std::vector<block_impulse<float>>& block,
                 const std::vector<lattice_coord<float>> (&coord)[std::size_t{D}],
                 const std::size_t (&lo)[std::size_t{D}], const grid_run& rx, const grid_run& ry,
                 const grid_run& rz, std::vector<grid_column>& cols, std::vector<grid_row>& rows,
                 Put put) const;

  // One impulse of a filtered (or tangent-plane) kernel in E dimensions, without the
  // filter's amplitude (which scales the sum): w e^{-A d^T Q d - Phi^T M Phi}
  // cos(2 pi <Phi, Q d>) tau(s) (one exponential of the summed exponents), added to sum
  // and, with G, its derivative by d to grad. In this order in every backend: v = Q d,
  // d^T Q d = <d, v>, theta = <Phi, v>, Phi^T M Phi = sum of m2_rc Phi_r Phi_c (r <= c).
  template <class T, int E, bool G>
  static void filtered_pair(const detail::gabor_filter_coefs<T, E>& f, T neg_a, T a, T taper_k,
                            const T* d, T s, T w, const T* phi, T& sum, T* grad) {
    using detail::gabor_sym;
    T qd[std::size_t{E}];
    for (int i = 0; i < E; ++i) {
      T z = f.q[gabor_sym<E>(i, 0)] * d[0];
      for (int j = 1; j < E; ++j) z += f.q[gabor_sym<E>(i, j)] * d[j];
      qd[i] = z;
    }
    T dqd = d[0] * qd[0], theta = phi[0] * qd[0];
    for (int i = 1; i < E; ++i) {
      dqd += d[i] * qd[i];
      theta += phi[i] * qd[i];
    }
    T att = f.m2[0] * (phi[0] * phi[0]);
    for (int i = 0, k = 0; i < E; ++i)
      for (int j = i; j < E; ++j, ++k)
        if (k > 0) att += f.m2[k] * (phi[i] * phi[j]);
    // d^T Q d and att are finite for every footprint (gabor_filter): exp_neg's NaN
    // case never arises; a slightly positive sum (rounding) gives 1.
    const T p = w * detail::exp_neg(neg_a * dqd - att);
    const detail::sin_cos<T> sc = detail::sincos_turns(theta);
    if constexpr (G) {
      const detail::gabor_taper_value<T> tw = detail::gabor_taper_derivative(s, taper_k);
      const T pc = p * sc.cos, ps = T(detail::constants::kTwoPi) * ((p * tw.tau) * sc.sin);
      sum += pc * tw.tau;
      for (int i = 0; i < E; ++i) {
        T mu = f.q[gabor_sym<E>(i, 0)] * phi[0];  // (Q Phi)_i
        for (int j = 1; j < E; ++j) mu += f.q[gabor_sym<E>(i, j)] * phi[j];
        grad[i] += pc * ((tw.dtau + tw.dtau) * d[i] - (a + a) * (tw.tau * qd[i])) - ps * mu;
      }
    } else {
      sum += (p * sc.cos) * detail::gabor_taper(s, taper_k);
    }
  }

  // Solid noise filtered over footprint fp (gabor_filter, gabor/kernel.hpp).
  template <class T, bool G>
  value_gradient<T, D> filtered_eval(const vec<double, D>& p, const footprint<D>& fp) const {
    const detail::gabor_filter_coefs<T, D> flt(
        gabor_filter<D>(fp, kernel_.envelope_exponent(), inv_cell_));
    const T neg_a = T(-kernel_.envelope_exponent());
    const T a = T(kernel_.envelope_exponent()), taper_k = taper_k_<T>();
    // Sums by fours as the point form (detail::gabor_point_sum), value and gradient alike.
    detail::gabor_point_sum<T> psum, pg_sum[std::size_t{D}];
    const bool ok = for_each_pair<T>(p, [&](const T* d, const T*, T s, T w, const vec<T, D>& phi) {
      T ph[std::size_t{D}], term = 0, gterm[std::size_t{D}] = {};
      for (int i = 0; i < D; ++i) ph[i] = phi[i];
      filtered_pair<T, D, G>(flt, neg_a, a, taper_k, d, s, w, ph, term, gterm);
      psum.add(term);
      if constexpr (G)
        for (int i = 0; i < D; ++i) pg_sum[i].add(gterm[i]);
    });
    if (!ok) return nan_result<T>();
    // The amplitude scales the sums (every backend: (sum * amplitude) * scale).
    T sum = psum.total() * flt.amplitude, g[std::size_t{D}];
    for (int i = 0; i < D; ++i) g[i] = pg_sum[i].total() * flt.amplitude;
    return finish<T, G>(sum, g, T(scale_), T(scale_ * inv_cell_));
  }

  // Surface noise at p with unit normal n (double), filtered over fp.
  template <class T, bool G>
  value_gradient<T, D> surface_eval(const vec<double, 3>& p, const vec<double, 3>& n,
                                    const footprint<3>& fp) const {
    namespace c = detail::constants;
    vec<double, 3> t, b;
    const detail::gabor_filter_coefs<T, 2> flt(surface_frame(n, fp, t, b));
    const T neg_a = T(-kernel_.envelope_exponent());
    const T a = T(kernel_.envelope_exponent()), taper_k = taper_k_<T>();
    const T nt[3] = {T(n.x), T(n.y), T(n.z)}, tt[3] = {T(t.x), T(t.y), T(t.z)},
            bt[3] = {T(b.x), T(b.y), T(b.z)};
    // Kernel units per surface-cell unit, and 1 / h^2 in surface-cell units.
    const T to_kernel = T(c::kGaborSurfaceCell);
    const T inv_h2 = T((c::kGaborSurfaceCell / c::kGaborSurfaceSlab) *
                       (c::kGaborSurfaceCell / c::kGaborSurfaceSlab));
    const bool normalise = prm_.kind != gabor_kind::anisotropic;
    lattice_coord<T> cc[3];
    for (int ax = 0; ax < 3; ++ax) {
      cc[ax] = lattice_split<T>(p[ax] * inv_surface_cell_);
      if (std::isnan(cc[ax].f)) return nan_result<T>();
    }
    T sum = 0, g[3] = {};
    for (int nc = 0; nc < 27; ++nc) {
      int o[3];
      std::uint32_t cell[3];
      for (int ax = 0, mm = nc; ax < 3; ++ax, mm /= 3) {
        o[ax] = mm % 3 - 1;
        cell[ax] = cc[ax].i0 + static_cast<std::uint32_t>(o[ax]);
      }
      for_each_surface_impulse(cell, [&](const std::uint32_t* words) {
        T d[3];
        for (int ax = 0; ax < 3; ++ax)
          d[ax] = detail::gabor_offset(cc[ax].f, o[ax], impulse_position<T>(words, ax));
        const T zn = (nt[0] * d[0] + nt[1] * d[1]) + nt[2] * d[2];
        const T z2 = (zn * zn) * inv_h2;
        if (!(z2 < T(1))) return;
        const T dk[2] = {((tt[0] * d[0] + tt[1] * d[1]) + tt[2] * d[2]) * to_kernel,
                         ((bt[0] * d[0] + bt[1] * d[1]) + bt[2] * d[2]) * to_kernel};
        const T s = dk[0] * dk[0] + dk[1] * dk[1];
        if (!(s < T(1))) return;
        // The impulse's weight and 3D direction (anisotropic: omega0) and |Phi|.
        T u[4] = {};
        mark_values<T, 3>(words, u);
        const T w = T(2) * u[0] - T(1);
        vec<T, 3> dir;
        T phi = T(marks_.phi0());
        if (prm_.kind == gabor_kind::anisotropic) {
          for (int i = 0; i < 3; ++i) dir[i] = T(marks_.axis()[i]);
        } else {
          marks_.direction(u[1], u[2], dir);
          if (prm_.kind == gabor_kind::hybrid)
            phi = T(marks_.phi0()) + T(marks_.dphi()) * (u[3] - T(0.5));
        }
        const T vt = (tt[0] * dir[0] + tt[1] * dir[1]) + tt[2] * dir[2];
        const T vb = (bt[0] * dir[0] + bt[1] * dir[1]) + bt[2] * dir[2];
        T f = phi;
        if (normalise) {
          const T len2 = vt * vt + vb * vb;
          f = len2 > T(0) ? phi / std::sqrt(len2) : T(0);
        }
        const T ph[2] = {f * vt, f * vb};
        const detail::gabor_taper_value<T> slab = detail::gabor_taper_derivative(z2, taper_k);
        T gs = 0, gk[2] = {0, 0};
        filtered_pair<T, 2, G>(flt, neg_a, a, taper_k, dk, s, w, ph, gs, gk);
        sum += gs * slab.tau;
        if constexpr (G) {
          // d/dd of (kernel * slab taper): the kernel's in-plane derivative
          // (through dk = [t b]^T d sqrt(3/2)) and the slab's along n.
          const T dz = gs * (slab.dtau * ((zn + zn) * inv_h2));
          for (int ax = 0; ax < 3; ++ax)
            g[ax] += ((gk[0] * tt[ax] + gk[1] * bt[ax]) * to_kernel) * slab.tau + dz * nt[ax];
        }
      });
    }
    sum *= flt.amplitude;
    for (int ax = 0; ax < 3; ++ax) g[ax] *= flt.amplitude;
    return finish<T, G>(sum, g, T(surface_scale_), T(surface_scale_ * inv_surface_cell_));
  }

  template <class T, bool G>
  value_gradient<T, D> sample_eval(const sample_input<D>& s) const {
    if constexpr (D == 3) {
      if (s.has_normal) {
        const vec<double, 3>& n = s.normal;
        if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z))
          return nan_result<T>();
        vec<double, 3> unit;
        if (unit_normal(n, unit)) return surface_eval<T, G>(s.position, unit, s.fp);
        // A zero normal has no tangent plane: the solid noise.
      }
    }
    return filtered_eval<T, G>(s.position, s.fp);
  }

  template <class T, bool G>
  static value_gradient<T, D> finish(T sum, const T* g, T scale, T gradient_scale) {
    value_gradient<T, D> r{sum * scale, {}};
    if constexpr (G)
      for (int i = 0; i < D; ++i) r.gradient[i] = g[i] * gradient_scale;
    return r;
  }

  template <class T>
  static value_gradient<T, D> nan_result() {
    const T nan = std::numeric_limits<T>::quiet_NaN();
    value_gradient<T, D> r{nan, {}};
    for (int i = 0; i < D; ++i) r.gradient[i] = nan;
    return r;
  }
  template <class T>
  static T taper_k_() {
    return T(1.0 / (1.0 - detail::constants::kGaborTaperStart));
  }

  params prm_;
  gabor_kernel<D> kernel_;
  std::uint32_t key_ = 0;
  double inv_cell_ = 1, inv_surface_cell_ = 1;
  gabor_marks<D> marks_;
  std::shared_ptr<const poisson_table> table_, surface_table_;
  double scale_ = 1, surface_scale_ = 1;
};

}  // namespace hush

// The batch members' definitions (point_values, the grid's tiles).
#include "hush/gabor/batch.hpp"

// gabor_spectrum, and the SIMD backend's entry points and exec::simd binding, after the
// class they use.
#include "hush/gabor/simd_kernel.hpp"  // IWYU pragma: export
#include "hush/gabor/spectrum.hpp"     // IWYU pragma: export

#endif  // HUSH_GABOR_HPP
