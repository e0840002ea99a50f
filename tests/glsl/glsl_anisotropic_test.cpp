// Anisotropic noise on the GLSL backend (hush/glsl/anisotropic_program.hpp)
// against the CPU float path: samples with footprints and surface maps,
// points and grids, values (hardware bilinear filtering of the tile
// textures) and gradients (texelFetch), fbm and turbulence, 2 to 8
// orientations, both heuristic rules; within the tolerance the program
// states per sample. Also: tiles uploaded once per shared tile, least-squares
// rules refused, NaN positions.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "glsl_test_util.hpp"
#include "hush/glsl/device.hpp"

namespace {

using hush_glsl_test::headless;

hush::anisotropic make(int k, hush::fractal_kind kind, hush::weight_rule rule,
                       std::uint32_t seed = 9) {
  hush::anisotropic::params p;
  p.seed = seed;
  p.orientations = k;
  p.scales = 4;
  p.base_scale = 1;
  p.octaves = 2;
  p.kind = kind;
  p.tile_size = 64;
  p.filtering = rule;
  p.compensation = rule;
  return hush::anisotropic(p);
}

struct batch {
  std::vector<hush::vec2> pos;
  std::vector<hush::footprint<2>> fp;
  std::vector<hush::surface_map> maps;
};
batch make_batch(std::size_t n, std::uint32_t seed) {
  hush::rng r(seed);
  batch b;
  for (std::size_t i = 0; i < n; ++i) {
    const float extent = i % 4 == 3 ? 1e5f : 40.0f;
    b.pos.push_back({r.uniform(-extent, extent), r.uniform(-extent, extent)});
    const double w = std::exp2(r.uniform<double>(-8, 3));
    b.fp.push_back(
        i % 6 == 0 ? hush::footprint<2>{}
                   : hush::footprint<2>::from_derivatives(
                         hush::dvec2{w * r.uniform<double>(-1, 1), w * r.uniform<double>(-1, 1)},
                         hush::dvec2{w * r.uniform<double>(-1, 1), w * r.uniform<double>(-1, 1)}));
    auto m = hush::surface_map::from_matrix(r.uniform<double>(-3, 3), r.uniform<double>(-3, 3),
                                            r.uniform<double>(-3, 3), r.uniform<double>(-3, 3));
    if (i % 11 == 5) m = hush::surface_map::zero();
    if (i % 13 == 7) m.m10 = std::numeric_limits<float>::quiet_NaN();
    b.maps.push_back(m);
  }
  b.pos[7].x = std::numeric_limits<float>::quiet_NaN();
  return b;
}

// The tolerance of sample i (anisotropic_program.hpp): from its weights.
double tolerance(const hush::anisotropic& a, const batch& b, std::size_t i, bool fps, bool maps,
                 bool hardware) {
  hush::sample_input<2> in;
  if (fps) in.fp = b.fp[i];
  if (maps) {
    in.map = b.maps[i];
    in.has_map = true;
  }
  float w[12 * 8] = {};
  if (a.parameters().kind == hush::fractal_kind::fbm) {
    a.weights<float>(in, w);
  } else {
    float wk[12 * 8];
    double g = 1;
    for (int k = 0; k < a.parameters().octaves; ++k, g *= a.parameters().gain) {
      a.octave_weights<float>(in, k, wk);
      for (int j = 0; j < 12 * 8; ++j) w[j] += float(g) * std::fabs(wk[j]);
    }
  }
  return hush::glsl::noise_program<hush::anisotropic>::tolerance(a, w, hardware);
}

}  // namespace

TEST_CASE("glsl anisotropic: samples agree with the CPU within the stated tolerance") {
  auto& dev = headless().device;
  const batch b = make_batch(2000, 3);
  using hush::fractal_kind;
  using hush::weight_rule;
  double worst_ratio = 0, worst = 0;
  for (int k : {2, 4, 6, 8})
    for (fractal_kind kind : {fractal_kind::fbm, fractal_kind::turbulence})
      for (weight_rule rule : {weight_rule::centre, weight_rule::three_point}) {
        const hush::anisotropic a = make(k, kind, rule);
        for (int inputs = 0; inputs < 4; ++inputs) {
          const bool fps = inputs & 1, maps = inputs & 2;
          hush::samples<2> s;
          s.positions = {b.pos.data(), b.pos.size()};
          if (fps) s.footprints = {b.fp.data(), b.fp.size()};
          if (maps) s.surface_maps = {b.maps.data(), b.maps.size()};
          std::vector<float> cpu(b.pos.size()), gpu(b.pos.size());
          hush::evaluate(a, hush::exec::scalar, s, hush::span<float>(cpu));
          hush::evaluate(a, hush::exec::glsl{dev}, s, hush::span<float>(gpu));
          for (std::size_t i = 0; i < cpu.size(); ++i) {
            INFO("K " << k << " kind " << int(kind) << " rule " << int(rule) << " inputs " << inputs
                      << " sample " << i << ": cpu " << cpu[i] << " gpu " << gpu[i]);
            REQUIRE(std::isnan(cpu[i]) == std::isnan(gpu[i]));
            if (std::isnan(cpu[i])) continue;
            const double e = std::fabs(double(gpu[i]) - cpu[i]);
            const double tol = tolerance(a, b, i, fps, maps, true);
            CHECK(e <= tol);
            worst = std::max(worst, e);
            worst_ratio = std::max(worst_ratio, e / tol);
          }
        }
      }
  MESSAGE("llvmpipe, hardware bilinear: max |gpu - cpu| = " << worst << ", max error / tolerance = "
                                                            << worst_ratio);
}

