// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Gabor noise inside a user-written fragment shader (hush/glsl/gabor/shader.hpp) against the
// CPU: each kit function evaluated over a grid of pixels on llvmpipe (fragment_harness), its
// value and gradient compared with hush's double reference and scalar float path.
//
// Bounds (shader.hpp's contract): the walk repeats the CPU's float operations, so GLSL lies
// within gabor.hpp's float budget, scale 2^-21 (1 + 2 pi Phi) (N' + 1), of the double
// reference, plus the split of p / r in float (hush_gabor_split): the fraction within
// 2^-24 + 2^-33 x of the exact one (x = max |p_i| / r), which moves each of ~N' + 1 kernels
// by at most its slope per cell, 2A + 2 pi Phi + 3 / (1 - s0). Against the CPU's float path, the
// budget counts twice. Filtered values: the budget times filter_factor (Q and M from Jacobi in
// float). Gradients: each bound times 1 + the slope per noise unit. A differing Poisson count or
// mark would move a value by up to a whole kernel (~scale), hundreds of times these bounds.
//
// Positions are dyadic (origin + i step, step = 53/64 or a power of two apart), so the
// shader's float p is exact and the CPU evaluates the same point.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "glsl/glsl_test_util.hpp"
#include "glsl/shader_harness.hpp"
#include "hush/gabor.hpp"
#include "hush/glsl/gabor/shader.hpp"

