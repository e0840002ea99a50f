// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::glsl::noise_program<wavelet<D>>: wavelet noise (include/hush/wavelet.hpp)
// on the GPU, as a banded program (noise_program.hpp, compute_source.hpp).
//
// Every band coordinate 2^b x + o_b - 1/2 of every point and grid sample is
// formed and split on the CPU in double (wavelet::band_position,
// lattice_split<float> with wavelet::split_period()), as the CPU float path
// does, so the GPU sees the CPU's cells and fractions bit for bit, also far
// from the origin. The GPU then runs the CPU's float algorithm
// (hush/glsl/wavelet/glsl.hpp): per sample the plan of wavelet::make_plan
// (footprint width, fade or relative weights, normal, widening), per band the
// kernel, then scale and remapping.
//
// Data (noise_program::data_buffers): the tile's float coefficients at SSBO
// binding 5 (kFirstDataBinding), the tile-variant tile (wavelet_blend_tile) at 6 and the
// distribution table at 7, each owned by the shared object that holds it, so a
// tile is uploaded once per device however many noises use it. Unused bindings
// get a 16-byte buffer of zeros. The largest tile (2048^2 or 128^3 floats) is
// 16 MiB, the minimum GL_MAX_SHADER_STORAGE_BLOCK_SIZE of OpenGL 4.3.
//
// Tolerance (tests/wavelet/glsl_wavelet_test.cpp): hashes, cells, fractions and
// tap indices are the CPU's; the float arithmetic is the CPU's, in its order,
// except that GLSL may fuse multiply-adds, computes the per-sample plan (band
// weights, widening, normal) in float where the CPU uses double, and takes
// erf from Abramowitz & Stegun 7.1.26 (|error| <= 1.5e-7). Values are within
// 2 wavelet::float_budget() of the CPU float path for plain kernels (points,
// grids, footprints) and 2 float_budget(false) with projection or widening,
// plus 2e-6 * the remap's slope for the erf; gradients likewise with
// float_gradient_budget().
#ifndef HUSH_GLSL_WAVELET_PROGRAM_HPP
#define HUSH_GLSL_WAVELET_PROGRAM_HPP

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "hush/glsl/noise_program.hpp"
#include "hush/wavelet.hpp"

namespace hush {
namespace glsl {

template <int D>
struct noise_program<wavelet<D>> {
  using noise_type = wavelet<D>;
  static constexpr int dimension = D;
  static constexpr const char* name = D == 2 ? "wavelet2" : "wavelet3";
  static constexpr bool banded = true;
  static constexpr unsigned kTileBinding = kFirstDataBinding;
  static constexpr unsigned kBlendBinding = kFirstDataBinding + 1;
  static constexpr unsigned kTableBinding = kFirstDataBinding + 2;

  // The tile, variant tile and table SSBOs, and the macros the library reads them by.
  static std::string preamble() {
    auto ssbo = [](unsigned binding, const char* block, const char* array) {
      return "layout(std430, binding = " + std::to_string(binding) + ") readonly buffer " + block +
             " { float " + array + "[]; };\n";
    };
    return ssbo(kTileBinding, "hush_wavelet_tiles", "hush_wavelet_tile") +
           ssbo(kBlendBinding, "hush_wavelet_blends", "hush_wavelet_blend") +
           ssbo(kTableBinding, "hush_wavelet_tables", "hush_wavelet_table") +
           "#define HUSH_WAVELET_TILE(i) hush_wavelet_tile[i]\n"
           "#define HUSH_WAVELET_BLEND(i) hush_wavelet_blend[i]\n"
           "#define HUSH_WAVELET_TABLE(i) hush_wavelet_table[i]\n";
  }
  static std::vector<data_buffer> data_buffers(const noise_type& w) {
    std::vector<data_buffer> r;
    const auto tile = w.tile_ptr();
    r.push_back({kTileBinding, tile->coefficients(), tile->storage_size() * sizeof(float), tile});
    if (const auto blend = w.blend_tile_ptr())
      r.push_back({kBlendBinding, blend->coefficients(), blend->count() * sizeof(float), blend});
    else
      r.push_back(unused_data_buffer(kBlendBinding));
    if (const auto table = w.table_floats())
      r.push_back({kTableBinding, table->data(), table->size() * sizeof(float), table});
    else
      r.push_back(unused_data_buffer(kTableBinding));
    return r;
  }

