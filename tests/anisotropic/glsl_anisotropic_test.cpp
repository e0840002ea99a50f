// Anisotropic noise on the GLSL backend (hush/glsl/anisotropic_program.hpp)
// against the CPU float path: samples with footprints and surface maps,
// points and grids, values (hardware bilinear filtering of the tile
// textures) and gradients (texelFetch), fbm and turbulence, 2 to 8
// orientations, both heuristic rules; within the tolerance the program
// states per sample. Also: tiles uploaded once per shared tile, least-squares
// rules (the CPU's weights uploaded per sample), per-sample data split by the
// buffer limit, NaN positions; the uploaded least-squares weights against the
// double fits; the samples runner reading no footprint or map buffer.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "glsl/glsl_test_util.hpp"
#include "hush/glsl/compute_source.hpp"
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

// The batch's positions, with its footprints and surface maps when asked.
hush::samples<2> inputs(const batch& b, bool fps, bool maps) {
  hush::samples<2> s;
  s.positions = {b.pos.data(), b.pos.size()};
  if (fps) s.footprints = {b.fp.data(), b.fp.size()};
  if (maps) s.surface_maps = {b.maps.data(), b.maps.size()};
  return s;
}

// GPU values (hardware bilinear) against the CPU float path, sample by sample,
// within the stated tolerance; NaN exactly where the CPU has NaN. Returns the
// largest error / tolerance.
double check_against_cpu(const hush::anisotropic& a, const batch& b, bool fps, bool maps) {
  double worst = 0;
  const hush::samples<2> s = inputs(b, fps, maps);
  std::vector<float> cpu(b.pos.size()), gpu(b.pos.size());
  hush::evaluate(a, hush::exec::scalar, s, hush::span<float>(cpu));
  hush::evaluate(a, hush::exec::glsl{headless().device}, s, hush::span<float>(gpu));
  for (std::size_t i = 0; i < cpu.size(); ++i) {
    INFO("sample " << i << ": cpu " << cpu[i] << " gpu " << gpu[i]);
    REQUIRE(std::isnan(cpu[i]) == std::isnan(gpu[i]));
    if (std::isnan(cpu[i])) continue;
    const double e = std::fabs(double(gpu[i]) - cpu[i]), tol = tolerance(a, b, i, fps, maps, true);
    CHECK(e <= tol);
    worst = std::max(worst, e / tol);
  }
  return worst;
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
  MESSAGE(headless().device.renderer() << ", hardware bilinear: max |gpu - cpu| = " << worst
                                       << ", max error / tolerance = " << worst_ratio);
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
  CHECK(dev.texture_bytes() >= std::size_t{64} * 64 * 4 * sizeof(float));
}

// Grazing footprints: S = L^2 e e^T + (small) with L in [2^8, 2^12] and e
// within angles delta of perpendicular to an orientation d_i (K = 5, i = 1 ... 4:
// the axis-aligned i = 0 and 45 degrees, whose float products happen to be
// exact, would not show it), so q_i = d_i^T S d_i
// ~ L^2 delta^2 is small (weights well above 0) while S's entries are ~L^2:
// q_i formed in float from S would be off by ~2^-24 L^2 kappa_s, i.e. by
// whole units of the exponent. The per-sample q_i from the CPU's double keeps
// the GPU within the stated tolerance; the test also checks that such
// cancelling samples with large weights occur (else it would test nothing).
TEST_CASE(
    "glsl anisotropic: grazing footprints (cancelling quadratic forms) stay within tolerance") {
  const hush::anisotropic a = make(5, hush::fractal_kind::fbm, hush::weight_rule::centre, 31);
  batch b;
  hush::rng r(17);
  int cancelling = 0;
  for (int j = 0; j < 400; ++j) {
    const int i = 1 + j % 4;
    const double len = std::exp2(r.uniform<double>(8, 12));
    const hush::dvec2 d = a.direction(i);
    // e: perpendicular to d, turned by delta with kappa_0 L^2 delta^2 in about [2^-6, 2^4].
    const double delta = std::exp2(r.uniform<double>(-3, 2)) / (len * std::sqrt(a.kappa(0)));
    const double c = std::cos(delta), sn = std::sin(delta);
    const hush::dvec2 e{-d.y * c + d.x * sn, d.x * c + d.y * sn};
    const double thin = len * std::exp2(-20);
    b.pos.push_back({r.uniform(-40.0f, 40.0f), r.uniform(-40.0f, 40.0f)});
    b.fp.push_back(hush::footprint<2>::from_derivatives(hush::dvec2{len * e.x, len * e.y},
                                                        hush::dvec2{-thin * e.y, thin * e.x}));
    b.maps.push_back(hush::surface_map::identity());
    hush::sample_input<2> in;
    in.fp = b.fp.back();
    float w[12 * 8];
    a.weights<float>(in, w);
    const double entry =
        std::max(std::fabs(in.fp.covariance(0, 0)), std::fabs(in.fp.covariance(1, 1)));
    if (w[i + a.channels() * a.parameters().base_scale] > 0.1f && entry > 1e4) ++cancelling;
  }
  CHECK(cancelling > 40);
  const double grazing = check_against_cpu(a, b, true, false);
  MESSAGE(headless().device.renderer() << ", grazing footprints: max error / tolerance = "
                                       << grazing);
}