namespace {

constexpr double kPi = hush::detail::constants::kPi;
constexpr int kSide = 32;  // pixels per side of each grid (llvmpipe: ~1 s per draw)

template <int D>
typename hush::gabor<D>::params params_of(hush::gabor_kind kind) {
  typename hush::gabor<D>::params p;
  p.seed = 31;
  p.kind = kind;
  p.frequency = 1.3;
  p.orientation = 0.6;
  p.elevation = 0.3;
  if (kind == hush::gabor_kind::hybrid) {
    p.orientation_spread = 1.5;
    p.frequency_spread = 0.8;
  }
  return p;
}

template <int D>
double phi_max(const hush::gabor<D>& g) {
  return g.marks().phi0() + g.marks().dphi();
}
// The kernel's slope bound per cell.
template <int D>
double slope(const hush::gabor<D>& g) {
  return 2 * g.kernel().envelope_exponent() + 2 * kPi * phi_max(g) +
         3 / (1 - hush::detail::constants::kGaborTaperStart);
}
// gabor.hpp's float budget against the double reference (scale: scale() or surface_scale()).
template <int D>
double budget(const hush::gabor<D>& g, double scale) {
  return scale * std::ldexp(1.0, -21) * (1 + 2 * kPi * phi_max(g)) * (g.parameters().impulses + 1);
}
// The float split of p / r at x = max |p_i| / r.
template <int D>
double split_error(const hush::gabor<D>& g, double scale, double x) {
  return scale * (g.parameters().impulses + 1) * (std::ldexp(1.0, -24) + std::ldexp(x, -33)) *
         slope(g);
}
template <int D>
double filter_factor(const hush::gabor<D>& g) {
  const double phi = phi_max(g), a = g.kernel().envelope_exponent();
  return 1 + 2 * kPi * phi + kPi * kPi * phi * phi / a;
}
template <int D>
double gradient_factor(const hush::gabor<D>& g) {
  return 1 + slope(g) * g.inverse_cell();
}

struct errors {
  double value = 0, value_cpu = 0, grad = 0;
  int nan_mismatch = 0, compared = 0;
  void add(double got, double ref, double cpu) {
    if (std::isnan(ref) || std::isnan(got)) {
      nan_mismatch += std::isnan(ref) != std::isnan(got);
      return;
    }
    ++compared;
    value = std::max(value, std::fabs(got - ref));
    value_cpu = std::max(value_cpu, std::fabs(got - cpu));
  }
  void add_grad(double got, double ref) {
    if (!std::isnan(ref)) grad = std::max(grad, std::fabs(got - ref));
  }
};

hush_glsl_test::fragment_harness& harness() {
  static hush_glsl_test::fragment_harness h(hush_glsl_test::headless().context.loader());
  return h;
}

// Draws a fragment shader over width x height pixels: kit.source, then main() with
// `vec2 ij` (the pixel within its block, integers from 0), `int test_block` (rows
// kSide b ... kSide b + kSide - 1 are block b) and the uniforms test_ox, test_oy, test_oz,
// test_step, test_far (float), then `body`, which sets `colour`. Each draw compiles a program
// (llvmpipe: seconds for a 3D one), and GLSL compilers inline every call: so one draw per noise,
// its blocks computing different functions of the same p, and few calls in each.
struct draw_args {
  double origin[3] = {0, 0, 0};
  double step = 1, far = 0;
  int width = kSide, height = kSide;  // kSide b for b blocks
};
std::vector<float> draw(const hush::glsl::shader_kit& kit, const std::string& body,
                        const draw_args& a) {
  const std::string fs = "#version 430 core\n" + kit.source +
                         "uniform float test_ox, test_oy, test_oz, test_step, test_far;\n"
                         "out vec4 colour;\nvoid main() {\n"
                         "  vec2 ij = gl_FragCoord.xy - 0.5;\n"
                         "  int test_block = int(ij.y) / " +
                         std::to_string(kSide) +
                         ";\n"
                         "  ij.y -= float(test_block * " +
                         std::to_string(kSide) + ");\n" + body + "}\n";
  auto& h = harness();
  return h.draw(fs, kit, a.width, a.height, [&](hush::glsl::detail::gl_uint prog) {
    const auto& gl = h.gl();
    auto set = [&](const char* n, double v) {
      gl.Uniform1f(gl.GetUniformLocation(prog, n), float(v));
    };
    set("test_ox", a.origin[0]);
    set("test_oy", a.origin[1]);
    set("test_oz", a.origin[2]);
    set("test_step", a.step);
    set("test_far", a.far);
  });
}

// Channel c of pixel (i, j) of block b.
float px(const std::vector<float>& img, int i, int j, int c, int b = 0) {
  return img[std::size_t(4 * ((b * kSide + j) * kSide + i) + c)];
}

// The dyadic grid positions: origin + (i, j[, i + j]) step, exact in float.
template <int D>
hush::vec<double, D> grid_point(const draw_args& a, int i, int j) {
  hush::vec<double, D> p;
  p[0] = double(float(a.origin[0])) + i * a.step;
  p[1] = double(float(a.origin[1])) + j * a.step;
  if constexpr (D == 3) p[2] = double(float(a.origin[2])) + (i + j) * a.step;
  return p;
}
template <int D>
double extent(const hush::vec<double, D>& p) {
  double m = 0;
  for (int k = 0; k < D; ++k) m = std::max(m, std::fabs(p[k]));
  return m;
}

std::string kind_name(hush::gabor_kind k) {
  return k == hush::gabor_kind::isotropic     ? "isotropic"
         : k == hush::gabor_kind::anisotropic ? "anisotropic"
                                              : "hybrid";
}

constexpr hush::gabor_kind kKinds[] = {hush::gabor_kind::isotropic, hush::gabor_kind::anisotropic,
                                       hush::gabor_kind::hybrid};

// Surface noise's extra error from the float tangent frame (tests/gabor/glsl_gabor_test.cpp):
// normal and frame within ~2^-21 relative move each offset (< 2.5 kernel cells) by 2.5 2^-21,
// each kernel by that times its slope and the slab taper's.
double frame_error(const hush::gabor<3>& g) {
  namespace c = hush::detail::constants;
  const double taper = 3 / (1 - c::kGaborTaperStart);
  return g.surface_scale() * (g.parameters().impulses + 1) * 2.5 * std::ldexp(1.0, -21) *
         (slope(g) + taper * c::kGaborSurfaceCell / c::kGaborSurfaceSlab);
}

}  // namespace

