// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Anisotropic noise's SIMD kernels (hush/anisotropic/simd-inl.h) against
// scalar evaluation, on every SIMD target compiled into the suite and
// supported by this CPU. Built into the same four suites as
// perlin_simd_test.cpp (tests/simd/CMakeLists.txt): under HUSH_STRICT_FP
// (simd_strict_test, simd_static_test, simd_single_header_test) every value
// is the scalar value bit for bit; otherwise (simd_test) within twice the
// noise's float budget, as both are within one budget of the double reference.
// Covered: samples with and without footprints and surface maps (random,
// singular, huge, NaN), points, grids near and far, every tail length up to
// three vectors and across the kernel's 64-sample blocks, 2 to 8
// orientations, fbm and turbulence, every weight rule (least squares takes
// the scalar weights), and NaN / Inf / huge positions; values and gradients.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "hush/hush.hpp"
#include "simd/each_target.hpp"

#if HUSH_CONFIG_SIMD && !HUSH_CONFIG_SIMD_STATIC
#include <hwy/targets.h>
#endif

namespace {

[[maybe_unused]] bool same_bits(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  std::uint32_t ua = 0, ub = 0;
  std::memcpy(&ua, &a, sizeof a);
  std::memcpy(&ub, &b, sizeof b);
  return ua == ub;
}

// SIMD against scalar: bit for bit under strict FP, else within 2 budgets.
void compare(const std::vector<float>& simd, const std::vector<float>& scalar, double budget) {
  REQUIRE(simd.size() == scalar.size());
  for (std::size_t i = 0; i < simd.size(); ++i) {
    INFO("element " << i << ": simd " << simd[i] << ", scalar " << scalar[i]);
#if HUSH_CONFIG_STRICT_FP
    (void)budget;
    REQUIRE(same_bits(simd[i], scalar[i]));
#else
    REQUIRE(std::isnan(simd[i]) == std::isnan(scalar[i]));
    if (!std::isnan(simd[i])) REQUIRE(std::fabs(double(simd[i]) - scalar[i]) <= 2 * budget);
#endif
  }
}

// Gradients, SIMD against scalar: bit for bit under strict FP; otherwise
// fused multiply-adds change each of the 5 float operations per channel and
// subband by at most 1 ulp of terms bounded by the scale's texels per unit
// times the weighted texel range, and the gradient's own scale is
// max_s texels_per_unit(s) * bound() (times `stretch` with surface maps): a
// tolerance of 2^-16 of that leaves 2^8 ulp for the sums of up to 4 x 8 terms.
void compare_gradients(const hush::anisotropic& a, const std::vector<hush::vec2>& simd,
                       const std::vector<hush::vec2>& scalar, double stretch = 1.0) {
  REQUIRE(simd.size() == scalar.size());
  double tpu = 0;
  for (int s = 0; s < a.parameters().scales; ++s) tpu = std::max(tpu, a.texels_per_unit(s));
  const double tol = std::ldexp(1.0, -16) * tpu * a.bound() * stretch;
  for (std::size_t i = 0; i < simd.size(); ++i)
    for (int axis = 0; axis < 2; ++axis) {
      const float u = axis ? simd[i].y : simd[i].x, v = axis ? scalar[i].y : scalar[i].x;
      INFO("gradient " << i << " axis " << axis << ": simd " << u << ", scalar " << v);
#if HUSH_CONFIG_STRICT_FP
      (void)tol;
      REQUIRE(same_bits(u, v));
#else
      REQUIRE(std::isnan(u) == std::isnan(v));
      if (!std::isnan(u)) REQUIRE(std::fabs(double(u) - v) <= tol);
#endif
    }
}

hush::anisotropic make(int k, hush::fractal_kind kind, hush::weight_rule filtering,
                       hush::weight_rule compensation, std::uint32_t seed = 5) {
  hush::anisotropic::params p;
  p.seed = seed;
  p.orientations = k;
  p.scales = 4;
  p.base_scale = 1;
  p.octaves = 2;
  p.kind = kind;
  p.tile_size = 32;
  p.filtering = filtering;
  p.compensation = compensation;
  return hush::anisotropic(p);
}

// Random samples with a mix of footprints and maps, and the hard cases.
struct batch {
  std::vector<hush::vec2> pos;
  std::vector<hush::footprint<2>> fp;
  std::vector<hush::surface_map> maps;
};
batch make_batch(std::size_t n, std::uint32_t seed) {
  hush::rng r(seed);
  batch b;
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = INFINITY;
  for (std::size_t i = 0; i < n; ++i) {
    const double extent = i % 3 == 0 ? 1e5 : 30;
    hush::vec2 p{r.uniform(-1.0f, 1.0f) * float(extent), r.uniform(-1.0f, 1.0f) * float(extent)};
    if (i % 37 == 5) p.x = nan;
    if (i % 41 == 7) p.y = -inf;
    if (i % 43 == 9) p.x = 3e9f;     // beyond 2^31 texels: the lane-by-lane split
    if (i % 47 == 11) p.y = -1e38f;  // the product overflows nothing in double; huge cell
    b.pos.push_back(p);
    const double w = std::exp2(r.uniform<double>(-8, 4));
    if (i % 29 == 3)
      b.fp.push_back(hush::footprint<2>::isotropic(std::nan("")));
    else if (i % 31 == 4)
      b.fp.push_back(hush::footprint<2>::from_derivatives(hush::dvec2{w, 0}, hush::dvec2{0, 0}));
    else if (i % 5 == 0)
      b.fp.push_back(hush::footprint<2>{});
    else if (i % 53 == 13)
      // S ~ 1e-40: float(kappa_s q) is subnormal (the SIMD kernel's 4^s z_0 shortcut).
      b.fp.push_back(hush::footprint<2>::from_derivatives(hush::dvec2{1e-20, 3e-21},
                                                          hush::dvec2{-2e-21, 1e-20}));
    else if (i % 11 == 1) {
      // Indefinite by an ulp (a nearly singular S rounded to float): q clamped at 0.
      const float a = float(w * w * 1e6), up[3] = {a, std::nextafter(a, INFINITY), a};
      b.fp.push_back(hush::footprint<2>::from_covariance(up));
    }
    else
      b.fp.push_back(hush::footprint<2>::from_derivatives(
          hush::dvec2{w * r.uniform<double>(-1, 1), w * r.uniform<double>(-1, 1)},
          hush::dvec2{w * r.uniform<double>(-1, 1), w * r.uniform<double>(-1, 1)}));
    hush::surface_map m =
        hush::surface_map::from_matrix(r.uniform<double>(-3, 3), r.uniform<double>(-3, 3),
                                       r.uniform<double>(-3, 3), r.uniform<double>(-3, 3));
    if (i % 23 == 2) m = hush::surface_map::zero();
    if (i % 19 == 1) m.m01 = nan;  // built by hand: counts as the zero map
    if (i % 17 == 6) m = hush::surface_map::from_matrix(3e38, 1, 1, 3e38);
    if (i % 13 == 8) m = hush::surface_map::identity();
    b.maps.push_back(m);
  }
  return b;
}

// The noise on the batch through hush::evaluate with the given inputs; with
// grad, the gradients too (resized to n).
template <class Exec>
std::vector<float> run(const hush::anisotropic& a, const Exec& ex, const batch& b, std::size_t n,
                       bool fps, bool maps, std::vector<hush::vec2>* grad = nullptr) {
  hush::samples<2> s;
  s.positions = {b.pos.data(), n};
  if (fps) s.footprints = {b.fp.data(), n};
  if (maps) s.surface_maps = {b.maps.data(), n};
  std::vector<float> out(n);
  if (grad) {
    grad->resize(n);
    hush::evaluate(a, ex, s, hush::span<float>(out), hush::span<hush::vec2>(*grad));
  } else {
    hush::evaluate(a, ex, s, hush::span<float>(out));
  }
  return out;
}

// Values and gradients of the batch, SIMD against scalar (budget: the values').
void compare_with_gradients(const hush::anisotropic& a, const batch& b, std::size_t n, bool fps,
                            bool maps, double budget) {
  std::vector<hush::vec2> ref_grad, grad;
  const std::vector<float> ref = run(a, hush::exec::scalar, b, n, fps, maps, &ref_grad);
  compare(run(a, hush::exec::simd, b, n, fps, maps, &grad), ref, budget);
  compare_gradients(a, grad, ref_grad, maps ? a.bound_with_maps() / a.bound() : 1.0);
}

}  // namespace

