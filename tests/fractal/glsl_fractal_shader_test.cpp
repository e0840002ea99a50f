// Fractal sums of Perlin noise in a user-written fragment shader
// (hush/glsl/fractal/shader.hpp) on llvmpipe: hush_fractal_perlinD(p) and its gradient over a
// grid of float positions (read back from the shader), against the CPU float path within
// hush::glsl::shader_budget / shader_gradient_budget for the grid's |p|: default fBm, 8
// octaves at |p| <= 2^8, turbulence, explicit weights, periodic sums. The kits compile for
// GL 4.30, Vulkan 450 and GLSL ES 3.00.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "glsl/glsl_test_util.hpp"
#include "glsl/shader_harness.hpp"
#include "hush/glsl/fractal/shader.hpp"
#include "test_util.hpp"

namespace {

constexpr int kSide = 40;

template <int D>
using fractal_t = hush::fractal<hush::perlin<D>>;

// Positions origin + (gl_FragCoord.xy - 0.5) * step (3D: z = 0.7 x - 0.3 y + origin.z);
// out 0: (value, gradient), 1: p, 2: the value-only function.
template <int D>
std::string fragment(const hush::glsl::shader_kit& kit, double origin, double step, int out) {
  const std::string n = "hush_fractal_perlin" + std::to_string(D);
  const std::string o = std::to_string(origin), st = std::to_string(step);
  std::string s = "#version 430 core\n" + (out == 1 ? std::string() : kit.source) +
                  "out vec4 colour;\nvoid main() {\n  vec2 q = vec2(" + o + ") + (gl_FragCoord.xy - 0.5) * " +
                  st + ";\n";
  s += D == 2 ? "  vec2 p = q;\n" : "  vec3 p = vec3(q, 0.7 * q.x - 0.3 * q.y + 0.25);\n";
  if (out == 0)
    s += D == 2 ? "  colour = vec4(" + n + "_gradient(p), 0.0);\n" : "  colour = " + n + "_gradient(p);\n";
  else if (out == 1)
    s += D == 2 ? "  colour = vec4(p, 0.0, 0.0);\n" : "  colour = vec4(p, 0.0);\n";
  else
    s += "  colour = vec4(" + n + "(p));\n";
  return s + "}\n";
}

// Whether some band of fr is within `margin` of 0 at p (turbulence's gradient sign is then
// not determined by the error bound).
template <int D>
bool near_band_zero(const fractal_t<D>& fr, const hush::vec<double, D>& p, double margin) {
  for (int i = 0; i < fr.band_count(); ++i)
    if (std::fabs(fr.band_noise(i).template value<double>(fr.band_position(i, p))) <= margin)
      return true;
  return false;
}

template <int D>
void check(const fractal_t<D>& fr, double origin, double step, const char* label) {
  auto& h = hush_glsl_test::headless();
  hush_glsl_test::fragment_harness fh(h.context.loader());
  const auto kit = hush::glsl::shader_for(fr);
  std::vector<std::vector<float>> px;
  for (int out = 0; out <= 2; ++out)
    px.push_back(fh.draw(fragment<D>(kit, origin, step, out), kit, kSide, kSide));
  double pmax = 0;
  for (int i = 0; i < kSide * kSide; ++i)
    for (int a = 0; a < D; ++a) pmax = std::max(pmax, double(std::fabs(px[1][std::size_t(4 * i + a)])));
  const double tol = hush::glsl::shader_budget(fr, pmax);
  const double gtol = hush::glsl::shader_gradient_budget(fr, pmax);
  const bool turbulence = fr.parameters().kind == hush::fractal_kind::turbulence;
  hush_glsl_test::error_stats ev, eg, ed;
  for (int i = 0; i < kSide * kSide; ++i) {
    const std::size_t o = std::size_t(4 * i);
    hush::vec<float, D> p;
    for (int a = 0; a < D; ++a) p[a] = px[1][o + std::size_t(a)];
    const auto c = fr.template value_and_gradient<float>(hush::vec_cast<double>(p));
    const double gv = px[0][o];
    INFO(std::string(label) << " pixel " << i << ": gpu " << gv << ", cpu " << c.value);
    ev.add(std::fabs(gv - c.value));
    ed.add(std::fabs(gv - fr.template value<double>(hush::vec_cast<double>(p))));
    CHECK(std::fabs(gv - c.value) <= tol);
    CHECK(px[2][o] == px[0][o]);
    if (turbulence && near_band_zero<D>(fr, hush::vec_cast<double>(p), tol / fr.scale()))
      continue;
    for (int a = 0; a < D; ++a) {
      const double e = std::fabs(double(px[0][o + 1 + std::size_t(a)]) - c.gradient[a]);
      eg.add(e);
      CHECK(e <= gtol);
    }
  }
  const std::string note = std::string(label) + ": |p| <= " + std::to_string(pmax) + ": max |gpu - cpu float| " +
          std::to_string(ev.max) + " (budget " + std::to_string(tol) + "), |gpu - double| " +
          std::to_string(ed.max) + ", gradients " + std::to_string(eg.max) + " (budget " +
          std::to_string(gtol) + ")";
  MESSAGE(note);
  CHECK(ev.n == std::size_t(kSide * kSide));
}

}  // namespace

