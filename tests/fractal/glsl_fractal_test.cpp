// Tests of the GLSL programs of hush::fractal<hush::perlin<D>> (fBm and
// turbulence; backends/glsl, hush/glsl/noise_program.hpp) on a headless
// OSMesa (llvmpipe) context, against the double reference and the CPU float
// path.
//
// Tolerance. Points and grids alike have every band coordinate f_i x + o_i
// formed and split into cell and fraction on the CPU in double
// (fractal::band_position, hush::lattice_split<float>), so each band's GPU
// Perlin evaluation starts from the CPU's cells and fractions bit for bit and
// has no position error at all (a float band position f_i x + o_i formed on
// the GPU would err by up to |x f_i| 2^-24, moving the noise by L times that:
// 0.6 at x = 1e6, f_i = 16; that is why the split stays on the CPU). What is
// left is float arithmetic:
//  - band i's noise n_i is within e = 2^-16 of its double reference and its
//    gradient within e (1 + L) (the Perlin GLSL budget, glsl_test.cpp; L the
//    Lipschitz bound, 7.3 in 2D, 10.0 in 3D), with |n_i| <= 1, |grad n_i| <= L;
//  - the sum: float(w_i) (one rounding), the product, the nb additions and
//    the final float(scale) * sum each round once by at most u = 2^-24
//    relative (a fused multiply-add rounds once instead of twice: the same
//    bound); forward error of recursive summation: at most (nb + 3) u times
//    the sum of the terms' magnitudes, plus second order terms, covered by
//    taking (nb + 4) u.
// So, with K = scale() and the raw weights w_i, frequencies f_i:
//   |value - reference|      <= K sum |w_i|     (e + (nb + 4) u)       = value_budget
//   |gradient_a - reference| <= K sum |w_i| f_i (e + (nb + 4) u) (1 + L) = gradient_budget
// and twice these against the CPU float path (which meets the same bounds).
// Turbulence: |n| has the error of n; its gradient flips with the sign of
// n_i, so samples where some band's |n_i| <= 2e (GPU and reference may
// disagree on the sign there) are left out of the gradient check; the test
// counts them and requires them to be rare.
#include <doctest/doctest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "glsl/glsl_test_util.hpp"
#include "hush/exec.hpp"
#include "hush/glsl/compute_source.hpp"
#include "hush/glsl/device.hpp"
#include "hush/glsl/noise_program.hpp"
#include "hush/hush.hpp"
#include "test_util.hpp"