TEST_CASE(
    "anisotropic simd: samples and their gradients equal scalar evaluation (bit for bit under "
    "strict FP)") {
  const batch b = make_batch(300, 17);
  using hush::fractal_kind;
  using hush::weight_rule;
  for (int k : {2, 3, 4, 5, 8})
    for (fractal_kind kind : {fractal_kind::fbm, fractal_kind::turbulence})
      for (weight_rule rule : {weight_rule::centre, weight_rule::three_point}) {
        const hush::anisotropic a = make(k, kind, rule, rule);
        INFO("K " << k << ", kind " << int(kind) << ", rule "
                  << std::string(hush::weight_rule_name(rule)));
        for (int inputs = 0; inputs < 4; ++inputs) {
          const bool fps = inputs & 1, maps = inputs & 2;
          INFO("footprints " << fps << ", maps " << maps);
          const std::vector<float> ref = run(a, hush::exec::scalar, b, b.pos.size(), fps, maps);
          const double budget =
              maps ? a.float_budget() * a.bound_with_maps() / a.bound() : a.float_budget();
          for_each_target([&] {
            compare(run(a, hush::exec::simd, b, b.pos.size(), fps, maps), ref, budget);
            // With gradients: the same values, and the scalar code's gradients.
            compare_with_gradients(a, b, b.pos.size(), fps, maps, budget);
          });
        }
      }
}

