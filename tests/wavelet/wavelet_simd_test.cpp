// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The SIMD kernels of wavelet noise (hush/wavelet/simd-inl.h) against scalar evaluation,
// on every SIMD target compiled into the suite and supported by this CPU. Built like
// perlin_simd_test.cpp (tests/simd/CMakeLists.txt): bit-identical to scalar under
// HUSH_STRICT_FP (simd_strict_test, simd_static_test, simd_single_header_test), within
// twice wavelet::float_budget() / float_gradient_budget() otherwise (simd_test).
// Covered: points, grids and samples (with and without footprints; normals along each
// axis and general, exact and approximate projection, alone and mixed in a vector;
// widening), 2D and 3D, one band and several, values and gradients, every tail length
// up to three vectors, every distribution, tile variants, and the hard cases (NaN, Inf,
// |x| >= 2^31, far grids).
#include <doctest/doctest.h>

#include <algorithm>
#include <cfloat>
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

static_assert(HUSH_CONFIG_SIMD, "the SIMD suites need HUSH_SIMD_DYNAMIC or HUSH_SIMD_STATIC");

[[maybe_unused]] bool same_bits(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return std::memcmp(&a, &b, sizeof a) == 0;
}

double compare(const float* simd, const float* scalar, std::size_t n, double budget) {
  double worst = 0;
  for (std::size_t i = 0; i < n; ++i) {
    INFO("element " << i << ": simd " << simd[i] << ", scalar " << scalar[i]);
    if (std::isnan(simd[i]) || std::isnan(scalar[i])) {
      REQUIRE(std::isnan(simd[i]) == std::isnan(scalar[i]));
      continue;
    }
#if HUSH_CONFIG_STRICT_FP
    (void)budget;
    REQUIRE(same_bits(simd[i], scalar[i]));
#else
    REQUIRE(std::fabs(double(simd[i]) - scalar[i]) <= budget);
#endif
    worst = std::max(worst, std::fabs(double(simd[i]) - scalar[i]));
  }
  return worst;
}

// SIMD against scalar for one noise over `run(policy, out, grad)`, values alone and with
// gradients; returns the largest differences.
template <int D, class Noise, class Run>
std::pair<double, double> check_backend(const Noise& w, std::size_t n, Run run, bool plain) {
  std::vector<float> vs(n), vv(n), gv(n), gs(n);
  std::vector<hush::vec<float, D>> grs(n), grv(n);
  run(hush::exec::scalar, vs, nullptr);
  run(hush::exec::simd, vv, nullptr);
  const double value_budget = 2 * w.float_budget(plain);
  const double grad_budget = 2 * w.float_gradient_budget(plain);
  std::pair<double, double> worst{compare(vv.data(), vs.data(), n, value_budget), 0.0};
  run(hush::exec::scalar, gs, &grs);
  run(hush::exec::simd, gv, &grv);
  worst.first = std::max(worst.first, compare(gv.data(), gs.data(), n, value_budget));
  worst.second = compare(reinterpret_cast<const float*>(grv.data()),
                         reinterpret_cast<const float*>(grs.data()), n * D, grad_budget);
  return worst;
}

template <int D>
std::vector<hush::vec<float, D>> random_points(std::size_t n, float extent, std::uint32_t seed) {
  hush::rng r(seed, D);
  std::vector<hush::vec<float, D>> pts(n);
  for (auto& p : pts)
    for (int a = 0; a < D; ++a) p[a] = r.uniform(-extent, extent);
  return pts;
}

template <int D>
std::vector<hush::wavelet<D>> noises() {
  std::vector<hush::wavelet<D>> r;
  typename hush::wavelet<D>::params prm;
  prm.tile_size = D == 2 ? 32 : 16;
  prm.seed = 3;
  r.emplace_back(prm);  // one band
  prm.weights = {1, -0.5, 0.25, 0.125};
  prm.first_band = -2;
  r.emplace_back(prm);  // several, coarser and finer
  prm.distribution = hush::wavelet_distribution::uniform;
  r.emplace_back(prm);
  prm.distribution = hush::wavelet_distribution::table;
  prm.table = {-3, -1, 0, 0.5, 4};
  r.emplace_back(prm);
  prm = {};
  prm.tile_size = D == 2 ? 32 : 16;
  prm.relative_weights = true;
  prm.weights = {1, 0.5, 0.25};
  prm.first_band = -4;
  prm.relative_bands = 8;
  r.emplace_back(prm);  // infinite noise
  prm = {};
  prm.tile_size = D == 2 ? 32 : 16;
  prm.variant_overlap = 2;
  prm.weights = {1, 0.5};
  r.emplace_back(prm);  // tile variants (the kernels run the scalar code)
  return r;
}

template <int D>
void points_case() {
  for (const auto& w : noises<D>()) {
    std::vector<hush::vec<float, D>> pts = random_points<D>(200, 300, 1);
    // Hard cases in every lane position: NaN, Inf, -0, beyond 2^31, FLT_MAX, tiny negatives.
    const float hard[] = {NAN,   INFINITY, -INFINITY, -0.0f,       3e9f,
                          -5e9f, FLT_MAX,  -1e-30f,   16777216.0f, -1.0f};
    for (std::size_t i = 0; i < 40; ++i) pts[i * 3][i % D] = hard[i % 10];
    for_each_target([&] {
      for (std::size_t n :
           {std::size_t(1), std::size_t(7), std::size_t(17), std::size_t(49), pts.size()}) {
        CAPTURE(n);
        const hush::span<const hush::vec<float, D>> p(pts.data(), n);
        check_backend<D>(
            w, n,
            [&](auto policy, std::vector<float>& out, std::vector<hush::vec<float, D>>* grad) {
              if (grad)
                hush::evaluate(w, policy, p, hush::span<float>(out.data(), n),
                               hush::span<hush::vec<float, D>>(grad->data(), n));
              else
                hush::evaluate(w, policy, p, hush::span<float>(out.data(), n));
            },
            true);
      }
    });
  }
}