TEST_CASE(
    "gabor shader: 2D point noise and gradient equal the double reference, every kind, "
    "near the origin and at x = 2^12 and 2^20 cells") {
  for (const auto kind : kKinds) {
    const hush::gabor<2> noise(params_of<2>(kind));
    const hush::glsl::shader_kit kit = hush::glsl::shader_for(noise);
    const double r = 1 / noise.inverse_cell();
    // Block 0 near the origin, block 1 at x ~ 2^12 cells (test_oz: its offset), block 2 at
    // x ~ 2^20 cells (test_far; steps of 3/4 there, where float p is exact to 1/4).
    draw_args a;
    a.origin[0] = -13.25;
    a.origin[1] = -11.5;
    a.origin[2] = std::floor(4096 * r) - 26.0;
    a.far = std::floor(1048576 * r) - 26.0;
    a.step = 53.0 / 64.0;
    a.height = 3 * kSide;
    REQUIRE(a.far + 32 < 4194304.0);  // |p| < 2^22: multiples of 1/4 are floats
    const auto img =
        draw(kit,
             "  vec2 p = vec2(test_ox, test_oy) + ij * test_step;\n"
             "  if (test_block == 1) p += vec2(test_oz, -0.5 * test_oz);\n"
             "  if (test_block == 2) p = vec2(test_far, -0.5 * test_far) + ij * 0.75;\n"
             "  colour = vec4(hush_gabor2(p), hush_gabor2_gradient(p));\n",
             a);
    for (int b = 0; b < 3; ++b) {
      errors e;
      double x = 0, same = 0;
      for (int j = 0; j < kSide; ++j)
        for (int i = 0; i < kSide; ++i) {
          auto p = grid_point<2>(a, i, j);
          if (b == 1) p = {p[0] + a.origin[2], p[1] - 0.5 * a.origin[2]};
          if (b == 2) p = {a.far + 0.75 * i, -0.5 * a.far + 0.75 * j};
          x = std::max(x, extent(p) * noise.inverse_cell());
          const auto ref = noise.value_and_gradient<double>(p);
          const auto cpu = noise.value_and_gradient<float>(p);
          e.add(px(img, i, j, 0, b), ref.value, cpu.value);
          same = std::max(same, std::fabs(double(px(img, i, j, 0, b)) - px(img, i, j, 1, b)));
          for (int k = 0; k < 2; ++k) e.add_grad(px(img, i, j, 2 + k, b), ref.gradient[k]);
        }
      const double s = noise.scale();
      const double vt = budget(noise, s) + split_error(noise, s, x);
      MESSAGE("2D " << kind_name(kind) << " x <= " << x << ": |GLSL - double| " << e.value
                    << " (bound " << vt << "), |GLSL - CPU float| " << e.value_cpu << ", gradient "
                    << e.grad << " (" << vt * gradient_factor(noise) << ")");
      CHECK(e.compared == kSide * kSide);
      CHECK(e.value <= vt);
      CHECK(e.value_cpu <= vt + budget(noise, s));
      CHECK(e.grad <= vt * gradient_factor(noise));
      CHECK(same <= 2 * budget(noise, s));  // hush_gabor2 and _gradient's value: one walk
    }
  }
}

TEST_CASE("gabor shader: hush_gabor2_cell takes the engine's split: the CPU's field at 4e6 cells") {
  const hush::gabor<2> noise(params_of<2>(hush::gabor_kind::hybrid));
  const hush::glsl::shader_kit kit = hush::glsl::shader_for(noise);
  const auto img =
      draw(kit,
           "  uvec2 cell = uvec2(ij) + uvec2(3000000u, 4000000u);\n"
           "  vec2 f = fract(ij * 0.203125 + vec2(0.1328125, 0.5078125));  // never an integer\n"
           "  colour = vec4(hush_gabor2_cell(cell, f), f, 0.0);\n",
           draw_args{});
  errors e;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) {
      const hush::vec<double, 2> p{(3000000.0 + i + px(img, i, j, 1)) / noise.inverse_cell(),
                                   (4000000.0 + j + px(img, i, j, 2)) / noise.inverse_cell()};
      e.add(px(img, i, j, 0), noise.value<double>(p), noise.value<float>(p));
    }
  MESSAGE("hush_gabor2_cell at 4e6 cells: |GLSL - double| " << e.value << ", |GLSL - CPU float| "
                                                            << e.value_cpu << " (budget "
                                                            << budget(noise, noise.scale()) << ")");
  CHECK(e.compared == kSide * kSide);
  CHECK(e.value <= budget(noise, noise.scale()));
  CHECK(e.value_cpu <= 2 * budget(noise, noise.scale()));
}

