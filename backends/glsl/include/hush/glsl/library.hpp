// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush's GLSL function library: the generated constants (generator.hpp)
// followed by hand-written bodies that reference only generated names. The
// text compiles in every shader stage under `#version 330 core` (no SSBOs,
// images or other 4.x features) and carries no #version line, so it can be
// pasted or #included after the application's own.
//
//   std::string src = "#version 330 core\n" + hush::glsl::library() + my_shader;
//
// Functions (all names hush_*; D = 2 or 3; key = hush::seed_key(seed) on the CPU,
// or hush_seed_key(seed) here; period = uvecD per axis, 0 = not periodic):
//   uint  hush_hash32(uint x), hush_hash32(uint a, uint b), hush_seed_key(uint seed)
//   uint  hush_rotl(uint x, uint r), hush_lattice_hash(uint key, uint i, uint j[, uint k])
//   hush_lattice_coord hush_lattice_split(float x, uint period)   {i0, i1, f}
//   float hush_fade(float t), hush_fade_derivative(float t), hush_lerp(float a, float b, float t)
//   float hush_perlin2(vec2 p, uint key, uvec2 period)          value in [-1, 1]
//   vec3  hush_perlin2_gradient(vec2 p, uint key, uvec2 period) (value, d/dx, d/dy)
//   float hush_perlin3(vec3 p, uint key, uvec3 period)
//   vec4  hush_perlin3_gradient(vec3 p, uint key, uvec3 period) (value, d/dx, d/dy, d/dz)
//   hush_perlinD_cells[_gradient](uvecD i0, uvecD i1, vecD f, uint key): the same
//   from an already split position (cells i0, i1 = i0 + 1 wrapped; fraction f).
//   bool  hush_any_nonfinite(vecD v)
//   float hush_fractal_add(float sum, float n, float w, bool turbulence)   sum + w n (or w |n|)
//   vecD+1 hush_fractal_add_gradient(acc, vecD+1 ng, float w, float chain, bool turbulence)
//   one band's term of a fractal sum (include/hush/fractal.hpp), the CPU's operations.
//   hush_wavelet_*: wavelet noise (include/hush/wavelet.hpp), present only where the
//   including shader defines HUSH_WAVELET_TILE(i) (hush/glsl/wavelet/glsl.hpp).
//   hush_exp_neg, hush_sincos_turns, hush_stream_key/word, hush_gabor_*: Gabor
//   noise's pieces (hush/glsl/gabor/program.hpp states them and their contract).
//
// Contract: the bodies mirror the CPU float algorithm (include/hush/perlin.hpp,
// core/hash.hpp, core/lattice.hpp) operation by operation: the same gradient
// index mapping, Horner fade, lerp a + t * (b - a), dot order and final scale.
//  - Hashes use 32-bit `uint` arithmetic only, which GLSL defines modulo 2^32:
//    hush_hash32 and hush_lattice_hash equal the CPU's bit for bit.
//  - The lattice split of a float coordinate is exact (floor, x - floor(x) and
//    the cell modulo 2^32 or the period, also for |x| >= 2^31), so cells and
//    fractions equal the CPU's hush::lattice_split<float> of the same float.
//  - The remaining float arithmetic follows the CPU's order. GLSL lets the
//    compiler fuse a * b + c into one fma (no `precise` before 4.00), GLSL
//    4.x asks only that +, -, * be correctly rounded (3.30 states no operation
//    precision at all), and many GPUs flush denormals to zero. The forward
//    error analysis behind the CPU's 2^-16 budget bounds each op's rounding by
//    2^-24 relative, which a fused op also meets: with correctly rounded ops
//    (llvmpipe) values are within 2^-16 of the double reference and 2^-15 of
//    the CPU float result; a GPU whose ops err by up to 2 ulp doubles both
//    (2^-15, 2^-14). Gradients: the same times (1 + the noise's Lipschitz
//    bound). Denormal flushing only changes results below 1.2e-38 in
//    magnitude, and the split of a denormal coordinate (cell 0 or -1) on such
//    GPUs. Measured on llvmpipe: tests/glsl/glsl_test.cpp, hush/glsl/device.hpp.
//  - NaN or +-Inf in any coordinate gives NaN in every output component (the
//    point functions test the exponent bits, so fast-math folding cannot lose it).
#ifndef HUSH_GLSL_LIBRARY_HPP
#define HUSH_GLSL_LIBRARY_HPP

#include <string>

#include "hush/glsl/generator.hpp"

// Each noise's bodies, detail::noise_bodies(): the library part of the GLSL layer's list
// of noises.
#define HUSH_GLSL_NOISES_LIBRARY
#include "hush/glsl/noises.hpp"
#undef HUSH_GLSL_NOISES_LIBRARY

