// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Wavelet noise (include/hush/wavelet.hpp, Cook & DeRose 2005) in the user's own shader
// (hush/glsl/shader.hpp). shader_for(wavelet<D>) returns a kit whose functions take what a
// shader has: the position, for footprints the shader's own dFdx(p), dFdy(p) (or the
// covariance S = J J^T of the pixel's footprint), and in 3D the surface normal:
//
//   float hush_wavelet2(vec2 p)                                   all bands, no footprint
//   vec3  hush_wavelet2_gradient(vec2 p)                          (value, d/dx, d/dy)
//   float hush_wavelet2_filtered(vec2 p, vec2 dpdx, vec2 dpdy)    wavelet::sample(p, footprint)
//   vec3  hush_wavelet2_filtered_gradient(vec2 p, vec2 dpdx, vec2 dpdy)
//   vec4  hush_wavelet2_eval(vec2 p, mat2 S)                      (value, gradient, 0), S explicit
//   float hush_wavelet3(vec3 p),  vec4 hush_wavelet3_gradient(vec3 p)
//   float hush_wavelet3_filtered(vec3 p, vec3 dpdx, vec3 dpdy)
//   vec4  hush_wavelet3_filtered_gradient(vec3 p, vec3 dpdx, vec3 dpdy)
//   float hush_wavelet3_projected(vec3 p, vec3 n)                 sample(p, normal): sec. 3.7
//   float hush_wavelet3_projected_filtered(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy)
//   vec4  hush_wavelet3_eval(vec3 p, mat3 S, bool has_normal, vec3 n)  (value, gradient)
//
// Every mode of wavelet<D>::params runs in the shader: band weights (multiband), the
// footprint fade (the CPU's make_plan: largest footprint width, fade per band), infinite
// noise (relative_weights), basis widening, projection (exact or approximate), tile
// variants and the three distributions. The kit's source depends on D only; the parameters
// are in a std140 block, the data in textures read with texelFetch:
//   hush_waveletD_params  block    (binding 24 / 28): the CPU's plan inputs per band
//   hush_waveletD_tile    sampler  (25 / 29): R32F n x n (2D) or n x n x n (3D) texture, the
//                                  tile's coefficients (wavelet_tile::coefficient(i))
//   hush_waveletD_blend   sampler  (26 / 30): the same shape, the tile-variant tile
//                                  (wavelet_blend_tile), 1 texel when variant_overlap = 0
//   hush_waveletD_table   sampler  (27 / 31): R32F 2D, the distribution table, 256 entries a
//                                  row (kWaveletTableTextureWidth), 1 texel when unused
// The functions read the tile through the library's HUSH_WAVELET_TILE_AT hook
// (hush/glsl/wavelet/glsl.hpp): the B-spline sums, projections and remapping are the
// library's bodies, the ones hush's own runner executes. One wavelet kit (2D or 3D) per
// shader program; it may share the shader with the Perlin and fractal kits.
//
// Texture sizes: tiles are at most 2048^2 (2D) and 128^3 (3D), within GL_MAX_TEXTURE_SIZE
// (>= 16384 in GL 4.3, 2048 in ES 3.00) and GL_MAX_3D_TEXTURE_SIZE (>= 2048 in GL 4.3,
// 256 in ES 3.00): every tile size hush accepts fits every dialect. GLSL: 430 core,
// Vulkan 450, 300 es.
//
// Precision. The band positions are formed on the GPU: y_b = p 2^b + o_b with the offset
// split on the CPU into an integer cell (added to the lattice cell exactly) and a fraction
// in [0, 1) (exact for hush's derived offsets), so the only new rounding is that of
// p 2^b + frac(o_b) (p 2^b is exact): delta_b <= 2^-24 (|p| 2^b + 2) per coordinate.
// A band's derivative along each axis is at most 2 max_abs (coefficient units), so at
// |p| <= pmax, against the CPU float path at the same float p (sample(p, footprint)):
//   |value error| <= 2 float_budget(plain) + slope K sum_b |w_b| 2 D max_abs delta_b
//                    + (footprint: 2^-16 slope pre-bound, the plan in float)
// where slope is the remap's (gaussian_scale, sqrt(2/pi), table slope); shader_budget()
// below evaluates it, shader_gradient_budget() the gradient's (delta_b times 4 max_abs 2^b,
// the second derivative). Example: one band of a 32^2 tile at |p| <= 200: budget 3.6e-4,
// measured on llvmpipe 1.3e-5; footprints on a receding plane measured within 5e-6
// (tests/wavelet/glsl_wavelet_shader_test.cpp). For coordinates where
// this is too coarse, hush::evaluate with exec::glsl{device} splits band positions in
// double on the CPU.
#ifndef HUSH_GLSL_WAVELET_SHADER_HPP
#define HUSH_GLSL_WAVELET_SHADER_HPP

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hush/glsl/perlin/shader.hpp"
#include "hush/glsl/library.hpp"
#include "hush/glsl/shader.hpp"
#include "hush/glsl/wavelet/glsl.hpp"
#include "hush/wavelet.hpp"