namespace {

// A receding ground plane: the ray through pixel (i, j) of a camera at height 1 looking at
// the horizon meets the plane at p (noise units, scaled by 4); its footprints grow from
// ~0.25 to ~75 noise units per pixel towards the horizon. Block 0: the filtered value
// and gradient; 1: p and dFdx(p); 2: dFdy(p).
constexpr const char* kGroundPlane =
    "  vec2 uv = (ij + 0.5) * (1.0 / 32.0);\n"
    "  float t = 1.0 / (0.02 + 0.98 * uv.y);\n"
    "  vec2 p = vec2(test_ox, test_oy) + 4.0 * t * vec2(2.0 * uv.x - 1.0, 1.0);\n"
    "  vec2 dx = dFdx(p), dy = dFdy(p);\n"
    "  if (test_block == 0)\n"
    "    colour = vec4(hush_gabor2_filtered(p, dx, dy), hush_gabor2_filtered_gradient(p, dx, "
    "dy));\n"
    "  else if (test_block == 1)\n"
    "    colour = vec4(p, dx);\n"
    "  else\n"
    "    colour = vec4(dy, 0.0, 0.0);\n";

}  // namespace

TEST_CASE(
    "gabor shader: 2D filtered noise with the shader's dFdx / dFdy on a receding plane "
    "equals sample(p, footprint) of the same Jacobian") {
  for (const auto kind : {hush::gabor_kind::anisotropic, hush::gabor_kind::isotropic}) {
    const hush::gabor<2> noise(params_of<2>(kind));
    const hush::glsl::shader_kit kit = hush::glsl::shader_for(noise);
    draw_args a;
    a.origin[0] = 5.5;
    a.origin[1] = -3.25;
    a.height = 3 * kSide;
    const auto img = draw(kit, kGroundPlane, a);
    errors e;
    double x = 0, same = 0, widest = 0, narrowest = 1e30;
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i) {
        const hush::vec<double, 2> p{px(img, i, j, 0, 1), px(img, i, j, 1, 1)};
        const hush::vec2 dx{px(img, i, j, 2, 1), px(img, i, j, 3, 1)};
        const hush::vec2 dy{px(img, i, j, 0, 2), px(img, i, j, 1, 2)};
        const auto fp = hush::footprint<2>::from_derivatives(dx, dy);
        widest = std::max(widest, fp.max_width());
        narrowest = std::min(narrowest, fp.max_width());
        x = std::max(x, extent(p) * noise.inverse_cell());
        const hush::sample_input<2> in{p, fp};
        const auto ref = noise.sample_value_and_gradient<double>(in);
        const auto cpu = noise.sample_value_and_gradient<float>(in);
        e.add(px(img, i, j, 0), ref.value, cpu.value);
        same = std::max(same, std::fabs(double(px(img, i, j, 0)) - px(img, i, j, 1)));
        for (int k = 0; k < 2; ++k) e.add_grad(px(img, i, j, 2 + k), ref.gradient[k]);
      }
    const double s = noise.scale();
    const double vt = budget(noise, s) * filter_factor(noise) + split_error(noise, s, x);
    MESSAGE("2D filtered " << kind_name(kind) << ", footprints " << narrowest << " ... " << widest
                           << " units, x <= " << x << ": |GLSL - double| " << e.value << " (bound "
                           << vt << "), |GLSL - CPU float| " << e.value_cpu << ", gradient "
                           << e.grad << " (" << vt * gradient_factor(noise) << ")");
    CHECK(narrowest < 0.5);  // the plane spans point-like and wide footprints
    CHECK(widest > 20.0);
    CHECK(e.compared == kSide * kSide);
    CHECK(e.value <= vt);
    CHECK(e.value_cpu <= vt + budget(noise, s) * filter_factor(noise));
    CHECK(e.grad <= vt * gradient_factor(noise));
    CHECK(same <= 2 * budget(noise, s) * filter_factor(noise));
  }
}