// Least squares on the GPU: the runner uploads the CPU's own weights per
// sample (per-map fits cached on the CPU), so the GPU differs from the CPU
// float path only by the lookups: the same stated tolerance holds (its weight
// term is then an over-estimate). Maps drawn from 6 distinct ones, as on a
// mesh of few triangles; 150 samples keep the per-sample filter fits fast.
TEST_CASE("glsl anisotropic: least-squares weights agree with the CPU within the tolerance") {
  batch b = make_batch(150, 21);
  for (std::size_t i = 0; i < b.maps.size(); ++i) b.maps[i] = b.maps[i % 6];
  using hush::weight_rule;
  const std::pair<weight_rule, weight_rule> rules[] = {
      {weight_rule::least_squares, weight_rule::least_squares},
      {weight_rule::centre, weight_rule::least_squares},
      {weight_rule::least_squares, weight_rule::three_point}};
  double worst = 0;
  for (const auto& rule : rules)
    for (hush::fractal_kind kind : {hush::fractal_kind::fbm, hush::fractal_kind::turbulence})
      for (int k : {3, 6}) {
        hush::anisotropic::params p = make(k, kind, weight_rule::centre).parameters();
        p.filtering = rule.first;
        p.compensation = rule.second;
        const hush::anisotropic a(p);
        INFO("K " << k << " kind " << int(kind) << " rules " << int(rule.first) << "/"
                  << int(rule.second));
        worst = std::max(worst, check_against_cpu(a, b, true, true));
      }
  MESSAGE(headless().device.renderer() << ", least squares: max error / tolerance = " << worst);
}

TEST_CASE("glsl anisotropic: per-sample data split by the buffer limit gives the same results") {
  // 2 KiB buffers: K = 8 least-squares turbulence has 2 octaves x 4 scales x 8
  // channels = 64 floats (256 bytes) of weights per sample: 8 samples per batch,
  // one dispatch each.
  (void)headless();  // the context current on this thread
  hush::glsl::device::options opt;
  opt.max_buffer_bytes = 2048;
  hush::glsl::device small(hush_glsl_test::headless().context.loader(), opt);
  const batch b = make_batch(60, 8);
  for (hush::weight_rule rule : {hush::weight_rule::centre, hush::weight_rule::least_squares}) {
    const hush::anisotropic a = make(8, hush::fractal_kind::turbulence, rule);
    const hush::samples<2> s = inputs(b, true, true);
    std::vector<float> whole(b.pos.size()), split(b.pos.size());
    const std::size_t before = small.dispatches();
    hush::evaluate(a, hush::exec::glsl{headless().device}, s, hush::span<float>(whole));
    hush::evaluate(a, hush::exec::glsl{small}, s, hush::span<float>(split));
    // Per batch: the larger of the band triples (3 words x 2 axes x 4 scales)
    // and the per-sample data (centre: 2K + 1 = 17 floats; least squares: 64).
    const std::size_t words = std::max<std::size_t>(
        24, hush::glsl::noise_program<hush::anisotropic>::sample_data_floats(a));
    const std::size_t per_batch = opt.max_buffer_bytes / (4 * words);
    CHECK(small.dispatches() - before == (b.pos.size() + per_batch - 1) / per_batch);
    for (std::size_t i = 0; i < whole.size(); ++i) {
      REQUIRE(std::isnan(whole[i]) == std::isnan(split[i]));
      if (!std::isnan(whole[i])) CHECK(whole[i] == split[i]);
    }
  }
}

