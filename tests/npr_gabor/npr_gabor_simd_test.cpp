// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// NPR Gabor noise's SIMD splatting (hush/npr_gabor/simd-inl.h) against the scalar stage 2,
// on every SIMD target compiled into this test and supported by this CPU. Built into the
// four suites of tests/simd/CMakeLists.txt: under HUSH_STRICT_FP every pixel must equal
// render<float> on exec::scalar bit for bit; with contraction allowed within twice the
// kernel's float budget per pixel (2^-21 (1 + 2 pi |F| r) per kernel times the sum of the
// |weights| of the records covering it, hush/npr_gabor.hpp). Covered: a slanted, perturbed
// scene whose depths fall inside, in the soft band of, and beyond the depth tolerance, with
// foreign object and triangle ids and NaN, Inf, negative, zero and denormal depths sprinkled
// over every lane position; every test switch, the soft band, isotropic kernels, per-record
// frequencies and radii, and image sizes around the tile size (edges, tails, 1 pixel).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "hush/hush.hpp"
#include "npr_gabor_scenes.hpp"
#include "simd/each_target.hpp"

#if HUSH_CONFIG_SIMD && !HUSH_CONFIG_SIMD_STATIC
#include <hwy/targets.h>
#endif

namespace {

// A grid scene (tests/npr_gabor/npr_gabor_scenes.hpp) made harder: 1/z affine but slanted, the
// G-buffer depth off the plane by up to +-6% (the default tolerance is 2%: pass, soft band
// and fail all occur), some pixels showing another object or triangle, and bad depths.
struct hard_scene {
  npr_test::grid_scene sc;
  hush::frame f;
  hush::triangle_list t;

  hard_scene(std::size_t w, std::size_t h, double cell)
      : sc(w, h, -3.3, -5.1, cell, static_cast<int>(static_cast<double>(w) / cell) + 2,
           static_cast<int>(static_cast<double>(h) / cell) + 2) {
    auto inv_z = [](double x, double y) { return 0.5 + 0.001 * x + 0.0007 * y; };
    for (std::size_t v = 0; v < sc.screen.size(); ++v)
      sc.vdepth[v] = static_cast<float>(1.0 / inv_z(sc.screen[v].x, sc.screen[v].y));
    const float bad[] = {std::numeric_limits<float>::quiet_NaN(),
                         std::numeric_limits<float>::infinity(), -1.0f, 0.0f,
                         std::numeric_limits<float>::denorm_min() * 3};
    std::uint32_t s = 12345u;
    for (std::size_t p = 0; p < w * h; ++p) {
      s = s * 1664525u + 1013904223u;
      const double u = static_cast<double>(s >> 8) / 16777216.0;
      const double xc = static_cast<double>(p % w) + 0.5, yc = static_cast<double>(p / w) + 0.5;
      sc.depth[p] = static_cast<float>((1.0 + 0.12 * (u - 0.5)) / inv_z(xc, yc));
      if (u < 0.03) sc.object[p] = 2;
      if (u > 0.97) sc.triangle[p] ^= 1u;
      if (p % 97 < 5) sc.depth[p] = bad[p % 97];
    }
    f.depth = {sc.depth.data(), w, h};
    f.object_id = {sc.object.data(), w, h};
    f.triangle_id = {sc.triangle.data(), w, h};
    t.indices = sc.indices;
    t.screen = sc.screen;
    t.depth = sc.vdepth;
    t.triangle_id = sc.tri_id;
    t.object_id = sc.obj_id;
  }
};

// Per pixel, twice the float budget of the records covering it.
std::vector<double> budget_of(const std::vector<hush::npr_gabor_splat>& splats, std::size_t w,
                              std::size_t h) {
  std::vector<double> b(w * h, 0.0);
  for (const hush::npr_gabor_splat& s : splats) {
    const double per = 2.0 * std::ldexp(1.0, -21) *
                       (1.0 + 2.0 * 3.141592653589793 * std::hypot(s.fx, s.fy) * s.radius) *
                       std::fabs(s.weight);
    for (std::int32_t y = s.y0; y <= s.y1; ++y)
      for (std::int32_t x = s.x0; x <= s.x1; ++x)
        b[static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x)] += per;
  }
  return b;
}

void compare(const std::vector<float>& simd, const std::vector<float>& scalar,
             const std::vector<double>& budget) {
  std::size_t bad = simd.size();
  for (std::size_t i = 0; i < simd.size() && bad == simd.size(); ++i) {
#if HUSH_CONFIG_STRICT_FP
    (void)budget;
    if (std::memcmp(&simd[i], &scalar[i], sizeof(float)) != 0) bad = i;
#else
    if (!(std::fabs(double(simd[i]) - double(scalar[i])) <= budget[i])) bad = i;
#endif
  }
  if (bad < simd.size())
    INFO("pixel " << bad << ": simd " << simd[bad] << ", scalar " << scalar[bad]);
  REQUIRE(bad == simd.size());
}

