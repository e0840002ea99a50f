// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The `#version 430 core` compute shaders hush::glsl::device runs, one per
// (noise, values or values + gradient, points, grid or samples). They are plain text,
// so `hush glsl-export` writes the same sources for engines that dispatch
// them themselves. Interface of every runner (std430 SSBOs, 1D dispatch of
// kLocalSize-wide groups):
//   uniform uint hush_first, hush_count: this dispatch evaluates samples
//     n = hush_first + gl_GlobalInvocationID.x for n < hush_count;
//   points: binding 0 `float hush_in[]`, D floats per point (x, y[, z]);
//   grid:   binding 0 `uint hush_axis[]`, per sample index along each axis
//     (x axis, then y, then z) the triple (cell i0, next cell i1, floatBitsToUint
//     of the fraction), i.e. hush::lattice_split<float> of origin + step * i done
//     on the CPU in double; uniform uint hush_base (grid index of sample 0 of
//     the batch) and uvec3 hush_size (nx, ny, nz; nz = 1 in 2D);
//   binding 1 `float hush_out[]`: the value per sample, or with gradients
//     D + 1 floats per sample (value, d/dx, d/dy[, d/dz]);
//   the grid layout `#define`s HUSH_GRID (before the library), so a noise whose
//     float form differs between grids and points (Gabor noise: the separable
//     form on grids, the point form at points, as on the CPU) can tell them apart;
//   plus the noise's own uniforms (noise_program<Noise>::uniforms()).
// Samples (batch_layout::samples; hush::samples, core/samples.hpp): the
// points input above, plus per-sample footprints, normals and surface maps,
// each present when its uniform says so (the device binds a dummy buffer
// otherwise):
//   uniform uint hush_has_footprint: 1u when binding 2 `float hush_fp[]`
//     holds footprint<D>::kEntries floats per sample (the upper triangle of
//     the footprint matrix S, row by row: 2D xx, xy, yy; 3D xx, xy, xz, yy, yz, zz);
//   uniform uint hush_has_normal: 1u when binding 3 `float hush_nrm[]` holds
//     3 floats per sample;
//   uniform uint hush_has_map: 1u when binding 4 `float hush_map[]` holds the
//     surface map T per sample, 4 floats row by row (m00, m01, m10, m11);
// and the noise sees `matD fp` (S, symmetric; zero when absent), `vec3 nrm`
// (zero when absent), `bool has_nrm`, `mat2 smap` (T; the identity when
// absent) and `bool has_smap`, besides `p`:
// noise_program<Noise>::sample_call(bool gradient) is its expression.
// A noise's own data (noise_program::preamble, data_buffers) sits at SSBO bindings
// 5 and up (kFirstDataBinding), declared before the library.
// Banded noises see fp, nrm, has_nrm, smap and has_smap in every layout (at
// their defaults for points and grids). They read, for
// `uniform uint hush_bands` bands, band b's triples instead:
//   points: binding 0 `uint hush_axis[]`, per point, per band, per axis the
//     triple of the band coordinate split on the CPU in double
//     (3 D hush_bands words per point);
//   grid: the grid triples above for band 0 (nx + ny + nz triples), then
//     band 1's, ...
#ifndef HUSH_GLSL_COMPUTE_SOURCE_HPP
#define HUSH_GLSL_COMPUTE_SOURCE_HPP

#include <string>

#include "hush/core/samples.hpp"
#include "hush/glsl/dialect.hpp"
#include "hush/glsl/library.hpp"
#include "hush/glsl/noise_program.hpp"

