// Wavelet noise in a user-written fragment shader (hush/glsl/wavelet/shader.hpp) on llvmpipe.
// The shader forms its own positions, takes footprints from its own dFdx/dFdy on a
// receding plane, and calls the kit's functions; the test reads back the value, gradient,
// position and derivatives of every pixel and compares with the CPU's sample(p, footprint)
// (and sample(p, normal, footprint) in 3D) at the same float position and Jacobian: every
// value and gradient within hush::glsl::shader_budget / shader_gradient_budget, for one
// band, several bands, infinite noise, widening, tile variants, the three distributions and
// both projections. The kits compile for GL 4.30, Vulkan 450 and GLSL ES 3.00.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "glsl/glsl_test_util.hpp"
#include "glsl/shader_harness.hpp"
#include "hush/glsl/fractal/shader.hpp"
#include "hush/glsl/perlin/shader.hpp"
#include "hush/glsl/wavelet/shader.hpp"

namespace {

constexpr int kSide = 40;

enum class where { grid, plane };

// The shader: position p (a grid around -200 or a receding plane), its screen derivatives,
// the kit call `call` (a vec4: value, gradient), then output `out` of:
// 0 the call, 1 p, 2 dFdx(p), 3 dFdy(p), 4 the value-only functions.
template <int D>
std::string fragment(const hush::glsl::shader_kit& kit, where at, const std::string& call,
                     const std::string& value_call, int out) {
  std::string pos;
  if (at == where::grid)
    pos = "  vec2 q = vec2(-200.0, 150.0) + (gl_FragCoord.xy - 0.5) * 0.37;\n";
  else  // depth 1 ... 6.7 from the bottom row to the top: footprints from small to huge
    pos = "  float t = gl_FragCoord.y / " + std::to_string(kSide) +
          ".0;\n  float z = 1.0 / (1.15 - t);\n"
          "  vec2 q = vec2((gl_FragCoord.x / " +
          std::to_string(kSide) + ".0 - 0.5) * z * 3.0 - 3.0, z * 3.0 - 17.0);\n";
  pos += "  if (gl_FragCoord.x < 1.0 && gl_FragCoord.y < 1.0) q.x = uintBitsToFloat(0x7fc00000u);\n";
  if (D == 2)
    pos += "  vec2 p = q;\n";
  else  // a plane through the origin with normal (1, 2, 3)
    pos += "  vec3 p = q.x * vec3(2.0, -1.0, 0.0) * 0.4472136 + "
           "q.y * vec3(3.0, 6.0, -5.0) * 0.11952286;\n";
  const std::string v = D == 2 ? "vec2" : "vec3";
  const std::string pad = D == 2 ? ", 0.0, 0.0)" : ", 0.0)";
  // Each draw calls the kit once at most, and only draws 0 and 4 hold it: llvmpipe takes
  // seconds to compile a kit call (inlined whole). In 2D draw 0 holds both calls.
  const std::string what = out == 0   ? (D == 2 ? "vec4(" + call + ".xyz, " + value_call + ".x)"
                                                : call)
                           : out == 1 ? "vec4(p" + pad
                           : out == 2 ? "vec4(dx" + pad
                           : out == 3 ? "vec4(dy" + pad
                                      : value_call;
  const bool calls = out == 0 || out == 4;
  return "#version 430 core\n" + (calls ? kit.source : std::string()) +
         "out vec4 colour;\nvoid main() {\n" + pos +
         "  " + v + " dx = dFdx(p), dy = dFdy(p);\n  vec3 nrm = vec3(1.0, 2.0, 3.0);\n" +
         "  colour = " + what + ";\n}\n";
}

enum class kind { point, filtered, projected };

template <int D>
void check(const hush::wavelet<D>& w, where at, kind k, const char* label) {
  auto& h = hush_glsl_test::headless();
  hush_glsl_test::fragment_harness fh(h.context.loader());
  const hush::glsl::shader_kit kit = hush::glsl::shader_for(w);
  const std::string n = "hush_wavelet" + std::to_string(D);
  std::string call, value_calls;  // the (value, gradient) call; the value-only one
  if (k == kind::point) {
    call = D == 2 ? "vec4(" + n + "_gradient(p), 0.0)" : n + "_gradient(p)";
    value_calls = "vec4(" + n + "(p))";
  } else if (k == kind::filtered) {
    call = D == 2 ? "vec4(" + n + "_filtered_gradient(p, dx, dy), 0.0)"
                  : n + "_filtered_gradient(p, dx, dy)";
    value_calls = "vec4(" + n + "_filtered(p, dx, dy))";
  } else {
    call = "hush_wavelet3_eval(p, outerProduct(dx, dx) + outerProduct(dy, dy), true, nrm)";
    // The value-only functions: with the footprint (exact projection), or without (the
    // approximate one, compared with sample(p, normal)).
    value_calls = w.parameters().projection == hush::wavelet_projection::exact
                      ? "vec4(hush_wavelet3_projected_filtered(p, nrm, dx, dy))"
                      : "vec4(hush_wavelet3_projected(p, nrm))";
  }
  std::vector<std::vector<float>> px;
  // 3D: the value-only functions are drawn for the projections only (their own code; the
  // others return _eval(...).x).
  const bool value_draw = D == 3 && k == kind::projected;
  for (int out = 0; out <= (value_draw ? 4 : 3); ++out)
    px.push_back(fh.draw(fragment<D>(kit, at, call, value_calls, out), kit, kSide, kSide));
  const std::vector<float>& vals = value_draw ? px[4] : px[0];
  const std::size_t vch = value_draw ? 0 : 3;  // the value-only call's channel
  const bool plain = !w.parameters().widen && k != kind::projected;
  double pmax = 0;
  for (int i = 1; i < kSide * kSide; ++i)
    for (int a = 0; a < D; ++a) pmax = std::max(pmax, double(std::fabs(px[1][std::size_t(4 * i + a)])));
  const bool fp = k != kind::point;
  const double tol = hush::glsl::shader_budget(w, pmax, fp, plain);
  const double gtol = hush::glsl::shader_gradient_budget(w, pmax, fp, plain);
  hush_glsl_test::error_stats ev, eg, ed;
  int nans = 0, filtered_out = 0;
  for (int i = 0; i < kSide * kSide; ++i) {
    const std::size_t o = std::size_t(4 * i);
    hush::vec<float, D> p, dx, dy;
    for (int a = 0; a < D; ++a) {
      p[a] = px[1][o + std::size_t(a)];
      dx[a] = px[2][o + std::size_t(a)];
      dy[a] = px[3][o + std::size_t(a)];
    }
    hush::footprint<D> foot;
    if (fp) foot = hush::footprint<D>::from_derivatives(dx, dy);
    hush::value_gradient<float, D> c;
    double ref;
    if constexpr (D == 3) {
      if (k == kind::projected) {
        const hush::vec<float, 3> nrm{1.0f, 2.0f, 3.0f};
        c = w.sample_gradient(p, nrm, foot);
        ref = w.sample(hush::vec_cast<double>(p), hush::vec_cast<double>(nrm), foot);
      } else {
        c = w.sample_gradient(p, foot);
        ref = w.sample(hush::vec_cast<double>(p), foot);
      }
    } else {
      c = w.sample_gradient(p, foot);
      ref = w.sample(hush::vec_cast<double>(p), foot);
    }
    const float gv = px[0][o];
    INFO(std::string(label) << " pixel " << i << ": gpu " << gv << ", cpu " << c.value);
    REQUIRE(std::isnan(gv) == std::isnan(c.value));
    if (std::isnan(gv)) {
      ++nans;
      continue;
    }
    if (c.value == 0.0f && fp) ++filtered_out;
    ev.add(std::fabs(double(gv) - c.value));
    ed.add(std::fabs(double(gv) - ref));
    CHECK(std::fabs(double(gv) - c.value) <= tol);
    // The value-only functions return the same value (hush_wavelet3_projected: no footprint).
    bool point_projection = false;
    if constexpr (D == 3) {
      if (k == kind::projected && w.parameters().projection != hush::wavelet_projection::exact) {
        point_projection = true;
        const float c0 = w.sample(p, hush::vec<float, 3>{1.0f, 2.0f, 3.0f});
        CHECK(std::fabs(double(vals[o + vch]) - c0) <= hush::glsl::shader_budget(w, pmax, false, false));
      }
    }
    if (!point_projection && (D == 2 || value_draw)) CHECK(vals[o + vch] == gv);
    for (int a = 0; a < D; ++a) {
      eg.add(std::fabs(double(px[0][o + 1 + std::size_t(a)]) - c.gradient[a]));
      CHECK(std::fabs(double(px[0][o + 1 + std::size_t(a)]) - c.gradient[a]) <= gtol);
    }
  }
  CHECK(nans == 1);  // the NaN pixel, and only it
  CHECK(ev.n > 0);
  std::string note = std::string(label) + ": |p| <= " + std::to_string(pmax) +
                     ": max |gpu - cpu float| " + std::to_string(ev.max) + " (budget " +
                     std::to_string(tol) + "), |gpu - double| " + std::to_string(ed.max) +
                     ", gradients " + std::to_string(eg.max) + " (budget " +
                     std::to_string(gtol) + ")";
  if (fp) note += ", pixels filtered to 0: " + std::to_string(filtered_out);
  MESSAGE(note);
}

template <int D>
typename hush::wavelet<D>::params base() {
  typename hush::wavelet<D>::params prm;
  prm.tile_size = D == 2 ? 32 : 16;
  prm.seed = 5;
  return prm;
}

}  // namespace