  static std::string uniforms() {
    const std::string n = "[" + std::to_string(noise_type::kMaxBands) + "]";
    return "uniform uint hush_w_n;             // tile size\n"
           "uniform uint hush_w_cell;          // variants: cell pitch n - overlap; 0: periodic\n"
           "uniform uint hush_w_weight" +
           n + ";  // floatBitsToUint(float(raw band weight))\n" + "uniform uint hush_w_freq" + n +
           ";    // floatBitsToUint(2^b)\n" + "uniform uint hush_w_index" + n + ";   // uint(b)\n" +
           "uniform uint hush_w_key" + n + ";     // variants: the band's key\n" +
           "uniform uint hush_w_profile" + n + ";  // relative weights (float bits)\n" +
           "uniform uint hush_w_profile_size;  // their count\n"
           "uniform uint hush_w_scale;         // float(scale()) bits\n"
           "uniform uint hush_w_var;           // tile variance (float bits)\n"
           "uniform uint hush_w_pvar[3];       // projected variances per axis (float bits)\n"
           "uniform uint hush_w_flags;         // 1: relative weights, 2: widen, 4: exact "
           "projection\n"
           "uniform uint hush_w_dist;          // 0 gaussian, 1 uniform, 2 table\n"
           "uniform uint hush_w_gscale;        // gaussian_scale (float bits)\n"
           "uniform uint hush_w_table_size;    // distribution table entries\n"
           "// Band b's weight in the sum (wavelet::make_plan): the fade, or infinite noise's\n"
           "// profile, at level log2(2^b wmax) (wmax = 0: a point; infinite noise then uses b).\n"
           "float hush_w_band_weight(uint b, float log2w, bool point, bool relative) {\n"
           "  float index = float(int(hush_w_index[b]));\n"
           "  if (!relative) return uintBitsToFloat(hush_w_weight[b]) * "
           "hush_wavelet_fade_weight(index + log2w);\n"
           "  int k = int(hush_w_profile_size);\n"
           "  float o = -(point ? index : index + log2w);\n"
           "  if (!(o > -1.0) || !(o < float(k))) return 0.0;\n"
           "  if (o < 0.0) return uintBitsToFloat(hush_w_profile[0]) * hush_fade(o + 1.0);\n"
           "  if (o > float(k - 1)) return uintBitsToFloat(hush_w_profile[k - 1]) * "
           "hush_fade(float(k) - o);\n"
           "  int i = int(floor(o));\n"
           "  if (i >= k - 1) return uintBitsToFloat(hush_w_profile[k - 1]);\n"
           "  float t = hush_fade(o - float(i));\n"
           "  float lo = uintBitsToFloat(hush_w_profile[i]), hi = uintBitsToFloat(hush_w_profile[i "
           "+ "
           "1]);\n"
           "  return lo + t * (hi - lo);\n"
           "}\n";
  }
  static int band_count(const noise_type& w) { return w.band_count(); }
  static std::uint32_t band_period(const noise_type& w, int, int) { return w.split_period(); }
  static vec<double, D> band_position(const noise_type& w, int band, const vec<double, D>& p) {
    return w.band_position(band, p);
  }

