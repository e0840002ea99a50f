// Anisotropic noise in a user-written fragment shader (hush/glsl/anisotropic/shader.hpp) on
// llvmpipe, against the CPU's float sample(uv, footprint[, map]) at the same float inputs,
// within anisotropic_shader_tolerance per pixel: the shader's own dFdx/dFdy on a receding
// plane, given Jacobians and surface maps (mat2 T, and the texture-to-surface tangents),
// grazing footprints, NaN and non-finite inputs; 2 to 8 orientations, fbm and turbulence,
// centre and three-point rules. Also: the kit's resources (the tiles are the runner's
// texels, the block's words), its source independent of the parameters, least squares
// refused, the tolerance far below the noise's range, and the source compiling for GL 4.30,
// Vulkan 450 and GLSL ES 3.00.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <regex>
#include <string>
#include <vector>

#include "glsl/glsl_test_util.hpp"
#include "glsl/shader_harness.hpp"
#include "hush/glsl/anisotropic/shader.hpp"

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

constexpr int kW = 32, kH = 32;

// An RGBA32F input texture (binding 8 + slot) appended to a copy of the kit, so that a test
// feeds exact per-pixel inputs; pixel (x, y) reads texel (x, y).
hush::glsl::shader_kit with_inputs(hush::glsl::shader_kit kit,
                                   const std::vector<std::vector<float>>& inputs) {
  for (std::size_t t = 0; t < inputs.size(); ++t) {
    hush::glsl::shader_resource r;
    r.name = "test_in" + std::to_string(t);
    r.kind = hush::glsl::resource_kind::texture_2d;
    r.binding = 8 + unsigned(t);
    r.format = hush::glsl::texel_format::rgba32f;
    r.width = kW;
    r.height = kH;
    for (float v : inputs[t]) r.words.push_back(hush::glsl::float_word(v));
    kit.resources.push_back(r);
    kit.source += "layout(binding = " + std::to_string(8 + t) + ") uniform sampler2D test_in" +
                  std::to_string(t) + ";\n";
  }
  return kit;
}

struct error_ratio {
  double worst = 0, worst_abs = 0;
  void add(double e, double tol) {
    worst = std::max(worst, e / tol);
    worst_abs = std::max(worst_abs, e);
  }
};

// Per-pixel inputs given through textures: uv, the Jacobian and the map of pixel i.
struct pixel_inputs {
  std::vector<hush::vec2> uv, dx, dy;
  std::vector<hush::surface_map> maps;
  std::vector<hush::vec3> dp_du, dp_dv;
};

pixel_inputs random_inputs(std::uint32_t seed) {
  hush::rng r(seed);
  pixel_inputs in;
  for (int i = 0; i < kW * kH; ++i) {
    const float extent = i % 16 == 5 ? 1000.0f : 40.0f;
    in.uv.push_back({r.uniform(-extent, extent), r.uniform(-extent, extent)});
    const float w = float(std::exp2(r.uniform<double>(-8, 3)));
    const bool point = i % 9 == 0;
    in.dx.push_back(point ? hush::vec2{0, 0}
                          : hush::vec2{w * r.uniform(-1.0f, 1.0f), w * r.uniform(-1.0f, 1.0f)});
    in.dy.push_back(point ? hush::vec2{0, 0}
                          : hush::vec2{w * r.uniform(-1.0f, 1.0f), w * r.uniform(-1.0f, 1.0f)});
    auto m = hush::surface_map::from_matrix(r.uniform<double>(-3, 3), r.uniform<double>(-3, 3),
                                            r.uniform<double>(-3, 3), r.uniform<double>(-3, 3));
    if (i % 11 == 5) m = hush::surface_map::zero();
    if (i % 13 == 7) m.m10 = std::numeric_limits<float>::quiet_NaN();
    in.maps.push_back(m);
    // Tangents at least ~25 degrees apart (the surface-map test's conditioning).
    const double a = r.uniform<double>(0, 6.283), b = a + r.uniform<double>(0.45, 2.7);
    const double lu = std::exp2(r.uniform<double>(-2, 2)), lv = std::exp2(r.uniform<double>(-2, 2));
    const double tilt = r.uniform<double>(-1, 1);
    in.dp_du.push_back({float(lu * std::cos(a)), float(lu * std::sin(a)), float(lu * tilt)});
    in.dp_dv.push_back({float(lv * std::cos(b)), float(lv * std::sin(b)), float(-lv * tilt)});
  }
  const float nan = std::numeric_limits<float>::quiet_NaN(),
              inf = std::numeric_limits<float>::infinity();
  in.uv[7].x = nan;
  in.uv[100].y = inf;
  in.dx[33].y = nan;
  in.dy[34].x = inf;
  in.dx[35] = {3e30f, 1e30f};
  return in;
}

