// Tests of the GLSL backend (backends/glsl): the generated constants, the
// hand-written bodies and hush::glsl::device, on a headless OSMesa (llvmpipe)
// context. Every GPU result is compared with the CPU library: hashes and the
// lattice split bit for bit, Perlin noise within the tolerances derived below.
//
// Tolerances. llvmpipe evaluates GLSL float +, -, * with IEEE correct rounding
// (LLVM on the host's SIMD units) but may fuse a * b + c into one fma, which
// rounds once where the CPU rounds twice. The forward error analysis behind
// the CPU float budget (perlin.hpp, tests/perlin/perlin_test.cpp: 2^-16 of the double
// reference for values) bounds every rounding by 2^-24 relative; a fused op
// meets the same bound, so the GPU values are within the same 2^-16 of the
// double reference, and within 2^-15 of the CPU float values (triangle
// inequality). Gradients: those budgets times 1 + the Lipschitz bound of the
// noise, as in perlin_test.cpp. The inputs to that arithmetic (cells and
// fractions) are identical to the CPU's: the lattice-split test checks them bit
// for bit, and grids split on the CPU.
#include <doctest/doctest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "glsl_test_util.hpp"
#include "hush/exec.hpp"
#include "hush/glsl/compute_source.hpp"
#include "hush/glsl/device.hpp"
#include "hush/glsl/export.hpp"
#include "hush/glsl/generator.hpp"
#include "hush/glsl/library.hpp"
#include "hush/glsl/headless.hpp"
#include "hush/hush.hpp"
#include "test_util.hpp"

