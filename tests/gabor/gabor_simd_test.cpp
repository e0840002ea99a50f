// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Gabor noise's SIMD kernels (hush/gabor/simd-inl.h) against scalar
// evaluation, on every SIMD target compiled into this test and supported by
// this CPU. Built into the same suites as perlin_simd_test.cpp
// (tests/simd/CMakeLists.txt): under HUSH_STRICT_FP (simd_strict_test,
// simd_static_test, simd_single_header_test) bit-identical to scalar, values
// and gradients; otherwise (simd_test) within twice the float budget of
// gabor.hpp. Covered: random points with every tail length up to three
// vectors and the hard cases in every lane position, points crowded in a few
// cells (the shared-cell path) beside far and NaN ones, grids near and far, with
// negative and coarse steps (the points path) and fine ones (the block path:
// blocks across cells, several blocks per row, rows overflowing to Inf halfway),
// 2D and 3D, every kind, samples with footprints (sparse and crowded; random, rank 1,
// zero, NaN, huge and tiny) and with normals
// (surface noise: unit, tiny, zero and non-finite normals, with and without footprints).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "hush/hush.hpp"
#include "simd/each_target.hpp"

#if HUSH_CONFIG_SIMD && !HUSH_CONFIG_SIMD_STATIC
#include <hwy/targets.h>
#endif