// Few kit calls per case: llvmpipe takes seconds to compile each (inlined whole).
TEST_CASE("wavelet shader 2D: one band, points and dFdx/dFdy footprints") {
  const hush::wavelet<2> one(base<2>());
  check<2>(one, where::grid, kind::point, "2D one band, grid");
  check<2>(one, where::plane, kind::filtered, "2D one band, receding plane");
}

TEST_CASE("wavelet shader 2D: four bands, points and dFdx/dFdy footprints") {
  auto prm = base<2>();
  prm.weights = {1, -0.5, 0.25, 0.125};
  prm.first_band = -2;
  const hush::wavelet<2> multi(prm);
  check<2>(multi, where::grid, kind::point, "2D four bands, grid");
  check<2>(multi, where::plane, kind::filtered, "2D four bands, receding plane");
}

TEST_CASE("wavelet shader 2D: the uniform and the table distributions") {
  auto prm = base<2>();
  prm.weights = {1, 0.5};
  prm.distribution = hush::wavelet_distribution::uniform;
  check<2>(hush::wavelet<2>(prm), where::plane, kind::filtered, "2D uniform");
  prm.distribution = hush::wavelet_distribution::table;
  prm.table = {-3, -1, 0, 0.5, 4};
  check<2>(hush::wavelet<2>(prm), where::plane, kind::filtered, "2D table");
}