namespace {

using hush_glsl_test::error_stats;
using hush_glsl_test::headless;
using hush_glsl_test::random_points;
using hush_test::lipschitz_bound;

namespace gd = hush::glsl::detail;
using hush_test::splitmix64;

const double kValueBudget = std::ldexp(1.0, -16);  // GPU vs double reference (header comment)

std::uint32_t bits_of(float f) {
  std::uint32_t u = 0;
  std::memcpy(&u, &f, sizeof u);
  return u;
}
float float_of(std::uint32_t u) {
  float f = 0;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

// Runs `main_body` (GLSL statements using n, src[], dst[]) in a 430 compute
// shader after the library, over `threads` invocations; returns dst.
std::vector<std::uint32_t> run_kernel(const std::string& main_body,
                                      const std::vector<std::uint32_t>& src, std::size_t dst_words,
                                      std::size_t threads) {
  const gd::gl_api& gl = headless().device.gl();
  const std::string source =
      "#version 430 core\nlayout(local_size_x = 64) in;\n" + hush::glsl::library() +
      "layout(std430, binding = 0) readonly buffer src_block { uint src[]; };\n"
      "layout(std430, binding = 1) writeonly buffer dst_block { uint dst[]; };\n"
      "uniform uint count;\n"
      "void main() {\n  uint n = gl_GlobalInvocationID.x;\n  if (n >= count) return;\n" +
      main_body + "\n}\n";
  const gd::gl_program prog = gd::link_program(gl, {{gd::kGlComputeShader, source}});
  gd::gl_uint buf[2] = {0, 0};
  gl.GenBuffers(2, buf);
  const std::vector<std::uint32_t> in = src.empty() ? std::vector<std::uint32_t>{0u} : src;
  gl.BindBuffer(gd::kGlShaderStorageBuffer, buf[0]);
  gl.BufferData(gd::kGlShaderStorageBuffer, gd::gl_sizeiptr(in.size() * 4), in.data(),
                gd::kGlStreamDraw);
  gl.BindBufferBase(gd::kGlShaderStorageBuffer, 0, buf[0]);
  gl.BindBuffer(gd::kGlShaderStorageBuffer, buf[1]);
  gl.BufferData(gd::kGlShaderStorageBuffer, gd::gl_sizeiptr(dst_words * 4), nullptr,
                gd::kGlDynamicRead);
  gl.BindBufferBase(gd::kGlShaderStorageBuffer, 1, buf[1]);
  gl.UseProgram(prog.id());
  gl.Uniform1ui(gl.GetUniformLocation(prog.id(), "count"), gd::gl_uint(threads));
  gl.DispatchCompute(gd::gl_uint((threads + 63) / 64), 1, 1);
  gl.MemoryBarrier(gd::kGlBufferUpdateBarrierBit);
  std::vector<std::uint32_t> dst(dst_words);
  gl.GetBufferSubData(gd::kGlShaderStorageBuffer, 0, gd::gl_sizeiptr(dst_words * 4), dst.data());
  gl.UseProgram(0);
  gl.DeleteBuffers(2, buf);
  gl.check("run_kernel");
  return dst;
}

// Hash inputs: the edge words every operand should see, then random words.
constexpr std::array<std::uint32_t, 12> kEdgeWords = {
    0u,          1u,          2u,          0x7FFFFFFFu, 0x80000000u, 0x80000001u,
    0xFFFFFFFEu, 0xFFFFFFFFu, 0x9E3779B9u, 0x0000FFFFu, 0xFFFF0000u, 12345u};
constexpr std::size_t kRandomHashInputs = 100000;

// `arity`-word tuples: all combinations of edge words (up to 12^3), then random ones.
std::vector<std::uint32_t> hash_inputs(int arity, std::uint64_t seed) {
  std::vector<std::uint32_t> v;
  const std::size_t e = kEdgeWords.size();
  std::size_t combos = 1;
  for (int a = 0; a < std::min(arity, 3); ++a) combos *= e;
  for (std::size_t c = 0; c < combos; ++c) {
    std::size_t r = c;
    for (int a = 0; a < arity; ++a) {
      v.push_back(a < 3 ? kEdgeWords[r % e] : kEdgeWords[(c * 7 + 3) % e]);
      if (a < 3) r /= e;
    }
  }
  splitmix64 rng{seed};
  for (std::size_t i = 0; i < kRandomHashInputs * std::size_t(arity); ++i)
    v.push_back(rng.next_u32());
  return v;
}

// ---- Hashes: bit for bit.

TEST_CASE("hash32 and seed_key equal the CPU bit for bit on edge and 1e5 random words") {
  const std::vector<std::uint32_t> in = hash_inputs(1, 11);
  const std::size_t n = in.size();
  const auto out = run_kernel(
      "dst[2u * n] = hush_hash32(src[n]); dst[2u * n + 1u] = hush_seed_key(src[n]);", in, 2 * n, n);
  std::size_t bad = 0;
  for (std::size_t i = 0; i < n; ++i)
    bad += (out[2 * i] != hush::hash32(in[i])) + (out[2 * i + 1] != hush::seed_key(in[i]));
  CHECK(bad == 0);
}

TEST_CASE("hash32 of a pair and rotl equal the CPU bit for bit") {
  const std::vector<std::uint32_t> in = hash_inputs(2, 12);
  const std::size_t n = in.size() / 2;
  const auto out = run_kernel(
      "dst[2u * n] = hush_hash32(src[2u * n], src[2u * n + 1u]);\n"
      "dst[2u * n + 1u] = hush_rotl(src[2u * n], 1u + src[2u * n + 1u] % 31u);",
      in, 2 * n, n);
  std::size_t bad = 0;
  for (std::size_t i = 0; i < n; ++i) {
    bad += out[2 * i] != hush::hash32(in[2 * i], in[2 * i + 1]);
    bad += out[2 * i + 1] != hush::rotl(in[2 * i], 1u + in[2 * i + 1] % 31u);
  }
  CHECK(bad == 0);
}

TEST_CASE("lattice_hash 2D and 3D equal the CPU bit for bit on edge and 1e5 random cells") {
  const std::vector<std::uint32_t> in3 = hash_inputs(3, 13), in4 = hash_inputs(4, 14);
  const std::size_t n3 = in3.size() / 3, n4 = in4.size() / 4;
  const auto out3 = run_kernel(
      "dst[n] = hush_lattice_hash(src[3u * n], src[3u * n + 1u], src[3u * n + 2u]);", in3, n3, n3);
  const auto out4 = run_kernel(
      "dst[n] = hush_lattice_hash(src[4u * n], src[4u * n + 1u], src[4u * n + 2u], src[4u * n + "
      "3u]);",
      in4, n4, n4);
  std::size_t bad = 0;
  for (std::size_t i = 0; i < n3; ++i)
    bad += out3[i] != hush::lattice_hash(in3[3 * i], in3[3 * i + 1], in3[3 * i + 2]);
  for (std::size_t i = 0; i < n4; ++i)
    bad +=
        out4[i] != hush::lattice_hash(in4[4 * i], in4[4 * i + 1], in4[4 * i + 2], in4[4 * i + 3]);
  CHECK(n3 >= kRandomHashInputs);
  CHECK(n4 >= kRandomHashInputs);
  CHECK(bad == 0);
}

// ---- The lattice split: bit for bit with hush::lattice_split<float>.

TEST_CASE("lattice split of a float equals hush::lattice_split bit for bit, all periods") {
  std::vector<float> xs = {
      0.0f,           -0.0f,         1.0f,           -1.0f,        0.5f,         -0.5f,
      -1e-30f,        1e-30f,        -1e-7f,         16777216.0f,  -16777218.0f, 2147483520.0f,
      -2147483520.0f, 2147483648.0f, -2147483648.0f, 3e9f,         -3e9f,        4294967296.0f,
      -4294967296.0f, 1e20f,         -1e20f,         FLT_MAX,      -FLT_MAX,     1e-38f,
      -1e-38f,        1e-40f,        -1e-40f,        -FLT_TRUE_MIN};
  // Random bit patterns: every exponent, both signs, subnormals too (llvmpipe keeps them).
  splitmix64 rng{21};
  while (xs.size() < 20000) {
    const float x = float_of(rng.next_u32());
    if (std::isfinite(x)) xs.push_back(x);
  }
  const std::uint32_t periods[] = {0u, 1u, 2u, 3u, 7u, 255u, 65536u, 1000003u, 2147483647u};
  std::vector<std::uint32_t> in;
  for (float x : xs)
    for (std::uint32_t p : periods) in.insert(in.end(), {bits_of(x), p});
  const std::size_t n = in.size() / 2;
  const auto out = run_kernel(
      "hush_lattice_coord c = hush_lattice_split(uintBitsToFloat(src[2u * n]), src[2u * n + 1u]);\n"
      "dst[3u * n] = c.i0; dst[3u * n + 1u] = c.i1; dst[3u * n + 2u] = floatBitsToUint(c.f);",
      in, 3 * n, n);
  // GLSL lets a GPU flush subnormal floats to zero (GLSL 4.60 sec. 4.7.1; NVIDIA does, measured
  // on an H100): a subnormal x may split as +-0 does, a move of at most 2^-126 (hush/glsl/device.hpp).
  std::size_t bad = 0, flushed = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const float x = float_of(in[2 * i]);
    const hush::lattice_coord<float> c = hush::lattice_split<float>(x, in[2 * i + 1]);
    const auto same = [&](const hush::lattice_coord<float>& e) {
      return out[3 * i] == e.i0 && out[3 * i + 1] == e.i1 && out[3 * i + 2] == bits_of(e.f);
    };
    bool ok = same(c);
    if (!ok && std::fpclassify(x) == FP_SUBNORMAL &&
        (same(hush::lattice_split<float>(0.0f, in[2 * i + 1])) ||
         same(hush::lattice_split<float>(-0.0f, in[2 * i + 1])))) {
      ok = true;
      ++flushed;
    }
    if (!ok && bad < 5)
      MESSAGE("x = " << float_of(in[2 * i]) << " period " << in[2 * i + 1] << ": gpu ("
                     << out[3 * i] << ", " << out[3 * i + 1] << ", " << float_of(out[3 * i + 2])
                     << "), cpu (" << c.i0 << ", " << c.i1 << ", " << c.f << ")");
    bad += !ok;
  }
  MESSAGE(flushed << " subnormal inputs split as zero (the GPU flushes subnormals)");
  CHECK(bad == 0);
}

// ---- The generated constants.

// The numeric literals of GLSL text outside comments: tokens starting with a
// digit (or '.' and a digit) that are not part of an identifier.
std::vector<std::string> numeric_literals(const std::string& text) {
  std::vector<std::string> found;
  bool comment = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (comment) {
      comment = ch != '\n';
      continue;
    }
    if (ch == '/' && i + 1 < text.size() && text[i + 1] == '/') {
      comment = true;
      continue;
    }
    const bool ident_before =
        i > 0 && (std::isalnum(static_cast<unsigned char>(text[i - 1])) || text[i - 1] == '_');
    const bool starts =
        std::isdigit(static_cast<unsigned char>(ch)) ||
        (ch == '.' && i + 1 < text.size() && std::isdigit(static_cast<unsigned char>(text[i + 1])));
    if (!starts || ident_before) continue;
    std::size_t j = i;
    while (j < text.size() &&
           (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '.' ||
            ((text[j] == '-' || text[j] == '+') && (text[j - 1] == 'e' || text[j - 1] == 'E'))))
      ++j;
    found.push_back(text.substr(i, j - i));
    i = j - 1;
  }
  return found;
}