template <int D>
void grid_case() {
  for (const auto& w : noises<D>()) {
    std::vector<hush::grid<D>> grids;
    hush::grid<D> g;
    for (int a = 0; a < D; ++a) {
      g.origin[a] = 0.3125 * (a + 1);
      g.step[a] = 1.0 / 7;
      g.size[a] = D == 2 ? 37 : 11;
    }
    grids.push_back(g);
    // Columns running backwards, several per coefficient (the grid kernel's lane lookups
    // with a vector's base at its last column), then columns spanning more than a tile
    // (its gathers from the wrapped row table).
    g.origin[0] = -5.3;
    g.step[0] = -0.2;
    grids.push_back(g);
    g.step[0] = 7.3;
    grids.push_back(g);
    for (int a = 0; a < D; ++a) {
      g.origin[a] = a == 0 ? 1e9 : -3e15;  // far from the origin
      g.step[a] = a == 1 ? -0.75 : 2.5;    // negative and coarser than a coefficient
    }
    grids.push_back(g);
    g.origin[0] = 1e300;  // band positions overflow: taken as 0
    grids.push_back(g);
    for (const auto& gr : grids)
      for_each_target([&] {
        check_backend<D>(
            w, gr.count(),
            [&](auto policy, std::vector<float>& out, std::vector<hush::vec<float, D>>* grad) {
              if (grad)
                hush::evaluate_grid(w, policy, gr, hush::span<float>(out),
                                    hush::span<hush::vec<float, D>>(*grad));
              else
                hush::evaluate_grid(w, policy, gr, hush::span<float>(out));
            },
            true);
      });
  }
}

template <int D>
void samples_case(bool widen, bool normals,
                  hush::wavelet_projection projection = hush::wavelet_projection::exact,
                  bool footprints = true) {
  for (auto w : noises<D>()) {
    auto prm = w.parameters();
    prm.widen = widen;
    prm.projection = projection;
    const hush::wavelet<D> noise{prm};
    const std::size_t n = 150;
    std::vector<hush::vec<float, D>> pts = random_points<D>(n, 50, 2);
    pts[5][0] = NAN;
    std::vector<hush::footprint<D>> fps(n);
    std::vector<hush::vec3> nrm(n);
    hush::rng r(7);
    for (std::size_t i = 0; i < n; ++i) {
      // Points, thin and round footprints over 8 octaves, and "everything".
      const double width =
          i % 9 == 0 ? 0.0 : std::ldexp(r.uniform<double>(0.5, 1.0), int(i % 8) - 6);
      fps[i] = hush::footprint<D>::isotropic(width);
      if (i % 11 == 3) fps[i] = hush::footprint<D>::isotropic(NAN);
      // The SIMD kernel per normal: along z, x, y (beta or B2 along it), general, none
      // (a zero normal). Whole vectors of one kind first (blocks of 16 samples), then
      // every kind mixed within vectors.
      const int kind = i < 80 ? int(i / 16) : int(i % 5);
      const hush::vec3 general{r.uniform(-1.f, 1.f), r.uniform(-1.f, 1.f), r.uniform(-1.f, 1.f)};
      nrm[i] = kind == 0   ? hush::vec3{0, 0, 2}
               : kind == 1 ? hush::vec3{-3, 0, 0}
               : kind == 2 ? hush::vec3{0, 0.5, 0}
               : kind == 3 ? general
                           : hush::vec3{0, 0, 0};
    }
    hush::samples<D> s;
    s.positions = pts;
    if (footprints) s.footprints = fps;  // without: the kernels reuse the bands' plan
    if (D == 3 && normals) s.normals = nrm;
    for_each_target([&] {
      check_backend<D>(
          noise, n,
          [&](auto policy, std::vector<float>& out, std::vector<hush::vec<float, D>>* grad) {
            if (grad)
              hush::evaluate(noise, policy, s, hush::span<float>(out),
                             hush::span<hush::vec<float, D>>(*grad));
            else
              hush::evaluate(noise, policy, s, hush::span<float>(out));
          },
          !widen && !normals);
    });
  }
}

}  // namespace

TEST_CASE("wavelet simd: point batches agree with scalar evaluation (2D, 3D, every distribution)") {
  points_case<2>();
  points_case<3>();
}

TEST_CASE("wavelet simd: grids agree with scalar evaluation, near, far and overflowing") {
  grid_case<2>();
  grid_case<3>();
}

TEST_CASE("wavelet simd: samples with footprints, normals and widening agree with scalar") {
  samples_case<2>(false, false);
  samples_case<2>(true, false);
  samples_case<3>(false, false);
  samples_case<3>(true, true);
}

// Projected lanes run vector kernels (along an axis: beta or B2 taps; any other normal:
// the exact projection's knots per lane, or the paper's approximation over the union of
// the lanes' slabs); every kind, alone in a vector and mixed.
TEST_CASE("wavelet simd: projected samples (axis and general normals, exact and approximate)") {
  for (const bool footprints : {true, false}) {
    samples_case<3>(false, true, hush::wavelet_projection::exact, footprints);
    samples_case<3>(false, true, hush::wavelet_projection::approximate, footprints);
  }
  samples_case<2>(false, false, hush::wavelet_projection::exact, false);
}
