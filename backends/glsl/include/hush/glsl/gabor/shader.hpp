// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Gabor noise (include/hush/gabor.hpp; Lagae et al. 2009) inside the user's own shader:
// shader_for(gabor<D>) returns a kit (hush/glsl/shader.hpp) whose functions run the whole
// sparse convolution per invocation: the split of p / r into cell and fraction, each of the
// 3^D cells' impulse streams (hush::rng of lattice_hash(key, cell), the Poisson count from
// the CPU's poisson_table thresholds, the marks), the kernel sum and the unit-variance
// scale; filtered over the pixel's footprint from the shader's own dFdx / dFdy (paper
// sec. 5), and in 3D surface noise with a normal (sec. 4.3). The walk is hush's batch
// runner's (hush/glsl/gabor/walk.hpp, one text for both), and its data (float constants,
// Poisson thresholds) come from the same functions (gabor_par_words, gabor_table_words).
//
//   hush::gabor<2> noise{prm};
//   const hush::glsl::shader_kit kit = hush::glsl::shader_for(noise);
//   fs = "#version 430 core\n" + kit.source + "... hush_gabor2_filtered(p, dFdx(p), dFdy(p)) ...";
//   // one resource: the std140 block hush_gabor_params at HUSH_GABOR_PARAMS_BINDING (4)
//
// GLSL functions (D = 2 or 3; p in noise units; dpdx, dpdy: noise units per pixel, the
// shader's dFdx(p), dFdy(p) or any Jacobian columns; gradients d/dp in noise units):
//   float hush_gaborD(vecD p)                            noise(p): the point form
//   vec(D+1) hush_gaborD_gradient(vecD p)                (value, gradient)
//   float hush_gaborD_filtered(vecD p, vecD dpdx, vecD dpdy)
//                                  sample(p, footprint<D>::from_derivatives(dpdx, dpdy))
//   vec(D+1) hush_gaborD_filtered_gradient(vecD p, vecD dpdx, vecD dpdy)
//   float hush_gaborD_cell(uvecD cell, vecD f)           noise at (cell + f) r: the engine
//                                                        splits p / r itself (exact cells)
//   3D only, surface noise (gabor<3>::sample(p, normal[, footprint])):
//   float hush_gabor3_surface(vec3 p, vec3 n)
//   float hush_gabor3_surface_filtered(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy)
//   vec4  hush_gabor3_surface_gradient(p, n)
//   vec4  hush_gabor3_surface_filtered_gradient(p, n, dpdx, dpdy)
//
// Contract:
//  - The same impulses as the CPU: cells, hash streams, Poisson counts and marks are integer
//    computations equal bit for bit, and every mark field becomes a float exactly. Every
//    kind (isotropic, anisotropic, hybrid: the orientation and frequency ranges) and every
//    parameter the CPU accepts are covered; the kit's source depends only on D, parameters
//    are the block's words.
//  - Precision against the double reference gabor<D> (value): with x = max_i |p_i| / r
//    (r = kernel radius, 1 / inverse_cell()),
//      |GLSL - double| <= scale (N' + 1) [2^-21 (1 + 2 pi Phi)
//                                         + (2^-24 + 2^-33 x) (2A + 2 pi Phi + k)]
//    (Phi = |F| r, the largest cell frequency; A = the envelope exponent; k = 3 / (1 - s0),
//    the taper's slope): the first term is gabor.hpp's float budget (the walk repeats the
//    CPU's float operations), the second the split of p / r in float (hush_gabor_split: the
//    fraction within 2^-24 + 2^-33 x, times the kernel's slope per cell). Filtered values: the
//    first term times (1 + 2 pi Phi + pi^2 Phi^2 / A) for the float filter (Jacobi in float).
//    Gradients: each bound times (1 + (2A + 2 pi Phi + k) / r). Surface noise: the same
//    with surface_scale, plus the float tangent frame's error (tests/gabor/
//    glsl_gabor_test.cpp frame_error). Tested for x <= 2^20 (tests/gabor/
//    glsl_gabor_shader_test.cpp); the split term grows with x (and float p itself is
//    coarser than the noise beyond x ~ 2^22): engines with larger coordinates split p / r
//    themselves (in double or camera-relative) and call hush_gaborD_cell, whose bound is the
//    first term at any cell, or use hush::evaluate with exec::glsl (the CPU split). On GPUs
//    whose +, -, * err by up to 2 ulp, twice.
//  - NaN or +-Inf in p gives NaN; every footprint (zero, rank 1, NaN, huge) a finite value,
//    as on the CPU (a non-finite derivative is the largest footprint, about 0). Surface:
//    a zero normal gives the solid noise (filtered), a non-finite one NaN.
//  - One Gabor kit per shader program (2D or 3D: the two define the same helper names).
//  - GLSL 4.30 core, Vulkan 450 (set HUSH_DESCRIPTOR_SET) and GLSL ES 3.00 (one uniform
//    block, no textures or buffers; bound by name there).
#ifndef HUSH_GLSL_GABOR_SHADER_HPP
#define HUSH_GLSL_GABOR_SHADER_HPP

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hush/detail/constants.hpp"
#include "hush/gabor.hpp"
#include "hush/glsl/gabor/walk.hpp"
#include "hush/glsl/library.hpp"
#include "hush/glsl/shader.hpp"