  // wavelet::make_plan in GLSL (fp, nrm, has_nrm are the sample's; zero for points and grids).
  static std::string band_begin(bool) {
    std::string s = std::string("  hush_wv_n = hush_w_n;\n  hush_wv_dim = ") +
                    (D == 2 ? "2u" : "3u") +
                    ";\n  hush_wv_cell = int(hush_w_cell);\n"
                    "  vec4 acc = vec4(0.0);\n  bool bad = false;\n"
                    "  float wmax = hush_footprint_max_width(fp);\n"
                    "  bool everything = hush_wavelet_filters_everything(wmax);\n"
                    "  float log2w = wmax > 0.0 ? log2(wmax) : -HUSH_FLOAT_HUGE;\n"
                    "  bool project = false;\n  int naxis = -1;\n  vec3 un = vec3(0.0);\n"
                    "  bool exact = (hush_w_flags & 4u) != 0u, widen = (hush_w_flags & 2u) != 0u;\n"
                    "  bool relative = (hush_w_flags & 1u) != 0u;\n";
    if (D == 3)
      s += "  if (has_nrm && !hush_any_nonfinite(nrm)) {\n"
           "    float m = max(max(abs(nrm.x), abs(nrm.y)), abs(nrm.z));\n"
           "    if (m > 0.0) {\n"
           "      un = nrm / m;\n      un = un / length(un);\n      project = true;\n"
           "      bvec3 z = equal(un, vec3(0.0));\n"
           "      if (int(z.x) + int(z.y) + int(z.z) == 2) {\n"
           "        naxis = z.x ? (z.y ? 2 : 1) : 0;\n        un = vec3(0.0);\n        un[naxis] = "
           "1.0;\n"
           "      }\n    }\n  }\n";
    s += "  float variance = uintBitsToFloat(hush_w_var);\n"
         "  if (project) variance = un.x * un.x * uintBitsToFloat(hush_w_pvar[0]) + un.y * un.y * "
         "uintBitsToFloat(hush_w_pvar[1]) + un.z * un.z * uintBitsToFloat(hush_w_pvar[2]);\n"
         "  if (project && exact) {  // hush::detail::wavelet_oblique_variance_ratio\n"
         "    vec3 q = un * un;\n"
         "    variance *= 1.0 + uintBitsToFloat(" +
         std::to_string(bits(static_cast<float>(hush::detail::kWaveletObliqueS2))) +
         "u) * (q.x * q.y + q.y * q.z + q.z * q.x) + uintBitsToFloat(" +
         std::to_string(bits(static_cast<float>(hush::detail::kWaveletObliqueS3))) +
         "u) * (q.x * q.y * q.z);\n  }\n"
         "  vec3 extent2 = vec3(0.0);\n"
         "  if (widen) {\n"
         "    for (int a = 0; a < " +
         std::to_string(D) + "; ++a) {\n      vec" + std::to_string(D) + " pa = vec" +
         std::to_string(D) + "(0.0);\n      pa[a] = 1.0;\n";
    if (D == 3) s += "      if (project) pa -= un * un[a];\n";
    s += "      extent2[a] = max(dot(pa, fp * pa), 0.0);\n    }\n  }\n"
         "  float sumsq = 0.0;\n"
         "  for (uint b = 0u; b < hush_bands; ++b) {\n"
         "    float w = hush_w_band_weight(b, log2w, !(wmax > 0.0), relative);\n"
         "    sumsq += w * w;\n  }\n"
         "  float scale = relative ? (sumsq > 0.0 ? 1.0 / sqrt(variance * sumsq) : 0.0)\n"
         "                         : uintBitsToFloat(hush_w_scale) * "
         "sqrt(uintBitsToFloat(hush_w_var) / variance);\n";
    return s;
  }
  static std::string band_step(bool) {
    return std::string(
               "    bad = bad || hush_any_nonfinite(f);\n"
               "    float wb = everything ? 0.0 : hush_w_band_weight(b, log2w, !(wmax > 0.0), "
               "relative);\n"
               "    if (!bad && wb != 0.0) {\n") +
           (D == 2 ? "      hush_wv_i0 = uvec3(i0, 0u);\n" : "      hush_wv_i0 = i0;\n") +
           "      hush_wv_key = hush_w_key[b];\n"
           "      float freq = uintBitsToFloat(hush_w_freq[b]);\n"
           "      vec3 s = vec3(1.0);\n"
           "      if (widen)\n"
           "        for (int a = 0; a < " +
           std::to_string(D) + "; ++a) s[a] = hush_wavelet_widen(extent2[a], freq);\n" +
           (D == 2 ? "      vec4 r = hush_wavelet_band(vec3(f, 0.0), false, -1, un, exact, s);\n"
                   : "      vec4 r = hush_wavelet_band(f, project, naxis, un, exact, s);\n") +
           "      acc.x += wb * r.x;\n"
           "      acc.yzw += (wb * freq) * r.yzw;\n"
           "    }\n";
  }
  static std::string band_result(bool gradient) {
    const std::string out =
        "(bad ? vec4(hush_nan()) : hush_wavelet_output(acc, everything, scale, hush_w_dist, "
        "uintBitsToFloat(hush_w_gscale), hush_w_table_size))";
    if (!gradient) return out + ".x";
    return D == 2 ? out + ".xyz" : out;
  }