TEST_CASE("gabor shader: degenerate footprints and NaN positions give the CPU's answers") {
  const hush::gabor<2> noise(params_of<2>(hush::gabor_kind::hybrid));
  const hush::glsl::shader_kit kit = hush::glsl::shader_for(noise);
  // Pixel i: zero, rank 1, 1e-15 and 1e15 (scaled to the cap) per pixel, NaN, Inf, 1e6 in
  // every entry; pixel 7 a NaN position, 8 an infinite one.
  const std::string body =
      "  int i = int(ij.x);\n"
      "  float nan = uintBitsToFloat(0x7fc00000u), inf = uintBitsToFloat(0x7f800000u);\n"
      "  vec2 dxs[7] = vec2[7](vec2(0.0), vec2(0.3, 0.2), vec2(1e-15, 0.0), vec2(1e15, 0.0),\n"
      "                        vec2(nan, 0.0), vec2(inf, 0.0), vec2(1e6));\n"
      "  vec2 dys[7] = vec2[7](vec2(0.0), vec2(0.6, 0.4), vec2(0.0, 1e-15), vec2(0.0, 1e15),\n"
      "                        vec2(0.0, 1.0), vec2(0.0, 1.0), vec2(1e6));\n"
      "  vec2 p = vec2(2.375, -1.625);\n"
      "  if (i == 7) p.x = nan;\n"
      "  if (i == 8) p.y = inf;\n"
      "  int k = min(i, 6);\n"
      "  colour = vec4(hush_gabor2_filtered(p, dxs[k], dys[k]),\n"
      "                hush_gabor2_filtered_gradient(p, dxs[k], dys[k]).yz, hush_gabor2(p));\n";
  draw_args a;
  a.width = 9;
  a.height = 1;
  const auto img = draw(kit, body, a);
  const double nan = std::numeric_limits<double>::quiet_NaN(),
               inf = std::numeric_limits<double>::infinity();
  const hush::vec<double, 2> dxs[7] = {{0, 0},   {0.3, 0.2}, {1e-15, 0}, {1e15, 0},
                                       {nan, 0}, {inf, 0},   {1e6, 1e6}};
  const hush::vec<double, 2> dys[7] = {{0, 0}, {0.6, 0.4}, {0, 1e-15}, {0, 1e15},
                                       {0, 1}, {0, 1},     {1e6, 1e6}};
  const double vt = budget(noise, noise.scale()) * filter_factor(noise) +
                    split_error(noise, noise.scale(), 2.375 * noise.inverse_cell());
  for (int i = 0; i < 7; ++i) {
    INFO("footprint " << i);
    const hush::vec<float, 2> dx{float(dxs[i][0]), float(dxs[i][1])};
    const hush::vec<float, 2> dy{float(dys[i][0]), float(dys[i][1])};
    const hush::sample_input<2> in{{2.375, -1.625}, hush::footprint<2>::from_derivatives(dx, dy)};
    const auto ref = noise.sample_value_and_gradient<double>(in);
    const float v = img[std::size_t(4 * i)];
    CHECK(std::isfinite(v));
    CHECK(std::isfinite(img[std::size_t(4 * i + 1)]));
    CHECK(std::isfinite(img[std::size_t(4 * i + 2)]));
    CHECK(std::fabs(v - ref.value) <= vt);
  }
  for (int i = 7; i < 9; ++i)
    for (int c = 0; c < 4; ++c) CHECK(std::isnan(img[std::size_t(4 * i + c)]));
}