TEST_CASE("wavelet shader 2D: infinite noise and basis widening") {
  auto prm = base<2>();
  prm.relative_weights = true;
  prm.weights = {1, 0.5, 0.25};
  prm.first_band = -4;
  prm.relative_bands = 10;
  check<2>(hush::wavelet<2>(prm), where::plane, kind::filtered, "2D infinite noise");
  prm = base<2>();
  prm.weights = {1, 0.5, 0.25};
  prm.widen = true;
  check<2>(hush::wavelet<2>(prm), where::plane, kind::filtered, "2D widened");
}

TEST_CASE("wavelet shader 2D: tile variants") {
  auto prm = base<2>();
  prm.weights = {1, 0.5};
  prm.variant_overlap = 2;
  check<2>(hush::wavelet<2>(prm), where::plane, kind::filtered, "2D tile variants");
}

TEST_CASE("wavelet shader 3D: one band, points and dFdx/dFdy footprints") {
  const hush::wavelet<3> one(base<3>());
  check<3>(one, where::grid, kind::point, "3D one band, grid");
  check<3>(one, where::plane, kind::filtered, "3D one band, receding plane");
}

TEST_CASE("wavelet shader 3D: three bands with footprints") {
  auto prm = base<3>();
  prm.weights = {1, 0.5, 0.25};
  prm.first_band = -1;
  check<3>(hush::wavelet<3>(prm), where::plane, kind::filtered, "3D three bands, receding plane");
}

// One case per projection: llvmpipe takes seconds to compile each projected evaluation.
TEST_CASE("wavelet shader 3D: projected onto the plane's normal, exact, with footprints") {
  auto prm = base<3>();
  prm.weights = {1, 0.5};
  check<3>(hush::wavelet<3>(prm), where::plane, kind::projected, "3D projected exact");
}

