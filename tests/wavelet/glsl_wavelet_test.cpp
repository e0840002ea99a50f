// Wavelet noise on the GLSL backend (hush/glsl/wavelet_program.hpp) on OSMesa's llvmpipe:
// points, grids and samples against the CPU float path within the stated tolerance (twice
// the float budgets, plus the GPU erf's 1.5e-7 through the remap), NaN in NaN out, the
// tile uploaded once per device however many noises share it, and the library's wavelet
// functions usable from a 330 fragment shader reading the tile from a texture buffer.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "glsl/glsl_test_util.hpp"
#include "hush/glsl/library.hpp"

namespace {

using hush_glsl_test::headless;

template <int D>
std::vector<hush::wavelet<D>> noises() {
  std::vector<hush::wavelet<D>> r;
  typename hush::wavelet<D>::params prm;
  prm.tile_size = D == 2 ? 32 : 16;
  prm.seed = 5;
  r.emplace_back(prm);
  prm.weights = {1, -0.5, 0.25, 0.125};
  prm.first_band = -2;
  r.emplace_back(prm);
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
  r.emplace_back(prm);
  prm = {};
  prm.tile_size = D == 2 ? 32 : 16;
  prm.variant_overlap = 2;
  prm.weights = {1, 0.5};
  r.emplace_back(prm);
  return r;
}

// Tolerance against the CPU float path (file comment of wavelet_program.hpp).
template <int D>
double value_tolerance(const hush::wavelet<D>& w, bool plain) {
  const auto& prm = w.parameters();
  double remap = 0;
  if (prm.distribution != hush::wavelet_distribution::gaussian) {
    double slope = 1;
    for (std::size_t i = 0; i + 1 < prm.table.size(); ++i)
      slope = std::max(slope,
                       std::fabs(prm.table[i + 1] - prm.table[i]) * double(prm.table.size() - 1));
    remap = 4e-7 * slope;
  }
  return 2 * w.float_budget(plain) + remap;
}

template <int D>
void compare(const hush::wavelet<D>& w, const std::vector<float>& gpu,
             const std::vector<float>& cpu, const std::vector<hush::vec<float, D>>& ggpu,
             const std::vector<hush::vec<float, D>>& gcpu, bool plain) {
  const double tol = value_tolerance(w, plain);
  const double gtol =
      2 * w.float_gradient_budget(plain) + tol * w.band_frequency(w.band_count() - 1);
  hush_glsl_test::error_stats ev, eg;
  for (std::size_t i = 0; i < cpu.size(); ++i) {
    INFO("sample " << i << ": gpu " << gpu[i] << ", cpu " << cpu[i]);
    REQUIRE(std::isnan(gpu[i]) == std::isnan(cpu[i]));
    if (std::isnan(cpu[i])) continue;
    ev.add(std::fabs(double(gpu[i]) - cpu[i]));
    REQUIRE(std::fabs(double(gpu[i]) - cpu[i]) <= tol);
    for (int a = 0; a < D; ++a) {
      REQUIRE(std::isnan(ggpu[i][a]) == std::isnan(gcpu[i][a]));
      if (std::isnan(gcpu[i][a])) continue;
      eg.add(std::fabs(double(ggpu[i][a]) - gcpu[i][a]));
      REQUIRE(std::fabs(double(ggpu[i][a]) - gcpu[i][a]) <= gtol);
    }
  }
  MESSAGE("max |gpu - cpu|: values " << ev.max << " (tolerance " << tol << "), gradients " << eg.max
                                     << " (" << gtol << ")");
}

template <int D, class Run>
void check(const hush::wavelet<D>& w, std::size_t n, Run run, bool plain) {
  auto& dev = headless().device;
  std::vector<float> cpu(n), gpu(n), cpu2(n), gpu2(n);
  std::vector<hush::vec<float, D>> gc(n), gg(n);
  run(hush::exec::scalar, cpu, nullptr);
  run(hush::exec::glsl{dev}, gpu, nullptr);
  run(hush::exec::scalar, cpu2, &gc);
  run(hush::exec::glsl{dev}, gpu2, &gg);
  std::vector<hush::vec<float, D>> none(n);
  compare<D>(w, gpu, cpu, none, none, plain);
  compare<D>(w, gpu2, cpu2, gg, gc, plain);
}

template <int D>
void points_case() {
  for (const auto& w : noises<D>()) {
    std::vector<hush::vec<float, D>> pts = hush_glsl_test::random_points<D>(300, 3);
    pts[7][0] = NAN;
    pts[8][D - 1] = INFINITY;
    check<D>(
        w, pts.size(),
        [&](auto policy, std::vector<float>& out, std::vector<hush::vec<float, D>>* grad) {
          if (grad)
            hush::evaluate(w, policy, hush::span<const hush::vec<float, D>>(pts),
                           hush::span<float>(out), hush::span<hush::vec<float, D>>(*grad));
          else
            hush::evaluate(w, policy, hush::span<const hush::vec<float, D>>(pts),
                           hush::span<float>(out));
        },
        true);
  }
}

template <int D>
void grid_case() {
  for (const auto& w : noises<D>()) {
    hush::grid<D> g;
    for (int a = 0; a < D; ++a) {
      g.origin[a] = a == 0 ? 1e6 + 0.3 : -0.7;
      g.step[a] = a == 1 ? -0.21 : 0.13;
      g.size[a] = D == 2 ? 31 : 9;
    }
    check<D>(
        w, g.count(),
        [&](auto policy, std::vector<float>& out, std::vector<hush::vec<float, D>>* grad) {
          if (grad)
            hush::evaluate_grid(w, policy, g, hush::span<float>(out),
                                hush::span<hush::vec<float, D>>(*grad));
          else
            hush::evaluate_grid(w, policy, g, hush::span<float>(out));
        },
        true);
  }
}

template <int D>
void samples_case(bool widen, bool normals, hush::wavelet_projection proj) {
  int index = 0;
  for (auto base : noises<D>()) {
    CAPTURE(D);
    CAPTURE(widen);
    CAPTURE(normals);
    CAPTURE(index++);
    auto prm = base.parameters();
    prm.widen = widen;
    prm.projection = proj;
    const hush::wavelet<D> w{prm};
    const std::size_t n = 120;
    std::vector<hush::vec<float, D>> pts = hush_glsl_test::random_points<D>(n, 4);
    std::vector<hush::footprint<D>> fps(n);
    std::vector<hush::vec3> nrm(n);
    hush::rng r(9);
    for (std::size_t i = 0; i < n; ++i) {
      const double width =
          i % 9 == 0 ? 0.0 : std::ldexp(r.uniform<double>(0.5, 1.0), int(i % 8) - 6);
      hush::vec<double, D> dx{}, dy{};  // every fifth: thin, along x
      dx[0] = width;
      dy[1] = width / 64;
      fps[i] = i % 5 == 1 ? hush::footprint<D>::from_derivatives(dx, dy)
                          : hush::footprint<D>::isotropic(width);
      if (i % 11 == 3) fps[i] = hush::footprint<D>::isotropic(NAN);
      const int kind = int(i % 4);
      nrm[i] = kind == 0   ? hush::vec3{0, -3, 0}
               : kind == 1 ? hush::vec3{r.uniform(-1.f, 1.f), r.uniform(-1.f, 1.f), 0.7f}
                           : hush::vec3{0, 0, 0};
    }
    hush::samples<D> s;
    s.positions = pts;
    s.footprints = fps;
    if (D == 3 && normals) s.normals = nrm;
    check<D>(
        w, n,
        [&](auto policy, std::vector<float>& out, std::vector<hush::vec<float, D>>* grad) {
          if (grad)
            hush::evaluate(w, policy, s, hush::span<float>(out),
                           hush::span<hush::vec<float, D>>(*grad));
          else
            hush::evaluate(w, policy, s, hush::span<float>(out));
        },
        !widen && !normals);
  }
}

}  // namespace