namespace hush {
namespace glsl {
namespace detail {

constexpr unsigned kGaborParamsBinding = 4;
constexpr const char* kGaborParamsMacro = "HUSH_GABOR_PARAMS_BINDING";

// The split of p / r (hush_gabor_split): 1 / r = c_hi + c_lo with c_hi's low
// kGaborSplitLowBits mantissa bits cleared (12 significant bits), p's high part masked the
// same way, so that p_hi c_hi and (p - p_hi) c_hi are exact float products (24 bits).
constexpr int kGaborSplitLowBits = 12;
constexpr std::uint32_t kGaborSplitMask = ~((std::uint32_t(1) << kGaborSplitLowBits) - 1u);
// (c_hi, c_lo) of c = 1 / cell side.
inline std::pair<float, float> gabor_split_pair(double c) {
  const float hi = bits_float(float_word(float(c)) & kGaborSplitMask);
  return {hi, float(c - double(hi))};
}

// uvec4 slots of the block's constants and thresholds.
constexpr int gabor_par_slots() { return (gabor_par::kCount + 3) / 4; }
template <int D>
constexpr int gabor_table_slots() {
  return gabor_table_entries<D>() / 4;
}

// The kit's entry points, for dimension dim: the split of p / r, the footprint, surface.
inline std::string gabor_shader_entries(int dim) {
  std::string s = R"glsl(
// footprint<D>::from_derivatives in float: S = dpdx dpdx^T + dpdy dpdy^T (noise units);
// columns beyond the cap W scaled to it, entries beyond W^2 scaled to it; non-finite: W^2 I.
mat3 hush_gabor_footprint(vec3 dx, vec3 dy) {
  float w = hush_gabor_max_width, m = 0.0;
  bool bad = false;
  mat3 s = mat3(0.0);
  for (uint a = 0u; a < hush_gabor_dim; ++a) {
    bad = bad || hush_is_nonfinite(dx[a]) || hush_is_nonfinite(dy[a]);
    m = max(m, max(abs(dx[a]), abs(dy[a])));
  }
  if (bad) {
    for (uint a = 0u; a < hush_gabor_dim; ++a) s[a][a] = w * w;
    return s;
  }
  float k = m > w ? w / m : 1.0, big = 0.0;
  for (uint r = 0u; r < hush_gabor_dim; ++r)
    for (uint c = 0u; c < hush_gabor_dim; ++c) {
      s[c][r] = (k * dx[r]) * (k * dx[c]) + (k * dy[r]) * (k * dy[c]);
      big = max(big, abs(s[c][r]));
    }
  if (big > w * w) s *= (w * w) / big;
  return s;
}
// p c (c = 1 / cell side = c.x + c.y, c.x with 12 significant bits) split into cell i0 and
// fraction f without rounding the product: p = hi + (p - hi) with hi p's high 12 bits, so
// hi c.x and (p - hi) c.x are exact, and p c.y is ~2^-11 of the whole. The fraction is
// within 2^-24 + 2^-33 |p c| of the exact one, whatever the compiler fuses (fusing an
// exact product changes nothing). False for a non-finite p.
bool hush_gabor_split(float p, vec2 c, out uint i0, out float f) {
  i0 = 0u;
  f = 0.0;
  if (hush_is_nonfinite(p)) return false;
  float hi = uintBitsToFloat(floatBitsToUint(p) & hush_gabor_split_mask);
  hush_lattice_coord a = hush_lattice_split(hi * c.x, 0u);
  if (hush_is_nonfinite(a.f)) return false;
  float g = a.f + ((p - hi) * c.x + p * c.y);
  float k = floor(g);
  f = min(g - k, HUSH_ONE_MINUS_ULP);
  i0 = a.i0 + uint(int(k));
  return true;
}
// The solid noise (value, gradient) at p: p / r split (hush_gabor_split), the point form or,
// `filtered`, the filtered kernels of footprint fp.
vec4 hush_gabor_at(vec3 p, bool filtered, mat3 fp, bool grad) {
  uvec3 i0 = uvec3(0u);
  vec3 f = vec3(0.0);
  for (uint a = 0u; a < hush_gabor_dim; ++a) {
    uint i;
    float fa;
    if (!hush_gabor_split(p[a], hush_gabor_inv_cell.xy, i, fa)) return vec4(hush_nan());
    i0[a] = i;
    f[a] = fa;
  }
  return hush_gabor_eval(i0, f, false, filtered, fp, grad);
}
)glsl";
  if (dim == 2) {
    s += R"glsl(float hush_gabor2(vec2 p) {
  return hush_gabor_at(vec3(p, 0.0), false, mat3(0.0), false).x;
}
vec3 hush_gabor2_gradient(vec2 p) {
  return hush_gabor_at(vec3(p, 0.0), false, mat3(0.0), true).xyz;
}
float hush_gabor2_filtered(vec2 p, vec2 dpdx, vec2 dpdy) {
  mat3 fp = hush_gabor_footprint(vec3(dpdx, 0.0), vec3(dpdy, 0.0));
  return hush_gabor_at(vec3(p, 0.0), true, fp, false).x;
}
vec3 hush_gabor2_filtered_gradient(vec2 p, vec2 dpdx, vec2 dpdy) {
  mat3 fp = hush_gabor_footprint(vec3(dpdx, 0.0), vec3(dpdy, 0.0));
  return hush_gabor_at(vec3(p, 0.0), true, fp, true).xyz;
}
float hush_gabor2_cell(uvec2 cell, vec2 f) {
  return hush_gabor_eval(uvec3(cell, 0u), vec3(f, 0.0), false, false, mat3(0.0), false).x;
}
)glsl";
    return s;
  }
  s += R"glsl(float hush_gabor3(vec3 p) { return hush_gabor_at(p, false, mat3(0.0), false).x; }
vec4 hush_gabor3_gradient(vec3 p) { return hush_gabor_at(p, false, mat3(0.0), true); }
float hush_gabor3_filtered(vec3 p, vec3 dpdx, vec3 dpdy) {
  return hush_gabor_at(p, true, hush_gabor_footprint(dpdx, dpdy), false).x;
}
vec4 hush_gabor3_filtered_gradient(vec3 p, vec3 dpdx, vec3 dpdy) {
  return hush_gabor_at(p, true, hush_gabor_footprint(dpdx, dpdy), true);
}
float hush_gabor3_cell(uvec3 cell, vec3 f) {
  return hush_gabor_eval(cell, f, false, false, mat3(0.0), false).x;
}
// Surface noise (gabor<3>::sample_eval with a normal): a non-finite normal gives NaN, a zero
// one the solid noise; else p / (r sqrt(3/2)) split (hush_gabor_split) and the tangent-plane
// sum.
vec4 hush_gabor_surface_at(vec3 p, vec3 n, mat3 fp, bool grad) {
  if (hush_any_nonfinite(n)) return vec4(hush_nan());
  vec3 u;
  if (!hush_gabor_unit_normal(n, u)) return hush_gabor_at(p, true, fp, grad);
  uvec3 i0;
  vec3 f;
  for (uint a = 0u; a < 3u; ++a) {
    uint i;
    float fa;
    if (!hush_gabor_split(p[a], hush_gabor_inv_cell.zw, i, fa)) return vec4(hush_nan());
    i0[a] = i;
    f[a] = fa;
  }
  return hush_gabor_surface_eval(i0, f, u, fp, grad);
}
float hush_gabor3_surface(vec3 p, vec3 n) {
  return hush_gabor_surface_at(p, n, mat3(0.0), false).x;
}
vec4 hush_gabor3_surface_gradient(vec3 p, vec3 n) {
  return hush_gabor_surface_at(p, n, mat3(0.0), true);
}
float hush_gabor3_surface_filtered(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy) {
  return hush_gabor_surface_at(p, n, hush_gabor_footprint(dpdx, dpdy), false).x;
}
vec4 hush_gabor3_surface_filtered_gradient(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy) {
  return hush_gabor_surface_at(p, n, hush_gabor_footprint(dpdx, dpdy), true);
}
)glsl";
  return s;
}