TEST_CASE("fractal shader 2D: default fBm, and 8 octaves at |p| <= 2^8 within the budget") {
  check<2>(fractal_t<2>(), -3.0, 0.17, "2D default fBm");
  typename fractal_t<2>::params prm;
  prm.octaves = 8;
  prm.seed = 3;
  const fractal_t<2> eight(prm);
  check<2>(eight, -256.0, 12.8, "2D 8 octaves, |p| <= 2^8");
  // The examples of the header's comment: the default fBm and 8 octaves at |p| <= 2^8.
  MESSAGE("budgets at |p| <= 2^8: default " << hush::glsl::shader_budget(fractal_t<2>(), 256.0)
                                            << ", 8 octaves " << hush::glsl::shader_budget(eight, 256.0));
  CHECK(hush::glsl::shader_budget(fractal_t<2>(), 256.0) < 7e-3);
  CHECK(hush::glsl::shader_budget(eight, 256.0) < 1.1e-2);
}

TEST_CASE("fractal shader 2D: turbulence, explicit weights and a periodic sum") {
  typename fractal_t<2>::params prm;
  prm.kind = hush::fractal_kind::turbulence;
  prm.norm = hush::normalization::unit_range;
  prm.octaves = 6;
  check<2>(fractal_t<2>(prm), 40.0, 0.9, "2D turbulence");
  prm = {};
  prm.weights = {1.0, 0.0, -0.5, 0.3};
  prm.octaves = 4;
  prm.lacunarity = 3.0;
  prm.period = {4, 6};
  prm.norm = hush::normalization::none;
  check<2>(fractal_t<2>(prm), -10.0, 0.51, "2D weights, lacunarity 3, periodic");
}

TEST_CASE("fractal shader 3D: fBm near and at |p| <= 2^8, turbulence") {
  typename fractal_t<3>::params prm;
  prm.octaves = 6;
  check<3>(fractal_t<3>(prm), -2.0, 0.11, "3D fBm");
  check<3>(fractal_t<3>(prm), -256.0, 12.8, "3D fBm, |p| <= 2^8");
  prm.kind = hush::fractal_kind::turbulence;
  prm.norm = hush::normalization::unit_range;
  prm.period = {3, 4, 5};
  check<3>(fractal_t<3>(prm), 7.0, 0.3, "3D periodic turbulence");
}

TEST_CASE("fractal shader: the block holds the bands, the source only the type") {
  typename fractal_t<3>::params prm;
  prm.octaves = 3;
  prm.period = {3, 4, 5};
  const fractal_t<3> fr(prm);
  const auto kit = hush::glsl::shader_for(fr);
  REQUIRE(kit.resources.size() == 1u);
  const auto& w = kit.resources[0].words;
  CHECK(w[0] == 3u);
  const std::size_t lattice = 8 + 2 * 4 * 32;  // config, scalars, band[32], offset[32]
  CHECK(w[lattice + 4 * 2] == hush::seed_key(fr.band_noise(2).parameters().seed));
  CHECK(w[lattice + 4 * 2 + 3] == 20u);  // 5 * lacunarity^2
  CHECK(kit.source == hush::glsl::shader_for(fractal_t<3>()).source);
}

#ifdef HUSH_GLSLANG_VALIDATOR
TEST_CASE("fractal shader: both kits compile for GL 4.30 core, Vulkan 450 and GLSL ES 3.00") {
  using hush_glsl_test::dialect;
  const std::string main2 =
      "layout(location = 0) out highp vec4 colour;\nvoid main() {\n"
      "  colour = vec4(hush_fractal_perlin2_gradient(gl_FragCoord.xy), "
      "hush_fractal_perlin2(gl_FragCoord.yx));\n}\n";
  const std::string main3 =
      "layout(location = 0) out highp vec4 colour;\nvoid main() {\n"
      "  colour = hush_fractal_perlin3_gradient(gl_FragCoord.xyx) + "
      "vec4(hush_fractal_perlin3(gl_FragCoord.xyz));\n}\n";
  const auto k2 = hush::glsl::shader_for(fractal_t<2>());
  const auto k3 = hush::glsl::shader_for(fractal_t<3>());
  for (dialect d : {dialect::gl430, dialect::vulkan450, dialect::es300})
    for (const auto& text : {k2.source + main2, k3.source + main3}) {
      const auto r = hush_glsl_test::glslang_compile(text, d, "fractal_shader_kit");
      INFO(hush_glsl_test::dialect_name(d) << ": " << r.log.substr(0, 3000));
      CHECK(r.ok);
    }
}
#endif
