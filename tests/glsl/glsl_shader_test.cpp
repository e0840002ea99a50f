// hush/glsl/shader.hpp: a kit's resources reach a user-written fragment shader as declared
// (std140 offsets, texel order, bindings), and its declarations compile in every dialect.
#include <doctest/doctest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "glsl/glsl_test_util.hpp"
#include "glsl/shader_harness.hpp"
#include "hush/glsl/shader.hpp"

namespace {

using hush::glsl::resource_kind;
using hush::glsl::shader_kit;
using hush::glsl::shader_resource;
using hush::glsl::texel_format;

// A kit with one block (a float, a vec3 that std140 aligns to 16 bytes, a uint), one 2D
// RG32F texture of 3 x 2 texels and one 3D R32UI texture of 2 x 2 x 2, each texel a
// different value, and functions that read them.
shader_kit test_kit() {
  shader_kit kit;
  shader_resource block;
  block.name = "test_params";
  block.kind = resource_kind::uniform_block;
  block.binding = 3;
  block.binding_macro = "TEST_PARAMS_BINDING";
  block.words = hush::glsl::std140_writer().f(0.5f).vec3(1.0f, 2.0f, 3.0f).u(7u).words();
  shader_resource tex2;
  tex2.name = "test_tex2";
  tex2.kind = resource_kind::texture_2d;
  tex2.binding = 1;
  tex2.binding_macro = "TEST_TEX2_BINDING";
  tex2.format = texel_format::rg32f;
  tex2.width = 3;
  tex2.height = 2;
  for (int t = 0; t < 6; ++t) {
    tex2.words.push_back(hush::glsl::float_word(float(t)));
    tex2.words.push_back(hush::glsl::float_word(float(10 * t)));
  }
  shader_resource tex3;
  tex3.name = "test_tex3";
  tex3.kind = resource_kind::texture_3d;
  tex3.binding = 2;
  tex3.binding_macro = "TEST_TEX3_BINDING";
  tex3.format = texel_format::r32ui;
  tex3.width = tex3.height = tex3.depth = 2;
  for (std::uint32_t t = 0; t < 8; ++t) tex3.words.push_back(100u + t);
  kit.resources = {tex2, tex3, block};
  kit.source = std::string(hush::glsl::kShaderPrelude) +
               hush::glsl::resource_layout("TEST_PARAMS_BINDING", 3, "std140") +
               "uniform test_params { float a; vec3 b; uint c; } test_p;\n" +
               hush::glsl::resource_layout("TEST_TEX2_BINDING", 1, "") +
               "uniform sampler2D test_tex2;\n" +
               hush::glsl::resource_layout("TEST_TEX3_BINDING", 2, "") +
               "uniform highp usampler3D test_tex3;\n"
               "float test_value(int i) {\n"
               "  if (i == 0) return test_p.a;\n"
               "  if (i < 4) return test_p.b[i - 1];\n"
               "  if (i == 4) return float(test_p.c);\n"
               "  if (i < 11) { int t = i - 5; return texelFetch(test_tex2, ivec2(t % 3, t / 3), 0).g; }\n"
               "  int t = i - 11; return float(texelFetch(test_tex3, ivec3(t % 2, (t / 2) % 2, t / 4), 0).r);\n"
               "}\n";
  return kit;
}

}  // namespace

TEST_CASE("std140_writer: scalars pack, vec3 aligns to 16 bytes, the block pads to 16") {
  const auto w = hush::glsl::std140_writer().f(1.0f).vec3(2.0f, 3.0f, 4.0f).u(5u).words();
  REQUIRE(w.size() == 8u);
  CHECK(w[0] == hush::glsl::float_word(1.0f));
  CHECK(w[1] == 0u);
  CHECK(w[4] == hush::glsl::float_word(2.0f));
  CHECK(w[6] == hush::glsl::float_word(4.0f));
  CHECK(w[7] == 5u);
  const auto v = hush::glsl::std140_writer().f(1.0f).vec2(2.0f, 3.0f).words();
  CHECK(v[2] == hush::glsl::float_word(2.0f));  // vec2 aligns to 8 bytes
}

TEST_CASE("bound_kit: a fragment shader reads the block, the 2D and the 3D texture as declared") {
  auto& h = hush_glsl_test::headless();
  hush_glsl_test::fragment_harness fh(h.context.loader());
  const shader_kit kit = test_kit();
  const std::string fs = "#version 430 core\n" + kit.source +
                         "out vec4 colour;\n"
                         "void main() { colour = vec4(test_value(int(gl_FragCoord.x)), 0.0, 0.0, 1.0); }\n";
  const std::vector<float> px = fh.draw(fs, kit, 19, 1);
  const float want[19] = {0.5f, 1, 2, 3, 7, 0, 10, 20, 30, 40, 50, 100, 101, 102, 103, 104, 105, 106, 107};
  for (int i = 0; i < 19; ++i) CHECK(px[std::size_t(4 * i)] == want[i]);
}

#ifdef HUSH_GLSLANG_VALIDATOR
TEST_CASE("a kit's declarations compile for GL 4.30 core, Vulkan 450 and GLSL ES 3.00") {
  const shader_kit kit = test_kit();
  const std::string main_fn =
      "layout(location = 0) out highp vec4 colour;\n"
      "void main() { colour = vec4(test_value(int(gl_FragCoord.x))); }\n";
  using hush_glsl_test::dialect;
  for (dialect d : {dialect::gl430, dialect::vulkan450, dialect::es300}) {
    const auto r = hush_glsl_test::glslang_compile(kit.source + main_fn, d, "shader_test_kit");
    INFO(hush_glsl_test::dialect_name(d) << ": " << r.log);
    CHECK(r.ok);
  }
}
#endif