namespace hush {
namespace glsl {
namespace detail {

// Hashing: core/hash.hpp, operation by operation.
constexpr const char* kHashBody = R"glsl(
// ---- Hashing (core/hash.hpp): 32-bit uint arithmetic only, equal to the CPU bit for bit.
uint hush_hash32(uint x) {
  x ^= x >> HUSH_HASH_SHIFT1;
  x *= HUSH_HASH_MUL1;
  x ^= x >> HUSH_HASH_SHIFT2;
  x *= HUSH_HASH_MUL2;
  x ^= x >> HUSH_HASH_SHIFT3;
  return x;
}
uint hush_hash32(uint a, uint b) { return hush_hash32(hush_hash32(a + HUSH_GOLDEN_GAMMA) ^ b); }
uint hush_seed_key(uint seed) { return hush_hash32(seed + HUSH_GOLDEN_GAMMA); }
uint hush_rotl(uint x, uint r) { return (x << r) | (x >> (HUSH_WORD_BITS - r)); }
uint hush_lattice_hash(uint key, uint i, uint j) {
  return hush_hash32(key ^ (i * HUSH_LATTICE_PRIME_X) ^
                     hush_rotl(j * HUSH_LATTICE_PRIME_Y, HUSH_LATTICE_ROTATE_Y));
}
uint hush_lattice_hash(uint key, uint i, uint j, uint k) {
  return hush_hash32(key ^ (i * HUSH_LATTICE_PRIME_X) ^
                     hush_rotl(j * HUSH_LATTICE_PRIME_Y, HUSH_LATTICE_ROTATE_Y) ^
                     hush_rotl(k * HUSH_LATTICE_PRIME_Z, HUSH_LATTICE_ROTATE_Z));
}
)glsl";

// The lattice split: core/lattice.hpp for a float coordinate.
constexpr const char* kLatticeBody = R"glsl(
// ---- Lattice split (core/lattice.hpp).
bool hush_is_nonfinite(float x) {
  return (floatBitsToUint(x) & HUSH_FLOAT_EXP_MASK) == HUSH_FLOAT_EXP_MASK;
}
float hush_nan() { return uintBitsToFloat(HUSH_FLOAT_QNAN); }
// floor(x) modulo the period (0: modulo 2^32) for an integral finite float fl.
// |fl| < 2^31 converts through int; beyond, fl = m * 2^e with a 24-bit m and
// e >= 8 is decoded from its bits and reduced exactly (m << e wraps mod 2^32;
// mod a period, e doublings mod p), like the CPU's exact fmod.
uint hush_floor_mod(float fl, uint period) {
  if (abs(fl) < HUSH_INT_LIMIT) {
    int i = int(fl);
    if (period == 0u) return uint(i);  // two's complement: i mod 2^32
    uint r = uint(abs(i)) % period;
    return (i < 0 && r != 0u) ? period - r : r;
  }
  uint b = floatBitsToUint(fl);
  uint e = ((b >> HUSH_FLOAT_MANTISSA_BITS) & HUSH_FLOAT_EXP_FIELD) -
           (HUSH_FLOAT_EXP_BIAS + HUSH_FLOAT_MANTISSA_BITS);
  uint m = (b & HUSH_FLOAT_MANTISSA_MASK) | (1u << HUSH_FLOAT_MANTISSA_BITS);
  uint r;
  if (period == 0u) {
    r = e >= HUSH_WORD_BITS ? 0u : m << e;
  } else {
    r = m % period;
    for (uint s = 0u; s < e; ++s) {  // period <= 2^31 - 1, so r << 1 cannot overflow
      r <<= 1u;
      if (r >= period) r -= period;
    }
  }
  if ((b & HUSH_FLOAT_SIGN_MASK) == 0u || r == 0u) return r;
  return period == 0u ? 0u - r : period - r;
}
struct hush_lattice_coord {
  uint i0;  // floor(x) modulo 2^32 (or the period)
  uint i1;  // the next cell, wrapped the same way
  float f;  // x - floor(x) in [0, 1); NaN when x is not finite
};
hush_lattice_coord hush_lattice_split(float x, uint period) {
  hush_lattice_coord c;
  if (hush_is_nonfinite(x)) {
    c.i0 = 0u;
    c.i1 = period == 1u ? 0u : 1u;
    c.f = hush_nan();
    return c;
  }
  float fl = floor(x);
  c.f = min(x - fl, HUSH_ONE_MINUS_ULP);  // exact difference; rounds to 1 only for tiny negative x
  c.i0 = hush_floor_mod(fl, period);
  c.i1 = c.i0 + 1u;
  if (period != 0u && c.i1 == period) c.i1 = 0u;
  return c;
}
)glsl";

}  // namespace detail

// The hand-written bodies, in order: hashing and the lattice split, then each noise's
// (hush/glsl/<noise>/glsl.hpp, in the order of the list of noises, hush/glsl/noises.hpp);
// tests check they hold no numeric literal besides the 2^D-cell structure integers
// (0, 1, 2, 4, 8).
inline std::string library_bodies() {
  return std::string(detail::kHashBody) + detail::kLatticeBody + detail::noise_bodies();
}

// The whole function library: a header comment naming the hush version, the
// generated constants, then the bodies. No #version line.
inline std::string library() {
  return "// hush " HUSH_VERSION_STRING
         " GLSL function library (generated; #version 330 core or later, any stage).\n" +
         constants_block() + library_bodies();
}

namespace detail {

// The generated constants and the library, each once per shader however many kits for the
// user's shader (hush/glsl/shader.hpp) it holds: every kit starts with what it needs of them,
// under these guards, so kits combine in one shader.
inline std::string constants_once() {
  return "#ifndef HUSH_GLSL_CONSTANTS\n#define HUSH_GLSL_CONSTANTS\n" + constants_block() +
         "#endif  // HUSH_GLSL_CONSTANTS\n";
}
inline std::string library_once() {
  return constants_once() + "#ifndef HUSH_GLSL_LIBRARY\n#define HUSH_GLSL_LIBRARY\n" +
         library_bodies() + "#endif  // HUSH_GLSL_LIBRARY\n";
}

}  // namespace detail

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_LIBRARY_HPP
