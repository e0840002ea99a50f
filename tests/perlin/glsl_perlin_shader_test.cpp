// Perlin noise in a user-written fragment shader (hush/glsl/perlin/shader.hpp) on llvmpipe:
// hush_perlinD(p) and hush_perlinD_gradient(p) over a grid of exact float positions, near
// the origin and far out, periodic and not, within the stated bounds of the double reference
// and the CPU float path; the kit compiles for GL 4.30, Vulkan 450 and GLSL ES 3.00.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "glsl/glsl_test_util.hpp"
#include "glsl/shader_harness.hpp"
#include "hush/glsl/perlin/shader.hpp"
#include "test_util.hpp"

namespace {

constexpr int kSide = 48;
constexpr double kBudget = 0x1p-16;  // the library's bound against the double reference

// The shader's positions: p = origin + (gl_FragCoord.xy - 0.5) * step, exact in float for
// a power-of-two step and an origin on its grid; 3D: z = origin.z + x / 2 (exact too).
template <int D>
std::string fragment(const hush::glsl::shader_kit& kit, double ox, double oy, double oz,
                     double step, bool gradient) {
  const std::string pos = D == 2 ? "vec2 p = o.xy + q;\n"
                                 : "vec3 p = vec3(o.xy + q, o.z + q.x * 0.5);\n";
  const std::string call = gradient ? "vec4(hush_perlin" + std::to_string(D) + "_gradient(p)" +
                                          (D == 2 ? ", 0.0)" : ")")
                                    : "vec4(hush_perlin" + std::to_string(D) + "(p))";
  return "#version 430 core\n" + kit.source + "out vec4 colour;\nvoid main() {\n" +
         "  vec3 o = vec3(" + std::to_string(ox) + ", " + std::to_string(oy) + ", " +
         std::to_string(oz) + ");\n  vec2 q = (gl_FragCoord.xy - 0.5) * " +
         std::to_string(step) + ";\n  " + pos + "  colour = " + call + ";\n}\n";
}

template <int D>
void check_grid(const hush::perlin<D>& noise, double ox, double oy, double oz, double step) {
  auto& h = hush_glsl_test::headless();
  hush_glsl_test::fragment_harness fh(h.context.loader());
  const hush::glsl::shader_kit kit = hush::glsl::shader_for(noise);
  const auto vals = fh.draw(fragment<D>(kit, ox, oy, oz, step, false), kit, kSide, kSide);
  const auto grads = fh.draw(fragment<D>(kit, ox, oy, oz, step, true), kit, kSide, kSide);
  const double gbudget = kBudget * (1 + hush_test::lipschitz_bound<D>());
  hush_glsl_test::error_stats ref, cpu, grad;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) {
      hush::vec<double, D> p;
      p[0] = ox + i * step;
      p[1] = oy + j * step;
      if constexpr (D == 3) p[2] = oz + i * step * 0.5;
      const std::size_t px = std::size_t(4 * (j * kSide + i));
      const double v = vals[px];
      ref.add(std::fabs(v - noise.template value<double>(p)));
      cpu.add(std::fabs(v - noise.template value<float>(p)));
      const auto g = noise.template value_and_gradient<double>(p);
      grad.add(std::fabs(double(grads[px]) - g.value));
      for (int a = 0; a < D; ++a) grad.add(std::fabs(double(grads[px + 1 + a]) - g.gradient[a]));
    }
  MESSAGE("perlin" << D << " at (" << ox << ", " << oy << "): max |gpu - double| " << ref.max
                   << ", |gpu - cpu float| " << cpu.max << ", gradients " << grad.max);
  CHECK(ref.max <= kBudget);
  CHECK(cpu.max <= 2 * kBudget);
  CHECK(grad.max <= gbudget);
  CHECK(ref.max > 0.0);  // the grid is not all lattice points
}

template <int D>
hush::perlin<D> periodic_noise() {
  typename hush::perlin<D>::params prm;
  prm.seed = 11;
  for (int a = 0; a < D; ++a) prm.period[std::size_t(a)] = 5 + a;
  return hush::perlin<D>(prm);
}

}  // namespace

TEST_CASE("perlin shader: hush_perlin2(p) and its gradient match the CPU near and far") {
  check_grid<2>(hush::perlin<2>(3), -3.0, -2.0, 0.0, 0x1p-3);
  check_grid<2>(hush::perlin<2>(3), 1048576.0, -65536.5, 0.0, 0x1p-3);
  check_grid<2>(periodic_noise<2>(), -7.25, 3.5, 0.0, 0x1p-2);
}

TEST_CASE("perlin shader: hush_perlin3(p) and its gradient match the CPU near and far") {
  check_grid<3>(hush::perlin<3>(4), -3.0, -2.0, 0.75, 0x1p-3);
  check_grid<3>(hush::perlin<3>(4), 262144.0, -65536.5, -1e5, 0x1p-3);
  check_grid<3>(periodic_noise<3>(), -7.25, 3.5, 1.0, 0x1p-2);
}

TEST_CASE("perlin shader: the kit's block holds the key and period, its source only the type") {
  const auto kit = hush::glsl::shader_for(periodic_noise<3>());
  REQUIRE(kit.resources.size() == 1u);
  const auto& b = kit.resources[0];
  CHECK(b.name == "hush_perlin3_params");
  CHECK(b.words[0] == hush::seed_key(11));
  CHECK(b.words[4] == 5u);  // uvec3 period aligned to 16 bytes
  CHECK(b.words[6] == 7u);
  CHECK(kit.source == hush::glsl::shader_for(hush::perlin<3>(9)).source);
  CHECK(kit.source != hush::glsl::shader_for(hush::perlin<2>(9)).source);
}

#ifdef HUSH_GLSLANG_VALIDATOR
TEST_CASE("perlin shader: both kits compile for GL 4.30 core, Vulkan 450 and GLSL ES 3.00") {
  using hush_glsl_test::dialect;
  for (const auto& kit :
       {hush::glsl::shader_for(hush::perlin<2>(1)), hush::glsl::shader_for(hush::perlin<3>(1))}) {
    const bool two = kit.source.find("hush_perlin2_params") != std::string::npos;
    const std::string main_fn =
        std::string("layout(location = 0) out highp vec4 colour;\nvoid main() {\n") +
        (two ? "  colour = vec4(hush_perlin2(gl_FragCoord.xy), hush_perlin2_gradient(gl_FragCoord.xy));\n"
             : "  colour = hush_perlin3_gradient(gl_FragCoord.xyx) + vec4(hush_perlin3(gl_FragCoord.xyz));\n") +
        "}\n";
    for (dialect d : {dialect::gl430, dialect::vulkan450, dialect::es300}) {
      const auto r = hush_glsl_test::glslang_compile(kit.source + main_fn, d, "perlin_shader_kit");
      INFO(hush_glsl_test::dialect_name(d) << ": " << r.log.substr(0, 2000));
      CHECK(r.ok);
    }
  }
}
#endif