// mode 0: hush_anisotropic(uv, mat2 J); 1: hush_anisotropic_mapped(uv, dx, dy, T);
// 2: hush_anisotropic_surface(uv, dx, dy, dp_du, dp_dv). Returns the shader's values.
std::vector<float> draw_inputs(const hush::anisotropic& a, const pixel_inputs& in, int mode) {
  std::vector<float> t0, t1, t2;
  for (int i = 0; i < kW * kH; ++i) {
    const std::size_t q = std::size_t(i);
    t0.insert(t0.end(), {in.uv[q].x, in.uv[q].y, in.dx[q].x, in.dx[q].y});
    t1.insert(t1.end(), {in.dy[q].x, in.dy[q].y, in.dp_dv[q].y, in.dp_dv[q].z});
    if (mode == 2)
      t2.insert(t2.end(), {in.dp_du[q].x, in.dp_du[q].y, in.dp_du[q].z, in.dp_dv[q].x});
    else
      t2.insert(t2.end(), {in.maps[q].m00, in.maps[q].m10, in.maps[q].m01, in.maps[q].m11});
  }
  const hush::glsl::shader_kit kit = with_inputs(hush::glsl::shader_for(a), {t0, t1, t2});
  const std::string call =
      mode == 0   ? "hush_anisotropic(a.xy, mat2(a.zw, b.xy))"
      : mode == 1 ? "hush_anisotropic_mapped(a.xy, a.zw, b.xy, mat2(c.xy, c.zw))"
                  : "hush_anisotropic_surface(a.xy, a.zw, b.xy, c.xyz, vec3(c.w, b.zw))";
  const std::string fs =
      "#version 430 core\n" + kit.source +
      "out vec4 colour;\n"
      "void main() {\n"
      "  ivec2 px = ivec2(gl_FragCoord.xy);\n"
      "  vec4 a = texelFetch(test_in0, px, 0), b = texelFetch(test_in1, px, 0),\n"
      "       c = texelFetch(test_in2, px, 0);\n"
      "  colour = vec4(" +
      call +
      ", 0.0, 0.0, 1.0);\n"
      "}\n";
  hush_glsl_test::fragment_harness fh(headless().context.loader());
  const std::vector<float> px = fh.draw(fs, kit, kW, kH);
  std::vector<float> out(std::size_t(kW * kH));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = px[4 * i];
  return out;
}

// The CPU's float sample and the map the GPU was given, for pixel q of `in` in `mode`.
hush::surface_map cpu_map(const pixel_inputs& in, std::size_t q, int mode) {
  if (mode == 1) return in.maps[q];
  const hush::vec3 u = in.dp_du[q], v = in.dp_dv[q];
  return hush::surface_map::from_triangle({0, 0, 0}, {u.x, u.y, u.z}, {v.x, v.y, v.z}, {0, 0},
                                          {1, 0}, {0, 1});
}

// Compares one draw of `mode` with the CPU pixel by pixel; returns the error ratio.
error_ratio check_inputs(const hush::anisotropic& a, const pixel_inputs& in, int mode) {
  const std::vector<float> gpu = draw_inputs(a, in, mode);
  error_ratio r;
  for (std::size_t q = 0; q < gpu.size(); ++q) {
    const hush::footprint<2> fp = hush::footprint<2>::from_derivatives(in.dx[q], in.dy[q]);
    hush::surface_map m = mode == 0 ? hush::surface_map::identity() : cpu_map(in, q, mode);
    const float cpu = mode == 0 ? a.sample(in.uv[q], fp) : a.sample(in.uv[q], fp, m);
    INFO("mode " << mode << " pixel " << q << ": cpu " << cpu << " gpu " << gpu[q]);
    REQUIRE(std::isnan(cpu) == std::isnan(gpu[q]));
    if (std::isnan(cpu)) continue;
    // The surface path's T: its float entries err by a few ulp of T's size for tangents
    // ~25 degrees apart or more (the shader forms T in ~12 float operations, each within
    // u = 2^-24 of its result; the smallest sine 0.43 and edge ratio 4^2 grow it by 40):
    // 2^-14 of T's largest entry leaves margin.
    const double largest =
        std::max({std::fabs(m.m00), std::fabs(m.m01), std::fabs(m.m10), std::fabs(m.m11)});
    const double tol = hush::glsl::anisotropic_shader_tolerance(
        a, in.uv[q], in.dx[q], in.dy[q], mode == 0 ? nullptr : &m,
        mode == 2 ? std::ldexp(largest, -14) : 0.0);
    const double e = std::fabs(double(gpu[q]) - cpu);
    CHECK(e <= tol);
    r.add(e, tol);
  }
  return r;
}

}  // namespace