namespace {

// 3D: the slanted plane p = o + (i, j, i + j) step plus a quadratic bend (dyadic, exact), so
// footprints vary per pixel; n a normal varying over the image (not unit length); footprints
// the shader's derivatives times 8. FUNCTIONS computes blocks 0 (two values), 1 and 2 (two
// gradients) from p, n, dx, dy; block 3 holds dx, block 4 dy.
std::string bent_plane(const std::string& functions) {
  return "  vec3 p = vec3(test_ox, test_oy, test_oz) + vec3(ij, ij.x + ij.y) * test_step +\n"
         "           vec3(ij.x * ij.x, ij.y * ij.y, ij.x * ij.y) * (1.0 / 256.0);\n"
         "  vec3 n = vec3(ij.x - 15.5, ij.y - 15.5, 7.0);\n"
         "  vec3 dx = 8.0 * dFdx(p), dy = 8.0 * dFdy(p);\n" +
         functions +
         "  else if (test_block == 3) colour = vec4(dx, 0.0);\n"
         "  else colour = vec4(dy, 0.0);\n";
}

}  // namespace

TEST_CASE("gabor shader: 3D point, filtered and surface noise equal the double reference") {
  // Hybrid noise: every mark drawn (direction in the cap, frequency in its range); the other
  // kinds share the walk with the runner, tested for each kind in glsl_gabor_test.cpp.
  const hush::gabor<3> noise(params_of<3>(hush::gabor_kind::hybrid));
  const hush::glsl::shader_kit kit = hush::glsl::shader_for(noise);
  draw_args a;
  a.origin[0] = -7.75;
  a.origin[1] = 3.5;
  a.origin[2] = -20.125;
  a.step = 0.4375;
  a.height = 5 * kSide;
  // img[0]: the solid functions; img[1]: surface noise.
  const std::vector<float> img[2] = {
      draw(kit,
           bent_plane(
               "  if (test_block == 0)\n"
               "    colour = vec4(hush_gabor3(p), hush_gabor3_filtered(p, dx, dy), 0.0, 0.0);\n"
               "  else if (test_block == 1) colour = hush_gabor3_gradient(p);\n"
               "  else if (test_block == 2) colour = hush_gabor3_filtered_gradient(p, dx, dy);\n"),
           a),
      draw(kit,
           bent_plane("  if (test_block == 0)\n"
                      "    colour = vec4(hush_gabor3_surface(p, n),\n"
                      "                  hush_gabor3_surface_filtered(p, n, dx, dy), 0.0, 0.0);\n"
                      "  else if (test_block == 1) colour = hush_gabor3_surface_gradient(p, n);\n"
                      "  else if (test_block == 2)\n"
                      "    colour = hush_gabor3_surface_filtered_gradient(p, n, dx, dy);\n"),
           a)};
  // e[2 s + f]: s solid / surface, f point / filtered.
  errors e[4];
  double x = 0;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) {
      hush::vec<double, 3> p = grid_point<3>(a, i, j);
      p[0] += i * i / 256.0;
      p[1] += j * j / 256.0;
      p[2] += i * j / 256.0;
      x = std::max(x, extent(p) * std::max(noise.inverse_cell(), noise.inverse_surface_cell()));
      const hush::vec<double, 3> n{i - 15.5, j - 15.5, 7.0};
      hush::vec3 dx, dy;
      for (int k = 0; k < 3; ++k) {
        dx[k] = px(img[0], i, j, k, 3);
        dy[k] = px(img[0], i, j, k, 4);
        CHECK(dx[k] == px(img[1], i, j, k, 3));
      }
      const auto fp = hush::footprint<3>::from_derivatives(dx, dy);
      for (int sf = 0; sf < 2; ++sf)
        for (int f = 0; f < 2; ++f) {
          hush::sample_input<3> in{p, f ? fp : hush::footprint<3>{}, n, sf == 1};
          const bool point = sf == 0 && f == 0;
          const auto ref = point ? noise.value_and_gradient<double>(p)
                                 : noise.sample_value_and_gradient<double>(in);
          const float cpu = point ? noise.value<float>(p) : noise.sample_value<float>(in);
          errors& ef = e[2 * sf + f];
          ef.add(px(img[sf], i, j, f, 0), ref.value, cpu);
          // The gradient functions' values: the same walk.
          ef.add(px(img[sf], i, j, 0, 1 + f), ref.value, cpu);
          for (int k = 0; k < 3; ++k) ef.add_grad(px(img[sf], i, j, 1 + k, 1 + f), ref.gradient[k]);
        }
    }
  const double s = noise.scale(), ss = std::max(noise.scale(), noise.surface_scale());
  const double ff = filter_factor(noise);
  const double bound[4] = {budget(noise, s) + split_error(noise, s, x),
                           budget(noise, s) * ff + split_error(noise, s, x),
                           budget(noise, ss) + split_error(noise, ss, x) + frame_error(noise),
                           budget(noise, ss) * ff + split_error(noise, ss, x) + frame_error(noise)};
  const std::string what[4] = {"point", "filtered", "surface", "filtered surface"};
  const double gf = 1 + slope(noise) * std::max(noise.inverse_cell(), noise.inverse_surface_cell());
  for (int f = 0; f < 4; ++f) {
    MESSAGE("3D hybrid " << what[f] << ", x <= " << x << ": |GLSL - double| " << e[f].value
                         << " (bound " << bound[f] << "), |GLSL - CPU float| " << e[f].value_cpu
                         << ", gradient " << e[f].grad << " (" << bound[f] * gf << ")");
    CHECK(e[f].compared == 2 * kSide * kSide);
    CHECK(e[f].nan_mismatch == 0);
    CHECK(e[f].value <= bound[f]);
    CHECK(e[f].grad <= bound[f] * gf);
  }
}