namespace hush {
namespace glsl {

// Entries per row of the distribution-table texture: 256 rows of 256 hold the largest
// table (65536 entries) within ES 3.00's 2048-texel limit.
constexpr unsigned kWaveletTableTextureWidth = 256u;

namespace detail {

// Default bindings of the 2D and 3D kits: params, tile, blend, table (distinct numbers, as
// Vulkan's descriptor set shares them between blocks and samplers).
constexpr unsigned kWaveletShaderBinding[2][4] = {{24u, 25u, 26u, 27u}, {28u, 29u, 30u, 31u}};

template <int D>
std::string wavelet_shader_source() {
  const std::string d = std::to_string(D), w = "hush_wavelet" + d, W = "HUSH_WAVELET" + d;
  const std::string v = "vec" + d, m = "mat" + d, P = w + "_p";
  const unsigned* bind = kWaveletShaderBinding[D - 2];
  const std::string sampler = D == 2 ? "sampler2D" : "sampler3D";
  std::string s = std::string(kShaderPrelude);
  s += resource_layout(W + "_PARAMS_BINDING", bind[0], "std140") + "uniform " + w +
       "_params {\n"
       "  uvec4 config;    // tile size n, cell pitch (0: periodic tile), band count, flags\n"
       "                   // (1 relative weights, 2 widening, 4 exact projection)\n"
       "  uvec4 remap;     // distribution (0 gaussian, 1 uniform, 2 table), table size,\n"
       "                   // relative profile size, split period (n, or 0 with variants)\n"
       "  vec4 scalars;    // scale K, tile variance, gaussian scale\n"
       "  vec4 pvar;       // projected variances along x, y, z (3D)\n"
       "  vec4 band[" +
       std::to_string(wavelet<D>::kMaxBands) +
       "];  // 2^b, raw weight w_b, b, relative profile weight k\n"
       "  vec4 frac[" +
       std::to_string(wavelet<D>::kMaxBands) +
       "];  // fraction of the band offset o_b - 1/2 per axis\n"
       "  uvec4 cell[" +
       std::to_string(wavelet<D>::kMaxBands) +
       "]; // its integer part modulo the split period per axis; w: variant key\n"
       "} " +
       P + ";\n";
  for (int r = 1; r <= 3; ++r) {
    const char* what[4] = {"", "_TILE", "_BLEND", "_TABLE"};
    const char* name[4] = {"", "_tile", "_blend", "_table"};
    s += resource_layout(W + what[r] + "_BINDING", bind[r], "");
    s += "uniform highp ";
    s += r == 3 ? std::string("sampler2D") : sampler;
    s += " " + w + name[r] + ";\n";
  }
  const std::string tw = std::to_string(kWaveletTableTextureWidth);
  s += "#define HUSH_WAVELET_TILE_AT(c) texelFetch(" + w + "_tile, (c)" +
       (D == 2 ? ".xy" : "") + ", 0).r\n";
  s += D == 2 ? "#define HUSH_WAVELET_BLEND(i) texelFetch(" + w +
                    "_blend, ivec2((i) % int(hush_wv_n), (i) / int(hush_wv_n)), 0).r\n"
              : "#define HUSH_WAVELET_BLEND(i) texelFetch(" + w +
                    "_blend, ivec3((i) % int(hush_wv_n), ((i) / int(hush_wv_n)) % "
                    "int(hush_wv_n), (i) / int(hush_wv_n * hush_wv_n)), 0).r\n";
  s += "#define HUSH_WAVELET_TABLE(i) texelFetch(" + w + "_table, ivec2(int(i) % " + tw +
       ", int(i) / " + tw + "), 0).r\n";
  s += library_once() + wavelet_body();
  // The plan (wavelet::make_plan) per sample from the block, then the bands.
  s += "// ---- Wavelet noise of the " + w +
       "_params block (hush/glsl/wavelet/shader.hpp).\n"
       "// Band b's weight (wavelet::make_plan): the fade of its level log2(2^b wmax), or\n"
       "// infinite noise's profile (a point: level b).\n"
       "float " +
       w +
       "_band_weight(uint b, float log2w, bool point, bool relative) {\n"
       "  vec4 band = " +
       P +
       ".band[b];\n"
       "  if (!relative) return band.y * hush_wavelet_fade_weight(band.z + log2w);\n"
       "  int k = int(" +
       P +
       ".remap.z);\n"
       "  float o = -(point ? band.z : band.z + log2w);\n"
       "  if (!(o > -1.0) || !(o < float(k))) return 0.0;\n"
       "  if (o < 0.0) return " +
       P +
       ".band[0].w * hush_fade(o + 1.0);\n"
       "  if (o > float(k - 1)) return " +
       P +
       ".band[k - 1].w * hush_fade(float(k) - o);\n"
       "  int i = int(floor(o));\n"
       "  if (i >= k - 1) return " +
       P +
       ".band[k - 1].w;\n"
       "  float t = hush_fade(o - float(i));\n"
       "  float lo = " +
       P + ".band[i].w, hi = " + P +
       ".band[i + 1].w;\n"
       "  return lo + t * (hi - lo);\n"
       "}\n";
  s += "vec4 " + w + "_eval(" + v + " p, " + m + " S" +
       (D == 3 ? ", bool has_nrm, vec3 nrm" : "") +
       ") {\n"
       "  if (hush_any_nonfinite(p)) return vec4(hush_nan());\n"
       "  hush_wv_n = " +
       P + ".config.x;\n  hush_wv_dim = " + d + "u;\n  hush_wv_cell = int(" + P +
       ".config.y);\n"
       "  uint nb = " +
       P + ".config.z, flags = " + P + ".config.w, period = " + P +
       ".remap.w;\n"
       "  bool relative = (flags & 1u) != 0u, widen = (flags & 2u) != 0u;\n"
       "  bool exact = (flags & 4u) != 0u;\n"
       "  float wmax = hush_footprint_max_width(S);\n"
       "  // A NaN or infinite derivative filters everything, as footprint::from_derivatives.\n"
       "  bool everything = hush_wavelet_filters_everything(wmax);\n"
       "  for (int a = 0; a < " + d + "; ++a) everything = everything || hush_any_nonfinite(S[a]);\n"
       "  float log2w = wmax > 0.0 ? log2(wmax) : -HUSH_FLOAT_HUGE;\n"
       "  bool point = !(wmax > 0.0);\n"
       "  bool project = false;\n  int naxis = -1;\n  vec3 un = vec3(0.0);\n";
  if (D == 3)
    s += "  if (has_nrm && !hush_any_nonfinite(nrm)) {\n"
         "    float mx = max(max(abs(nrm.x), abs(nrm.y)), abs(nrm.z));\n"
         "    if (mx > 0.0) {\n"
         "      un = nrm / mx;\n      un = un / length(un);\n      project = true;\n"
         "      bvec3 z = equal(un, vec3(0.0));\n"
         "      if (int(z.x) + int(z.y) + int(z.z) == 2) {\n"
         "        naxis = z.x ? (z.y ? 2 : 1) : 0;\n        un = vec3(0.0);\n"
         "        un[naxis] = 1.0;\n      }\n    }\n  }\n";
  s += "  float variance = " + P +
       ".scalars.y;\n"
       "  if (project) variance = dot(un * un, " +
       P +
       ".pvar.xyz);\n"
       "  if (project && exact) {  // hush::detail::wavelet_oblique_variance_ratio\n"
       "    vec3 q = un * un;\n"
       "    variance *= 1.0 + uintBitsToFloat(" +
       std::to_string(float_word(static_cast<float>(hush::detail::kWaveletObliqueS2))) +
       "u) * (q.x * q.y + q.y * q.z + q.z * q.x) + uintBitsToFloat(" +
       std::to_string(float_word(static_cast<float>(hush::detail::kWaveletObliqueS3))) +
       "u) * (q.x * q.y * q.z);\n  }\n"
       "  vec3 extent2 = vec3(0.0);\n"
       "  if (widen) {\n"
       "    for (int a = 0; a < " +
       d + "; ++a) {\n      " + v + " pa = " + v + "(0.0);\n      pa[a] = 1.0;\n";
  if (D == 3) s += "      if (project) pa -= un * un[a];\n";
  s += "      extent2[a] = max(dot(pa, S * pa), 0.0);\n    }\n  }\n"
       "  float sumsq = 0.0;\n"
       "  for (uint b = 0u; b < nb; ++b) {\n"
       "    float wb = " +
       w +
       "_band_weight(b, log2w, point, relative);\n"
       "    sumsq += wb * wb;\n  }\n"
       "  float scale = relative ? (sumsq > 0.0 ? 1.0 / sqrt(variance * sumsq) : 0.0)\n"
       "                         : " +
       P + ".scalars.x * sqrt(" + P +
       ".scalars.y / variance);\n"
       "  vec4 acc = vec4(0.0);\n"
       "  for (uint b = 0u; b < nb; ++b) {\n"
       "    float wb = everything ? 0.0 : " +
       w +
       "_band_weight(b, log2w, point, relative);\n"
       "    if (wb == 0.0) continue;\n"
       "    float freq = " +
       P +
       ".band[b].x;\n"
       "    // The band position p 2^b + o_b: the cell of p 2^b + frac(o_b) plus the offset's\n"
       "    // integer cell, modulo the split period (0: modulo 2^32).\n"
       "    vec3 f = vec3(0.0);\n    uvec3 i0 = uvec3(0u);\n"
       "    for (int a = 0; a < " +
       d +
       "; ++a) {\n"
       "      float x = p[a] * freq;\n"
       "      if (hush_is_nonfinite(x)) x = 0.0;  // the CPU's overflowing band coordinate\n"
       "      hush_lattice_coord c = hush_lattice_split(x + " +
       P +
       ".frac[b][a], period);\n"
       "      uint i = c.i0 + " +
       P +
       ".cell[b][a];\n"
       "      if (period != 0u && i >= period) i -= period;\n"
       "      i0[a] = i;\n      f[a] = c.f;\n    }\n"
       "    hush_wv_i0 = i0;\n    hush_wv_key = " +
       P +
       ".cell[b].w;\n"
       "    vec3 s = vec3(1.0);\n"
       "    if (widen)\n"
       "      for (int a = 0; a < " +
       d +
       "; ++a) s[a] = hush_wavelet_widen(extent2[a], freq);\n"
       "    vec4 r = hush_wavelet_band(f, project, naxis, un, exact, s);\n"
       "    acc.x += wb * r.x;\n"
       "    acc.yzw += (wb * freq) * r.yzw;\n"
       "  }\n"
       "  return hush_wavelet_output(acc, everything, scale, " +
       P + ".remap.x, " + P + ".scalars.z, " + P +
       ".remap.y);\n"
       "}\n";
  // The public functions.
  const std::string zero = m + "(0.0)";
  const std::string point_args = D == 3 ? ", false, vec3(0.0)" : "";
  const std::string fp = m + " S = outerProduct(dpdx, dpdx) + outerProduct(dpdy, dpdy);\n";
  const std::string g = D == 2 ? ".xyz" : "";
  const std::string gt = D == 2 ? "vec3" : "vec4";
  s += "float " + w + "(" + v + " p) { return " + w + "_eval(p, " + zero + point_args +
       ").x; }\n" + gt + " " + w + "_gradient(" + v + " p) { return " + w + "_eval(p, " + zero +
       point_args + ")" + g + "; }\n" + "float " + w + "_filtered(" + v + " p, " + v +
       " dpdx, " + v + " dpdy) {\n  " + fp + "  return " + w + "_eval(p, S" + point_args +
       ").x;\n}\n" + gt + " " + w + "_filtered_gradient(" + v + " p, " + v + " dpdx, " + v +
       " dpdy) {\n  " + fp + "  return " + w + "_eval(p, S" + point_args + ")" + g + ";\n}\n";
  if (D == 3)
    s += "float hush_wavelet3_projected(vec3 p, vec3 n) {\n"
         "  return hush_wavelet3_eval(p, mat3(0.0), true, n).x;\n}\n"
         "float hush_wavelet3_projected_filtered(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy) {\n  " +
         fp + "  return hush_wavelet3_eval(p, S, true, n).x;\n}\n";
  return s;
}

// One resource of a wavelet kit.
inline shader_resource wavelet_resource(const std::string& name, resource_kind kind,
                                        unsigned binding, const std::string& macro,
                                        const std::string& layout) {
  shader_resource r;
  r.name = name;
  r.kind = kind;
  r.binding = binding;
  r.binding_macro = macro;
  r.layout = layout;
  return r;
}

// The remap's largest slope (the factor by which it scales value errors).
template <int D>
double wavelet_remap_slope(const wavelet<D>& w) {
  const auto& prm = w.parameters();
  switch (prm.distribution) {
    case wavelet_distribution::gaussian:
      return prm.gaussian_scale;
    case wavelet_distribution::uniform:
      return 2 * hush::detail::constants::kInvSqrt2Pi;
    case wavelet_distribution::table: {
      double steepest = 0;
      for (std::size_t i = 0; i + 1 < prm.table.size(); ++i)
        steepest = std::max(steepest, std::fabs(prm.table[i + 1] - prm.table[i]));
      return steepest * static_cast<double>(prm.table.size() - 1) * hush::detail::constants::kInvSqrt2Pi;
    }
  }
  return 1.0;
}

// |value| before the remap, at most (wavelet's pre-remap bound), and the band weights'
// share of it: weight_i / (sum of |weights|), times that bound, is band i's largest part.
template <int D>
double wavelet_pre_bound(const wavelet<D>& w) {
  double smallest = w.tile().variance();
  if constexpr (D == 3)
    for (int a = 0; a < 3; ++a)
      for (bool exact : {true, false})
        smallest = std::min(smallest, w.tile().projected_variance(a, exact));
  const auto& prm = w.parameters();
  if (prm.relative_weights)
    return std::sqrt((static_cast<double>(prm.weights.size()) + 1.0) / smallest) *
           w.tile().max_abs();
  double sum_sq = 0, sum_abs = 0;
  for (int i = 0; i < w.band_count(); ++i) {
    sum_sq += w.band_raw_weight(i) * w.band_raw_weight(i);
    sum_abs += std::fabs(w.band_raw_weight(i));
  }
  return sum_abs * w.tile().max_abs() / std::sqrt(smallest * sum_sq);
}

// The position term of the budgets (file comment): sum over bands of the band's share of
// the pre-remap bound times 2 D delta_b (gradient: times 2^b and 2 more, the second
// derivative's 4 max_abs against the first's 2).
template <int D>
double wavelet_position_term(const wavelet<D>& w, double pmax, bool gradient) {
  const auto& prm = w.parameters();
  double sum_abs = 0;
  for (int i = 0; i < w.band_count(); ++i) sum_abs += std::fabs(w.band_raw_weight(i));
  const double u = std::ldexp(1.0, -24);
  double term = 0;
  for (int i = 0; i < w.band_count(); ++i) {
    const double share =
        prm.relative_weights ? 1.0 : std::fabs(w.band_raw_weight(i)) / std::max(sum_abs, 1e-300);
    const double f = w.band_frequency(i);
    const double delta = u * (pmax * f + 2.0);
    term += share * 2.0 * D * delta * (gradient ? 2.0 * f : 1.0);
  }
  return term * wavelet_pre_bound(w) * wavelet_remap_slope(w);
}

}  // namespace detail

// The bound on |kit value - CPU float value| (sample(p, footprint) at the same float p) for
// |p_a| <= pmax (file comment); `footprint`: the filtered functions; `plain`: no
// projection and no widening (wavelet::float_budget's argument).
template <int D>
double shader_budget(const wavelet<D>& w, double pmax, bool footprint, bool plain = true) {
  const double u = std::ldexp(1.0, -24);
  return 2 * w.float_budget(plain) + 16 * u * w.bound() +
         detail::wavelet_position_term(w, pmax, false) +
         (footprint ? std::ldexp(1.0, -16) * detail::wavelet_pre_bound(w) *
                          detail::wavelet_remap_slope(w)
                    : 0.0);
}
// The same for each gradient component.
template <int D>
double shader_gradient_budget(const wavelet<D>& w, double pmax, bool footprint,
                              bool plain = true) {
  const double top = w.band_frequency(w.band_count() - 1);
  return 2 * w.float_gradient_budget(plain) + 2 * top * shader_budget(w, 0.0, footprint, plain) +
         detail::wavelet_position_term(w, pmax, true);
}

// The kit of wavelet noise, 2D or 3D (file comment).
template <int D>
shader_kit shader_for(const wavelet<D>& w) {
  const auto& prm = w.parameters();
  const std::string d = std::to_string(D), name = "hush_wavelet" + d, W = "HUSH_WAVELET" + d;
  const unsigned* bind = detail::kWaveletShaderBinding[D - 2];
  constexpr int kMax = wavelet<D>::kMaxBands;
  shader_kit kit;
  kit.source = detail::wavelet_shader_source<D>();

  // The block: the CPU's plan inputs (wavelet_program.hpp's uniforms, and the offsets).
  const std::uint32_t n = static_cast<std::uint32_t>(prm.tile_size);
  const std::uint32_t period = w.split_period();
  const int nb = w.band_count();
  std140_writer b;
  b.uvec4(n, prm.variant_overlap > 0 ? n - static_cast<std::uint32_t>(prm.variant_overlap) : 0u,
          static_cast<std::uint32_t>(nb),
          (prm.relative_weights ? 1u : 0u) | (prm.widen ? 2u : 0u) |
              (prm.projection == wavelet_projection::exact ? 4u : 0u));
  b.uvec4(static_cast<std::uint32_t>(prm.distribution),
          static_cast<std::uint32_t>(prm.table.size()),
          static_cast<std::uint32_t>(prm.relative_weights ? prm.weights.size() : 0u), period);
  b.vec4(static_cast<float>(w.scale()), static_cast<float>(w.tile().variance()),
         static_cast<float>(prm.gaussian_scale), 0.0f);
  float pvar[3] = {0, 0, 0};
  if constexpr (D == 3)
    for (int a = 0; a < 3; ++a)
      pvar[a] = static_cast<float>(
          w.tile().projected_variance(a, prm.projection == wavelet_projection::exact));
  b.vec4(pvar[0], pvar[1], pvar[2], 0.0f);
  for (int i = 0; i < kMax; ++i) {
    const bool on = i < nb;
    const float profile = prm.relative_weights && i < static_cast<int>(prm.weights.size())
                              ? static_cast<float>(prm.weights[static_cast<std::size_t>(i)])
                              : 0.0f;
    b.vec4(on ? static_cast<float>(w.band_frequency(i)) : 0.0f,
           on ? static_cast<float>(w.band_raw_weight(i)) : 0.0f,
           on ? static_cast<float>(w.band_index(i)) : 0.0f, profile);
  }
  // Band i's offset o_b - 1/2 (its position at p = 0), split into its integer cell
  // modulo the split period and its fraction.
  std::uint32_t cells[static_cast<std::size_t>(kMax)][4] = {};
  float fracs[static_cast<std::size_t>(kMax)][4] = {};
  for (int i = 0; i < nb; ++i) {
    const vec<double, D> o = w.band_position(i, vec<double, D>{});
    for (int a = 0; a < D; ++a) {
      const double fl = std::floor(o[a]);
      fracs[i][a] = static_cast<float>(o[a] - fl);
      if (fracs[i][a] >= 1.0f) fracs[i][a] = std::nextafter(1.0f, 0.0f);
      const lattice_coord<float> c = lattice_split<float>(fl, period);
      cells[i][a] = c.i0;
    }
    cells[i][3] = w.variant_key(i);
  }
  for (int i = 0; i < kMax; ++i) b.vec4(fracs[i][0], fracs[i][1], fracs[i][2], 0.0f);
  for (int i = 0; i < kMax; ++i) b.uvec4(cells[i][0], cells[i][1], cells[i][2], cells[i][3]);
  auto block = detail::wavelet_resource(
      name + "_params", resource_kind::uniform_block, bind[0], W + "_PARAMS_BINDING",
      "std140: uvec4 config, uvec4 remap, vec4 scalars, vec4 pvar, vec4 band[" +
          std::to_string(kMax) + "], vec4 frac[" + std::to_string(kMax) + "], uvec4 cell[" +
          std::to_string(kMax) + "] (see the declaration in the kit's source)");
  block.words = b.words();

  // The tile, unpadded (wavelet_tile::coefficient order: x fastest).
  auto tile = detail::wavelet_resource(name + "_tile", D == 2 ? resource_kind::texture_2d
                                                                : resource_kind::texture_3d,
                                       bind[1], W + "_TILE_BINDING",
                                       "R32F n^" + d + " texels, the tile's coefficients, "
                                       "read with texelFetch; nearest, repeat");
  tile.width = tile.height = n;
  tile.depth = D == 3 ? n : 0u;
  const std::size_t count = w.tile().count();
  tile.words.resize(count);
  for (std::size_t i = 0; i < count; ++i) tile.words[i] = float_word(w.tile().coefficient(i));

  auto blend = detail::wavelet_resource(name + "_blend", tile.kind, bind[2], W + "_BLEND_BINDING",
                                        "R32F, the tile-variant tile (wavelet_blend_tile) in the "
                                        "tile's shape; 1 texel when variant_overlap = 0");
  if (const auto bt = w.blend_tile_ptr()) {
    blend.width = blend.height = n;
    blend.depth = D == 3 ? n : 0u;
    for (std::size_t i = 0; i < bt->count(); ++i)
      blend.words.push_back(float_word(bt->coefficients()[i]));
  } else {
    blend.width = blend.height = 1u;
    blend.depth = D == 3 ? 1u : 0u;
    blend.words = {0u};
  }

  auto table = detail::wavelet_resource(
      name + "_table", resource_kind::texture_2d, bind[3], W + "_TABLE_BINDING",
      "R32F, the distribution table, entry i at (i % " +
          std::to_string(kWaveletTableTextureWidth) + ", i / " +
          std::to_string(kWaveletTableTextureWidth) + "); 1 texel unless distribution = table");
  if (const auto t = w.table_floats()) {
    const std::size_t rows = (t->size() + kWaveletTableTextureWidth - 1) / kWaveletTableTextureWidth;
    table.width = rows > 1 ? kWaveletTableTextureWidth : static_cast<unsigned>(t->size());
    table.height = static_cast<unsigned>(rows);
    table.words.assign(std::size_t(table.width) * table.height, 0u);
    for (std::size_t i = 0; i < t->size(); ++i) table.words[i] = float_word((*t)[i]);
  } else {
    table.width = table.height = 1u;
    table.words = {0u};
  }
  kit.resources = {block, tile, blend, table};
  kit.versions = "430 core, Vulkan 450, 300 es";
  const std::string v = "vec" + d;
  kit.usage = "// float " + name + "(" + v + " p), " + name + "_filtered(" + v + " p, " + v +
              " dpdx, " + v + " dpdy)" +
              (D == 3 ? ",\n// " + name + "_projected(vec3 p, vec3 n), " + name +
                            "_projected_filtered(p, n, dpdx, dpdy)"
                      : std::string()) +
              "\n// _gradient variants return (value, gradient); " + name +
              "_eval(p, S...) takes the footprint covariance.\n"
              "// Error against hush's float path: hush::glsl::shader_budget(noise, max |p|, "
              "footprint).\n";
  return kit;
}

// The wavelet kits' sources for `hush glsl-export`: hush_wavelet2_shader.glsl,
// hush_wavelet3_shader.glsl.
inline std::vector<std::pair<std::string, std::string>> wavelet_shader_exports() {
  return {{"hush_wavelet2_shader.glsl", detail::wavelet_shader_source<2>()},
          {"hush_wavelet3_shader.glsl", detail::wavelet_shader_source<3>()}};
}

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_WAVELET_SHADER_HPP