  static void set_uniforms(const detail::gl_api& gl, detail::gl_uint program, const noise_type& w) {
    const auto& prm = w.parameters();
    constexpr int kMax = noise_type::kMaxBands;
    std::uint32_t weight[std::size_t{kMax}] = {}, freq[std::size_t{kMax}] = {},
                  index[std::size_t{kMax}] = {}, key[std::size_t{kMax}] = {},
                  profile[std::size_t{kMax}] = {};
    const int nb = w.band_count();
    for (int b = 0; b < nb; ++b) {
      const auto i = static_cast<std::size_t>(b);
      weight[i] = bits(static_cast<float>(w.band_raw_weight(b)));
      freq[i] = bits(static_cast<float>(w.band_frequency(b)));
      index[i] = static_cast<std::uint32_t>(w.band_index(b));
      key[i] = w.variant_key(b);
    }
    for (std::size_t i = 0; i < prm.weights.size(); ++i)
      profile[i] = bits(static_cast<float>(prm.weights[i]));
    auto u1 = [&](const char* name, std::uint32_t v) {
      gl.Uniform1ui(gl.GetUniformLocation(program, name), v);
    };
    auto uv = [&](const char* name, const std::uint32_t* v, int count) {
      gl.Uniform1uiv(gl.GetUniformLocation(program, name), static_cast<detail::gl_sizei>(count), v);
    };
    u1("hush_w_n", static_cast<std::uint32_t>(prm.tile_size));
    u1("hush_w_cell", prm.variant_overlap > 0
                          ? static_cast<std::uint32_t>(prm.tile_size - prm.variant_overlap)
                          : 0u);
    uv("hush_w_weight", weight, kMax);
    uv("hush_w_freq", freq, kMax);
    uv("hush_w_index", index, kMax);
    uv("hush_w_key", key, kMax);
    uv("hush_w_profile", profile, kMax);
    u1("hush_w_profile_size", static_cast<std::uint32_t>(prm.weights.size()));
    u1("hush_w_scale", bits(static_cast<float>(w.scale())));
    u1("hush_w_var", bits(static_cast<float>(w.tile().variance())));
    std::uint32_t pvar[3] = {};
    if constexpr (D == 3)
      for (int a = 0; a < 3; ++a)
        pvar[a] = bits(static_cast<float>(
            w.tile().projected_variance(a, prm.projection == wavelet_projection::exact)));
    uv("hush_w_pvar", pvar, 3);
    u1("hush_w_flags", (prm.relative_weights ? 1u : 0u) | (prm.widen ? 2u : 0u) |
                           (prm.projection == wavelet_projection::exact ? 4u : 0u));
    u1("hush_w_dist", static_cast<std::uint32_t>(prm.distribution));
    u1("hush_w_gscale", bits(static_cast<float>(prm.gaussian_scale)));
    u1("hush_w_table_size", static_cast<std::uint32_t>(prm.table.size()));
  }

 private:
  static std::uint32_t bits(float f) {
    std::uint32_t u = 0;
    std::memcpy(&u, &f, sizeof u);
    return u;
  }
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_WAVELET_PROGRAM_HPP