TEST_CASE("gabor shader: 3D surface normals: zero gives the solid noise, NaN and Inf give NaN") {
  const hush::gabor<3> noise(params_of<3>(hush::gabor_kind::isotropic));
  const hush::glsl::shader_kit kit = hush::glsl::shader_for(noise);
  const std::string body =
      "  int i = int(ij.x);\n"
      "  float nan = uintBitsToFloat(0x7fc00000u), inf = uintBitsToFloat(0x7f800000u);\n"
      "  vec3 ns[4] = vec3[4](vec3(0.0), vec3(nan, 0.0, 1.0), vec3(0.0, inf, 0.0), vec3(0.0, 0.0, "
      "-1.0));\n"
      "  vec3 p = vec3(1.25, -2.5, 0.625);\n"
      "  colour = vec4(hush_gabor3_surface(p, ns[i]),\n"
      "                hush_gabor3_surface_filtered(p, ns[i], vec3(0.5, 0.0, 0.0), vec3(0.0, 0.5, "
      "0.0)),\n"
      "                0.0, 0.0);\n";
  draw_args a;
  a.width = 4;
  a.height = 1;
  const auto img = draw(kit, body, a);
  const hush::vec<double, 3> p{1.25, -2.5, 0.625};
  const auto fp =
      hush::footprint<3>::from_derivatives(hush::vec<double, 3>{0.5, 0, 0}, {0, 0.5, 0});
  // Zero normal: the solid noise, sample(p, footprint), unfiltered and filtered.
  const double solid = budget(noise, noise.scale()) * filter_factor(noise);
  CHECK(std::fabs(img[0] - noise.sample(p, hush::footprint<3>{})) <= solid);
  CHECK(std::fabs(img[1] - noise.sample(p, fp)) <= solid);
  for (int i = 1; i < 3; ++i) {
    CHECK(std::isnan(img[std::size_t(4 * i)]));
    CHECK(std::isnan(img[std::size_t(4 * i + 1)]));
  }
  const hush::vec<double, 3> down{0, 0, -1};
  const double surface =
      budget(noise, noise.surface_scale()) * filter_factor(noise) + frame_error(noise);
  CHECK(std::fabs(img[12] - noise.sample(p, down)) <= surface);
  CHECK(std::fabs(img[13] - noise.sample(p, down, fp)) <= surface);
}