namespace {

constexpr double kPi = hush::detail::constants::kPi;

template <int D>
typename hush::gabor<D>::params gabor_params(hush::gabor_kind kind) {
  typename hush::gabor<D>::params p;
  p.seed = 9;
  p.kind = kind;
  p.orientation = 0.7;
  p.elevation = -0.4;
  if (kind == hush::gabor_kind::hybrid) {
    p.orientation_spread = 2.0;
    p.frequency_spread = 0.5;
  }
  return p;
}

// gabor.hpp's float budget (tests/gabor/gabor_test.cpp): scale 2^-21 (1 + 2 pi Phi)
// (N' + 1); SIMD and scalar are each within it of the double reference. The
// gradient's: the same times (1 + the per-kernel slope bound in noise units,
// (2A + 2 pi Phi + 3 / (1 - s0)) / r).
template <int D>
double value_budget(const hush::gabor<D>& g) {
  const double phi = g.marks().phi0() + g.marks().dphi();
  return 2 * g.scale() * std::ldexp(1.0, -21) * (1 + 2 * kPi * phi) * (g.parameters().impulses + 1);
}
template <int D>
double gradient_budget(const hush::gabor<D>& g) {
  const double phi = g.marks().phi0() + g.marks().dphi(), a = g.kernel().envelope_exponent();
  const double slope =
      (2 * a + 2 * kPi * phi + 3 / (1 - hush::detail::constants::kGaborTaperStart)) *
      g.inverse_cell();
  return value_budget(g) * (1 + slope);
}

void compare(const float* simd, const float* scalar, std::size_t n, double budget) {
  for (std::size_t i = 0; i < n; ++i) {
    INFO("element " << i << ": simd " << simd[i] << ", scalar " << scalar[i]);
    if (std::isnan(simd[i]) || std::isnan(scalar[i])) {
      REQUIRE((std::isnan(simd[i]) && std::isnan(scalar[i])));
      continue;
    }
#if HUSH_CONFIG_STRICT_FP
    (void)budget;
    REQUIRE(std::memcmp(&simd[i], &scalar[i], sizeof(float)) == 0);
#else
    REQUIRE(std::fabs(double(simd[i]) - scalar[i]) <= budget);
#endif
  }
}

template <int D>
void check_points(const hush::gabor<D>& g, const std::vector<hush::vec<float, D>>& pts) {
  const std::size_t n = pts.size();
  const hush::span<const hush::vec<float, D>> in(pts.data(), n);
  std::vector<float> a(n), b(n), c(n);
  std::vector<hush::vec<float, D>> ga(n), gb(n);
  hush::evaluate(g, hush::exec::scalar, in, hush::span<float>(a),
                 hush::span<hush::vec<float, D>>(ga));
  for_each_target([&] {
    hush::evaluate(g, hush::exec::simd, in, hush::span<float>(b),
                   hush::span<hush::vec<float, D>>(gb));
    hush::evaluate(g, hush::exec::simd, in, hush::span<float>(c));
    compare(b.data(), a.data(), n, value_budget(g));
    compare(c.data(), a.data(), n, value_budget(g));
    compare(reinterpret_cast<const float*>(gb.data()), reinterpret_cast<const float*>(ga.data()),
            n * D, gradient_budget(g));
  });
}

template <int D>
void check_grid(const hush::gabor<D>& g, const hush::grid<D>& grid) {
  const std::size_t n = grid.count();
  std::vector<float> a(n), b(n), c(n);
  std::vector<hush::vec<float, D>> ga(n), gb(n);
  hush::evaluate_grid(g, hush::exec::scalar, grid, hush::span<float>(a),
                      hush::span<hush::vec<float, D>>(ga));
  for_each_target([&] {
    hush::evaluate_grid(g, hush::exec::simd, grid, hush::span<float>(b),
                        hush::span<hush::vec<float, D>>(gb));
    hush::evaluate_grid(g, hush::exec::simd, grid, hush::span<float>(c));
    compare(b.data(), a.data(), n, value_budget(g));
    compare(c.data(), a.data(), n, value_budget(g));
    compare(reinterpret_cast<const float*>(gb.data()), reinterpret_cast<const float*>(ga.data()),
            n * D, gradient_budget(g));
  });
}

// Random points in [-half, half]^D with the hard cases spread over lane
// positions. A small half crowds many points into each cell: the shared-cell
// path (each cell's impulses drawn once and summed by every point that sees
// it), with the far and non-finite points beside them in the same call.
template <int D>
std::vector<hush::vec<float, D>> test_points(std::size_t n, std::uint32_t seed,
                                             float half = 40.0f) {
  hush::rng r(seed);
  std::vector<hush::vec<float, D>> pts(n);
  for (auto& p : pts)
    for (int a = 0; a < D; ++a) p[a] = r.uniform<float>(-half, half);
  const float specials[] = {std::numeric_limits<float>::quiet_NaN(),
                            std::numeric_limits<float>::infinity(),
                            -1.0f,
                            -0.0f,
                            std::nextafter(-1.0f, 0.0f),
                            4294967296.0f,
                            -3e9f,
                            1e-40f,
                            std::numeric_limits<float>::max()};
  std::size_t at = 0;
  for (const float s : specials) {
    at = (at * 7 + 5) % n;
    pts[at][at % D] = s;
  }
  return pts;
}

}  // namespace