TEST_CASE("anisotropic simd: least-squares weights take the scalar weight code") {
  const batch b = make_batch(70, 19);
  const hush::anisotropic a = make(4, hush::fractal_kind::fbm, hush::weight_rule::least_squares,
                                   hush::weight_rule::least_squares);
  const std::vector<float> ref = run(a, hush::exec::scalar, b, b.pos.size(), true, true);
  for_each_target([&] {
    compare(run(a, hush::exec::simd, b, b.pos.size(), true, true), ref, a.float_budget() * 8);
    compare_with_gradients(a, b, b.pos.size(), true, true, a.float_budget() * 8);
  });
}

TEST_CASE("anisotropic simd: every tail length, points and samples") {
  const batch b = make_batch(3 * 64 + 1, 23);
  const hush::anisotropic a =
      make(4, hush::fractal_kind::fbm, hush::weight_rule::centre, hush::weight_rule::centre);
  for_each_target([&] {
    for (std::size_t n = 1; n <= b.pos.size(); n += (n < 50 ? 1 : 13)) {
      INFO("n = " << n);
      compare(run(a, hush::exec::simd, b, n, true, true),
              run(a, hush::exec::scalar, b, n, true, true), a.float_budget() * 8);
      std::vector<float> simd(n), scalar(n);
      hush::evaluate(a, hush::exec::simd, hush::span<const hush::vec2>(b.pos.data(), n),
                     hush::span<float>(simd));
      hush::evaluate(a, hush::exec::scalar, hush::span<const hush::vec2>(b.pos.data(), n),
                     hush::span<float>(scalar));
      compare(simd, scalar, a.float_budget());
      // Points with gradients.
      std::vector<hush::vec2> simd_grad(n), scalar_grad(n);
      hush::evaluate(a, hush::exec::simd, hush::span<const hush::vec2>(b.pos.data(), n),
                     hush::span<float>(simd), hush::span<hush::vec2>(simd_grad));
      hush::evaluate(a, hush::exec::scalar, hush::span<const hush::vec2>(b.pos.data(), n),
                     hush::span<float>(scalar), hush::span<hush::vec2>(scalar_grad));
      compare(simd, scalar, a.float_budget());
      compare_gradients(a, simd_grad, scalar_grad);
    }
  });
}

TEST_CASE("anisotropic simd: grids near and far, and gradients") {
  const hush::anisotropic a =
      make(8, hush::fractal_kind::fbm, hush::weight_rule::centre, hush::weight_rule::centre);
  for (const hush::dvec2 origin :
       {hush::dvec2{0.1, -3.7}, hush::dvec2{1e9, -3e15}, hush::dvec2{-1e300, 5}}) {
    hush::grid<2> g;
    g.origin = origin;
    g.step = {0.0371, -0.0593};
    g.size = {77, 9};
    std::vector<float> ref(g.count());
    hush::evaluate_grid(a, hush::exec::scalar, g, hush::span<float>(ref));
    for_each_target([&] {
      std::vector<float> out(g.count());
      hush::evaluate_grid(a, hush::exec::simd, g, hush::span<float>(out));
      compare(out, ref, a.float_budget());
      // With gradients: the same values, and the gradients of the scalar code.
      std::vector<hush::vec2> grad(g.count()), ref_grad(g.count());
      std::vector<float> ref_value(g.count());
      hush::evaluate_grid(a, hush::exec::simd, g, hush::span<float>(out),
                          hush::span<hush::vec2>(grad));
      hush::evaluate_grid(a, hush::exec::scalar, g, hush::span<float>(ref_value),
                          hush::span<hush::vec2>(ref_grad));
      compare(out, ref_value, a.float_budget());
      compare_gradients(a, grad, ref_grad);
    });
  }
}
