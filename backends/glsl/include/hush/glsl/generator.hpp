// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The generated part of hush's GLSL: every number the shader bodies use,
// written at run time from the C++ constants (hush/detail/constants.hpp and
// the float-format facts of std::numeric_limits<float>), in the style of
// Filament's CodeGenerator. No number is typed twice: the GLSL block below is
// produced from constant_table(), the tests read back every entry from a
// shader and compare it bit for bit with the table, and they check that the
// hand-written bodies (hush/glsl/library.hpp) contain no other number.
//
// Exactness: a float constant is emitted as the shortest decimal of at most
// 9 significant digits that converts back to the same float (9 digits always
// suffice for IEEE binary32). A conforming compiler's conversion of that
// literal yields float(constant) bit for bit; even a compiler converting via
// double cannot double-round it, because such a decimal lies within 1e-9
// relative of the float and never near a rounding midpoint (2^-25 relative).
#ifndef HUSH_GLSL_GENERATOR_HPP
#define HUSH_GLSL_GENERATOR_HPP

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "hush/config.hpp"
#include "hush/core/bspline.hpp"
#include "hush/core/error.hpp"
#include "hush/core/footprint.hpp"
#include "hush/core/lattice.hpp"
#include "hush/detail/constants.hpp"

namespace hush {
namespace glsl {

// One generated GLSL constant: `const uint NAME = ...;` or `const float NAME = ...;`,
// or an array of them when values has more than one element.
struct glsl_constant {
  enum class type { u32, f32 };
  std::string name;                 // HUSH_*
  type kind;                        // GLSL uint or float
  bool array;                       // declared as NAME[values.size()]
  std::vector<std::uint32_t> bits;  // the uint values, or the floats' IEEE bit patterns
  std::string what;                 // one-line comment: where it comes from
};

namespace detail {

inline std::uint32_t float_bits(float f) {
  std::uint32_t u = 0;
  std::memcpy(&u, &f, sizeof u);
  return u;
}
inline float bits_float(std::uint32_t u) {
  float f = 0;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

inline glsl_constant uint_constant(const char* name, std::uint32_t v, const char* what) {
  return {name, glsl_constant::type::u32, false, {v}, what};
}
// Scalars and tables of floats: each double constant rounded to float once, as
// the CPU float path does (T(c) in perlin.hpp).
inline glsl_constant float_constant(const char* name, double v, const char* what) {
  return {name, glsl_constant::type::f32, false, {float_bits(static_cast<float>(v))}, what};
}
template <std::size_t N>
glsl_constant float_table(const char* name, const double (&v)[N], const char* what) {
  glsl_constant c{name, glsl_constant::type::f32, true, {}, what};
  for (std::size_t i = 0; i < N; ++i) c.bits.push_back(float_bits(static_cast<float>(v[i])));
  return c;
}

// A piecewise kernel of core/bspline.hpp as one flat table, piece after piece,
// coefficients in ascending powers.
template <int P, int O>
glsl_constant kernel_table(const char* name, const hush::detail::piecewise_kernel<P, O>& k,
                           const char* what) {
  glsl_constant c{name, glsl_constant::type::f32, true, {}, what};
  for (std::size_t p = 0; p < P; ++p)
    for (std::size_t j = 0; j < O; ++j) c.bits.push_back(float_bits(static_cast<float>(k.c[p][j])));
  return c;
}

// Wavelet noise (include/hush/wavelet.hpp, hush/glsl/wavelet/glsl.hpp): its kernels'
// piece tables and layout, quadrature and erf constants.
inline std::vector<glsl_constant> wavelet_constants() {
  namespace c = hush::detail::constants;
  namespace h = hush::detail;
  auto u = [](const char* name, int v, const char* what) {
    return uint_constant(name, static_cast<std::uint32_t>(v), what);
  };
  return {
      kernel_table("HUSH_BSPLINE_PIECES", h::kBspline, "quadratic B-spline B, 3 pieces"),
      kernel_table("HUSH_BSPLINE_DPIECES", h::kBsplineDerivative, "B', 3 pieces"),
      kernel_table("HUSH_BSPLINE2_PIECES", h::kBspline2, "B2(u) = B(u / 2) / 2, 6 pieces"),
      kernel_table("HUSH_BSPLINE2_DPIECES", h::kBspline2Derivative, "B2', 6 pieces"),
      kernel_table("HUSH_BETA_PIECES", h::kBeta, "beta = B * B2, the exact projection, 9 quintics"),
      kernel_table("HUSH_BETA_DPIECES", h::kBetaDerivative, "beta', 9 pieces"),
      u("HUSH_BSPLINE_ORDER", h::kBspline.order, "coefficients per piece of B"),
      u("HUSH_BSPLINE_PIECE_COUNT", h::kBspline.pieces, "pieces of B (its support)"),
      u("HUSH_BSPLINE2_PIECE_COUNT", h::kBspline2.pieces, "pieces of B2"),
      u("HUSH_BETA_ORDER", h::kBeta.order, "coefficients per piece of beta"),
      u("HUSH_BETA_PIECE_COUNT", h::kBeta.pieces, "pieces of beta"),
      float_constant("HUSH_BSPLINE_HALF_SUPPORT", h::kBspline.half_support(), "B's half support"),
      float_constant("HUSH_BSPLINE2_HALF_SUPPORT", h::kBspline2.half_support(),
                     "B2's half support"),
      float_constant("HUSH_BETA_HALF_SUPPORT", h::kBeta.half_support(), "beta's half support"),
      float_constant("HUSH_BETA_FIRST_TAP", h::fixed_kernel_first_tap<h::kBeta.pieces>(),
                     "first tap of beta along the normal"),
      u("HUSH_BETA_TAPS", h::fixed_kernel_taps<h::kBeta.pieces>(), "taps of beta"),
      float_constant("HUSH_BSPLINE2_FIRST_TAP", h::fixed_kernel_first_tap<h::kBspline2.pieces>(),
                     "first tap of B2 along the normal"),
      u("HUSH_BSPLINE2_TAPS", h::fixed_kernel_taps<h::kBspline2.pieces>(), "taps of B2"),
      u("HUSH_WAVELET_MAX_TAPS", h::kWaveletMaxTaps, "most taps of a kernel along one axis"),
      u("HUSH_WAVELET_MAX_KNOTS", c::kWaveletMaxKnots, "knots of the exact general projection"),
      uint_constant("HUSH_WAVELET_VARIANT_SHIFT", c::kWaveletVariantShift,
                    "tile variants: permutation = ((h >> s) * D!) >> s"),
      uint_constant("HUSH_WAVELET_PERMUTATIONS2", h::wavelet_permutations(2), "2!"),
      uint_constant("HUSH_WAVELET_PERMUTATIONS3", h::wavelet_permutations(3), "3!"),
      u("HUSH_WAVELET_ROW_PAD", c::kWaveletRowPad,
        "3D tile rows repeat their first coefficients (wavelet_tile::coefficients)"),
      float_constant("HUSH_WAVELET_CELL_OFFSET", c::kWaveletCellOffset,
                     "coefficient i sits at y = i; taps start at floor(y - offset)"),
      float_constant("HUSH_WAVELET_STRETCH", c::kWaveletProjectionStretch,
                     "projection: B stretched along the normal"),
      float_constant("HUSH_WAVELET_WIDEN_START", c::kWaveletWidenStart,
                     "widening starts at this coefficient spacing in pixels"),
      float_constant("HUSH_WAVELET_WIDEN_END", c::kWaveletWidenEnd,
                     "widening stops growing at this spacing in pixels"),
      float_constant("HUSH_FOOTPRINT_MAX_WIDTH", c::kFootprintMaxWidth,
                     "the widest footprint: filters everything"),
      float_constant("HUSH_THREE", static_cast<double>(hush::footprint<3>::dimension),
                     "the dimension of a 3D footprint (Smith's eigenvalue formula)"),
      {"HUSH_FLOAT_HUGE",
       glsl_constant::type::f32,
       false,
       {float_bits(std::numeric_limits<float>::max())},
       "the largest float, for open interval ends"},
      float_constant("HUSH_INV_SQRT2", c::kInvSqrt2, "1 / sqrt(2)"),
      float_constant("HUSH_INV_SQRT_2PI", c::kInvSqrt2Pi, "1 / sqrt(2 pi), the normal density"),
      u("HUSH_GAUSS_ORDER", c::kGaussLegendreOrder, "Gauss-Legendre nodes per piece"),
      float_table("HUSH_GAUSS_NODE", c::kGaussLegendreNode, "Gauss-Legendre nodes on [-1, 1]"),
      float_table("HUSH_GAUSS_WEIGHT", c::kGaussLegendreWeight, "Gauss-Legendre weights"),
      float_constant("HUSH_ERF_P", c::kErfP, "erf, Abramowitz & Stegun 7.1.26: p"),
      float_table("HUSH_ERF_A", c::kErfA, "erf, Abramowitz & Stegun 7.1.26: a1 ... a5"),
  };
}

}  // namespace detail

// Every constant of the generated GLSL block, in emission order. Values come
// from hush::detail::constants (the algorithms' numbers) and from
// std::numeric_limits<float> (the IEEE binary32 layout the lattice split's
// large-coordinate path decodes).
inline std::vector<glsl_constant> constant_table() {
  namespace c = hush::detail::constants;
  using detail::float_bits;
  using detail::float_constant;
  using detail::float_table;
  using detail::uint_constant;
  using flt = std::numeric_limits<float>;
  const std::uint32_t inf_bits = float_bits(flt::infinity());
  const std::uint32_t mantissa_bits = static_cast<std::uint32_t>(flt::digits - 1);
  std::vector<glsl_constant> table = {
      uint_constant("HUSH_HASH_SHIFT1", c::kHashShift1, "hash32 (lowbias32) first xor-shift"),
      uint_constant("HUSH_HASH_MUL1", c::kHashMul1, "hash32 first multiplier"),
      uint_constant("HUSH_HASH_SHIFT2", c::kHashShift2, "hash32 second xor-shift"),
      uint_constant("HUSH_HASH_MUL2", c::kHashMul2, "hash32 second multiplier"),
      uint_constant("HUSH_HASH_SHIFT3", c::kHashShift3, "hash32 third xor-shift"),
      uint_constant("HUSH_LATTICE_PRIME_X", c::kLatticePrimeX, "lattice fold multiplier, x"),
      uint_constant("HUSH_LATTICE_PRIME_Y", c::kLatticePrimeY, "lattice fold multiplier, y"),
      uint_constant("HUSH_LATTICE_PRIME_Z", c::kLatticePrimeZ, "lattice fold multiplier, z"),
      uint_constant("HUSH_LATTICE_ROTATE_Y", c::kLatticeRotateY, "lattice fold rotation, y"),
      uint_constant("HUSH_LATTICE_ROTATE_Z", c::kLatticeRotateZ, "lattice fold rotation, z"),
      uint_constant("HUSH_GOLDEN_GAMMA", c::kGoldenGamma, "seed/stream separation, 2^32/phi"),
      uint_constant("HUSH_WORD_BITS",
                    static_cast<std::uint32_t>(std::numeric_limits<std::uint32_t>::digits),
                    "bits of a hash word (rotations)"),
      float_constant("HUSH_FADE5", c::kFade5, "quintic fade s(t) = 6t^5 - 15t^4 + 10t^3"),
      float_constant("HUSH_FADE4", c::kFade4, "fade, t^4 coefficient"),
      float_constant("HUSH_FADE3", c::kFade3, "fade, t^3 coefficient"),
      float_constant("HUSH_FADE_DERIV4", 5 * c::kFade5, "fade derivative, t^4 coefficient"),
      float_constant("HUSH_FADE_DERIV3", 4 * c::kFade4, "fade derivative, t^3 coefficient"),
      float_constant("HUSH_FADE_DERIV2", 3 * c::kFade3, "fade derivative, t^2 coefficient"),
      float_table("HUSH_PERLIN2_GRAD_X", c::kPerlin2GradX, "2D gradients (unit, 45 degrees), x"),
      float_table("HUSH_PERLIN2_GRAD_Y", c::kPerlin2GradY, "2D gradients, y"),
      uint_constant("HUSH_PERLIN2_GRAD_SHIFT", c::kPerlin2GradShift, "2D index = hash >> shift"),
      float_table("HUSH_PERLIN3_GRAD_X", c::kPerlin3GradX, "3D gradients (cube edges), x"),
      float_table("HUSH_PERLIN3_GRAD_Y", c::kPerlin3GradY, "3D gradients, y"),
      float_table("HUSH_PERLIN3_GRAD_Z", c::kPerlin3GradZ, "3D gradients, z"),
      uint_constant("HUSH_PERLIN3_GRAD_COUNT", static_cast<std::uint32_t>(c::kPerlin3GradCount),
                    "3D gradient count"),
      uint_constant("HUSH_PERLIN3_INDEX_SHIFT", c::kPerlin3IndexShift,
                    "3D index = ((hash >> s) * count) >> s"),
      float_constant("HUSH_PERLIN2_SCALE", c::kPerlin2Scale, "2D output scale 1/B"),
      float_constant("HUSH_PERLIN3_SCALE", c::kPerlin3Scale, "3D output scale 1/B"),
      {"HUSH_ONE_MINUS_ULP",
       glsl_constant::type::f32,
       false,
       {float_bits(hush::detail::one_minus_ulp<float>())},
       "largest float below 1: the fraction's clamp (core/lattice.hpp)"},
      {"HUSH_INT_LIMIT",
       glsl_constant::type::f32,
       false,
       {float_bits(
           static_cast<float>(std::uint32_t(1) << std::numeric_limits<std::int32_t>::digits))},
       "2^31: cells below it in magnitude convert through int"},
      uint_constant("HUSH_FLOAT_EXP_MASK", inf_bits, "IEEE binary32 exponent field (bits of +inf)"),
      uint_constant("HUSH_FLOAT_EXP_FIELD", inf_bits >> mantissa_bits,
                    "exponent field after the shift"),
      uint_constant("HUSH_FLOAT_MANTISSA_BITS", mantissa_bits, "stored mantissa bits"),
      uint_constant("HUSH_FLOAT_MANTISSA_MASK", (std::uint32_t(1) << mantissa_bits) - 1u,
                    "stored mantissa field"),
      uint_constant("HUSH_FLOAT_EXP_BIAS", static_cast<std::uint32_t>(flt::max_exponent - 1),
                    "exponent bias"),
      uint_constant("HUSH_FLOAT_SIGN_MASK", float_bits(-0.0f), "sign bit (bits of -0.0)"),
      uint_constant("HUSH_FLOAT_QNAN", float_bits(flt::quiet_NaN()),
                    "quiet NaN returned for non-finite input"),
      float_constant("HUSH_FLOAT_MIN_NORMAL", static_cast<double>(flt::min()),
                     "smallest normal float (approx_math.hpp log2: -inf below)"),
      // Anisotropic noise (hush/anisotropic.hpp, hush/detail/approx_math.hpp).
      uint_constant("HUSH_ANISO_MAX_ORIENTATIONS",
                    static_cast<std::uint32_t>(c::kAnisoMaxOrientations),
                    "orientations of the steerable bank, at most"),
      uint_constant("HUSH_ANISO_MAX_SCALES", static_cast<std::uint32_t>(c::kAnisoMaxScales),
                    "scales of the steerable bank, at most"),
      float_table("HUSH_ANISO_EXP2", c::kAnisoSeries.exp2, "2^r on [-1/2, 1/2]: Taylor, degree 7"),
      float_table("HUSH_ANISO_LOG2", c::kAnisoSeries.log2, "log2: (2 / ln 2) atanh series in z^2"),
      float_table("HUSH_ANISO_SINPI", c::kAnisoSeries.sinpi, "sin(pi z) on [-1/2, 1/2], in z^2"),
      float_constant("HUSH_ANISO_SQRT2", c::kSqrt2, "log2's reduction to [sqrt(1/2), sqrt(2))"),
      float_constant("HUSH_ANISO_SIDE", c::kAnisoThreePointSide, "three-point rule: side weight"),
      float_constant("HUSH_ANISO_CENTRE", c::kAnisoThreePointCentre,
                     "three-point rule: centre weight"),
      float_constant("HUSH_ANISO_OFFSET", c::kAnisoThreePointOffset,
                     "three-point rule: offset in octaves"),
      // ---- Elementary functions (detail/elementary.hpp) and Gabor noise (gabor.hpp).
      float_constant("HUSH_LOG2E", c::kLog2E, "exp: log2(e)"),
      float_constant("HUSH_LN2_HI", c::kLn2Hi, "exp: ln 2, high part (9 bits)"),
      float_constant("HUSH_LN2_LO", c::kLn2Lo, "exp: ln 2 - high part"),
      float_constant("HUSH_EXP_FLOOR", c::kExpFloor, "exp: 0 below this argument"),
      uint_constant("HUSH_EXP_DEGREE", static_cast<std::uint32_t>(c::kExpDegree),
                    "exp: polynomial degree"),
      float_table("HUSH_EXP_POLY", c::kExpPoly, "exp: e^r coefficients, r^0 first"),
      uint_constant("HUSH_SIN_DEGREE", static_cast<std::uint32_t>(c::kSinDegree),
                    "sin(2 pi r) = r S(r^2): degree of S"),
      float_table("HUSH_SIN_POLY", c::kSinPoly, "sin: S coefficients"),
      uint_constant("HUSH_COS_DEGREE", static_cast<std::uint32_t>(c::kCosDegree),
                    "cos(2 pi r) = C(r^2): degree of C"),
      float_table("HUSH_COS_POLY", c::kCosPoly, "cos: C coefficients"),
      float_constant("HUSH_TURNS_REDUCE_LIMIT", c::kTurnsReduceLimit,
                     "sincos_turns: reduce t - floor(t) at and above this |t|"),
      float_constant("HUSH_TWO_PI", c::kTwoPi, "2 pi"),
      uint_constant("HUSH_GABOR_BYTE_BITS", c::kGaborByteBits, "Gabor marks: byte field width"),
      uint_constant("HUSH_GABOR_BYTE_MASK", c::kGaborByteMask, "Gabor marks: byte field mask"),
      float_constant("HUSH_GABOR_BYTE_SCALE", c::kGaborByteScale, "byte m -> (2m + 1) 2^-9"),
      uint_constant("HUSH_GABOR_HALF_BITS", c::kGaborHalfBits, "Gabor marks: half field width"),
      uint_constant("HUSH_GABOR_HALF_MASK", c::kGaborHalfMask, "Gabor marks: half field mask"),
      float_constant("HUSH_GABOR_HALF_SCALE", c::kGaborHalfScale, "half m -> (2m + 1) 2^-17"),
      uint_constant("HUSH_GABOR_SOLID_STREAM", c::kGaborSolidStream,
                    "Gabor: the cells' hush::rng stream (solid noise)"),
      uint_constant("HUSH_GABOR_SURFACE_STREAM", c::kGaborSurfaceStream,
                    "Gabor: the surface process's hush::rng stream"),
      float_constant("HUSH_GABOR_SURFACE_CELL", c::kGaborSurfaceCell,
                     "Gabor surface noise: kernel cells per surface cell, sqrt(3/2)"),
      float_constant("HUSH_GABOR_SURFACE_INV_H2",
                     (c::kGaborSurfaceCell / c::kGaborSurfaceSlab) *
                         (c::kGaborSurfaceCell / c::kGaborSurfaceSlab),
                     "Gabor surface noise: 1 / h^2 in surface cells"),
      uint_constant("HUSH_GABOR_JACOBI_SWEEPS", c::kGaborGlslJacobiSweeps,
                    "Gabor filtering: Jacobi sweeps at most"),
      float_constant("HUSH_GABOR_JACOBI_TOLERANCE", c::kGaborGlslJacobiTolerance,
                     "Gabor filtering: Jacobi stops below this off/diagonal energy"),
  };
  for (glsl_constant& k : detail::wavelet_constants()) table.push_back(std::move(k));
  return table;
}

// A GLSL literal equal to the constant: `16u` or `0x7feb352du` for uint; for
// float the integer with ".0" when the value is one (up to 2^32), else the
// shortest round-trip decimal (at most 9 significant digits) with a `.` or an
// exponent so it parses as float. Throws std::logic_error for a non-finite float.
inline std::string glsl_literal(glsl_constant::type kind, std::uint32_t bits) {
  char buf[48];
  if (kind == glsl_constant::type::u32) {
    // Shifts and counts read best in decimal, multipliers and masks in hex.
    std::snprintf(buf, sizeof buf, bits < 0x10000u ? "%uu" : "0x%08xu", bits);
    return buf;
  }
  const float f = detail::bits_float(bits);
  if (!std::isfinite(f)) hush::detail::raise_error<std::logic_error>("hush::glsl: non-finite float constant");
  if (std::floor(f) == f && std::fabs(f) <= 4294967296.0f) {
    std::snprintf(buf, sizeof buf, "%.1f", static_cast<double>(f));  // exact: "-15.0"
    return buf;
  }
  for (int digits = 1; digits <= 9; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, static_cast<double>(f));
    if (std::strtof(buf, nullptr) == f) break;
  }
  std::string s = buf;
  if (s.find_first_of(".eE") == std::string::npos) s += ".0";
  return s;
}

// The GLSL declaration block of constant_table(): one `const` per line with
// its origin as a comment. Valid in every stage under #version 330 core.
inline std::string constants_block() {
  std::string out = "// ---- Constants, generated by hush " HUSH_VERSION_STRING
                    " from hush/detail/constants.hpp (hush::glsl::constant_table()).\n";
  for (const glsl_constant& k : constant_table()) {
    const char* type = k.kind == glsl_constant::type::u32 ? "uint" : "float";
    const std::string n = std::to_string(k.bits.size());
    out += std::string("const ") + type + " " + k.name;
    if (k.array) {
      out.append("[").append(n).append("] = ").append(type).append("[").append(n).append("](");
      for (std::size_t i = 0; i < k.bits.size(); ++i)
        out += (i ? ", " : "") + glsl_literal(k.kind, k.bits[i]);
      out += ")";
    } else {
      out += " = " + glsl_literal(k.kind, k.bits[0]);
    }
    out += ";  // " + k.what + "\n";
  }
  return out;
}

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_GENERATOR_HPP