// Renders `prm` on both backends through the splat list (with `edit` applied to the
// records) and compares.
template <class Edit>
void check_backends(const hard_scene& hs, const hush::npr_gabor::params& prm, Edit edit) {
  const hush::npr_gabor noise{prm};
  const std::size_t w = hs.f.width(), h = hs.f.height();
  std::vector<hush::npr_gabor_splat> splats;
  noise.make_splats(hs.f, hs.t, splats);
  edit(splats);
  std::vector<float> scalar(w * h, -7.0f), simd(w * h, -7.0f);
  noise.splat(hush::exec::scalar, hs.f, splats.data(), splats.size(),
              hush::image_view<float>{scalar.data(), w, h});
  const std::vector<double> budget = budget_of(splats, w, h);
  std::size_t nonzero = 0;
  for (float v : scalar) nonzero += v != 0.0f;
  // Every scene leaves pixels with noise (the comparison is not of zeros).
  if (!splats.empty() && w * h > 64) CHECK(nonzero > w * h / 4);
  for_each_target([&] {
    std::fill(simd.begin(), simd.end(), -7.0f);
    noise.splat(hush::exec::simd, hs.f, splats.data(), splats.size(),
                hush::image_view<float>{simd.data(), w, h});
    compare(simd, scalar, budget);
  });
}

void check_backends(const hard_scene& hs, const hush::npr_gabor::params& prm) {
  check_backends(hs, prm, [](std::vector<hush::npr_gabor_splat>&) {});
}

}  // namespace

TEST_CASE("npr_gabor SIMD splatting equals scalar with every visibility test combination") {
  const hard_scene hs(301, 203, 4.7);
  for (int mode = 0; mode < 16; ++mode) {
    hush::npr_gabor::params prm;
    prm.object_test = (mode & 1) != 0;
    prm.triangle_test = (mode & 2) != 0;
    prm.depth_test = (mode & 4) != 0;
    prm.soft_depth = (mode & 8) != 0;
    prm.orientation = 0.3;
    INFO("object " << prm.object_test << " triangle " << prm.triangle_test << " depth "
                   << prm.depth_test << " soft " << prm.soft_depth);
    check_backends(hs, prm);
  }
}

TEST_CASE("npr_gabor SIMD splatting equals scalar: isotropic, other kernels, every image size") {
  hush::npr_gabor::params prm;
  prm.isotropic = true;
  prm.soft_depth = true;
  prm.frequency = 0.31;
  prm.bandwidth = 0.15;
  prm.impulses = 24;
  for (std::size_t w : {1u, 7u, 16u, 17u, 33u, 64u}) {
    for (std::size_t h : {1u, 15u, 16u, 31u}) {
      INFO("size " << w << "x" << h);
      const hard_scene hs(w, h, 3.1);
      check_backends(hs, prm);
    }
  }
}

TEST_CASE("npr_gabor SIMD splatting honours per-record frequency, radius and weight") {
  const hard_scene hs(160, 90, 5.3);
  hush::npr_gabor::params prm;
  prm.soft_depth = true;
  check_backends(hs, prm, [](std::vector<hush::npr_gabor_splat>& splats) {
    REQUIRE(splats.size() > 100);
    for (std::size_t i = 0; i < splats.size(); ++i) {
      hush::npr_gabor_splat& s = splats[i];
      const double k = static_cast<double>(i % 7) / 7.0;
      s.fx = 0.4 * std::cos(6.0 * k);
      s.fy = 0.4 * std::sin(6.0 * k);
      s.radius *= 0.5 + 0.5 * k;  // within the record's pixel range
      s.weight *= 1.0 + k;
    }
  });
}

TEST_CASE("npr_gabor render on exec::simd is the splat list splatted, and 0 without records") {
  const hard_scene hs(97, 61, 4.1);
  const hush::npr_gabor noise{hush::npr_gabor::params{}};
  const std::size_t w = 97, h = 61;
  std::vector<float> a(w * h), b(w * h, 3.0f);
  noise.render(hush::exec::simd, hs.f, hs.t, hush::image_view<float>{a.data(), w, h});
  std::vector<hush::npr_gabor_splat> splats;
  noise.make_splats(hs.f, hs.t, splats);
  noise.splat(hush::exec::simd, hs.f, splats.data(), splats.size(),
              hush::image_view<float>{b.data(), w, h});
  CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
  noise.splat(hush::exec::simd, hs.f, splats.data(), 0, hush::image_view<float>{b.data(), w, h});
  CHECK(std::all_of(b.begin(), b.end(), [](float v) { return v == 0.0f; }));
}
