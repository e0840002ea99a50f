// hush/glsl/vulkan_params.hpp: the std140 layout of a shader's Vulkan params block (offsets
// glslang reports for the same declarations) and the writer that fills it by name. Every
// exported shader's layout is compared with glslang's reflection by glslang_matrix.py.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "hush/glsl/dialect.hpp"
#include "hush/glsl/export.hpp"
#include "hush/glsl/vulkan_params.hpp"

namespace {

using hush::glsl::vulkan_param;
using hush::glsl::vulkan_params;
using hush::glsl::vulkan_params_layout;
using hush::glsl::vulkan_params_layout_of;

// A compute shader for OpenGL with a loose uniform of every kind std140 lays out differently,
// arrays sized by a literal, a const and a #define, and two declarators on one line.
constexpr const char* kSource =
    "#version 430 core\n"
    "// test shader\n"
    "layout(local_size_x = 1) in;\n"
    "const uint N_CONST = 3u;\n"
    "#define N_DEFINE 2  // elements\n"
    "layout(std430, binding = 0) buffer O { float o[]; };\n"
    "uniform float a;      // 0\n"
    "uniform vec2 v2;      // 8: vec2 aligns to 8\n"
    "uniform vec3 b;       // 16: vec3 aligns to 16\n"
    "uniform float c;      // 28: packs after the vec3's 12 bytes\n"
    "uniform mat3 m;       // 32: three 16-byte columns\n"
    "uniform mat2x3 m23;   // 80: two columns of vec3\n"
    "uniform mat3x2 m32;   // 112: three columns of vec2, each a 16-byte slot\n"
    "uniform bool flag;    // 160\n"
    "uniform ivec2 iv[N_DEFINE];  // 176, stride 16\n"
    "uniform bvec3 bv;     // 208\n"
    "uniform mat2 ma[2];   // 224, stride 32\n"
    "layout(binding = 1) uniform sampler2D tex;\n"
    "uniform uint u, last[N_CONST];  // 288; 304, stride 16\n"
    "uniform uvec2 uv;     // 352: uvec2 aligns to 8\n"
    "uniform int i;        // 360\n"
    "void main() { o[0] = a + texture(tex, vec2(0.0)).x; }\n";

// The offsets glslangValidator -V -q reports for these members in a std140 block (glslang 12).
struct expected_member {
  const char* name;
  const char* type;
  std::size_t count, offset, stride;
};
const expected_member kExpected[] = {
    {"a", "float", 0, 0, 0},      {"v2", "vec2", 0, 8, 0},     {"b", "vec3", 0, 16, 0},
    {"c", "float", 0, 28, 0},     {"m", "mat3", 0, 32, 0},     {"m23", "mat2x3", 0, 80, 0},
    {"m32", "mat3x2", 0, 112, 0}, {"flag", "bool", 0, 160, 0}, {"iv", "ivec2", 2, 176, 16},
    {"bv", "bvec3", 0, 208, 0},   {"ma", "mat2", 2, 224, 32},  {"u", "uint", 0, 288, 0},
    {"last", "uint", 3, 304, 16}, {"uv", "uvec2", 0, 352, 0},  {"i", "int", 0, 360, 0},
};

std::uint32_t word_at(const std::vector<std::byte>& bytes, std::size_t offset) {
  std::uint32_t w = 0;
  REQUIRE(offset + 4 <= bytes.size());
  std::memcpy(&w, bytes.data() + offset, sizeof w);
  return w;
}
float float_at(const std::vector<std::byte>& bytes, std::size_t offset) {
  const std::uint32_t w = word_at(bytes, offset);
  float f;
  std::memcpy(&f, &w, sizeof f);
  return f;
}

}  // namespace

TEST_CASE("vulkan_params_layout_of: std140 offsets of every member kind equal glslang's") {
  const std::string shader = hush::glsl::dual_dialect(kSource, "test_params");
  const vulkan_params_layout layout = vulkan_params_layout_of(shader);
  CHECK(layout.block == "test_params");
  CHECK(layout.binding == hush::glsl::kVulkanParamsBinding);
  REQUIRE(layout.members.size() == sizeof kExpected / sizeof kExpected[0]);
  for (std::size_t k = 0; k < layout.members.size(); ++k) {
    const vulkan_param& m = layout.members[k];
    INFO(m.name);
    CHECK(m.name == kExpected[k].name);
    CHECK(m.type == kExpected[k].type);
    CHECK(m.count == kExpected[k].count);
    CHECK(m.offset == kExpected[k].offset);
    CHECK(m.stride == kExpected[k].stride);
  }
  CHECK(layout.size == 364);             // the end of the last member, int i at 360: glslang's size
  CHECK(layout.find("tex") == nullptr);  // opaque: a binding of its own, not a member
}