// The kit's GLSL for dimension dim: prelude, hush's library (once per shader), the block,
// its accessors, the walk and the entry points.
inline std::string gabor_shader_source(int dim) {
  const int table_slots = (dim == 3 ? gabor_table_slots<3>() : gabor_table_slots<2>());
  return std::string(kShaderPrelude) + detail::library_once() +
         resource_layout(kGaborParamsMacro, kGaborParamsBinding, "std140") +
         "uniform hush_gabor_params {\n"
         "  uint hush_gabor_key;                 // seed_key(seed)\n"
         "  uint hush_gabor_kind;                // 0 isotropic, 1 anisotropic, 2 hybrid\n"
         "  uint hush_gabor_words;               // stream words per impulse\n"
         "  uint hush_gabor_table_size;          // solid Poisson thresholds\n"
         "  uint hush_gabor_surface_table_size;  // surface Poisson thresholds (3D)\n"
         "  uint hush_gabor_split_mask;          // clears a float's low 12 mantissa bits\n"
         "  float hush_gabor_max_width;          // footprint's cap W\n"
         "  vec4 hush_gabor_inv_cell;  // 1 / r, 1 / (r sqrt(3/2)) (3D), each as (high 12 bits, "
         "rest)\n"
         "  uvec4 hush_gabor_par[" +
         std::to_string(gabor_par_slots()) +
         "];     // float bits of the CPU's float constants\n"
         "  uvec4 hush_gabor_table[" +
         std::to_string(table_slots) + "];  // Poisson thresholds (3D: surface table at " +
         std::to_string(hush::detail::constants::kGaborMaxThresholds) +
         ")\n};\n"
         "float hush_gp(uint i) { return uintBitsToFloat(hush_gabor_par[i >> 2u][i & 3u]); }\n"
         "uint hush_gabor_threshold(uint i) { return hush_gabor_table[i >> 2u][i & 3u]; }\n" +
         gabor_walk_body(dim) + gabor_shader_entries(dim);
}