TEST_CASE("anisotropic shader: dFdx/dFdy on a receding plane agree with the CPU's sample") {
  // uv of a receding plane (perspective: the footprint grows and stretches towards the top);
  // draw 1 writes (noise, uv), draw 2 the shader's dFdx(uv), dFdy(uv) of the same expression.
  const std::string uv_expr =
      "  vec2 s = gl_FragCoord.xy;\n"
      "  float w = 1.0 / (1.0 + s.y * test_p[0]);\n"
      "  vec2 uv = vec2(test_p[1] + (s.x - test_p[2]) * test_p[3] * w, test_p[4] * w * s.y);\n";
  const float params[][5] = {{0.02f, 3.5f, 16.0f, 0.1f, 0.3f}, {0.4f, -7.25f, 16.0f, 1.7f, 2.1f}};
  using hush::fractal_kind;
  using hush::weight_rule;
  error_ratio all;
  for (int k : {2, 4, 6, 8})
    for (fractal_kind kind : {fractal_kind::fbm, fractal_kind::turbulence})
      for (weight_rule rule : {weight_rule::centre, weight_rule::three_point}) {
        const hush::anisotropic a = make(k, kind, rule);
        const hush::glsl::shader_kit kit = hush::glsl::shader_for(a);
        const std::string head = "#version 430 core\n" + kit.source +
                                 "uniform float test_p[5];\nout vec4 colour;\nvoid main() {\n" +
                                 uv_expr;
        const std::string fs_value =
            head + "  colour = vec4(hush_anisotropic(uv, dFdx(uv), dFdy(uv)), uv, 0.0);\n}\n";
        const std::string fs_jacobian = head + "  colour = vec4(dFdx(uv), dFdy(uv));\n}\n";
        const float* prm = params[(k + int(kind)) % 2];
        hush_glsl_test::fragment_harness fh(headless().context.loader());
        auto set = [&](hush::glsl::detail::gl_uint prog) {
          fh.gl().Uniform1fv(fh.gl().GetUniformLocation(prog, "test_p"), 5, prm);
        };
        const std::vector<float> v = fh.draw(fs_value, kit, kW, kH, set);
        const std::vector<float> j = fh.draw(fs_jacobian, kit, kW, kH, set);
        for (std::size_t q = 0; q < std::size_t(kW * kH); ++q) {
          const hush::vec2 uv{v[4 * q + 1], v[4 * q + 2]};
          const hush::vec2 dx{j[4 * q], j[4 * q + 1]}, dy{j[4 * q + 2], j[4 * q + 3]};
          const float cpu = a.sample(uv, hush::footprint<2>::from_derivatives(dx, dy));
          INFO("K " << k << " kind " << int(kind) << " rule " << int(rule) << " pixel " << q
                    << ": cpu " << cpu << " gpu " << v[4 * q]);
          const double tol = hush::glsl::anisotropic_shader_tolerance(a, uv, dx, dy, nullptr);
          const double e = std::fabs(double(v[4 * q]) - cpu);
          CHECK(e <= tol);
          all.add(e, tol);
        }
      }
  MESSAGE(headless().device.renderer() << ", dFdx/dFdy: max |gpu - cpu| = " << all.worst_abs
                                       << ", max error / tolerance = " << all.worst);
}

TEST_CASE("anisotropic shader: given Jacobians and surface maps agree with the CPU's sample") {
  const pixel_inputs in = random_inputs(3);
  using hush::fractal_kind;
  using hush::weight_rule;
  error_ratio r[3];
  for (int k : {3, 4, 8})
    for (fractal_kind kind : {fractal_kind::fbm, fractal_kind::turbulence})
      for (weight_rule rule : {weight_rule::centre, weight_rule::three_point}) {
        const hush::anisotropic a = make(k, kind, rule, 5);
        for (int mode = 0; mode < 3; ++mode) {
          const error_ratio e = check_inputs(a, in, mode);
          r[mode].worst = std::max(r[mode].worst, e.worst);
          r[mode].worst_abs = std::max(r[mode].worst_abs, e.worst_abs);
        }
      }
  MESSAGE(headless().device.renderer()
          << ": max |gpu - cpu| / max error over tolerance: mat2 Jacobian " << r[0].worst_abs
          << " / " << r[0].worst << ", mapped " << r[1].worst_abs << " / " << r[1].worst
          << ", surface tangents " << r[2].worst_abs << " / " << r[2].worst);
}