TEST_CASE("wavelet shader 3D: projected onto the plane's normal, approximate") {
  auto prm = base<3>();
  prm.weights = {1, 0.5};
  prm.projection = hush::wavelet_projection::approximate;
  check<3>(hush::wavelet<3>(prm), where::plane, kind::projected, "3D projected approximate");
}

TEST_CASE("wavelet shader 3D: projected and widened") {
  auto prm = base<3>();
  prm.weights = {1, 0.5};
  prm.widen = true;
  check<3>(hush::wavelet<3>(prm), where::plane, kind::projected, "3D projected widened");
}

TEST_CASE("wavelet shader: the kit's resources (block, tile texels, table rows)") {
  auto prm = base<3>();
  prm.distribution = hush::wavelet_distribution::table;
  prm.table.assign(300, 0.0);
  for (std::size_t i = 0; i < prm.table.size(); ++i) prm.table[i] = double(i) / 299.0;
  const hush::wavelet<3> w(prm);
  const auto kit = hush::glsl::shader_for(w);
  REQUIRE(kit.resources.size() == 4u);
  const auto* tile = kit.find("hush_wavelet3_tile");
  REQUIRE(tile != nullptr);
  CHECK(tile->kind == hush::glsl::resource_kind::texture_3d);
  CHECK(tile->width * tile->height * tile->depth == tile->words.size());
  CHECK(tile->words[17 + 16 * 3] == hush::glsl::float_word(w.tile().coefficient(17 + 16 * 3)));
  const auto* table = kit.find("hush_wavelet3_table");
  REQUIRE(table != nullptr);
  CHECK(table->width == hush::glsl::kWaveletTableTextureWidth);
  CHECK(table->height == 2u);
  CHECK(table->words[299] == hush::glsl::float_word(1.0f));
  CHECK(kit.source == hush::glsl::shader_for(hush::wavelet<3>(base<3>())).source);
}

#ifdef HUSH_GLSLANG_VALIDATOR
TEST_CASE("wavelet shader: both kits compile for GL 4.30 core, Vulkan 450 and GLSL ES 3.00") {
  using hush_glsl_test::dialect;
  const std::string main2 =
      "layout(location = 0) out highp vec4 colour;\nvoid main() {\n"
      "  vec2 p = gl_FragCoord.xy;\n"
      "  colour = vec4(hush_wavelet2_filtered_gradient(p, dFdx(p), dFdy(p)), hush_wavelet2(p));\n}\n";
  const std::string main3 =
      "layout(location = 0) out highp vec4 colour;\nvoid main() {\n"
      "  vec3 p = gl_FragCoord.xyx;\n"
      "  colour = hush_wavelet3_filtered_gradient(p, dFdx(p), dFdy(p)) +\n"
      "           vec4(hush_wavelet3_projected_filtered(p, vec3(1.0), dFdx(p), dFdy(p)));\n}\n";
  const auto k2 = hush::glsl::shader_for(hush::wavelet<2>(base<2>()));
  const auto k3 = hush::glsl::shader_for(hush::wavelet<3>(base<3>()));
  // The Perlin and fractal kits before the wavelet kit in one shader: the library once, the
  // wavelet bodies after it.
  const std::string shared =
      hush::glsl::shader_for(hush::perlin<2>(1)).source +
      hush::glsl::shader_for(hush::fractal<hush::perlin<3>>()).source + k2.source +
      "layout(location = 0) out highp vec4 colour;\nvoid main() {\n"
      "  vec2 p = gl_FragCoord.xy;\n"
      "  colour = vec4(hush_perlin2(p), hush_fractal_perlin3(p.xyx), hush_wavelet2(p), 1.0);\n}\n";
  for (dialect d : {dialect::gl430, dialect::vulkan450, dialect::es300}) {
    for (const auto& text : {k2.source + main2, k3.source + main3, shared}) {
      const auto r = hush_glsl_test::glslang_compile(text, d, "wavelet_shader_kit");
      INFO(hush_glsl_test::dialect_name(d) << ": " << r.log.substr(0, 3000));
      CHECK(r.ok);
    }
  }
}
#endif