TEST_CASE("glsl anisotropic: gradients (texelFetch) agree with the CPU") {
  auto& dev = headless().device;
  const batch b = make_batch(500, 5);
  for (hush::fractal_kind kind : {hush::fractal_kind::fbm, hush::fractal_kind::turbulence}) {
    const hush::anisotropic a = make(5, kind, hush::weight_rule::centre);
    hush::samples<2> s;
    s.positions = {b.pos.data(), b.pos.size()};
    s.footprints = {b.fp.data(), b.fp.size()};
    s.surface_maps = {b.maps.data(), b.maps.size()};
    std::vector<float> cpu(b.pos.size()), gpu(b.pos.size());
    std::vector<hush::vec2> gc(b.pos.size()), gg(b.pos.size());
    hush::evaluate(a, hush::exec::scalar, s, hush::span<float>(cpu), hush::span<hush::vec2>(gc));
    hush::evaluate(a, hush::exec::glsl{dev}, s, hush::span<float>(gpu), hush::span<hush::vec2>(gg));
    for (std::size_t i = 0; i < cpu.size(); ++i) {
      if (std::isnan(cpu[i])) {
        CHECK(std::isnan(gpu[i]));
        continue;
      }
      const double tol = tolerance(a, b, i, true, true, false);
      CHECK(std::fabs(double(gpu[i]) - cpu[i]) <= tol);
      // Slopes carry the scale's texels per unit (up to 64 here) on top.
      const double gtol = tol * 8 * a.texels_per_unit(a.parameters().scales - 1);
      CHECK(std::fabs(double(gg[i].x) - gc[i].x) <= gtol);
      CHECK(std::fabs(double(gg[i].y) - gc[i].y) <= gtol);
    }
  }
}

TEST_CASE("glsl anisotropic: points and grids, tiles uploaded once per shared tile") {
  auto& dev = headless().device;
  const hush::anisotropic a = make(4, hush::fractal_kind::fbm, hush::weight_rule::centre, 77);
  const std::size_t uploads = dev.texture_uploads();
  hush::grid<2> g;
  g.origin = {-3.3, 1e6};
  g.step = {0.0173, 0.031};
  g.size = {50, 20};
  std::vector<float> cpu(g.count()), gpu(g.count());
  hush::evaluate_grid(a, hush::exec::scalar, g, hush::span<float>(cpu));
  hush::evaluate_grid(a, hush::exec::glsl{dev}, g, hush::span<float>(gpu));
  float w[12 * 8];
  a.weights<float>(hush::sample_input<2>{}, w);
  const double tol = hush::glsl::noise_program<hush::anisotropic>::tolerance(a, w, true);
  for (std::size_t i = 0; i < cpu.size(); ++i) CHECK(std::fabs(double(gpu[i]) - cpu[i]) <= tol);
  // A second noise on the same tile, and a second call: no new upload.
  const hush::anisotropic same_tile =
      make(4, hush::fractal_kind::turbulence, hush::weight_rule::three_point, 77);
  const std::vector<hush::vec2> pts = {{0.5f, 0.25f}, {-7.0f, 3.0f}};
  std::vector<float> out(2);
  hush::evaluate(same_tile, hush::exec::glsl{dev}, hush::span<const hush::vec2>(pts),
                 hush::span<float>(out));
  hush::evaluate(a, hush::exec::glsl{dev}, hush::span<const hush::vec2>(pts),
                 hush::span<float>(out));
  // K = 4: one RGBA texture (bound to both samplers), shared by both noises.
  CHECK(dev.texture_uploads() == uploads + 1);
  CHECK(dev.texture_bytes() >= 64 * 64 * 4 * sizeof(float));
}

TEST_CASE("glsl anisotropic: least-squares rules are refused on the GPU, naming the rule") {
  auto& dev = headless().device;
  const hush::anisotropic a = make(4, hush::fractal_kind::fbm, hush::weight_rule::least_squares);
  const std::vector<hush::vec2> pts = {{0.5f, 0.25f}};
  std::vector<float> out(1);
  CHECK_THROWS_WITH_AS(hush::evaluate(a, hush::exec::glsl{dev}, hush::span<const hush::vec2>(pts),
                                      hush::span<float>(out)),
                       doctest::Contains("least-squares"), hush::invalid_argument);
}