TEST_CASE("gabor shader: the kit's source depends on D only and is what glsl-export writes") {
  auto p = params_of<2>(hush::gabor_kind::isotropic);
  const auto k1 = hush::glsl::shader_for(hush::gabor<2>(p));
  p.seed = 99;
  p.kind = hush::gabor_kind::hybrid;
  p.orientation_spread = 1.0;
  p.impulses = 40;
  const auto k2 = hush::glsl::shader_for(hush::gabor<2>(p));
  CHECK(k1.source == k2.source);
  CHECK(k1.resources.size() == 1u);
  CHECK(k1.resources[0].words != k2.resources[0].words);
  const auto k3 = hush::glsl::shader_for(hush::gabor<3>(params_of<3>(hush::gabor_kind::hybrid)));
  CHECK(k3.source != k1.source);
  // The block's std140 size (docs/gpu.md): 32 bytes of scalars, vec4 1 / r, 7 uvec4 of
  // constants, the thresholds (192 per table) 4 to a uvec4.
  CHECK(k1.resources[0].words.size() * 4 == 928u);
  CHECK(k3.resources[0].words.size() * 4 == 1696u);
  const auto files = hush::glsl::gabor_shader_exports();
  REQUIRE(files.size() == 2u);
  CHECK(files[0].first == "hush_gabor2_shader.glsl");
  CHECK(files[0].second == k1.usage + k1.source);
  CHECK(files[1].second == k3.usage + k3.source);
}

#ifdef HUSH_GLSLANG_VALIDATOR
TEST_CASE(
    "gabor shader: the 2D and 3D kits compile for GL 4.30 core, Vulkan 450 and GLSL ES 3.00") {
  using hush_glsl_test::dialect;
  const std::string main2 =
      "layout(location = 0) out highp vec4 colour;\n"
      "void main() {\n"
      "  vec2 q = gl_FragCoord.xy * 0.37;\n"
      "  colour = vec4(hush_gabor2(q), hush_gabor2_filtered(q, dFdx(q), dFdy(q)),\n"
      "                hush_gabor2_gradient(q).y + hush_gabor2_filtered_gradient(q, dFdx(q), "
      "dFdy(q)).z,\n"
      "                hush_gabor2_cell(uvec2(q), fract(q)));\n"
      "}\n";
  const std::string main3 =
      "layout(location = 0) out highp vec4 colour;\n"
      "void main() {\n"
      "  vec3 q = gl_FragCoord.xyz * 0.37;\n"
      "  vec3 n = vec3(0.0, 0.0, 1.0);\n"
      "  colour = vec4(hush_gabor3(q) + hush_gabor3_filtered(q, dFdx(q), dFdy(q)),\n"
      "                hush_gabor3_surface(q, n) + hush_gabor3_surface_filtered(q, n, dFdx(q), "
      "dFdy(q)),\n"
      "                hush_gabor3_gradient(q).y + hush_gabor3_filtered_gradient(q, dFdx(q), "
      "dFdy(q)).z,\n"
      "                hush_gabor3_surface_gradient(q, n).w + hush_gabor3_cell(uvec3(q), fract(q)) "
      "+\n"
      "                hush_gabor3_surface_filtered_gradient(q, n, dFdx(q), dFdy(q)).x);\n"
      "}\n";
  const auto k2 = hush::glsl::shader_for(hush::gabor<2>(params_of<2>(hush::gabor_kind::isotropic)));
  const auto k3 = hush::glsl::shader_for(hush::gabor<3>(params_of<3>(hush::gabor_kind::isotropic)));
  for (dialect d : {dialect::gl430, dialect::vulkan450, dialect::es300}) {
    for (int dim : {2, 3}) {
      const std::string src = (dim == 2 ? k2.source + main2 : k3.source + main3);
      const auto r = hush_glsl_test::glslang_compile(src, d, "gabor_shader_" + std::to_string(dim));
      INFO(dim << "D, " << std::string(hush_glsl_test::dialect_name(d)) << ": " << r.log);
      CHECK(r.ok);
    }
  }
}
#endif