// The least-squares weights the GPU receives (sample_data: uploaded per sample, no GL
// here) against the double fits: the float path fits in double and rounds, then forms
// gamma * lambda * octave weight in float, a few roundings of 2^-24 each of the largest
// weight's size; 2^-20 of it leaves margin and still fails for a weight off by one
// float ulp of 16 (a wrong channel, scale or octave shows as O(1)).
TEST_CASE("glsl anisotropic: uploaded least-squares weights equal the double fits") {
  using np = hush::glsl::noise_program<hush::anisotropic>;
  const batch b = make_batch(24, 5);
  for (hush::fractal_kind kind : {hush::fractal_kind::fbm, hush::fractal_kind::turbulence})
    for (int k : {3, 8}) {
      const hush::anisotropic a = make(k, kind, hush::weight_rule::least_squares);
      const std::size_t per_pass = std::size_t(a.parameters().scales) * a.channels();
      const int passes = kind == hush::fractal_kind::fbm ? 1 : a.parameters().octaves;
      REQUIRE(np::sample_data_floats(a) == per_pass * std::size_t(passes));
      std::vector<float> got(np::sample_data_floats(a));
      std::vector<double> want(per_pass);
      for (std::size_t i = 0; i < b.pos.size(); ++i) {
        hush::sample_input<2> in;
        in.position = hush::vec_cast<double>(b.pos[i]);
        in.fp = b.fp[i];
        in.map = b.maps[i];
        in.has_map = true;
        np::sample_data(a, in, got.data());
        for (int pass = 0; pass < passes; ++pass) {
          if (kind == hush::fractal_kind::fbm)
            a.weights<double>(in, want.data());
          else
            a.octave_weights<double>(in, pass, want.data());
          double largest = 0;
          for (double w : want) largest = std::max(largest, std::fabs(w));
          for (std::size_t j = 0; j < per_pass; ++j) {
            INFO("K " << k << " kind " << int(kind) << " sample " << i << " pass " << pass
                      << " weight " << j);
            CHECK(std::fabs(got[std::size_t(pass) * per_pass + j] - want[j]) <=
                  std::ldexp(largest, -20));
          }
        }
      }
    }
}

// Footprints and maps reach the anisotropic program only through its per-sample data
// (q_i, |T^T d_i|^2, |det T|, or the weights): the samples runner neither reads them
// (its source indexes neither buffer) nor, so, needs them uploaded (device.hpp skips
// them: reads_sample_inputs); a noise without sample data (gabor) still reads its own.
TEST_CASE("glsl anisotropic: the samples runner reads no footprint or map buffer") {
  for (bool gradient : {false, true}) {
    const std::string s =
        hush::glsl::compute_source<hush::anisotropic>(hush::glsl::batch_layout::samples, gradient);
    // Declared (bindings 2 and 4 stay bound), never indexed by a sample.
    CHECK(s.find("hush_fp[e") == std::string::npos);
    CHECK(s.find("hush_map[4u") == std::string::npos);
    CHECK(s.find("bool has_smap = hush_has_map != 0u;") != std::string::npos);
    const std::string g = hush::glsl::compute_source<hush::gabor<2>>(
        hush::glsl::batch_layout::samples, gradient);
    CHECK(g.find("hush_fp[e") != std::string::npos);
  }
}