inline std::string gabor_shader_usage(int dim) {
  const std::string d = std::to_string(dim), v = "vec" + d, g = "vec" + std::to_string(dim + 1);
  std::string s =
      "// hush Gabor noise " + d +
      "D in your shader (hush/glsl/gabor/shader.hpp). p in noise units; dpdx, dpdy = dFdx(p),\n"
      "// dFdy(p) or a Jacobian's columns; gradients d/dp.\n"
      "//   float hush_gabor" +
      d + "(" + v + " p); " + g + " hush_gabor" + d + "_gradient(" + v +
      " p)\n"
      "//   float hush_gabor" +
      d + "_filtered(" + v + " p, " + v + " dpdx, " + v + " dpdy); " + g + " hush_gabor" + d +
      "_filtered_gradient(...)\n"
      "//   float hush_gabor" +
      d + "_cell(uvec" + d + " cell, " + v +
      " f): the noise at (cell + f) r, cells split by the engine\n";
  if (dim == 3)
    s += "//   float hush_gabor3_surface(vec3 p, vec3 n), hush_gabor3_surface_filtered(p, n, dpdx, "
         "dpdy);\n"
         "//   vec4 hush_gabor3_surface_gradient(p, n), hush_gabor3_surface_filtered_gradient(p, "
         "n, dpdx, dpdy)\n";
  s += "// Resource: uniform block hush_gabor_params (std140) at HUSH_GABOR_PARAMS_BINDING "
       "(default 4).\n"
       "// Error against hush's double reference, x = max |p_i| / r:\n"
       "//   scale (N' + 1) [2^-21 (1 + 2 pi Phi) + (2^-24 + 2^-33 x) (2A + 2 pi Phi + 3 / (1 - "
       "s0))]\n"
       "// (filtered: first term times 1 + 2 pi Phi + pi^2 Phi^2 / A), tested for x <= 2^20;\n"
       "// _cell: the first term at any cell. NaN p gives NaN. One Gabor kit per program.\n";
  return s;
}