// Literals the bodies may hold: the integers of a 2^D cell's structure
// (corner indices and bits 0 ... 8), unsigned 0 and 1, 1.0 (a cell's width)
// and 0.0 (the sign test of a turbulence band).
bool structural_literal(const std::string& lit) {
  // Structure, not constants: small counts, 2 for exact halving and doubling,
  // 4 for the channels of an RGBA texel.
  static const char* const kAllowed[] = {"0", "1",  "2",  "3",  "4",  "5",   "6",   "7",
                                         "8", "0u", "1u", "2u", "4u", "1.0", "0.0", "2.0"};
  return std::find_if(std::begin(kAllowed), std::end(kAllowed),
                      [&](const char* a) { return lit == a; }) != std::end(kAllowed);
}

std::vector<std::string> referenced_names(const std::string& text) {
  std::vector<std::string> names;
  for (std::size_t i = text.find("HUSH_"); i != std::string::npos; i = text.find("HUSH_", i + 1)) {
    if (i > 0 && (std::isalnum(static_cast<unsigned char>(text[i - 1])) || text[i - 1] == '_'))
      continue;
    std::size_t j = i;
    while (j < text.size() && (std::isupper(static_cast<unsigned char>(text[j])) ||
                               std::isdigit(static_cast<unsigned char>(text[j])) || text[j] == '_'))
      ++j;
    names.push_back(text.substr(i, j - i));
  }
  return names;
}

TEST_CASE("every generated GLSL constant reads back equal to the C++ table bit for bit") {
  const std::vector<hush::glsl::glsl_constant> table = hush::glsl::constant_table();
  std::string body;
  std::vector<std::uint32_t> want;
  for (const auto& k : table) {
    for (std::size_t i = 0; i < k.bits.size(); ++i) {
      const std::string ref = k.name + (k.array ? "[" + std::to_string(i) + "]" : "");
      body +=
          "  dst[" + std::to_string(want.size()) + "u] = " +
          (k.kind == hush::glsl::glsl_constant::type::f32 ? "floatBitsToUint(" + ref + ")" : ref) +
          ";\n";
      want.push_back(k.bits[i]);
    }
  }
  const auto got = run_kernel(body, {}, want.size(), 1);
  std::size_t bad = 0;
  for (std::size_t i = 0; i < want.size(); ++i) bad += got[i] != want[i];
  CHECK(bad == 0);
  CHECK(want.size() >= 70);  // 37 names, the gradient tables 8 + 8 + 12 * 3 elements
}

TEST_CASE("the constant table holds the C++ constants, each rounded to float once") {
  namespace c = hush::detail::constants;
  std::map<std::string, std::vector<std::uint32_t>> by_name;
  for (const auto& k : hush::glsl::constant_table()) by_name[k.name] = k.bits;
  auto f = [](double v) { return bits_of(static_cast<float>(v)); };
  CHECK(by_name.at("HUSH_HASH_MUL1") == std::vector<std::uint32_t>{c::kHashMul1});
  CHECK(by_name.at("HUSH_HASH_MUL2") == std::vector<std::uint32_t>{c::kHashMul2});
  CHECK(by_name.at("HUSH_HASH_SHIFT1") == std::vector<std::uint32_t>{c::kHashShift1});
  CHECK(by_name.at("HUSH_HASH_SHIFT2") == std::vector<std::uint32_t>{c::kHashShift2});
  CHECK(by_name.at("HUSH_HASH_SHIFT3") == std::vector<std::uint32_t>{c::kHashShift3});
  CHECK(by_name.at("HUSH_LATTICE_PRIME_X") == std::vector<std::uint32_t>{c::kLatticePrimeX});
  CHECK(by_name.at("HUSH_LATTICE_PRIME_Y") == std::vector<std::uint32_t>{c::kLatticePrimeY});
  CHECK(by_name.at("HUSH_LATTICE_PRIME_Z") == std::vector<std::uint32_t>{c::kLatticePrimeZ});
  CHECK(by_name.at("HUSH_LATTICE_ROTATE_Y") == std::vector<std::uint32_t>{c::kLatticeRotateY});
  CHECK(by_name.at("HUSH_LATTICE_ROTATE_Z") == std::vector<std::uint32_t>{c::kLatticeRotateZ});
  CHECK(by_name.at("HUSH_GOLDEN_GAMMA") == std::vector<std::uint32_t>{c::kGoldenGamma});
  CHECK(by_name.at("HUSH_FADE5") == std::vector<std::uint32_t>{f(c::kFade5)});
  CHECK(by_name.at("HUSH_FADE4") == std::vector<std::uint32_t>{f(c::kFade4)});
  CHECK(by_name.at("HUSH_FADE3") == std::vector<std::uint32_t>{f(c::kFade3)});
  CHECK(by_name.at("HUSH_PERLIN2_SCALE") == std::vector<std::uint32_t>{f(c::kPerlin2Scale)});
  CHECK(by_name.at("HUSH_PERLIN3_SCALE") == std::vector<std::uint32_t>{f(c::kPerlin3Scale)});
  CHECK(by_name.at("HUSH_PERLIN2_GRAD_SHIFT") == std::vector<std::uint32_t>{c::kPerlin2GradShift});
  CHECK(by_name.at("HUSH_PERLIN3_INDEX_SHIFT") ==
        std::vector<std::uint32_t>{c::kPerlin3IndexShift});
  for (int i = 0; i < c::kPerlin2GradCount; ++i) {
    CHECK(by_name.at("HUSH_PERLIN2_GRAD_X")[std::size_t(i)] == f(c::kPerlin2GradX[i]));
    CHECK(by_name.at("HUSH_PERLIN2_GRAD_Y")[std::size_t(i)] == f(c::kPerlin2GradY[i]));
  }
  for (int i = 0; i < c::kPerlin3GradCount; ++i) {
    CHECK(by_name.at("HUSH_PERLIN3_GRAD_X")[std::size_t(i)] == f(c::kPerlin3GradX[i]));
    CHECK(by_name.at("HUSH_PERLIN3_GRAD_Y")[std::size_t(i)] == f(c::kPerlin3GradY[i]));
    CHECK(by_name.at("HUSH_PERLIN3_GRAD_Z")[std::size_t(i)] == f(c::kPerlin3GradZ[i]));
  }
  CHECK(by_name.at("HUSH_ONE_MINUS_ULP")[0] == bits_of(hush::detail::one_minus_ulp<float>()));
}