TEST_CASE("gabor simd: points agree with scalar evaluation, every kind and tail length") {
  for (const hush::gabor_kind kind :
       {hush::gabor_kind::isotropic, hush::gabor_kind::anisotropic, hush::gabor_kind::hybrid}) {
    INFO("kind " << static_cast<int>(kind));
    const hush::gabor<2> g2(gabor_params<2>(kind));
    const hush::gabor<3> g3(gabor_params<3>(kind));
    for (std::size_t n = 1; n <= 49; n += 3) {
      check_points(g2, test_points<2>(n, static_cast<std::uint32_t>(n)));
      check_points(g3, test_points<3>(n, static_cast<std::uint32_t>(n + 100)));
    }
    check_points(g2, test_points<2>(1000, 1));
    check_points(g3, test_points<3>(500, 2));
    check_points(g2, test_points<2>(1500, 3, 2.0f));  // ~90 points per cell
    check_points(g3, test_points<3>(400, 4, 2.0f));   // ~6 points per cell
    // Boxes about 9 cells wide: the padding lanes of a cell's candidate list (past its last
    // candidate) must stay outside every support wherever the cell sits in the box (they
    // once kept a stale cell offset, up to the box's width, and reached points near its
    // right edge: 70 of these 1500 points wrong by up to 1.1 on AVX3).
    check_points(g2, test_points<2>(1500, 5, 4.0f));
    check_points(g3, test_points<3>(800, 4, 4.0f));
    // Boxes of ~1200 cells (2D, ~4 points per cell) and ~2700 (3D, ~1.2) at N' = 16:
    // draw_box hashes their ~6000 and ~14000 impulses in several chunks of kDrawChunk, from
    // cells of ~5 impulses (one vector each; the N' = 128 case below has longer ones).
    check_points(g2, test_points<2>(4000, 6, 16.0f));
    check_points(g3, test_points<3>(2000, 7, 6.0f));
  }
  // Boxes of several bands: shared_points draws kShareBandImpulses' worth of slabs (at least
  // kShareBandMinSlabs) at a time, each band with its two neighbouring slabs, just before
  // its points. 2D: ~80 x 80 cells of ~5 impulses, 40 rows per band, 2 bands (~3.7 points per
  // cell); 3D: ~22^3 cells of ~3.8 impulses, 8 slabs per band, 3 bands (~0.8 points per cell).
  const hush::gabor<2> g2(gabor_params<2>(hush::gabor_kind::isotropic));
  const hush::gabor<3> g3(gabor_params<3>(hush::gabor_kind::isotropic));
  check_points(g2, test_points<2>(24000, 8, 48.0f));
  check_points(g3, test_points<3>(8000, 9, 12.0f));
}

TEST_CASE("gabor simd: crowded points with many cycles and impulses per cell agree with scalar") {
  // The kernel of kept impulses takes sin/cos without range reduction below
  // kTurnsReduceLimit / 2 cycles per cell (consts::small_turns; beyond, the
  // general sincos_turns, whose noises take ~1.6 ms per 3 cycles per cell to
  // construct: too slow here): F0 = 10, a = 0.3 put ~33 cycles in a cell, so
  // every quadrant and sign of the reduction-free form is reached; N' = 128
  // and ~24 points per cell: candidate lists of ~370 impulses per cell.
  hush::gabor<2>::params p = gabor_params<2>(hush::gabor_kind::hybrid);
  p.frequency = 10;
  p.bandwidth = 0.3;
  p.impulses = 128;
  const hush::gabor<2> g(p);
  check_points(g, test_points<2>(600, 5, 8.0f));
}