template <int D>
shader_kit gabor_kit(const gabor<D>& g) {
  std140_writer w;
  w.u(g.key())
      .u(static_cast<std::uint32_t>(g.marks().kind()))
      .u(static_cast<std::uint32_t>(g.words_per_impulse()))
      .u(static_cast<std::uint32_t>(g.table().thresholds().size()));
  if constexpr (D == 3)
    w.u(static_cast<std::uint32_t>(g.surface_table().thresholds().size()));
  else
    w.u(0u);
  w.u(kGaborSplitMask);
  w.f(float(hush::detail::constants::kFootprintMaxWidth));
  const auto solid = gabor_split_pair(g.inverse_cell());
  std::pair<float, float> surface{0.0f, 0.0f};
  if constexpr (D == 3) surface = gabor_split_pair(g.inverse_surface_cell());
  w.vec4(solid.first, solid.second, surface.first, surface.second);
  const auto par = gabor_par_words(g);
  for (int i = 0; i < gabor_par_slots() * 4; i += 4) {
    std::uint32_t q[4] = {};
    for (int k = 0; k < 4; ++k) q[k] = i + k < gabor_par::kCount ? par[static_cast<std::size_t>(i) + static_cast<std::size_t>(k)] : 0u;
    w.uvec4(q[0], q[1], q[2], q[3]);
  }
  const auto table = gabor_table_words(g);
  for (std::size_t i = 0; i < table.size(); i += 4)
    w.uvec4(table[i], table[i + 1], table[i + 2], table[i + 3]);
  shader_resource block;
  block.name = "hush_gabor_params";
  block.kind = resource_kind::uniform_block;
  block.binding = kGaborParamsBinding;
  block.binding_macro = kGaborParamsMacro;
  block.layout =
      "std140: uint key, kind, words, table_size, surface_table_size, split_mask; float "
      "max_width (bytes 0-27); vec4 inv_cell (32: 1 / r and 3D 1 / (r sqrt(3/2)), each as "
      "high 12 bits and rest); uvec4 par[" +
      std::to_string(gabor_par_slots()) + "] (float bits, detail::gabor_par); uvec4 table[" +
      std::to_string(gabor_table_slots<D>()) + "] (poisson_table thresholds)";
  block.words = w.words();
  shader_kit kit;
  kit.source = gabor_shader_source(D);
  kit.resources = {block};
  kit.versions = "430 core, Vulkan 450, 300 es";
  kit.usage = gabor_shader_usage(D);
  return kit;
}

}  // namespace detail

// Gabor noise's functions for the user's shader and its parameter block (file comment).
inline shader_kit shader_for(const gabor<2>& noise) { return detail::gabor_kit(noise); }
inline shader_kit shader_for(const gabor<3>& noise) { return detail::gabor_kit(noise); }

// The kit sources for `hush glsl-export` (they depend on D only): usage comment, then source.
inline std::vector<std::pair<std::string, std::string>> gabor_shader_exports() {
  std::vector<std::pair<std::string, std::string>> files;
  for (int d : {2, 3})
    files.emplace_back("hush_gabor" + std::to_string(d) + "_shader.glsl",
                       detail::gabor_shader_usage(d) + detail::gabor_shader_source(d));
  return files;
}

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_GABOR_SHADER_HPP