TEST_CASE("glsl wavelet: points agree with the CPU float path, NaN and Inf give NaN") {
  points_case<2>();
  points_case<3>();
}

TEST_CASE("glsl wavelet: grids far from the origin agree with the CPU float path") {
  grid_case<2>();
  grid_case<3>();
}

TEST_CASE("glsl wavelet: samples with footprints, widening and normals agree with the CPU") {
  samples_case<2>(false, false, hush::wavelet_projection::exact);
  samples_case<2>(true, false, hush::wavelet_projection::exact);
  samples_case<3>(false, false, hush::wavelet_projection::exact);
  samples_case<3>(false, true, hush::wavelet_projection::exact);
  samples_case<3>(true, true, hush::wavelet_projection::exact);
  samples_case<3>(false, true, hush::wavelet_projection::approximate);
  samples_case<3>(true, true, hush::wavelet_projection::approximate);
}

TEST_CASE("glsl wavelet: a tile shared by many noises is uploaded once per device") {
  auto& dev = headless().device;
  hush::wavelet<2>::params prm;
  prm.tile_size = 32;
  prm.seed = 77;
  const hush::wavelet<2> a{prm};
  prm.weights = {1, 0.5};  // another noise on the same tile
  const hush::wavelet<2> b{prm};
  REQUIRE(a.tile_ptr() == b.tile_ptr());
  std::vector<hush::vec2> pts = hush_glsl_test::random_points<2>(64, 1);
  std::vector<float> out(pts.size());
  hush::evaluate(a, hush::exec::glsl{dev}, hush::span<const hush::vec2>(pts),
                 hush::span<float>(out));
  const std::size_t after_first = dev.data_uploads();
  for (int i = 0; i < 3; ++i) {
    hush::evaluate(a, hush::exec::glsl{dev}, hush::span<const hush::vec2>(pts),
                   hush::span<float>(out));
    hush::evaluate(b, hush::exec::glsl{dev}, hush::span<const hush::vec2>(pts),
                   hush::span<float>(out));
  }
  CHECK(dev.data_uploads() == after_first);
  prm.seed = 78;  // a different tile is uploaded, and the first again after it
  const hush::wavelet<2> c{prm};
  hush::evaluate(c, hush::exec::glsl{dev}, hush::span<const hush::vec2>(pts),
                 hush::span<float>(out));
  CHECK(dev.data_uploads() == after_first + 1);
  hush::evaluate(a, hush::exec::glsl{dev}, hush::span<const hush::vec2>(pts),
                 hush::span<float>(out));
  CHECK(dev.data_uploads() == after_first + 2);
  std::vector<float> cpu(pts.size());
  hush::evaluate(a, hush::exec::scalar, hush::span<const hush::vec2>(pts), hush::span<float>(cpu));
  for (std::size_t i = 0; i < cpu.size(); ++i)
    CHECK(out[i] == doctest::Approx(cpu[i]).scale(1.0).epsilon(2 * a.float_budget()));
}