TEST_CASE("the bodies hold no number outside the generated block and use every constant") {
  // The library's bodies and the hand-written GLSL of the noise programs that
  // carry their own (anisotropic noise: it reads the runner's per-sample data, so in
  // its runner, not the library).
  using aniso = hush::glsl::noise_program<hush::anisotropic>;
  std::string bodies = hush::glsl::library_bodies() + hush::glsl::detail::kAnisotropicBody;
  for (bool g : {false, true})
    bodies += aniso::band_begin(g) + aniso::band_step(g) + aniso::band_result(g);
  std::vector<std::string> stray;
  for (const std::string& lit : numeric_literals(bodies))
    if (!structural_literal(lit)) stray.push_back(lit);
  CHECK_MESSAGE(stray.empty(), "literal in a body: " << (stray.empty() ? "" : stray[0]));
  // The scanner finds a retyped constant (it would fail the check above).
  const auto planted = numeric_literals(bodies + "\nx *= 0x7feb352du; y = 6.0 * t; z = 1e-3;\n");
  CHECK(std::count_if(planted.begin(), planted.end(),
                      [](const std::string& l) { return !structural_literal(l); }) == 3);

  // Every HUSH_ name the bodies use is a generated constant, and every
  // generated constant is used (a dropped table entry would not compile; an
  // unused one would be a number nothing reads).
  std::vector<std::string> names;
  for (const auto& k : hush::glsl::constant_table()) names.push_back(k.name);
  std::vector<std::string> used = referenced_names(bodies);
  // The macros by which an including shader hands wavelet noise its tile (wavelet_glsl.hpp)
  // and the wavelet bodies' include guard, and the runner's mark of the samples layout
  // (compute_source.hpp).
  const std::vector<std::string> hooks = {"HUSH_WAVELET_TILE", "HUSH_WAVELET_TILE_AT",
                                          "HUSH_WAVELET_BLEND", "HUSH_WAVELET_TABLE",
                                          "HUSH_WAVELET_BODY", "HUSH_SAMPLES"};
  used.erase(std::remove_if(used.begin(), used.end(),
                            [&](const std::string& u) {
                              return std::find(hooks.begin(), hooks.end(), u) != hooks.end();
                            }),
             used.end());
  for (const std::string& u : used)
    CHECK_MESSAGE(std::find(names.begin(), names.end(), u) != names.end(),
                  u << " is not generated");
  for (const std::string& n : names)
    CHECK_MESSAGE(std::find(used.begin(), used.end(), n) != used.end(), n << " is never used");
  // One declaration per table entry in the block, and nothing else declared there.
  const std::string block = hush::glsl::constants_block();
  CHECK(std::count(block.begin(), block.end(), '\n') == std::ptrdiff_t(names.size() + 1));
}

TEST_CASE("float literals round-trip: the emitted decimal is the float, also for awkward values") {
  using t = hush::glsl::glsl_constant::type;
  for (float v : {0.70710678f, 1.0f / 1.0363538f, 0.1f, -0.0f, FLT_MIN, FLT_MAX,
                  1.0f - FLT_EPSILON / 2, 16777216.0f, 3.0f}) {
    const std::string lit = hush::glsl::glsl_literal(t::f32, bits_of(v));
    CHECK(bits_of(std::strtof(lit.c_str(), nullptr)) == bits_of(v));
    CHECK(lit.find_first_of(".eE") != std::string::npos);
  }
  CHECK_THROWS_AS(hush::glsl::glsl_literal(t::f32, bits_of(std::numeric_limits<float>::infinity())),
                  std::logic_error);
  CHECK(hush::glsl::glsl_literal(t::u32, 0x7feb352du) == "0x7feb352du");
  CHECK(hush::glsl::glsl_literal(t::u32, 16u) == "16u");
  CHECK(hush::glsl::glsl_literal(t::f32, bits_of(-15.0f)) == "-15.0");
  CHECK(hush::glsl::glsl_literal(t::f32, bits_of(2147483648.0f)) == "2147483648.0");
}

// ---- The library in other stages.

// A `#version` directive (at the start of a line), not the word in a comment.
bool has_version_directive(const std::string& text) {
  return text.rfind("#version", 0) == 0 || text.find("\n#version") != std::string::npos;
}

TEST_CASE("the library compiles and links in a vertex and a fragment shader under 330 core") {
  const std::string lib = hush::glsl::library();
  CHECK_FALSE(has_version_directive(lib));
  CHECK(lib.find("buffer") == std::string::npos);  // no SSBOs: 330 has none
  const std::string vertex = "#version 330 core\n" + lib +
                             "layout(location = 0) in vec3 position;\n"
                             "uniform uint seed;\n"
                             "out vec4 v_noise;\n"
                             "void main() {\n"
                             "  uint key = hush_seed_key(seed);\n"
                             "  v_noise = hush_perlin3_gradient(position, key, uvec3(0u));\n"
                             "  gl_Position = vec4(position + 0.1 * v_noise.yzw, 1.0 + "
                             "hush_perlin3(position, key, uvec3(4u)));\n"
                             "}\n";
  const std::string fragment =
      "#version 330 core\n" + lib +
      "in vec4 v_noise;\n"
      "uniform uint seed;\n"
      "out vec4 color;\n"
      "void main() {\n"
      "  uint key = hush_hash32(seed, 3u);\n"
      "  vec3 g = hush_perlin2_gradient(gl_FragCoord.xy / 16.0, key, uvec2(8u, 0u));\n"
      "  float h = float(hush_lattice_hash(key, 1u, 2u, 3u) >> 24) / 255.0;\n"
      "  color = vec4(hush_perlin2(gl_FragCoord.xy, key, uvec2(0u)), g.yz, h) + v_noise;\n"
      "}\n";
  const gd::gl_api& gl = headless().device.gl();
  const gd::gl_program prog =
      gd::link_program(gl, {{gd::kGlVertexShader, vertex}, {gd::kGlFragmentShader, fragment}});
  CHECK(prog.id() != 0u);
}