TEST_CASE("gabor simd: grids agree with scalar evaluation (blocks, points path, far, negative)") {
  const hush::gabor<2> g2(gabor_params<2>(hush::gabor_kind::isotropic));
  const hush::gabor<2> h2(gabor_params<2>(hush::gabor_kind::hybrid));
  hush::grid<2> fine;  // ~45 samples per cell: the block path
  fine.origin = {0.3125, -2.71875};
  fine.step = {1.0 / 37, 1.0 / 37};
  fine.size = {131, 77};
  check_grid(g2, fine);
  check_grid(h2, fine);
  // Very fine rows (~370 samples per cell, blocks cut at 64 along x): most vectors lie
  // wholly inside the untapered disk or outside the support (skipped), few straddle.
  hush::grid<2> finer = fine;
  finer.step = {1.0 / 300, 1.0 / 29};
  finer.size = {700, 9};
  check_grid(g2, finer);
  hush::grid<2> far = fine;  // far from the origin, negative steps; rows of 2 blocks along x
  far.origin = {-1e9, 3.5e7};
  far.step = {-1.0 / 50, 1.0 / 64};
  far.size = {300, 40};
  check_grid(g2, far);
  // Rows that overflow to +Inf halfway (non-finite samples beside finite ones in one block:
  // every finite x here is a multiple of 2^32, cell 0 with fraction 0, so the block path).
  hush::grid<2> overflow = fine;
  overflow.origin = {1.79e308, 0.5};
  overflow.step = {1e305, 1.0 / 37};
  overflow.size = {150, 5};
  {
    std::vector<float> v(overflow.count());
    hush::evaluate_grid(g2, hush::exec::scalar, overflow, hush::span<float>(v));
    const auto nans = std::count_if(v.begin(), v.end(), [](float x) { return std::isnan(x); });
    REQUIRE(nans > 0);  // the premise: both kinds of sample in each row
    REQUIRE(nans < static_cast<std::ptrdiff_t>(v.size()));
  }
  check_grid(g2, overflow);
  // So far out that a double's spacing is 2^30 cells or more: ~21 samples per distinct
  // position, neighbouring ones' cells 2^30 or more apart (mod 2^32): blocks of one cell's run.
  hush::grid<2> huge = fine;
  huge.origin = {1e25, 0.25};
  huge.size = {200, 3};
  huge.step = {1e8, 1.0 / 37};
  check_grid(g2, huge);
  hush::grid<2> coarse = fine;  // about one sample per cell: the points path
  coarse.step = {0.9, -1.3};
  coarse.size = {40, 33};
  check_grid(h2, coarse);
  const hush::gabor<3> g3(gabor_params<3>(hush::gabor_kind::isotropic));
  const hush::gabor<3> a3(gabor_params<3>(hush::gabor_kind::anisotropic));
  hush::grid<3> cube;
  cube.origin = {0.3125, -2.71875, 5.0625};
  cube.step = {1.0 / 37, 1.0 / 29, -1.0 / 31};
  cube.size = {45, 23, 19};
  check_grid(g3, cube);
  check_grid(a3, cube);
  hush::grid<3> wide = cube;  // 3 blocks along x, cut within cells
  wide.size = {150, 7, 5};
  check_grid(g3, wide);
}

namespace {

// Samples with footprints of every size (and HARD_CASES row 12's degenerate ones), and,
// in 3D, the same with normals (surface noise; zero normals: the solid noise, non-finite
// ones: NaN, tiny ones: their direction) and with normals but no footprints. A small
// half crowds the points (filtered samples: the shared-cell path).
template <int D>
void check_samples(const hush::gabor<D>& g, std::size_t n, std::uint32_t seed,
                   float half = 40.0f) {
  const std::vector<hush::vec<float, D>> pts = test_points<D>(n, seed, half);
  std::vector<hush::footprint<D>> fps(n);
  std::vector<hush::vec3> nrm(n);
  hush::rng r(seed + 1000);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = std::pow(10.0, r.uniform<double>(-4.0, 1.0));
    hush::vec<double, D> dx, dy;
    for (int a = 0; a < D; ++a) {
      dx[a] = s * r.uniform<double>(-1, 1);
      dy[a] = s * r.uniform<double>(-1, 1);
    }
    if (i % 11 == 3) dy = dx;                           // rank 1
    if (i % 13 == 5) dx = dy = hush::vec<double, D>{};  // zero: the unfiltered noise
    if (i % 17 == 7) dx[0] = std::numeric_limits<double>::quiet_NaN();  // the widest
    // Huge (S ~ 1e30, capped at 2^64: the amplitude ~1e-30) and tiny (S ~ 1e-30)
    // footprints: 2D, the filters in lanes of doubles (filters_2d) against
    // gabor_filter<2>; 3D surface samples, the projection onto the tangent plane
    // (ill-conditioned here: it once differed from scalar by up to 180 ulp, GCC's
    // vectorizer dropping its float round trip in the SIMD targets' inlined copy).
    if (i % 29 == 9)
      for (int a = 0; a < D; ++a) dx[a] *= 1e15, dy[a] *= 1e15;
    if (i % 31 == 10)
      for (int a = 0; a < D; ++a) dx[a] *= 1e-15, dy[a] *= 1e-15;
    fps[i] = hush::footprint<D>::from_derivatives(dx, dy);
    nrm[i] = {r.uniform<float>(-1, 1), r.uniform<float>(-1, 1), r.uniform<float>(-1, 1)};
    if (i % 19 == 2) nrm[i] = {};                                             // the solid noise
    if (i % 23 == 4) nrm[i].y = std::numeric_limits<float>::infinity();       // NaN
    if (i % 7 == 1) nrm[i] = {nrm[i].x * 1e-30f, nrm[i].y * 1e-30f, 1e-38f};  // tiny
  }
  // 0: footprints, 1: footprints and normals, 2: normals only.
  for (const int variant : {0, 1, 2}) {
    if (variant != 0 && D == 2) continue;
    INFO("variant " << variant);
    using fp_span = hush::span<const hush::footprint<D>>;
    using normal_span = hush::span<const hush::vec3>;
    const hush::samples<D> s{pts, variant == 2 ? fp_span() : fp_span(fps),
                             variant == 0 ? normal_span() : normal_span(nrm)};
    std::vector<float> a(n), b(n), c(n);
    std::vector<hush::vec<float, D>> ga(n), gb(n);
    hush::evaluate(g, hush::exec::scalar, s, hush::span<float>(a),
                   hush::span<hush::vec<float, D>>(ga));
    for_each_target([&] {
      hush::evaluate(g, hush::exec::simd, s, hush::span<float>(b),
                     hush::span<hush::vec<float, D>>(gb));
      hush::evaluate(g, hush::exec::simd, s, hush::span<float>(c));
      // The filter adds the phase and attenuation terms to the budget (as on GLSL).
      const double phi = g.marks().phi0() + g.marks().dphi(), aa = g.kernel().envelope_exponent();
      double f = 1 + 2 * kPi * phi + kPi * kPi * phi * phi / aa;
      // Surface noise sums its terms with surface_scale() instead of scale().
      if constexpr (D == 3)
        if (variant != 0) f *= std::fmax(1.0, g.surface_scale() / g.scale());
      compare(b.data(), a.data(), n, value_budget(g) * f);
      compare(c.data(), a.data(), n, value_budget(g) * f);
      compare(reinterpret_cast<const float*>(gb.data()), reinterpret_cast<const float*>(ga.data()),
              n * D, gradient_budget(g) * f);
    });
  }
}

}  // namespace