TEST_CASE("glsl wavelet: the library's wavelet functions compile in a 330 fragment shader") {
  namespace gd = hush::glsl::detail;
  const std::string lib = hush::glsl::library();
  const std::string fragment =
      "#version 330 core\n"
      "uniform samplerBuffer tile;\n"
      "#define HUSH_WAVELET_TILE(i) texelFetch(tile, int(i)).x\n" +
      lib +
      "out vec4 color;\n"
      "void main() {\n"
      "  hush_wv_n = 64u;\n  hush_wv_dim = 2u;\n  hush_wv_cell = 0;\n"
      "  vec2 y = gl_FragCoord.xy / 8.0 - vec2(0.5);\n"
      "  hush_wv_i0 = uvec3(uvec2(floor(y)) % 64u, 0u);\n"
      "  color = hush_wavelet_band(vec3(fract(y), 0.0), false, -1, vec3(0.0), true, vec3(1.0));\n"
      "}\n";
  const std::string vertex =
      "#version 330 core\nlayout(location = 0) in vec2 p;\n"
      "void main() { gl_Position = vec4(p, 0.0, 1.0); }\n";
  const gd::gl_program prog = gd::link_program(
      headless().device.gl(), {{gd::kGlVertexShader, vertex}, {gd::kGlFragmentShader, fragment}});
  CHECK(prog.id() != 0u);
}
TEST_CASE("glsl wavelet: 16 bands along general normals stay within llvmpipe's loop budget") {
  // llvmpipe silently ends a shader's loops after 65535 iterations in total (wavelet_glsl.hpp):
  // 16 bands of the exact general projection still agree with the CPU (from about 21 bands
  // on they come out truncated: the documented limit of llvmpipe, not of real GPUs).
  for (const auto proj : {hush::wavelet_projection::exact, hush::wavelet_projection::approximate}) {
    hush::wavelet<3>::params prm;
    prm.tile_size = 16;
    prm.projection = proj;
    prm.first_band = -hush::wavelet<3>::kMaxBands / 2;
    prm.weights.assign(16, 1.0);
    const hush::wavelet<3> w{prm};
    const std::size_t n = 64;
    std::vector<hush::vec3> pts = hush_glsl_test::random_points<3>(n, 8), nrm(n);
    std::vector<hush::footprint<3>> fps(n, hush::footprint<3>::isotropic(0.0));
    hush::rng r(12);
    for (auto& v : nrm) v = {r.uniform(-1.f, 1.f), r.uniform(-1.f, 1.f), r.uniform(0.2f, 1.f)};
    hush::samples<3> s;
    s.positions = pts;
    s.footprints = fps;
    s.normals = nrm;
    check<3>(
        w, n,
        [&](auto policy, std::vector<float>& out, std::vector<hush::vec3>* grad) {
          if (grad)
            hush::evaluate(w, policy, s, hush::span<float>(out), hush::span<hush::vec3>(*grad));
          else
            hush::evaluate(w, policy, s, hush::span<float>(out));
        },
        false);
  }
}