// Grazing footprints (the batch suite's construction): J = [L e, thin e_perp] with e within
// delta of perpendicular to d_i, so q_i ~ L^2 delta^2 is small while J's entries are ~L. The
// shader's q_i = |J^T d_i|^2 stays a sum of squares; the CPU's d_i^T S d_i from S rounded to
// float differs from the exact q_i by 2^-24 |S| kappa_s in the exponent, which the tolerance
// carries (the Q_i term). Checks that weights well above 0 occur, else it tests nothing.
TEST_CASE("anisotropic shader: grazing footprints stay within the tolerance") {
  const hush::anisotropic a = make(5, hush::fractal_kind::fbm, hush::weight_rule::centre, 31);
  pixel_inputs in = random_inputs(4);
  hush::rng r(17);
  int heavy = 0;
  for (int q = 0; q < kW * kH; ++q) {
    const int i = 1 + q % 4;
    const double len = std::exp2(r.uniform<double>(4, 10));
    const hush::dvec2 d = a.direction(i);
    const double delta = std::exp2(r.uniform<double>(-3, 2)) / (len * std::sqrt(a.kappa(1)));
    const double c = std::cos(delta), sn = std::sin(delta);
    const hush::dvec2 e{-d.y * c + d.x * sn, d.x * c + d.y * sn};
    const double thin = len * std::exp2(-20);
    const std::size_t p = std::size_t(q);
    in.uv[p] = {r.uniform(-40.0f, 40.0f), r.uniform(-40.0f, 40.0f)};
    in.dx[p] = {float(len * e.x), float(len * e.y)};
    in.dy[p] = {float(-thin * e.y), float(thin * e.x)};
    hush::sample_input<2> s;
    s.fp = hush::footprint<2>::from_derivatives(in.dx[p], in.dy[p]);
    float w[12 * 8];
    a.weights<float>(s, w);
    if (w[i + a.channels() * a.parameters().base_scale] > 0.1f) ++heavy;
  }
  CHECK(heavy > 100);
  const error_ratio e = check_inputs(a, in, 0);
  MESSAGE(headless().device.renderer() << ", grazing: max |gpu - cpu| = " << e.worst_abs
                                       << ", max error / tolerance = " << e.worst);
}

// The tolerance is not vacuous: for ordinary inputs it is a small fraction of the noise's
// range (bound()), so a wrong weight, channel, scale or octave (an O(1) error) fails.
TEST_CASE("anisotropic shader: the tolerance is far below the noise's range") {
  const hush::anisotropic a = make(4, hush::fractal_kind::fbm, hush::weight_rule::centre);
  const pixel_inputs in = random_inputs(6);
  std::vector<double> ratio;
  for (std::size_t q = 0; q < in.uv.size(); ++q) {
    if (!std::isfinite(in.uv[q].x) || !std::isfinite(in.uv[q].y)) continue;
    const hush::surface_map m = in.maps[q];
    ratio.push_back(hush::glsl::anisotropic_shader_tolerance(a, in.uv[q], in.dx[q], in.dy[q], &m) /
                    a.bound_with_maps());
  }
  std::sort(ratio.begin(), ratio.end());
  CHECK(ratio[ratio.size() / 2] < 1e-4);
  CHECK(ratio[ratio.size() * 99 / 100] < 1e-2);
}