#if defined(HUSH_GLSL_HAVE_OSMESA)
TEST_CASE("osmesa_context refuses a width or height outside 1 ... 16384, naming it") {
  CHECK_THROWS_WITH_AS(hush::glsl::osmesa_context(0, 16), doctest::Contains("width = 0"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(hush::glsl::osmesa_context(16, -3), doctest::Contains("height = -3"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(hush::glsl::osmesa_context(16385, 16),
                       doctest::Contains("valid: 1 ... 16384"), hush::invalid_argument);
}
#endif

TEST_CASE("headless_context refuses a kind it does not have, naming HUSH_GL_CONTEXT") {
  CHECK_THROWS_WITH_AS(hush::glsl::headless_context("vulkan"),
                       doctest::Contains("HUSH_GL_CONTEXT = \"vulkan\""), hush::invalid_argument);
  CHECK(hush_glsl_test::headless().context.kind() ==
        hush::glsl::headless_context::kind_from_environment());
}

TEST_CASE("a shader that does not compile throws std::runtime_error carrying the driver log") {
  const gd::gl_api& gl = headless().device.gl();
  try {
    gd::link_program(
        gl,
        {{gd::kGlComputeShader,
          "#version 430 core\nlayout(local_size_x = 1) in;\nvoid main() { undeclared = 1; }\n"}});
    FAIL("no exception");
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    CHECK(what.find("compute shader does not compile") != std::string::npos);
    CHECK(what.find("undeclared") != std::string::npos);  // the driver's log names it
  }
}

// ---- Perlin through hush::evaluate / evaluate_grid.

// Compares GPU values/gradients with the double reference and the CPU float
// path at the same double positions; checks the budgets of the file comment.
template <int D, class Position>
void check_against_cpu(const hush::perlin<D>& p, std::size_t n, Position position, const float* v,
                       const hush::vec<float, D>* g, const char* what) {
  error_stats vd, vf, gdbl, gflt;
  for (std::size_t i = 0; i < n; ++i) {
    const hush::vec<double, D> x = position(i);
    const auto ref = p.template value_and_gradient<double>(x);
    const auto cpu = p.template value_and_gradient<float>(x);
    vd.add(std::fabs(double(v[i]) - ref.value));
    vf.add(std::fabs(double(v[i]) - double(cpu.value)));
    if (g)
      for (int a = 0; a < D; ++a) {
        const std::size_t k = std::size_t(a);
        gdbl.add(std::fabs(double(g[i][k]) - ref.gradient[k]));
        gflt.add(std::fabs(double(g[i][k]) - double(cpu.gradient[k])));
      }
  }
  std::ostringstream msg;
  msg << "perlin" << D << "d " << what << ": value vs double max " << vd.max << " rms " << vd.rms()
      << ", vs cpu float max " << vf.max << " rms " << vf.rms();
  if (g)
    msg << "; gradient vs double max " << gdbl.max << " rms " << gdbl.rms() << ", vs cpu float max "
        << gflt.max;
  MESSAGE(msg.str());
  const double grad_budget = kValueBudget * (1 + lipschitz_bound<D>());
  CHECK(vd.max <= kValueBudget);
  CHECK(vf.max <= 2 * kValueBudget);
  if (g) {
    CHECK(gdbl.max <= grad_budget);
    CHECK(gflt.max <= 2 * grad_budget);
  }
}

template <int D>
void check_points(const hush::perlin<D>& p, std::size_t n, std::uint32_t seed, const char* what) {
  const auto pts = random_points<D>(n, seed);
  std::vector<float> v(n), v_only(n);
  std::vector<hush::vec<float, D>> g(n);
  hush::evaluate(p, hush::exec::glsl{headless().device}, pts, v, g);
  hush::evaluate(p, hush::exec::glsl{headless().device}, pts, v_only);
  auto pos = [&](std::size_t i) { return hush::vec_cast<double>(pts[i]); };
  check_against_cpu<D>(p, n, pos, v.data(), g.data(), what);
  check_against_cpu<D>(p, n, pos, v_only.data(), nullptr, what);
}

TEST_CASE("perlin 2D and 3D points match the double reference within 2^-16") {
  check_points(hush::perlin<2>(7), 200000, 1, "points");
  check_points(hush::perlin<3>(7), 100000, 2, "points");
}

TEST_CASE("periodic perlin points match the CPU, including far outside the period") {
  hush::perlin<2>::params p2;
  p2.seed = 3;
  p2.period = {5, 7};
  hush::perlin<3>::params p3;
  p3.seed = 4;
  p3.period = {3, 0, 1000003};
  check_points(hush::perlin<2>(p2), 50000, 3, "periodic points");
  check_points(hush::perlin<3>(p3), 50000, 4, "periodic points");
}

template <int D>
void check_grid(const hush::perlin<D>& p, const hush::grid<D>& gr, const char* what) {
  const std::size_t n = gr.count();
  std::vector<float> v(n), v_only(n), cpu(n);
  std::vector<hush::vec<float, D>> g(n);
  hush::evaluate_grid(p, hush::exec::glsl{headless().device}, gr, v, g);
  hush::evaluate_grid(p, hush::exec::glsl{headless().device}, gr, v_only);
  auto pos = [&](std::size_t i) {
    std::array<std::size_t, D> ijk{};
    ijk[0] = i % gr.size[0];
    ijk[1] = (i / gr.size[0]) % gr.size[1];
    if constexpr (D == 3) ijk[2] = i / (gr.size[0] * gr.size[1]);
    return gr.position(ijk);
  };
  check_against_cpu<D>(p, n, pos, v.data(), g.data(), what);
  CHECK(
      std::equal(v.begin(), v.end(), v_only.begin()));  // same arithmetic with or without gradient
}

TEST_CASE(
    "perlin grids match the double reference: origin 0, 1e6, -1e9, negative steps, periodic") {
  const hush::perlin<2> p2(9);
  const hush::perlin<3> p3(9);
  check_grid(p2, hush::grid<2>{{0.1, -0.2}, {0.037, 0.05}, {256, 128}}, "grid at 0");
  check_grid(p2, hush::grid<2>{{1e6 + 0.3, 1e6}, {0.01, -0.02}, {256, 128}}, "grid at 1e6");
  check_grid(p2, hush::grid<2>{{-1e9, -1e9 + 0.5}, {-0.013, 0.011}, {256, 128}}, "grid at -1e9");
  check_grid(p3, hush::grid<3>{{0.1, -0.2, 0.3}, {0.037, 0.05, 0.11}, {40, 30, 20}}, "grid at 0");
  check_grid(p3, hush::grid<3>{{1e6, 1e6 + 0.25, -1e6}, {0.01, -0.02, 0.03}, {40, 30, 20}},
             "grid at 1e6");
  check_grid(p3, hush::grid<3>{{-1e9, -1e9, -1e9 + 0.5}, {-0.013, 0.011, -0.07}, {40, 30, 20}},
             "grid at -1e9");
  hush::perlin<2>::params pp2;
  pp2.seed = 5;
  pp2.period = {8, 3};
  hush::perlin<3>::params pp3;
  pp3.seed = 5;
  pp3.period = {4, 5, 6};
  check_grid(hush::perlin<2>(pp2), hush::grid<2>{{-3.3, 2.1}, {0.1, -0.07}, {200, 100}},
             "periodic grid");
  check_grid(hush::perlin<3>(pp3), hush::grid<3>{{-1e9, 7.5, -2.2}, {0.3, 0.2, -0.1}, {30, 20, 10}},
             "periodic grid");
}

TEST_CASE("perlin grids equal the CPU float grid to float rounding, and tile with their period") {
  hush::perlin<2>::params pp;
  pp.seed = 6;
  pp.period = {4, 4};
  const hush::perlin<2> p(pp);
  // Two grids a whole period apart: same cells and fractions, so identical output.
  const hush::grid<2> a{{0.25, 0.5}, {0.125, 0.125}, {64, 64}},
      b{{4.25, -3.5}, {0.125, 0.125}, {64, 64}};
  std::vector<float> va(a.count()), vb(b.count()), cpu(a.count());
  hush::evaluate_grid(p, hush::exec::glsl{headless().device}, a, va);
  hush::evaluate_grid(p, hush::exec::glsl{headless().device}, b, vb);
  hush::evaluate_grid(p, hush::exec::scalar, a, cpu);
  CHECK(va == vb);
  double max = 0;
  for (std::size_t i = 0; i < va.size(); ++i)
    max = std::max(max, std::fabs(double(va[i]) - cpu[i]));
  CHECK(max <= 2 * kValueBudget);
}

// ---- Hard cases.

TEST_CASE("NaN and infinite coordinates give NaN values and gradients") {
  const float nan = std::numeric_limits<float>::quiet_NaN(),
              inf = std::numeric_limits<float>::infinity();
  const std::vector<hush::vec2> p2 = {
      {nan, 0.5f}, {0.5f, inf}, {-inf, -inf}, {nan, nan}, {0.5f, 0.25f}};
  const std::vector<hush::vec3> p3 = {
      {nan, 0.5f, 0.5f}, {0.5f, 0.5f, -inf}, {inf, 1.0f, 2.0f}, {0.5f, 0.25f, 0.75f}};
  std::vector<float> v2(p2.size()), v3(p3.size());
  std::vector<hush::vec2> g2(p2.size());
  std::vector<hush::vec3> g3(p3.size());
  hush::perlin<2>::params pp;
  pp.period = {3, 1};
  for (const hush::perlin<2>& p : {hush::perlin<2>(1), hush::perlin<2>(pp)}) {
    hush::evaluate(p, hush::exec::glsl{headless().device}, p2, v2, g2);
    for (std::size_t i = 0; i + 1 < p2.size(); ++i) {
      CHECK(std::isnan(v2[i]));
      CHECK(std::isnan(g2[i].x));
      CHECK(std::isnan(g2[i].y));
    }
    CHECK(std::isfinite(v2.back()));
  }
  hush::evaluate(hush::perlin<3>(1), hush::exec::glsl{headless().device}, p3, v3, g3);
  for (std::size_t i = 0; i + 1 < p3.size(); ++i) {
    CHECK(std::isnan(v3[i]));
    CHECK((std::isnan(g3[i].x) && std::isnan(g3[i].y) && std::isnan(g3[i].z)));
  }
  CHECK(std::isfinite(v3.back()));
}

TEST_CASE("coordinates of magnitude 2^31 and beyond, -1 and tiny negatives agree with the CPU") {
  const std::vector<float> xs = {-1.0f,         1.0f,           -1e-30f,       -2.5e-8f,
                                 2147483648.0f, -2147483648.0f, 3e9f,          -3e9f,
                                 4294967296.0f, -4294967296.0f, 1e20f,         -1e30f,
                                 FLT_MAX,       -FLT_MAX,       2147483520.5f, -0.999999940f};
  std::vector<hush::vec3> pts;
  for (float x : xs)
    for (float y : {-1.0f, 0.3f, 3e9f}) pts.push_back({x, y, x * 0.5f});
  hush::perlin<3>::params pp;
  pp.seed = 2;
  pp.period = {7, 0, 65536};
  for (const hush::perlin<3>& p : {hush::perlin<3>(2), hush::perlin<3>(pp)}) {
    std::vector<float> v(pts.size());
    std::vector<hush::vec3> g(pts.size());
    hush::evaluate(p, hush::exec::glsl{headless().device}, pts, v, g);
    auto pos = [&](std::size_t i) { return hush::vec_cast<double>(pts[i]); };
    check_against_cpu<3>(p, pts.size(), pos, v.data(), g.data(), "hard coordinates");
  }
}

TEST_CASE("an empty batch dispatches nothing and writes nothing") {
  hush::glsl::device& dev = headless().device;
  const std::size_t before = dev.dispatches();
  std::vector<hush::vec2> none;
  std::vector<float> out;
  hush::evaluate(hush::perlin<2>(1), hush::exec::glsl{dev}, none, out);
  dev.evaluate_points(hush::perlin<2>(1), none.data(), 0, out.data(), nullptr);
  hush::evaluate_grid(hush::perlin<3>(1), hush::exec::glsl{dev},
                      hush::grid<3>{{0, 0, 0}, {1, 1, 1}, {4, 0, 4}}, out);
  CHECK(dev.dispatches() == before);
}

TEST_CASE(
    "a grid of 2^32 samples or too long for one SSBO is refused with hush::invalid_argument") {
  std::vector<float> out(1);
  CHECK_THROWS_AS(
      headless().device.evaluate_grid(
          hush::perlin<2>(1), hush::grid<2>{{0, 0}, {1, 1}, {65536, 65537}}, out.data(), nullptr),
      hush::invalid_argument);
  // The per-axis table must fit one SSBO: 12 bytes per sample index along each axis.
  hush::glsl::device::options opt;
  opt.max_buffer_bytes = 4096;
  hush::glsl::device small(headless().context.loader(), opt);
  std::vector<float> row(400);
  CHECK_THROWS_AS(small.evaluate_grid(hush::perlin<2>(1), hush::grid<2>{{0, 0}, {1, 1}, {400, 1}},
                                      row.data(), nullptr),
                  hush::invalid_argument);
  small.evaluate_grid(hush::perlin<2>(1), hush::grid<2>{{0, 0}, {1, 1}, {300, 1}}, row.data(),
                      nullptr);
  CHECK(row[299] == 0.0f);  // x = 299, y = 0: a lattice point
}

TEST_CASE("a batch split across many dispatches and buffers equals one dispatch bit for bit") {
  hush::glsl::device::options opt;
  opt.max_groups_per_dispatch = 3;
  opt.max_buffer_bytes = 4096;
  hush::glsl::device small(headless().context.loader(), opt);
  hush::glsl::device& big = headless().device;
  const hush::perlin<2> p2(4);
  const hush::perlin<3> p3(4);
  const auto pts = random_points<2>(10000, 9);
  std::vector<float> a(pts.size()), b(pts.size());
  std::vector<hush::vec2> ga(pts.size()), gb(pts.size());
  std::size_t before = small.dispatches();
  hush::evaluate(p2, hush::exec::glsl{small}, pts, a, ga);
  // 4096 bytes / (3 floats) = 341 samples per batch, 6 groups of 64, 3 per dispatch.
  const std::size_t batch = 4096 / (3 * sizeof(float)), batches = (pts.size() + batch - 1) / batch;
  std::size_t expect = 0;
  for (std::size_t k = 0; k < batches; ++k) {
    const std::size_t m = std::min(batch, pts.size() - k * batch);
    expect += ((m + 63) / 64 + 2) / 3;
  }
  CHECK(small.dispatches() - before == expect);
  hush::evaluate(p2, hush::exec::glsl{big}, pts, b, gb);
  CHECK(a == b);
  CHECK(std::memcmp(ga.data(), gb.data(), ga.size() * sizeof(hush::vec2)) == 0);

  const hush::grid<3> gr{{1e6, -5.5, 0.25}, {-0.05, 0.1, 0.03}, {33, 17, 9}};
  std::vector<float> c(gr.count()), d(gr.count());
  before = small.dispatches();
  hush::evaluate_grid(p3, hush::exec::glsl{small}, gr, c);
  CHECK(small.dispatches() - before > gr.count() / 1024);  // at most 1024 samples per batch
  hush::evaluate_grid(p3, hush::exec::glsl{big}, gr, d);
  CHECK(c == d);
}

TEST_CASE("a grid beyond GL_MAX_COMPUTE_WORK_GROUP_COUNT groups takes several dispatches") {
  // Just over one full dispatch at the GL limit (65535 groups of 64 on llvmpipe: GL 4.3's
  // minimum). Where one buffer cannot hold that many samples (NVIDIA: 2^31 - 1 groups), the
  // same minimum is set as the device's option instead: the split is the same code.
  std::unique_ptr<hush::glsl::device> capped;
  hush::glsl::device* chosen = &headless().device;
  constexpr std::size_t kGl43MinGroups = 65535;
  if ((chosen->max_groups_per_dispatch() * hush::glsl::kLocalSize + 4096) * sizeof(float) >
      chosen->max_buffer_bytes()) {
    hush::glsl::device::options opt;
    opt.max_groups_per_dispatch = kGl43MinGroups;
    capped = std::make_unique<hush::glsl::device>(headless().context.loader(), opt);
    chosen = capped.get();
  }
  hush::glsl::device& dev = *chosen;
  const std::size_t per_dispatch = dev.max_groups_per_dispatch() * hush::glsl::kLocalSize;
  const std::size_t nx = 2048, ny = per_dispatch / nx + 2;
  const hush::grid<2> gr{{-7.25, 3.5}, {0.03, -0.01}, {nx, ny}};
  const std::size_t n = gr.count();
  REQUIRE(n * sizeof(float) <= dev.max_buffer_bytes());  // one batch
  std::vector<float> v(n);
  const hush::perlin<2> p(8);
  const std::size_t before = dev.dispatches();
  hush::evaluate_grid(p, hush::exec::glsl{dev}, gr, v);
  CHECK(dev.dispatches() - before == (n + per_dispatch - 1) / per_dispatch);
  // Spot checks across both dispatches, including the last sample.
  double max = 0;
  for (std::size_t i = n - 1; i < n; i = i >= 997 ? i - 997 : n) {
    const std::size_t row = i / nx;  // the grid's j index
    const hush::vec<double, 2> x{gr.origin[0] + gr.step[0] * double(i % nx),
                                 gr.origin[1] + gr.step[1] * double(row)};
    max = std::max(max, std::fabs(double(v[i]) - p(x)));
  }
  CHECK(max <= kValueBudget);
}

// ---- The device's contract around the context.

TEST_CASE("the device names the renderer and restores the caller's program and SSBO binding") {
  hush::glsl::device& dev = headless().device;
  CHECK(dev.renderer().find("OpenGL 4.") != std::string::npos);
  const gd::gl_api& gl = dev.gl();
  const gd::gl_program mine =
      gd::link_program(gl, {{gd::kGlComputeShader,
                             "#version 430 core\nlayout(local_size_x = 1) in;\nvoid main() {}\n"}});
  gd::gl_uint buf = 0;
  gl.GenBuffers(1, &buf);
  gl.UseProgram(mine.id());
  gl.BindBuffer(gd::kGlShaderStorageBuffer, buf);
  std::vector<hush::vec2> pts = {{0.5f, 0.5f}};
  std::vector<float> out(1);
  hush::evaluate(hush::perlin<2>(1), hush::exec::glsl{dev}, pts, out);
  gd::gl_int program = 0, binding = 0;
  gl.GetIntegerv(gd::kGlCurrentProgram, &program);
  gl.GetIntegerv(gd::kGlShaderStorageBufferBinding, &binding);
  CHECK(gd::gl_uint(program) == mine.id());
  CHECK(gd::gl_uint(binding) == buf);
  gl.UseProgram(0);
  gl.DeleteBuffers(1, &buf);
}

void* loader_without_dispatch(const char* name) {
  if (std::string(name) == "glDispatchCompute") return nullptr;
  return hush_glsl_test::headless().context.loader()(name);
}

TEST_CASE("a loader missing an entry point or a null loader is refused with the name") {
  headless();  // a current context
  try {
    hush::glsl::device dev{&loader_without_dispatch};
    FAIL("no exception");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()).find("glDispatchCompute") != std::string::npos);
  }
  CHECK_THROWS_AS(hush::glsl::device{nullptr}, std::runtime_error);
}

// ---- hush glsl-export.

#if defined(HUSH_CLI_EXE)
std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// (name, has a samples runner) of every program in the list.
template <class... Noise>
std::vector<std::pair<std::string, bool>> program_list(const std::tuple<Noise...>*) {
  return {{hush::glsl::noise_program<Noise>::name, hush::glsl::has_samples_runner<Noise>()}...};
}

TEST_CASE("hush glsl-export writes the library and runners, which compile") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(HUSH_GLSL_SCRATCH) / "export";
  fs::remove_all(dir);
  const std::string cmd = std::string("'") + HUSH_CLI_EXE + "' glsl-export '" + dir.string() +
                          "' > '" + HUSH_GLSL_SCRATCH + "/export.log' 2>&1";
  fs::create_directories(HUSH_GLSL_SCRATCH);
  REQUIRE(std::system(cmd.c_str()) == 0);
  const std::string lib = slurp(dir / "hush_noise.glsl");
  CHECK(lib.find("hush " HUSH_VERSION_STRING) != std::string::npos);
  CHECK_FALSE(has_version_directive(lib));
  for (const auto& k : hush::glsl::constant_table()) CHECK(lib.find(k.name) != std::string::npos);
  CHECK(lib.find("0x7feb352du") != std::string::npos);
  // The written library compiles in a fragment shader; each runner compiles and links.
  const gd::gl_api& gl = headless().device.gl();
  gd::link_program(
      gl,
      {{gd::kGlVertexShader,
        "#version 330 core\n" + lib +
            "void main() { gl_Position = vec4(hush_perlin2(vec2(0.5), 1u, uvec2(0u))); }\n"},
       {gd::kGlFragmentShader, "#version 330 core\n" + lib +
                                   "out vec4 c;\nvoid main() { c = "
                                   "hush_perlin3_gradient(gl_FragCoord.xyz, 1u, uvec3(0u)); }\n"}});
  const auto files = hush::glsl::export_files();
  // Every program's runners, named here rather than derived from program_noises, so that a
  // program the export drops (or the list loses) fails: points and grid, values and
  // gradients, for every noise; samples too for those that take per-sample inputs.
  const std::vector<std::pair<std::string, bool>> programs = {
      {"perlin2", false},         {"perlin3", false}, {"fractal_perlin2", false},
      {"fractal_perlin3", false}, {"wavelet2", true}, {"wavelet3", true},
      {"gabor2", true},           {"gabor3", true},   {"anisotropic", true}};
  CHECK(program_list(static_cast<const hush::glsl::program_noises*>(nullptr)) == programs);
  std::vector<std::string> expected = {"hush_noise.glsl", "hush_coherent_pass.comp",
                                       "hush_npr_gabor_splat.vert", "hush_npr_gabor_splat.geom",
                                       "hush_npr_gabor_splat.frag"};
  for (const char* pass : {"lods", "scan", "roots", "expand", "children", "records", "plan"})
    expected.push_back(std::string("hush_npr_gabor_") + pass + ".comp");
  for (const auto& [name, samples] : programs)
    for (const char* layout : {"points", "grid", "samples"})
      if (samples || std::string(layout) != "samples")
        for (const char* gradient : {"", "_gradient"})
          expected.push_back("hush_" + name + "_" + layout + gradient + ".comp");
  // The kits for the user's shader (hush/glsl/<noise>/shader.hpp), hush_<noise>..._shader.glsl.
  for (const char* kit :
       {"hush_perlin2_shader.glsl", "hush_perlin3_shader.glsl", "hush_fractal_perlin2_shader.glsl",
        "hush_fractal_perlin3_shader.glsl", "hush_wavelet2_shader.glsl", "hush_wavelet3_shader.glsl",
        "hush_gabor2_shader.glsl", "hush_gabor3_shader.glsl", "hush_anisotropic_shader.glsl"})
    expected.push_back(kit);
  std::vector<std::string> names;
  for (const auto& f : files) names.push_back(f.name);
  std::sort(expected.begin(), expected.end());
  std::sort(names.begin(), names.end());
  CHECK(names == expected);  // 67 files: 46 runners, 9 shader kits and the 12 others
  CHECK(names.size() == 67);
  for (const auto& f : files) {
    REQUIRE(fs::exists(dir / f.name));
    CHECK(slurp(dir / f.name) == f.content);
    if (f.name.size() > 5 && f.name.substr(f.name.size() - 5) == ".comp")
      gd::link_program(gl, {{gd::kGlComputeShader, slurp(dir / f.name)}});
  }
  gd::link_program(gl, {{gd::kGlVertexShader, slurp(dir / "hush_npr_gabor_splat.vert")},
                        {gd::kGlGeometryShader, slurp(dir / "hush_npr_gabor_splat.geom")},
                        {gd::kGlFragmentShader, slurp(dir / "hush_npr_gabor_splat.frag")}});
}

TEST_CASE("hush glsl-export exits 2 with one line for a missing or unusable DIR") {
  namespace fs = std::filesystem;
  const fs::path scratch = fs::path(HUSH_GLSL_SCRATCH) / "export_bad";
  fs::remove_all(scratch);
  fs::create_directories(scratch);
  { std::ofstream(scratch / "file") << "x"; }
  for (const std::string& args :
       {std::string(""), "'" + (scratch / "file").string() + "'",
        "'" + (scratch / "file" / "sub").string() + "'", std::string("a b")}) {
    const fs::path err = scratch / "err.txt";
    const std::string cmd = std::string("'") + HUSH_CLI_EXE + "' glsl-export " + args + " 2> '" +
                            err.string() + "' > /dev/null";
    const int status = std::system(cmd.c_str());
    CHECK_MESSAGE(WEXITSTATUS(status) == 2, args);
    const std::string msg = slurp(err);
    CHECK(std::count(msg.begin(), msg.end(), '\n') == 1);
    CHECK(msg.rfind("hush glsl-export: ", 0) == 0);
  }
}
#endif

}  // namespace