TEST_CASE("vulkan_params_layout_of: a source and its dual_dialect output have one layout") {
  const vulkan_params_layout before = vulkan_params_layout_of(kSource);
  const vulkan_params_layout after =
      vulkan_params_layout_of(hush::glsl::dual_dialect(kSource, "test_params"));
  CHECK(before.block.empty());  // not through dual_dialect yet: no block name
  REQUIRE(before.members.size() == after.members.size());
  for (std::size_t k = 0; k < before.members.size(); ++k) {
    CHECK(before.members[k].name == after.members[k].name);
    CHECK(before.members[k].offset == after.members[k].offset);
  }
  CHECK(before.size == after.size);
  // A shader without loose uniforms has an empty block.
  const vulkan_params_layout none = vulkan_params_layout_of(
      "#version 430 core\n// x\nlayout(local_size_x = 1) in;\nvoid main() {}\n");
  CHECK(none.members.empty());
  CHECK(none.size == 0);
}

TEST_CASE("vulkan_params_layout_of: unsupported declarations name the member") {
  const std::string head = "#version 430 core\n// x\n";
  CHECK_THROWS_WITH_AS(vulkan_params_layout_of(head + "uniform dvec2 hush_d;\n"),
                       doctest::Contains("hush_d has type dvec2; valid: float, int, uint"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(vulkan_params_layout_of(head + "uniform uint hush_q[UNKNOWN];\n"),
                       doctest::Contains("hush_q is declared `hush_q[UNKNOWN]`"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(vulkan_params_layout_of(head + "uniform uint hush_q[2][3];\n"),
                       doctest::Contains("hush_q is declared"), hush::invalid_argument);
}

TEST_CASE("vulkan_params: set writes each value at its member's offset, elements by stride") {
  vulkan_params p{vulkan_params_layout_of(hush::glsl::dual_dialect(kSource, "test_params"))};
  REQUIRE(p.bytes().size() == 364);
  p.set("a", 0.5f)
      .set("v2", hush::vec2{-1.0f, -2.0f})
      .set("b", hush::vec3{1.0f, 2.0f, 3.0f})
      .set("c", 4.0f)
      .set("flag", true)
      .set("iv", 1, hush::vec<std::int32_t, 2>{-7, 8})
      .set("bv", hush::vec<bool, 3>{true, false, true})
      .set("last", 2, std::uint32_t{0xdeadbeefu})
      .set("uv", hush::vec<std::uint32_t, 2>{5u, 6u})
      .set("i", std::int32_t{-1})
      .set("m32", std::array<hush::vec2, 3>{hush::vec2{1, 2}, hush::vec2{3, 4}, hush::vec2{5, 6}})
      .set("ma", 1, std::array<hush::vec2, 2>{hush::vec2{7, 8}, hush::vec2{9, 10}});
  const std::vector<std::byte>& b = p.bytes();
  CHECK(float_at(b, 0) == 0.5f);
  CHECK(float_at(b, 8) == -1.0f);
  CHECK(float_at(b, 12) == -2.0f);
  CHECK(float_at(b, 16) == 1.0f);
  CHECK(float_at(b, 20) == 2.0f);
  CHECK(float_at(b, 24) == 3.0f);
  CHECK(float_at(b, 28) == 4.0f);
  CHECK(word_at(b, 160) == 1u);  // std140 bool: a uint
  CHECK(word_at(b, 176) == 0u);  // element 0 untouched
  CHECK(word_at(b, 192) == static_cast<std::uint32_t>(-7));
  CHECK(word_at(b, 196) == 8u);
  CHECK(word_at(b, 208) == 1u);
  CHECK(word_at(b, 212) == 0u);
  CHECK(word_at(b, 216) == 1u);
  CHECK(word_at(b, 304u + 2u * 16u) == 0xdeadbeefu);
  CHECK(word_at(b, 352) == 5u);
  CHECK(word_at(b, 356) == 6u);
  CHECK(word_at(b, 360) == 0xffffffffu);
  // mat3x2: column c at 112 + 16 c, rows packed in it.
  CHECK(float_at(b, 112) == 1.0f);
  CHECK(float_at(b, 116) == 2.0f);
  CHECK(float_at(b, 128) == 3.0f);
  CHECK(float_at(b, 144) == 5.0f);
  CHECK(float_at(b, 148) == 6.0f);
  // mat2 ma[2]: element 1 at 224 + 32, its second column 16 bytes further.
  CHECK(float_at(b, 256) == 7.0f);
  CHECK(float_at(b, 260) == 8.0f);
  CHECK(float_at(b, 224u + 32u + 16u) == 9.0f);
  // Nothing else was written: the 26 non-zero words above, every other word zero.
  std::size_t nonzero = 0;
  for (std::size_t at = 0; at < b.size(); at += 4) nonzero += word_at(b, at) != 0u ? 1u : 0u;
  CHECK(nonzero == 26);
}

TEST_CASE("vulkan_params: errors name the member and what is valid") {
  vulkan_params p{vulkan_params_layout_of(hush::glsl::dual_dialect(kSource, "test_params"))};
  CHECK_THROWS_WITH_AS(p.set("nope", 1.0f),
                       doctest::Contains("name = 'nope' is not a member of the block test_params; "
                                         "valid: a, v2, b, c, m"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(p.set("a", std::uint32_t{1}),
                       "hush::glsl::vulkan_params::set: a is a float, not a std::uint32_t; "
                       "valid: float",
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(p.set("uv", hush::vec<std::uint32_t, 3>{}),
                       doctest::Contains("uv is a uvec2, not a hush::vec<std::uint32_t, 3>; "
                                         "valid: hush::vec<std::uint32_t, 2>"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(p.set("m", hush::vec3{}),
                       doctest::Contains("valid: std::array<hush::vec<float, 3>, 3> (columns)"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(p.set("last", std::uint32_t{1}),
                       doctest::Contains("last is an array, uint[3]; valid: set(\"last\", "
                                         "element 0 ... 2, value)"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(p.set("last", 3, std::uint32_t{1}),
                       doctest::Contains("last element = 3 is out of range; valid: 0 ... 2"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(p.set("u", 0, std::uint32_t{1}),
                       doctest::Contains("u is not an array; valid: set(\"u\", value)"),
                       hush::invalid_argument);
  // A failed set writes nothing.
  CHECK(std::count(p.bytes().begin(), p.bytes().end(), std::byte{0}) ==
        static_cast<std::ptrdiff_t>(p.bytes().size()));
}

TEST_CASE("vulkan_params: every exported shader's block lays out, within 16 KiB, in block order") {
  std::size_t blocks = 0, largest = 0;
  for (const hush::glsl::export_file& f : hush::glsl::export_files()) {
    if (f.name.size() < 5 || f.name.compare(f.name.size() - 5, 5, ".glsl") == 0) continue;
    INFO(f.name);
    const vulkan_params_layout layout = vulkan_params_layout_of(f.content);
    CHECK(layout.block.empty() == layout.members.empty());  // a block exactly with uniforms
    if (layout.members.empty()) continue;
    ++blocks;
    largest = std::max(largest, layout.size);
    // The members in the order of the block's text (dual_dialect writes both from one list).
    const std::size_t head = f.content.find("uniform " + layout.block + " {");
    REQUIRE(head != std::string::npos);
    std::size_t at = head;
    for (const vulkan_param& m : layout.members) {
      at = f.content.find(" " + m.name, at);
      CHECK(at < f.content.find("};", head));
    }
  }
  CHECK(blocks > 0);
  CHECK(largest <= 16384);  // Vulkan's guaranteed maxUniformBufferRange (docs/gpu.md)
  // The names docs/gpu.md fills in its example.
  for (const hush::glsl::export_file& f : hush::glsl::export_files())
    if (f.name == "hush_fractal_perlin3_grid.comp") {
      vulkan_params p{vulkan_params_layout_of(f.content)};
      p.set("hush_bands", std::uint32_t{4})
          .set("hush_size", hush::vec<std::uint32_t, 3>{8u, 8u, 8u})
          .set("hush_key", 3, std::uint32_t{7u});
      CHECK(word_at(p.bytes(), p.layout().find("hush_key")->offset + std::size_t{48}) ==
            7u);  // 3 x 16
    }
}