TEST_CASE("anisotropic shader: the kit's tiles are the runner's texels, its source one per type") {
  const hush::anisotropic a4 = make(4, hush::fractal_kind::fbm, hush::weight_rule::centre, 2);
  const hush::anisotropic a7 =
      make(7, hush::fractal_kind::turbulence, hush::weight_rule::three_point, 3);
  const hush::glsl::shader_kit k4 = hush::glsl::shader_for(a4), k7 = hush::glsl::shader_for(a7);
  CHECK(k4.source == k7.source);  // parameters live in the block and the textures
  for (const auto* pair : {&k4, &k7}) {
    const auto& kit = *pair;
    REQUIRE(kit.find("hush_anisotropic_params") != nullptr);
    REQUIRE(kit.find("hush_anisotropic_tile0") != nullptr);
    REQUIRE(kit.find("hush_anisotropic_tile1") != nullptr);
  }
  // Tile 0 (and tile 1 for K > 4) are anisotropic_tile::rgba, what the batch runner uploads
  // (program.hpp textures()).
  const std::vector<float> t0 = a7.tile().rgba(0), t1 = a7.tile().rgba(1);
  const auto& r0 = *k7.find("hush_anisotropic_tile0");
  const auto& r1 = *k7.find("hush_anisotropic_tile1");
  REQUIRE(r0.words.size() == t0.size());
  REQUIRE(r1.words.size() == t1.size());
  CHECK(r0.width == 64u);
  bool same = true;
  for (std::size_t i = 0; i < t0.size(); ++i)
    same = same && r0.words[i] == hush::glsl::float_word(t0[i]) &&
           r1.words[i] == hush::glsl::float_word(t1[i]);
  CHECK(same);
  CHECK(k4.find("hush_anisotropic_tile1")->width == 1u);
  // The block: 3 vec4 headers, 8 directions, 12 scales, 12 octaves.
  CHECK(k7.find("hush_anisotropic_params")->words.size() == 4u * (3 + 8 + 12 + 12));
  CHECK(k7.find("hush_anisotropic_params")->words[0] == 7u);
  hush::anisotropic::params p = a4.parameters();
  p.compensation = hush::weight_rule::least_squares;
  CHECK_THROWS_AS(hush::glsl::shader_for(hush::anisotropic(p)), hush::invalid_argument);
}

// Every number of the kit's functions comes from the generated constants or the block: the
// hand-written GLSL holds only structural literals (0, 1, 2 for halving and doubling, the
// channel indices 0 ... 7 of two RGBA texels, 4 channels per texel), outside comments.
TEST_CASE("anisotropic shader: the kit's functions hold no number of their own") {
  std::string body = hush::glsl::detail::kAnisotropicShaderBody;
  body = std::regex_replace(body, std::regex("//[^\n]*"), "");
  const std::regex literal("(^|[^A-Za-z0-9_.])([0-9]+[.]?[0-9]*(e[-+]?[0-9]+)?u?)");
  const std::vector<std::string> allowed = {"0", "1",  "2",  "3",  "4",   "5",   "6",
                                            "7", "0u", "1u", "4u", "0.0", "1.0", "2.0"};
  int found = 0;
  for (auto it = std::sregex_iterator(body.begin(), body.end(), literal);
       it != std::sregex_iterator(); ++it) {
    const std::string lit = (*it)[2];
    INFO("literal " << lit);
    CHECK(std::find(allowed.begin(), allowed.end(), lit) != allowed.end());
    ++found;
  }
  CHECK(found > 10);  // the scan sees the body's literals
  const std::string planted = "x = 0.5 * y + 17u;";
  int stray = 0;
  for (auto it = std::sregex_iterator(planted.begin(), planted.end(), literal);
       it != std::sregex_iterator(); ++it)
    stray += std::find(allowed.begin(), allowed.end(), std::string((*it)[2])) == allowed.end();
  CHECK(stray == 2);
}

#ifdef HUSH_GLSLANG_VALIDATOR
TEST_CASE("anisotropic shader: the kit compiles for GL 4.30 core, Vulkan 450 and GLSL ES 3.00") {
  const hush::glsl::shader_kit kit = hush::glsl::shader_for(hush::anisotropic{});
  CHECK(kit.versions == "430 core, Vulkan 450, 300 es");
  const std::string main_fn =
      "layout(location = 0) out highp vec4 colour;\n"
      "#ifdef VULKAN\n"
      "layout(location = 0) in highp vec2 uv_in;\n"
      "layout(location = 1) in highp vec3 p_in;\n"
      "#else\n"
      "in highp vec2 uv_in;\n"
      "in highp vec3 p_in;\n"
      "#endif\n"
      "void main() {\n"
      "  vec2 uv = uv_in;\n"
      "  float a = hush_anisotropic(uv, dFdx(uv), dFdy(uv));\n"
      "  float b = hush_anisotropic(uv, mat2(dFdx(uv), dFdy(uv)));\n"
      "  float c = hush_anisotropic_mapped(uv, dFdx(uv), dFdy(uv), mat2(1.0));\n"
      "  float d = hush_anisotropic_surface(uv, dFdx(uv), dFdy(uv), dFdx(p_in), dFdy(p_in));\n"
      "  colour = vec4(a, b, c, d);\n"
      "}\n";
  using hush_glsl_test::dialect;
  for (dialect d : {dialect::gl430, dialect::vulkan450, dialect::es300}) {
    const auto r = hush_glsl_test::glslang_compile(kit.source + main_fn, d, "aniso_shader_kit");
    INFO(hush_glsl_test::dialect_name(d) << ": " << r.log);
    CHECK(r.ok);
  }
}
#endif