namespace hush {
namespace glsl {

// What a runner reads: an array of points, a uniform grid, or an array of
// samples (points with optional footprints and normals).
enum class batch_layout { points, grid, samples };

// The name of a layout: "points", "grid", "samples".
inline const char* layout_name(batch_layout layout) {
  switch (layout) {
    case batch_layout::points:
      return "points";
    case batch_layout::grid:
      return "grid";
    case batch_layout::samples:
      return "samples";
  }
  return "?";
}

// Whether hush::glsl::device runs Noise's samples runner: only for a noise that takes
// per-sample inputs (footprints, normals or surface maps); any other noise's samples
// are its points (the extras are never given).
template <class Noise>
constexpr bool has_samples_runner() {
  return hush::detail::takes_sample_inputs<Noise>::value;
}

// Invocations per work group of every runner (a multiple of the SIMD widths
// of GPUs (32, 64) and of llvmpipe's 8 or 16 lanes).
constexpr unsigned kLocalSize = 64;

namespace detail {

// "#version 430 core", the header comment, the work-group size and the
// library: the start of every runner.
template <class Noise>
std::string runner_preamble(batch_layout layout, bool gradient) {
  using np = noise_program<Noise>;
  std::string data;  // the noise's data buffers and macros, before the library reads them
  if constexpr (has_preamble<np>::value) data = np::preamble();
  return "#version 430 core\n// hush " HUSH_VERSION_STRING " compute runner: " +
         std::string(np::name) + (gradient ? ", values and gradients" : ", values") + ", " +
         layout_name(layout) +
         " (hush/glsl/compute_source.hpp).\nlayout(local_size_x = " + std::to_string(kLocalSize) +
         ") in;\n" +
         (layout == batch_layout::grid ? "#define HUSH_GRID 1  // this runner evaluates a grid\n"
                                       : "") +
         data + library() + "\n// ---- Runner.\n" + np::uniforms();
}

// GLSL: t[a] = offset of axis a's (i0, i1, fraction bits) triple in the axis
// table, from the C-order grid index g = hush_base + n (i fastest).
inline const char* grid_axis_offsets() {
  return "  uint g = hush_base + n;\n"
         "  uint t[3] = uint[3](3u * (g % hush_size.x),\n"
         "                      3u * (hush_size.x + (g / hush_size.x) % hush_size.y),\n"
         "                      3u * (hush_size.x + hush_size.y + g / (hush_size.x * "
         "hush_size.y)));\n";
}

// GLSL: the declarations of the samples layout's optional inputs (bindings
// 2 to 4, their presence uniforms).
inline const char* sample_input_declarations() {
  return "#define HUSH_SAMPLES 1  // this runner reads samples (fp, nrm, has_nrm exist)\n"
         "uniform uint hush_has_footprint;  // 1u: hush_fp holds a footprint per sample\n"
         "uniform uint hush_has_normal;     // 1u: hush_nrm holds a normal per sample\n"
         "uniform uint hush_has_map;        // 1u: hush_map holds a surface map per sample\n"
         "layout(std430, binding = 2) readonly buffer hush_footprints { float hush_fp[]; };\n"
         "layout(std430, binding = 3) readonly buffer hush_normals { float hush_nrm[]; };\n"
         "layout(std430, binding = 4) readonly buffer hush_maps { float hush_map[]; };\n";
}

// GLSL: fp (matD, the symmetric footprint matrix; zero when absent), nrm
// (vec3), has_nrm, smap (mat2, the surface map; identity when absent) and
// has_smap for sample n.
inline std::string read_sample_inputs(int dimension) {
  const std::string d = std::to_string(dimension);
  const int entries = dimension * (dimension + 1) / 2;
  std::string s = "  mat" + d + " fp = mat" + d + "(0.0);\n  if (hush_has_footprint != 0u) {\n";
  s += "    uint e = " + std::to_string(entries) + "u * n;\n";
  int e = 0;
  for (int r = 0; r < dimension; ++r)
    for (int c = r; c < dimension; ++c, ++e) {
      const std::string v = "hush_fp[e + " + std::to_string(e) + "u]";
      // GLSL matrices are indexed [column][row]; S is symmetric.
      s += "    fp[" + std::to_string(c) + "][" + std::to_string(r) + "] = " + v + ";\n";
      if (r != c)
        s += "    fp[" + std::to_string(r) + "][" + std::to_string(c) + "] = " + v + ";\n";
    }
  s += "  }\n  bool has_nrm = hush_has_normal != 0u;\n"
       "  vec3 nrm = has_nrm ? vec3(hush_nrm[3u * n], hush_nrm[3u * n + 1u], hush_nrm[3u * n + "
       "2u]) : vec3(0.0);\n"
       "  bool has_smap = hush_has_map != 0u;\n"
       "  // GLSL matrices are indexed [column][row]: smap[c][r] = T(r, c).\n"
       "  mat2 smap = has_smap ? mat2(hush_map[4u * n], hush_map[4u * n + 2u], hush_map[4u * n + "
       "1u], hush_map[4u * n + 3u]) : mat2(1.0);\n";
  return s;
}

// GLSL: the sample inputs at their defaults (fp zero, no normal, identity
// map), for banded programs evaluated at points or on grids; with `flags`
// (the samples layout of a program that does not read them: noise_program's
// reads_sample_inputs), has_nrm and has_smap from their presence uniforms.
inline std::string default_sample_inputs(int dimension, bool flags = false) {
  const std::string d = std::to_string(dimension);
  return "  mat" + d + " fp = mat" + d + "(0.0);\n  bool has_nrm = " +
         (flags ? "hush_has_normal != 0u" : "false") + ";\n  vec3 nrm = vec3(0.0);\n" +
         "  bool has_smap = " + (flags ? "hush_has_map != 0u" : "false") +
         ";\n  mat2 smap = mat2(1.0);\n";
}

// GLSL: the samples layout's inputs of sample n as Noise's program reads them.
template <class Noise>
std::string sample_inputs(int dimension) {
  return reads_sample_inputs<Noise>::value ? read_sample_inputs(dimension)
                                           : default_sample_inputs(dimension, true);
}

// GLSL: i0, i1 (uvecD) and f (vecD) read from the triples at `base` + t[a].
inline std::string read_cells(int dimension, const std::string& base, const std::string& indent) {
  const std::string d = std::to_string(dimension);
  std::string i0, i1, f;
  for (int a = 0; a < dimension; ++a) {
    const std::string ta = base + "t[" + std::to_string(a) + "]";
    i0 += std::string(a ? ", " : "") + "hush_axis[" + ta + "]";
    i1 += std::string(a ? ", " : "") + "hush_axis[" + ta + " + 1u]";
    f += std::string(a ? ", " : "") + "uintBitsToFloat(hush_axis[" + ta + " + 2u])";
  }
  return indent + "uvec" + d + " i0 = uvec" + d + "(" + i0 + ");\n" + indent + "uvec" + d +
         " i1 = uvec" + d + "(" + i1 + ");\n" + indent + "vec" + d + " f = vec" + d + "(" + f +
         ");\n";
}

// GLSL: the sample's result `expr` (float, or vec(D+1) value and gradient)
// into hush_out, then the end of main().
inline std::string store_result(int dimension, bool gradient, const std::string& expr) {
  if (!gradient) return "  hush_out[n] = " + expr + ";\n}\n";
  const std::string stride = std::to_string(dimension + 1);
  std::string s = "  vec" + stride + " r = " + expr + ";\n";
  for (int c = 0; c <= dimension; ++c)
    s += "  hush_out[" + stride + "u * n + " + std::to_string(c) + "u] = r." +
         (c == 0 ? 'x' : "yzw"[c - 1]) + ";\n";
  return s + "}\n";
}

// The runner of a banded noise (file comment): the band loop around the
// noise's band_step, on CPU-split triples for points and grids alike.
template <class Noise>
std::string banded_source(batch_layout layout, bool gradient) {
  using np = noise_program<Noise>;
  constexpr int D = np::dimension;
  const std::string d = std::to_string(D);
  std::string s = runner_preamble<Noise>(layout, gradient) +
                  "uniform uint hush_bands;  // bands summed\n"
                  "uniform uint hush_first;  // first sample of this dispatch\n"
                  "uniform uint hush_count;  // samples in the batch\n";
  if (layout == batch_layout::grid)
    s += "uniform uint hush_base;   // grid index of the batch's first sample\n"
         "uniform uvec3 hush_size;  // samples along x, y, z\n";
  if (layout == batch_layout::samples) s += sample_input_declarations();
  s += "layout(std430, binding = 0) readonly buffer hush_axes { uint hush_axis[]; };\n"
       "layout(std430, binding = 1) writeonly buffer hush_output { float hush_out[]; };\n"
       "void main() {\n"
       "  uint n = hush_first + gl_GlobalInvocationID.x;\n"
       "  if (n >= hush_count) return;\n";
  s += layout == batch_layout::samples ? sample_inputs<Noise>(D) : default_sample_inputs(D);
  if (layout != batch_layout::grid) {
    // Triple of axis a of band b at t[a] + band_stride * b.
    s += "  uint band_stride = 3u * " + d +
         "u;\n  uint t0 = band_stride * hush_bands * n;\n"
         "  uint t[3] = uint[3](t0, t0 + 3u, t0 + 6u);\n";
  } else {
    s += std::string(grid_axis_offsets()) +
         "  uint band_stride = 3u * (hush_size.x + hush_size.y + hush_size.z);\n";
  }
  s += np::band_begin(gradient) + "  for (uint b = 0u; b < hush_bands; ++b) {\n" +
       read_cells(D, "band_stride * b + ", "    ") + np::band_step(gradient) + "  }\n";
  return s + store_result(D, gradient, np::band_result(gradient));
}

// The runner of a plain noise (point_call / cells_call).
template <class Noise>
std::string plain_source(batch_layout layout, bool gradient) {
  using np = noise_program<Noise>;
  constexpr int D = np::dimension;
  const std::string d = std::to_string(D);
  std::string s = runner_preamble<Noise>(layout, gradient) +
                  "uniform uint hush_first;  // first sample of this dispatch\n"
                  "uniform uint hush_count;  // samples in the batch\n";
  if (layout != batch_layout::grid) {
    s += "layout(std430, binding = 0) readonly buffer hush_input { float hush_in[]; };\n";
    if (layout == batch_layout::samples) s += sample_input_declarations();
  } else {
    s += "uniform uint hush_base;   // grid index of the batch's first sample\n"
         "uniform uvec3 hush_size;  // samples along x, y, z\n"
         "layout(std430, binding = 0) readonly buffer hush_axes { uint hush_axis[]; };\n";
  }
  s += "layout(std430, binding = 1) writeonly buffer hush_output { float hush_out[]; };\n"
       "void main() {\n"
       "  uint n = hush_first + gl_GlobalInvocationID.x;\n"
       "  if (n >= hush_count) return;\n";
  if (layout != batch_layout::grid) {
    s += "  vec" + d + " p = vec" + d + "(";
    for (int a = 0; a < D; ++a)
      s += std::string(a ? ", " : "") + "hush_in[" + d + "u * n + " + std::to_string(a) + "u]";
    s += ");\n";
  } else {
    s += std::string(grid_axis_offsets()) + read_cells(D, "", "  ");
  }
  if (layout == batch_layout::points)
    return s + store_result(D, gradient, np::point_call(gradient));
  if (layout == batch_layout::grid) return s + store_result(D, gradient, np::cells_call(gradient));
  if constexpr (has_sample_call<np>::value) {
    return s + sample_inputs<Noise>(D) + store_result(D, gradient, np::sample_call(gradient));
  } else {
    // A noise that takes no footprint or normal: the extras are never given
    // (exec.hpp validates), so the point evaluation is its sample evaluation.
    return s + sample_inputs<Noise>(D) + store_result(D, gradient, np::point_call(gradient));
  }
}

}  // namespace detail

// The name of a runner, also its file's name without `.comp`:
// hush_<noise>_<points|grid|samples>[_gradient].
template <class Noise>
std::string runner_name(batch_layout layout, bool gradient) {
  return std::string("hush_") + noise_program<Noise>::name + "_" + layout_name(layout) +
         (gradient ? "_gradient" : "");
}

// The compute shader source for Noise (see the file comment for its interface), for OpenGL
// 4.3 core and Vulkan alike (hush/glsl/dialect.hpp: under Vulkan its uniforms are the std140
// block <runner name>_params at binding kVulkanParamsBinding).
template <class Noise>
std::string compute_source(batch_layout layout, bool gradient) {
  std::string s;
  if constexpr (is_banded<noise_program<Noise>>::value)
    s = detail::banded_source<Noise>(layout, gradient);
  else
    s = detail::plain_source<Noise>(layout, gradient);
  return dual_dialect(s, runner_name<Noise>(layout, gradient) + "_params");
}

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_COMPUTE_SOURCE_HPP