namespace {

using hush_glsl_test::error_stats;
using hush_glsl_test::headless;
using hush_glsl_test::random_points;
using hush_test::lipschitz_bound;

template <int D>
using fractal_t = hush::fractal<hush::perlin<D>>;

const double kNoiseBudget = std::ldexp(1.0, -16);  // one band's Perlin value (file comment)
const double kUlp = std::ldexp(1.0, -24);          // float unit roundoff

static_assert(hush::glsl::has_program_v<fractal_t<2>> && hush::glsl::has_program_v<fractal_t<3>>,
              "fractal sums of Perlin noise have GLSL programs");
static_assert(!hush::glsl::has_program_v<fractal_t<2>*>, "a pointer is no noise");

// The budgets of the file comment.
template <int D>
double value_budget(const fractal_t<D>& fr) {
  double sum = 0;
  for (int i = 0; i < fr.band_count(); ++i) sum += std::fabs(fr.band_raw_weight(i));
  return fr.scale() * sum * (kNoiseBudget + (fr.band_count() + 4) * kUlp);
}
template <int D>
double gradient_budget(const fractal_t<D>& fr) {
  double sum = 0;
  for (int i = 0; i < fr.band_count(); ++i)
    sum += std::fabs(fr.band_raw_weight(i)) * fr.band_frequency(i);
  return fr.scale() * sum * (kNoiseBudget + (fr.band_count() + 4) * kUlp) *
         (1 + lipschitz_bound<D>());
}

// Whether some band of fr is within 2 kNoiseBudget of 0 at x (turbulence's
// gradient sign is then not determined by the budget).
template <int D>
bool near_band_zero(const fractal_t<D>& fr, const hush::vec<double, D>& x) {
  for (int i = 0; i < fr.band_count(); ++i)
    if (std::fabs(fr.band_noise(i).template value<double>(fr.band_position(i, x))) <=
        2 * kNoiseBudget)
      return true;
  return false;
}

// GPU values (and gradients) v, g at positions position(i) against the double
// reference and the CPU float path, within the file comment's budgets.
template <int D, class Position>
void check_against_cpu(const fractal_t<D>& fr, std::size_t n, Position position, const float* v,
                       const hush::vec<float, D>* g, const std::string& what,
                       bool random_inputs = true) {
  error_stats vd, vf, gdbl, gflt;
  std::size_t skipped = 0;
  const bool turbulence = fr.parameters().kind == hush::fractal_kind::turbulence;
  for (std::size_t i = 0; i < n; ++i) {
    const hush::vec<double, D> x = position(i);
    const auto ref = fr.template value_and_gradient<double>(x);
    const auto cpu = fr.template value_and_gradient<float>(x);
    vd.add(std::fabs(double(v[i]) - ref.value));
    vf.add(std::fabs(double(v[i]) - double(cpu.value)));
    if (!g) continue;
    if (turbulence && near_band_zero<D>(fr, x)) {
      ++skipped;
      continue;
    }
    for (int a = 0; a < D; ++a) {
      const std::size_t k = std::size_t(a);
      gdbl.add(std::fabs(double(g[i][k]) - ref.gradient[k]));
      gflt.add(std::fabs(double(g[i][k]) - double(cpu.gradient[k])));
    }
  }
  const double vb = value_budget<D>(fr), gb = gradient_budget<D>(fr);
  std::ostringstream msg;
  msg << "fractal perlin" << D << "d " << what << " (" << fr.band_count()
      << " bands): value vs double max " << vd.max << " rms " << vd.rms() << ", vs cpu float max "
      << vf.max << " (budget " << vb << ")";
  if (g)
    msg << "; gradient vs double max " << gdbl.max << " rms " << gdbl.rms() << ", vs cpu float max "
        << gflt.max << " (budget " << gb << "), " << skipped << " near-zero samples skipped";
  MESSAGE(msg.str());
  CHECK(vd.max <= vb);
  CHECK(vf.max <= 2 * vb);
  if (g) {
    CHECK(gdbl.max <= gb);
    CHECK(gflt.max <= 2 * gb);
    // Random inputs: a band within 2^-15 of zero has probability about
    // 2^-15 * density * bands, far below 1%. (Lattice points, e.g. huge
    // integral coordinates, are exactly zero in every band.)
    if (random_inputs) CHECK(skipped * 100 <= n);
  }
}

template <int D>
void check_points(const fractal_t<D>& fr, std::size_t n, std::uint32_t seed,
                  const std::string& what) {
  const auto pts = random_points<D>(n, seed);
  std::vector<float> v(n), v_only(n);
  std::vector<hush::vec<float, D>> g(n);
  hush::evaluate(fr, hush::exec::glsl{headless().device}, pts, v, g);
  hush::evaluate(fr, hush::exec::glsl{headless().device}, pts, v_only);
  auto pos = [&](std::size_t i) { return hush::vec_cast<double>(pts[i]); };
  check_against_cpu<D>(fr, n, pos, v.data(), g.data(), what + " points");
  check_against_cpu<D>(fr, n, pos, v_only.data(), nullptr, what + " points, values only");
}

template <int D>
hush::vec<double, D> grid_position(const hush::grid<D>& gr, std::size_t i) {
  std::array<std::size_t, D> ijk{};
  ijk[0] = i % gr.size[0];
  ijk[1] = (i / gr.size[0]) % gr.size[1];
  if constexpr (D == 3) ijk[2] = i / (gr.size[0] * gr.size[1]);
  return gr.position(ijk);
}

// GPU grid against the double reference, and against the CPU float grid
// (hush::exec::scalar) sample by sample.
template <int D>
void check_grid(const fractal_t<D>& fr, const hush::grid<D>& gr, const std::string& what) {
  const std::size_t n = gr.count();
  std::vector<float> v(n), v_only(n), cpu(n);
  std::vector<hush::vec<float, D>> g(n), cpu_g(n);
  hush::evaluate_grid(fr, hush::exec::glsl{headless().device}, gr, v, g);
  hush::evaluate_grid(fr, hush::exec::glsl{headless().device}, gr, v_only);
  hush::evaluate_grid(fr, hush::exec::scalar, gr, cpu, cpu_g);
  check_against_cpu<D>(
      fr, n, [&](std::size_t i) { return grid_position<D>(gr, i); }, v.data(), g.data(),
      what + " grid", false);  // grid rows can run along a band's lattice lines
  check_against_cpu<D>(
      fr, n, [&](std::size_t i) { return grid_position<D>(gr, i); }, v_only.data(), nullptr,
      what + " grid, values only");
  double worst = 0;
  for (std::size_t i = 0; i < n; ++i) worst = std::max(worst, std::fabs(double(v[i]) - cpu[i]));
  CHECK(worst <= 2 * value_budget<D>(fr));
}

template <int D>
typename fractal_t<D>::params turbulence_7() {
  typename fractal_t<D>::params p;
  p.seed = 11;
  p.kind = hush::fractal_kind::turbulence;
  p.norm = hush::normalization::unit_range;
  p.octaves = 7;
  return p;
}

template <int D>
typename fractal_t<D>::params explicit_weights() {
  typename fractal_t<D>::params p;
  p.seed = 12;
  p.octaves = 5;
  p.weights = {1.0, 0.0, -0.7, 0.25, 2.0};
  p.norm = hush::normalization::none;
  p.lacunarity = 1.9;
  p.frequency = 0.37;
  return p;
}

template <int D>
typename fractal_t<D>::params periodic() {
  typename fractal_t<D>::params p;
  p.seed = 13;
  p.octaves = 4;
  p.lacunarity = 3.0;
  p.period[0] = 3;
  p.period[1] = 5;
  if constexpr (D == 3) p.period[2] = 0;
  return p;
}

template <int D>
typename fractal_t<D>::params one_octave() {
  typename fractal_t<D>::params p;
  p.seed = 14;
  p.octaves = 1;
  return p;
}

template <int D>
typename fractal_t<D>::params max_octaves() {
  typename fractal_t<D>::params p;
  p.seed = 15;
  p.octaves = fractal_t<D>::kMaxOctaves;
  p.gain = 0.7;
  return p;
}

TEST_CASE("fractal perlin points: default fBm matches the double reference and CPU within budget") {
  check_points(fractal_t<2>(), 60000, 1, "default fbm");
  check_points(fractal_t<3>(), 30000, 2, "default fbm");
}

TEST_CASE("fractal perlin points: turbulence unit_range 7 octaves within budget") {
  check_points(fractal_t<2>(turbulence_7<2>()), 30000, 3, "turbulence");
  check_points(fractal_t<3>(turbulence_7<3>()), 20000, 4, "turbulence");
}

TEST_CASE("fractal perlin points: explicit weights with a zero and a negative, norm none") {
  check_points(fractal_t<2>(explicit_weights<2>()), 30000, 5, "explicit weights");
  check_points(fractal_t<3>(explicit_weights<3>()), 20000, 6, "explicit weights");
}

TEST_CASE("fractal perlin points: periodic, 1 octave and 32 octaves within budget") {
  check_points(fractal_t<2>(periodic<2>()), 20000, 7, "periodic");
  check_points(fractal_t<3>(periodic<3>()), 20000, 8, "periodic");
  check_points(fractal_t<2>(one_octave<2>()), 20000, 9, "1 octave");
  check_points(fractal_t<3>(one_octave<3>()), 20000, 10, "1 octave");
  check_points(fractal_t<2>(max_octaves<2>()), 5000, 11, "32 octaves");
  check_points(fractal_t<3>(max_octaves<3>()), 3000, 12, "32 octaves");
}

TEST_CASE("fractal perlin grids near and far match the double reference and the CPU float grid") {
  for (const auto& fr : {fractal_t<2>(), fractal_t<2>(turbulence_7<2>()),
                         fractal_t<2>(explicit_weights<2>()), fractal_t<2>(one_octave<2>())}) {
    check_grid(fr, hush::grid<2>{{0.1, -0.2}, {0.037, 0.05}, {128, 64}}, "at 0");
    check_grid(fr, hush::grid<2>{{1e6 + 0.3, 1e6}, {0.01, -0.02}, {128, 64}}, "at 1e6");
    check_grid(fr, hush::grid<2>{{-1e9, -1e9 + 0.5}, {-0.013, 0.011}, {128, 64}}, "at -1e9");
  }
  for (const auto& fr :
       {fractal_t<3>(), fractal_t<3>(turbulence_7<3>()), fractal_t<3>(explicit_weights<3>())}) {
    check_grid(fr, hush::grid<3>{{0.1, -0.2, 0.3}, {0.037, 0.05, 0.11}, {24, 20, 10}}, "at 0");
    check_grid(fr, hush::grid<3>{{1e6, 1e6 + 0.25, -1e6}, {0.01, -0.02, 0.03}, {24, 20, 10}},
               "at 1e6");
    check_grid(fr, hush::grid<3>{{-1e9, -1e9, -1e9 + 0.5}, {-0.013, 0.011, -0.07}, {24, 20, 10}},
               "at -1e9");
  }
  check_grid(fractal_t<2>(max_octaves<2>()), hush::grid<2>{{-5.5, 3.25}, {0.07, 0.03}, {64, 32}},
             "32 octaves");
}

TEST_CASE("periodic fractal perlin grids tile: grids a whole period apart are equal bit for bit") {
  // The sum repeats every period / frequency along each periodic axis.
  const fractal_t<2> f2(periodic<2>());
  const hush::grid<2> a{{0.25, 0.5}, {0.125, 0.125}, {48, 48}},
      b{{0.25 + 3 * 7, 0.5 - 5 * 3}, {0.125, 0.125}, {48, 48}};
  std::vector<float> va(a.count()), vb(b.count());
  hush::evaluate_grid(f2, hush::exec::glsl{headless().device}, a, va);
  hush::evaluate_grid(f2, hush::exec::glsl{headless().device}, b, vb);
  CHECK(va == vb);
  check_grid(f2, b, "periodic, shifted by whole periods");
  const fractal_t<3> f3(periodic<3>());
  check_grid(f3, hush::grid<3>{{-1e9, 7.5, -2.2}, {0.3, 0.2, -0.1}, {20, 16, 8}}, "periodic");
}

TEST_CASE("fractal perlin: NaN and infinite coordinates give NaN values and gradients") {
  const float nan = std::numeric_limits<float>::quiet_NaN(),
              inf = std::numeric_limits<float>::infinity();
  const std::vector<hush::vec2> p2 = {{nan, 0.5f}, {0.5f, inf}, {-inf, -inf}, {0.5f, 0.25f}};
  const std::vector<hush::vec3> p3 = {{nan, 0.5f, 0.5f}, {0.5f, 0.5f, -inf}, {0.5f, 0.25f, 0.75f}};
  for (const fractal_t<2>& fr :
       {fractal_t<2>(), fractal_t<2>(turbulence_7<2>()), fractal_t<2>(periodic<2>())}) {
    std::vector<float> v(p2.size());
    std::vector<hush::vec2> g(p2.size());
    hush::evaluate(fr, hush::exec::glsl{headless().device}, p2, v, g);
    for (std::size_t i = 0; i + 1 < p2.size(); ++i)
      CHECK((std::isnan(v[i]) && std::isnan(g[i].x) && std::isnan(g[i].y)));
    CHECK(std::isfinite(v.back()));
    hush::evaluate(fr, hush::exec::glsl{headless().device}, p2, v);
    for (std::size_t i = 0; i + 1 < p2.size(); ++i) CHECK(std::isnan(v[i]));
  }
  std::vector<float> v(p3.size());
  std::vector<hush::vec3> g(p3.size());
  hush::evaluate(fractal_t<3>(turbulence_7<3>()), hush::exec::glsl{headless().device}, p3, v, g);
  for (std::size_t i = 0; i + 1 < p3.size(); ++i)
    CHECK((std::isnan(v[i]) && std::isnan(g[i].x) && std::isnan(g[i].y) && std::isnan(g[i].z)));
  CHECK(std::isfinite(v.back()));
}

TEST_CASE("fractal perlin: huge coordinates up to FLT_MAX agree with the CPU within budget") {
  const std::vector<float> xs = {-1.0f, -1e-30f, 2147483648.0f, -3e9f,    4294967296.0f,
                                 1e20f, -1e30f,  FLT_MAX,       -FLT_MAX, 1e37f};
  std::vector<hush::vec3> pts;
  for (float x : xs)
    for (float y : {-1.0f, 0.3f, 3e9f}) pts.push_back({x, y, x * 0.5f});
  for (const fractal_t<3>& fr : {fractal_t<3>(), fractal_t<3>(max_octaves<3>()),
                                 fractal_t<3>(periodic<3>()), fractal_t<3>(turbulence_7<3>())}) {
    std::vector<float> v(pts.size());
    std::vector<hush::vec3> g(pts.size());
    hush::evaluate(fr, hush::exec::glsl{headless().device}, pts, v, g);
    for (float x : v) CHECK(std::isfinite(x));
    auto pos = [&](std::size_t i) { return hush::vec_cast<double>(pts[i]); };
    check_against_cpu<3>(fr, pts.size(), pos, v.data(), g.data(), "huge coordinates", false);
  }
}

TEST_CASE(
    "fractal perlin batches split across buffers and dispatches equal one batch bit for bit") {
  const fractal_t<3> fr(turbulence_7<3>());
  const auto pts = random_points<3>(3000, 21);
  std::vector<float> one(pts.size()), many(pts.size());
  std::vector<hush::vec3> g_one(pts.size()), g_many(pts.size());
  hush::evaluate(fr, hush::exec::glsl{headless().device}, pts, one, g_one);
  // 7 bands x 3 axes x 3 words = 252 bytes per point: 16 KiB holds 65 points.
  hush::glsl::device small(headless().context.loader(), {2, 16384});
  const std::size_t before = small.dispatches();
  hush::evaluate(fr, hush::exec::glsl{small}, pts, many, g_many);
  CHECK(small.dispatches() - before >= pts.size() / 65);
  CHECK(one == many);
  for (std::size_t i = 0; i < pts.size(); ++i) CHECK(g_one[i] == g_many[i]);
}

TEST_CASE("a fractal grid whose band tables exceed the buffer limit is refused") {
  hush::glsl::device small(headless().context.loader(),
                           {0, std::size_t{12} * 1000});  // 1000 triples
  std::vector<float> out(std::size_t{100} * 100);
  // 200 axis samples x 5 bands = 1000 triples fit; 6 bands do not.
  hush::evaluate_grid(fractal_t<2>(), hush::exec::glsl{small},
                      hush::grid<2>{{0, 0}, {0.1, 0.1}, {100, 100}}, out);
  fractal_t<2>::params p;
  p.octaves = 6;
  CHECK_THROWS_AS(hush::evaluate_grid(fractal_t<2>(p), hush::exec::glsl{small},
                                      hush::grid<2>{{0, 0}, {0.1, 0.1}, {100, 100}}, out),
                  hush::invalid_argument);
}

TEST_CASE("fractal runners declare kMaxOctaves band uniforms and call the library's band terms") {
  for (const auto layout : {hush::glsl::batch_layout::points, hush::glsl::batch_layout::grid})
    for (const bool gradient : {false, true}) {
      const std::string s = hush::glsl::compute_source<fractal_t<3>>(layout, gradient);
      CHECK(s.find("hush_fractal_add") != std::string::npos);
      CHECK(s.find("uniform uint hush_key[" + std::to_string(fractal_t<3>::kMaxOctaves) + "]") !=
            std::string::npos);
    }
}

}  // namespace