TEST_CASE("gabor simd: filtered samples agree with scalar evaluation, every kind, 2D and 3D") {
  for (const hush::gabor_kind kind :
       {hush::gabor_kind::isotropic, hush::gabor_kind::anisotropic, hush::gabor_kind::hybrid}) {
    INFO("kind " << static_cast<int>(kind));
    const hush::gabor<2> g2(gabor_params<2>(kind));
    const hush::gabor<3> g3(gabor_params<3>(kind));
    for (std::size_t n : {1u, 7u, 16u, 33u, 300u}) {
      check_samples(g2, n, static_cast<std::uint32_t>(n));
      check_samples(g3, n, static_cast<std::uint32_t>(n + 50));
    }
    // Crowded (~90 points per cell in 2D, ~6 in 3D) beside far and non-finite ones:
    // filtered samples on the shared-cell path, its outliers on the lockstep path.
    check_samples(g2, 1500, 3, 2.0f);
    check_samples(g3, 400, 4, 2.0f);
    check_samples(g2, 1500, 5, 4.0f);  // boxes ~9 cells wide (check_points' padding case)
  }
  // Sparse impulses (N' = 0.5: a cell's 3 x 3 neighbourhood empty with probability
  // e^{-9 N' / pi} ~ 0.24) under crowded points (~90 per cell): runs of points without
  // pairs, several ending within one vector of pairs, where shared_filtered's kernel
  // (gradients; 2D values compute the filter's terms in the test) gathers each lane's
  // filter instead of permuting those of consecutive points (3 or more points within one
  // vector since its window of point ends: the loop past the window).
  auto sparse = gabor_params<2>(hush::gabor_kind::isotropic);
  sparse.impulses = 0.5;
  check_samples(hush::gabor<2>(sparse), 1500, 5, 2.0f);
}
