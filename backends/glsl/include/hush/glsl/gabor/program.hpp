// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Gabor noise (include/hush/gabor.hpp) in GLSL: the library bodies every
// Gabor-type noise can reuse (hush's own exp and sin/cos, the cell streams,
// the word fields, the kernel's taper and separable factors) and
// noise_program<gabor<D>>, the runner's part (uniforms and the cell loop).
//
// Library functions (hush/glsl/gabor/glsl.hpp, part of library();
// constants from generator.hpp, no other number):
//   float hush_exp_neg(float x)             detail::exp_neg<float>: e^x, x <= 0
//   vec2  hush_sincos_turns(float t)        detail::sincos_turns<float>: (sin, cos)(2 pi t)
//   uint  hush_stream_key(uint seed, uint stream)   hush::rng(seed, stream)'s key
//   uint  hush_stream_word(uint key, uint counter)  its word number `counter`
//   float hush_gabor_byte(uint w, uint i), hush_gabor_half(uint w, uint i)
//                                            detail::gabor_byte / gabor_half
//   float hush_gabor_taper(float s, float k), vec2 hush_gabor_taper_derivative(s, k)
//   hush_gabor_axis hush_gabor_axis_factors(float d, float neg_a, float phi)
//   hush_gabor_row  hush_gabor_row_of(float w, y[, z])
//   float hush_gabor_pair(x, row, k), vec3 hush_gabor_pair_gradient(x, row, k, a)
//                                            gabor_kernel.hpp's separable kernel (grids)
//   float hush_gabor_point_phase(phi, d, dim), hush_gabor_point_term(w, s, theta, neg_a, k),
//   vec3 hush_gabor_point_term_gradient(w, s, theta, neg_a, k, a)
//                                            its point form (points)
//   vec3 hush_gabor_gradient_of_harmonics(pc, ps, s, k, a)   both forms' gradient
//   bool hush_gabor_unit_normal(n, out u), void hush_gabor_basis(n, out t, out b)
//                                            gabor<3>::unit_normal, detail::orthonormal_basis
//   uint hush_gabor_surface_stream(key, cell), vec4 hush_gabor_plane_offsets(d, n, t, b)
//                                            the surface process's stream and slab offsets
//
// The runner (noise_program<gabor<D>> below) is a banded program (one band in 2D, two in 3D)
// (noise_program.hpp): the CPU splits p / r into cell and fraction in double
// (as gabor<D>::eval does), the shader walks the 3^D cells around it (3D
// samples with a normal: the 27 surface cells of band 1). Its
// contract:
//  - the same integer path as the CPU: lattice_hash of the noise's key, the
//    cell's hush::rng stream, the Poisson count from the first word by the
//    same thresholds (a uniform array), the impulses' words and fields; the
//    fields become floats exactly ((2m + 1) 2^-9 or 2^-17), so every count,
//    position, weight and frequency mark equals the CPU's;
//  - the float arithmetic follows the CPU's order and form (gabor<D>::eval):
//    a grid's samples the separable form (gabor<D>::grid_sample), points the
//    point form (gabor_point_term), told apart by the runner's HUSH_GRID
//    (compute_source.hpp); GLSL may fuse a * b + c
//    and asks only for correctly rounded +, -, * (library.hpp), so values
//    differ from the CPU float result within twice gabor.hpp's float budget
//    (each op's error is bounded the same way), measured in
//    tests/gabor/glsl_gabor_test.cpp;
//  - samples with footprints (hush::samples): the filter of gabor_filter
//    (gabor_kernel.hpp) computed per sample in float (cyclic Jacobi on the
//    footprint matrix instead of the CPU's double Jacobi): within a stated
//    tolerance of the CPU (the test); degenerate footprints stay finite;
//  - 3D samples with a normal (surface noise, gabor.hpp sec. 4.3): in 3D the
//    program has a second band, p / (r sqrt(3/2)) split on the CPU in double
//    (gabor<3>::surface_eval's split), and the surface Poisson table follows
//    the solid one in hush_table. The shader forms the unit normal, the
//    tangent frame (Duff et al.) and the filter of the footprint projected
//    onto the plane in float (the CPU: double, rounded to float), then sums
//    the slab's impulses with the CPU's integer path and operation order
//    (simd/gabor-inl.h eval_surface); within the float budget plus the float
//    frame's error of the double reference (the test). A zero normal is the
//    solid noise, a NaN or +-Inf component gives NaN, as on the CPU. No fp64
//    anywhere in the shader; exp and sin/cos are hush's polynomials (not the
//    GPU's builtins), so they carry the CPU's error bounds on any GPU that
//    rounds +, -, * correctly;
//  - NaN or +-Inf in a coordinate gives NaN.
#ifndef HUSH_GLSL_GABOR_PROGRAM_HPP
#define HUSH_GLSL_GABOR_PROGRAM_HPP

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

#include "hush/detail/constants.hpp"
#include "hush/gabor.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/noise_program.hpp"

namespace hush {
namespace glsl {
// Gabor noise, 2D and 3D, as a banded program: band 0's position is p / r
// (cell units), band 1's (3D: surface noise) p / (r sqrt(3/2)), split on the
// CPU in double. Uniforms: hush_key (seed_key(seed)), hush_kind (0 isotropic,
// 1 anisotropic, 2 hybrid), hush_words (words per impulse), hush_table_size
// and hush_table[] (the Poisson thresholds; 3D: hush_surface_table_size and
// the surface table at kGaborMaxThresholds), hush_par[] (float bits of the
// float constants the CPU uses, indices below). In 3D that is about 430 uniform
// components with the runner's, within the 512 that GL 4.3 guarantees a
// compute shader (GL_MAX_COMPUTE_UNIFORM_COMPONENTS).
template <int D>
struct noise_program<gabor<D>> {
  static constexpr int dimension = D;
  static constexpr const char* name = D == 2 ? "gabor2" : "gabor3";
  static constexpr bool banded = true;
  // hush_table's entries: the solid table, and in 3D the surface table after it.
  static constexpr int kTableEntries = hush::detail::constants::kGaborMaxThresholds * (D == 3 ? 2 : 1);

  // hush_par indices.
  enum par : int {
    kNegA,
    kA,
    kTaperK,
    kScale,
    kGradScale,
    kTheta0,
    kSpread,
    kPhi0,
    kDPhi,
    kOneMinusCap,
    kFixed,                    // 3
    kFrameT = kFixed + 3,      // 3
    kFrameB = kFrameT + 3,     // 3
    kFrameAxis = kFrameB + 3,  // 3
    kFilterK = kFrameAxis + 3,
    kFilterM,
    kSurfaceScale,      // 3D: surface_scale()
    kSurfaceGradScale,  // 3D: surface_scale() / surface cell
    kCount
  };

  static std::string uniforms() {
    namespace c = hush::detail::constants;
    const std::string d = std::to_string(D);
    std::string s =
        "uniform uint hush_key;         // seed_key(seed)\n"
        "uniform uint hush_kind;        // 0 isotropic, 1 anisotropic, 2 hybrid\n"
        "uniform uint hush_words;       // stream words per impulse\n"
        "uniform uint hush_table_size;  // Poisson thresholds used (solid)\n" +
        std::string(D == 3 ? "uniform uint hush_surface_table_size;  // (surface process)\n"
                           : "") +
        "uniform uint hush_table[" + std::to_string(kTableEntries) +
        "];  // poisson_table::thresholds(): solid" +
        (D == 3 ? ", then the surface table's at " + std::to_string(c::kGaborMaxThresholds)
                : std::string()) +
        "\n"
        "uniform uint hush_par[" +
        std::to_string(kCount) + "];  // float bits of the CPU's float constants\n";
    s += "const uint hush_gabor_dim = " + d + "u;\n";
    if (D == 3)
      s += "const uint hush_surface_table = " + std::to_string(c::kGaborMaxThresholds) + "u;\n";
    for (const auto& [n, i] : {std::pair<const char*, int>{"NEG_A", kNegA},
                               {"A", kA},
                               {"TAPER_K", kTaperK},
                               {"SCALE", kScale},
                               {"GRAD_SCALE", kGradScale},
                               {"THETA0", kTheta0},
                               {"SPREAD", kSpread},
                               {"PHI0", kPhi0},
                               {"DPHI", kDPhi},
                               {"ONE_MINUS_CAP", kOneMinusCap},
                               {"FIXED", kFixed},
                               {"FRAME_T", kFrameT},
                               {"FRAME_B", kFrameB},
                               {"FRAME_AXIS", kFrameAxis},
                               {"FILTER_K", kFilterK},
                               {"FILTER_M", kFilterM},
                               {"SURFACE_SCALE", kSurfaceScale},
                               {"SURFACE_GRAD_SCALE", kSurfaceGradScale}})
      s += std::string("const uint hush_gp_") + n + " = " + std::to_string(i) + "u;\n";
    s += R"glsl(float hush_gp(uint i) { return uintBitsToFloat(hush_par[i]); }
// poisson_table::count: the number of thresholds <= u (sorted: stop at the first above),
// of the table at hush_table[base], `size` entries.
uint hush_gabor_count(uint u, uint base, uint size) {
  uint n = 0u;
  for (uint k = 0u; k < size; ++k) {
    if (hush_table[base + k] > u) break;
    ++n;
  }
  return n;
}
// gabor_marks::direction: the unit 3D direction of an impulse's second word (isotropic,
// hybrid), uniform in the cap around omega0.
vec3 hush_gabor_direction(uint w1) {
  float ct = 1.0 - hush_gp(hush_gp_ONE_MINUS_CAP) * hush_gabor_half(w1, 0u);
  float st = sqrt((1.0 - ct) * (1.0 + ct));
  vec2 sc = hush_sincos_turns(hush_gabor_half(w1, 1u));
  float lx = st * sc.y, ly = st * sc.x;
  vec3 dir;
  for (uint i = 0u; i < 3u; ++i)
    dir[i] = (hush_gp(hush_gp_FRAME_T + i) * lx + hush_gp(hush_gp_FRAME_B + i) * ly) +
             hush_gp(hush_gp_FRAME_AXIS + i) * ct;
  return dir;
}
// gabor_marks::draw: weight and frequency vector (cycles per cell) of an impulse's words.
float hush_gabor_marks(uint w0, uint w1, uint w2, out vec3 phi) {
  float w = float(2) * hush_gabor_byte(w0, hush_gabor_dim) - 1.0;
  if (hush_kind == 1u) {
    phi = vec3(hush_gp(hush_gp_FIXED), hush_gp(hush_gp_FIXED + 1u), hush_gp(hush_gp_FIXED + 2u));
    return w;
  }
  bool hybrid = hush_kind == 2u;
  float half_ = 1.0 / float(2);
  if (hush_gabor_dim == 2u) {
    float f = hybrid ? hush_gp(hush_gp_PHI0) + hush_gp(hush_gp_DPHI) * (hush_gabor_half(w1, 0u) - half_)
                     : hush_gp(hush_gp_PHI0);
    vec2 sc = hush_sincos_turns(hush_gp(hush_gp_THETA0) +
                                hush_gp(hush_gp_SPREAD) * (hush_gabor_byte(w0, 3u) - half_));
    phi = vec3(f * sc.y, f * sc.x, 0.0);
  } else {
    float f = hybrid ? hush_gp(hush_gp_PHI0) + hush_gp(hush_gp_DPHI) * (hush_gabor_half(w2, 0u) - half_)
                     : hush_gp(hush_gp_PHI0);
    phi = f * hush_gabor_direction(w1);
  }
  return w;
}
// gabor<D>::filtered_pair in `dim` dimensions: the term (value, d/dd) of one impulse
// without the amplitude (which scales the sum), w e^{-A d^T Q d - Phi^T M Phi}
// cos(2 pi <Phi, Q d>) tau(s) (one exponential), in its order: v = Q d, <d, v>,
// <Phi, v>, Phi^T M Phi as the sum over i <= j of (M_ij, doubled off the diagonal)
// Phi_i Phi_j, reading Q and M's upper triangles (gabor_filter_coefs).
vec4 hush_gabor_filtered_pair(mat3 q, mat3 m, vec3 d, float s, float w, vec3 phi, uint dim,
                              bool grad) {
  float neg_a = hush_gp(hush_gp_NEG_A), a = hush_gp(hush_gp_A), tk = hush_gp(hush_gp_TAPER_K);
  float qd[3];
  for (uint i = 0u; i < dim; ++i) {
    float z = q[i][0] * d[0];  // entry (min(i, j), max(i, j)): q[max][min] (column, row)
    for (uint j = 1u; j < dim; ++j) z += q[max(i, j)][min(i, j)] * d[j];
    qd[i] = z;
  }
  float dqd = d[0] * qd[0], theta = phi[0] * qd[0];
  for (uint i = 1u; i < dim; ++i) {
    dqd += d[i] * qd[i];
    theta += phi[i] * qd[i];
  }
  float att = m[0][0] * (phi[0] * phi[0]);
  for (uint i = 0u; i < dim; ++i)
    for (uint j = i; j < dim; ++j)
      if (i + j > 0u) att += (j == i ? m[j][i] : float(2) * m[j][i]) * (phi[i] * phi[j]);
  float p = w * hush_exp_neg(neg_a * dqd - att);
  vec2 sc = hush_sincos_turns(theta);
  vec4 r = vec4(0.0);
  if (grad) {
    vec2 tw = hush_gabor_taper_derivative(s, tk);
    float pc = p * sc.y, ps = HUSH_TWO_PI * ((p * tw.x) * sc.x);
    r.x = pc * tw.x;
    for (uint i = 0u; i < dim; ++i) {
      float mu = q[i][0] * phi[0];  // (Q Phi)_i
      for (uint j = 1u; j < dim; ++j) mu += q[max(i, j)][min(i, j)] * phi[j];
      r[1u + i] = pc * ((tw.y + tw.y) * d[i] - (a + a) * (tw.x * qd[i])) - ps * mu;
    }
  } else {
    r.x = (p * sc.y) * hush_gabor_taper(s, tk);
  }
  return r;
}
// The solid noise's unscaled sum and gradient sum at cell i0 + fraction f
// (gabor<D>::eval: the separable form on a grid's samples (`separable`), the point form
// at points; or filtered_eval with filter q, m when `filtered`, without its amplitude).
vec4 hush_gabor_sum(uvec3 i0, vec3 f, bool separable, bool filtered, mat3 q, mat3 m, bool grad) {
  float neg_a = hush_gp(hush_gp_NEG_A), a = hush_gp(hush_gp_A), tk = hush_gp(hush_gp_TAPER_K);
  float sum = 0.0;
  vec3 g = vec3(0.0);
  // Points (unfiltered and filtered) sum by fours (gabor_point_sum): kept term k into
  // partial sum k mod 4; the separable form in one chain.
  bool fours = !separable;
  vec4 part = vec4(0.0), gpart[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
  uint kept = 0u;
  uint cells = hush_gabor_dim == 2u ? 9u : 27u;
  for (uint n = 0u; n < cells; ++n) {
    int o[3];
    uint cell[3], rest = n;
    for (uint ax = 0u; ax < 3u; ++ax) {
      o[ax] = ax < hush_gabor_dim ? int(rest % 3u) - 1 : 0;
      rest /= 3u;
      cell[ax] = i0[ax] + uint(o[ax]);
    }
    uint key = hush_gabor_cell_stream(hush_key, uvec3(cell[0], cell[1], cell[2]), hush_gabor_dim);
    uint count = hush_gabor_count(hush_stream_word(key, 0u), 0u, hush_table_size);
    for (uint k = 0u; k < count; ++k) {
      uint counter = 1u + k * hush_words;
      uint w0 = hush_stream_word(key, counter);
      float d[3], d2[3];
      for (uint ax = 0u; ax < 3u; ++ax) {
        d[ax] = ax < hush_gabor_dim ? f[ax] - (float(o[ax]) + hush_gabor_byte(w0, ax)) : 0.0;
        d2[ax] = d[ax] * d[ax];
      }
      float s = hush_gabor_dim == 2u ? d2[0] + d2[1] : d2[0] + (d2[1] + d2[2]);
      if (!(s < 1.0)) continue;
      uint w1 = hush_words > 1u ? hush_stream_word(key, counter + 1u) : 0u;
      uint w2 = hush_words > 2u ? hush_stream_word(key, counter + 2u) : 0u;
      vec3 phi;
      float w = hush_gabor_marks(w0, w1, w2, phi);
      if (!filtered) {
        vec3 pg;  // (value, u, v): d/dd_i = u d_i - v phi_i
        if (separable) {
          hush_gabor_axis ax0 = hush_gabor_axis_factors(d[0], neg_a, phi[0]);
          hush_gabor_axis ax1 = hush_gabor_axis_factors(d[1], neg_a, phi[1]);
          hush_gabor_row row;
          if (hush_gabor_dim == 2u) {
            row = hush_gabor_row_of(w, ax1);
          } else {
            row = hush_gabor_row_of(w, ax1, hush_gabor_axis_factors(d[2], neg_a, phi[2]));
          }
          pg = grad ? hush_gabor_pair_gradient(ax0, row, tk, a)
                    : vec3(hush_gabor_pair(ax0, row, tk), 0.0, 0.0);
        } else {
          float theta = hush_gabor_point_phase(phi, vec3(d[0], d[1], d[2]), hush_gabor_dim);
          pg = grad ? hush_gabor_point_term_gradient(w, s, theta, neg_a, tk, a)
                    : vec3(hush_gabor_point_term(w, s, theta, neg_a, tk), 0.0, 0.0);
        }
        if (fours) {
          uint j = kept & 3u;
          ++kept;
          part[j] += pg.x;
          if (grad)
            for (uint i = 0u; i < hush_gabor_dim; ++i) gpart[i][j] += pg.y * d[i] - pg.z * phi[i];
          continue;
        }
        sum += pg.x;
        if (grad)
          for (uint i = 0u; i < hush_gabor_dim; ++i) g[i] += pg.y * d[i] - pg.z * phi[i];
        continue;
      }
      vec4 t = hush_gabor_filtered_pair(q, m, vec3(d[0], d[1], d[2]), s, w, phi, hush_gabor_dim,
                                        grad);
      uint j = kept & 3u;
      ++kept;
      part[j] += t.x;
      if (grad)
        for (uint i = 0u; i < hush_gabor_dim; ++i) gpart[i][j] += t[1u + i];
    }
  }
  if (fours) {
    sum = (part.x + part.y) + (part.z + part.w);
    for (uint i = 0u; i < hush_gabor_dim; ++i)
      g[i] = (gpart[i].x + gpart[i].y) + (gpart[i].z + gpart[i].w);
  }
  return vec4(sum, g);
}
// The noise (value, gradient) at cell i0 + fraction f, filtered over footprint fp;
// unfiltered in the separable form on a grid's samples (`separable`), else the point form.
vec4 hush_gabor_eval(uvec3 i0, vec3 f, bool separable, bool filtered, mat3 fp, bool grad) {
  mat3 q = mat3(1.0), m = mat3(0.0);
  float amp = 1.0;
  if (filtered)
    amp = hush_gabor_filter(fp, hush_gabor_dim, hush_gp(hush_gp_FILTER_K), hush_gp(hush_gp_FILTER_M),
                            q, m);
  // (sum * amplitude) * scale (unfiltered: amplitude 1).
  vec4 r = hush_gabor_sum(i0, f, separable, filtered, q, m, grad) * amp;
  return vec4(r.x * hush_gp(hush_gp_SCALE), r.yzw * hush_gp(hush_gp_GRAD_SCALE));
}
)glsl";
    if (D == 3)
      s += R"glsl(// ---- Surface noise (3D; gabor<3>::sample_eval with a normal, surface_eval).
// The surface process's unscaled sum and gradient sum at surface cell i0 + fraction f
// for unit normal n, tangents t, b and the plane's filter q, m without its amplitude
// (gabor<3>::surface_eval, operation by operation).
vec4 hush_gabor_surface_sum(uvec3 i0, vec3 f, vec3 n, vec3 t, vec3 b, mat3 q, mat3 m, bool grad) {
  float tk = hush_gp(hush_gp_TAPER_K);
  bool normalise = hush_kind != 1u;
  bool hybrid = hush_kind == 2u;
  float half_ = 1.0 / float(2);
  float sum = 0.0;
  vec3 g = vec3(0.0);
  for (uint nc = 0u; nc < 27u; ++nc) {
    int o[3];
    uint cell[3], rest = nc;
    for (uint ax = 0u; ax < 3u; ++ax) {
      o[ax] = int(rest % 3u) - 1;
      rest /= 3u;
      cell[ax] = i0[ax] + uint(o[ax]);
    }
    uint key = hush_gabor_surface_stream(hush_key, uvec3(cell[0], cell[1], cell[2]));
    uint count =
        hush_gabor_count(hush_stream_word(key, 0u), hush_surface_table, hush_surface_table_size);
    for (uint k = 0u; k < count; ++k) {
      uint counter = 1u + k * hush_words;
      uint w0 = hush_stream_word(key, counter);
      vec3 d;
      for (uint ax = 0u; ax < 3u; ++ax) d[ax] = f[ax] - (float(o[ax]) + hush_gabor_byte(w0, ax));
      vec4 o4 = hush_gabor_plane_offsets(d, n, t, b);  // zn, z2, dk
      float zn = o4.x, z2 = o4.y;
      if (!(z2 < 1.0)) continue;
      vec3 dk = vec3(o4.zw, 0.0);
      float s = dk.x * dk.x + dk.y * dk.y;
      if (!(s < 1.0)) continue;
      // The impulse's weight and 3D direction (anisotropic: omega0) and |Phi|.
      float w = float(2) * hush_gabor_byte(w0, 3u) - 1.0;
      vec3 dir;
      float phi = hush_gp(hush_gp_PHI0);
      if (hush_kind == 1u) {
        dir = vec3(hush_gp(hush_gp_FRAME_AXIS), hush_gp(hush_gp_FRAME_AXIS + 1u),
                   hush_gp(hush_gp_FRAME_AXIS + 2u));
      } else {
        dir = hush_gabor_direction(hush_stream_word(key, counter + 1u));
        if (hybrid)
          phi = hush_gp(hush_gp_PHI0) +
                hush_gp(hush_gp_DPHI) * (hush_gabor_half(hush_stream_word(key, counter + 2u), 0u) - half_);
      }
      float vt = (t.x * dir.x + t.y * dir.y) + t.z * dir.z;
      float vb = (b.x * dir.x + b.y * dir.y) + b.z * dir.z;
      float fq = phi;
      if (normalise) {
        float len2 = vt * vt + vb * vb;
        fq = len2 > 0.0 ? phi / sqrt(len2) : 0.0;
      }
      vec2 slab = hush_gabor_taper_derivative(z2, tk);
      vec4 r = hush_gabor_filtered_pair(q, m, dk, s, w, vec3(fq * vt, fq * vb, 0.0), 2u, grad);
      sum += r.x * slab.x;
      if (grad) {
        // d/dd of (kernel * slab taper): in the plane through dk, along n through z2.
        float dz = r.x * (slab.y * ((zn + zn) * HUSH_GABOR_SURFACE_INV_H2));
        for (uint ax = 0u; ax < 3u; ++ax)
          g[ax] += ((r.y * t[ax] + r.z * b[ax]) * HUSH_GABOR_SURFACE_CELL) * slab.x + dz * n[ax];
      }
    }
  }
  return vec4(sum, g);
}
// Surface noise (value, gradient) at surface cell i0 + fraction f with unit normal n,
// filtered over footprint fp (S, 3D) projected onto the tangent plane (surface_frame).
vec4 hush_gabor_surface_eval(uvec3 i0, vec3 f, vec3 n, mat3 fp, bool grad) {
  vec3 t, b;
  hush_gabor_basis(n, t, b);
  vec3 axes[2] = vec3[2](t, b);
  mat3 plane = mat3(0.0);
  for (uint i = 0u; i < 2u; ++i)
    for (uint j = i; j < 2u; ++j) {
      float v = 0.0;
      for (uint r = 0u; r < 3u; ++r)
        for (uint k = 0u; k < 3u; ++k) v += axes[i][r] * fp[k][r] * axes[j][k];
      plane[j][i] = v;
      plane[i][j] = v;
    }
  mat3 q, m;
  float amp =
      hush_gabor_filter(plane, 2u, hush_gp(hush_gp_FILTER_K), hush_gp(hush_gp_FILTER_M), q, m);
  vec4 r = hush_gabor_surface_sum(i0, f, n, t, b, q, m, grad) * amp;
  return vec4(r.x * hush_gp(hush_gp_SURFACE_SCALE), r.yzw * hush_gp(hush_gp_SURFACE_GRAD_SCALE));
}
)glsl";
    return s;
  }

  // Band 0: the solid process's cells; band 1 (3D): the surface process's.
  static int band_count(const gabor<D>&) { return D == 3 ? 2 : 1; }
  static std::uint32_t band_period(const gabor<D>&, int, int) { return 0; }
  // p / r (band 0) or p / (r sqrt(3/2)) (band 1) in double: gabor<D>::for_each_pair's
  // and surface_eval's splits.
  static vec<double, D> band_position(const gabor<D>& g, int band, const vec<double, D>& p) {
    double inv = g.inverse_cell();
    if constexpr (D == 3)
      if (band == 1) inv = g.inverse_surface_cell();
    vec<double, D> q;
    for (int a = 0; a < D; ++a) q[a] = p[a] * inv;
    return q;
  }
  // Samples (compute_source.hpp defines HUSH_SAMPLES) filter over fp; in 3D
  // a non-zero finite normal selects surface noise (band 1), a zero normal the
  // solid noise (band 0) and a non-finite one NaN, as gabor<3>::sample_eval.
  // Points and grids evaluate the plain solid noise: grids (HUSH_GRID) in the
  // separable form, points in the point form, as gabor<D>::eval chooses.
  static std::string band_begin(bool) {
    const std::string surface =
        D == 3 ? "  vec3 unit_n = vec3(0.0);\n  bool surface = false;\n" : "";
    return "  vec4 acc = vec4(0.0);\n  bool bad = false;\n" + surface +
           "#ifdef HUSH_SAMPLES\n"
           "  mat3 fp3 = mat3(fp);\n  bool filtered = true;\n" +
           std::string(D == 3 ? "  if (has_nrm) {\n    bad = hush_any_nonfinite(nrm);\n"
                                "    surface = !bad && hush_gabor_unit_normal(nrm, unit_n);\n  }\n"
                              : "") +
           "#else\n"
           "  mat3 fp3 = mat3(0.0);\n  bool filtered = false;\n"
           "#endif\n"
           "#ifdef HUSH_GRID\n"
           "  bool separable = true;  // a grid's samples: the separable form\n"
           "#else\n"
           "  bool separable = false;  // points: the point form\n"
           "#endif\n";
  }
  static std::string band_step(bool gradient) {
    const std::string g = gradient ? "true" : "false";
    if constexpr (D == 2)
      return "    bad = bad || hush_any_nonfinite(f);\n    if (!bad) acc = "
             "hush_gabor_eval(uvec3(i0, 0u), vec3(f, 0.0), separable, filtered, fp3, " +
             g + ");\n";
    return "    bad = bad || hush_any_nonfinite(f);\n"
           "    if (!bad && (b == 1u) == surface)\n"
           "      acc = b == 0u ? hush_gabor_eval(i0, f, separable, filtered, fp3, " +
           g + ")\n                    : hush_gabor_surface_eval(i0, f, unit_n, fp3, " + g +
           ");\n";
  }
  static std::string band_result(bool gradient) {
    if (!gradient) return "bad ? hush_nan() : acc.x";
    const std::string t = "vec" + std::to_string(D + 1);
    return "bad ? " + t + "(hush_nan()) : " + t + (D == 2 ? "(acc.xyz)" : "(acc)");
  }

  static void set_uniforms(const hush::glsl::detail::gl_api& gl,
                           hush::glsl::detail::gl_uint program, const gabor<D>& g) {
    namespace c = hush::detail::constants;
    auto loc = [&](const char* n) { return gl.GetUniformLocation(program, n); };
    gl.Uniform1ui(loc("hush_key"), g.key());
    gl.Uniform1ui(loc("hush_kind"), static_cast<std::uint32_t>(g.marks().kind()));
    gl.Uniform1ui(loc("hush_words"), static_cast<std::uint32_t>(g.words_per_impulse()));
    const auto& t = g.table().thresholds();
    gl.Uniform1ui(loc("hush_table_size"), static_cast<std::uint32_t>(t.size()));
    // Both tables in one array (the surface table at kGaborMaxThresholds).
    std::uint32_t table[std::size_t{kTableEntries}] = {};
    std::copy(t.begin(), t.end(), table);
    if constexpr (D == 3) {
      const auto& st = g.surface_table().thresholds();
      gl.Uniform1ui(loc("hush_surface_table_size"), static_cast<std::uint32_t>(st.size()));
      std::copy(st.begin(), st.end(), table + c::kGaborMaxThresholds);
    }
    gl.Uniform1uiv(loc("hush_table"), kTableEntries, table);
    std::uint32_t par[kCount] = {};
    const gabor_marks<D>& m = g.marks();
    // The float constants exactly as the CPU's float path rounds them.
    const double a = g.kernel().envelope_exponent();
    par[kNegA] = bits(float(-a));
    par[kA] = bits(float(a));
    par[kTaperK] = bits(float(1.0 / (1.0 - c::kGaborTaperStart)));
    par[kScale] = bits(float(g.scale()));
    par[kGradScale] = bits(float(g.scale() * g.inverse_cell()));
    par[kTheta0] = bits(float(m.theta0()));
    par[kSpread] = bits(float(m.spread_turns()));
    par[kPhi0] = bits(float(m.phi0()));
    par[kDPhi] = bits(float(m.dphi()));
    if constexpr (D == 3) par[kOneMinusCap] = bits(float(1.0 - m.cos_cap()));
    for (int i = 0; i < 3; ++i) {
      par[kFixed + i] = bits(i < D ? float(m.fixed_frequency()[i]) : 0.0f);
      if constexpr (D == 3) {
        par[kFrameT + i] = bits(float(m.frame_t()[i]));
        par[kFrameB + i] = bits(float(m.frame_b()[i]));
        par[kFrameAxis + i] = bits(float(m.frame_axis()[i]));
      }
    }
    // gabor_filter's k = 2 A sigma^2 / r^2 and pi^2 / A.
    par[kFilterK] = bits(float(2.0 * a * c::kPixelFilterSigma * c::kPixelFilterSigma *
                               g.inverse_cell() * g.inverse_cell()));
    par[kFilterM] = bits(float(c::kPi * c::kPi / a));
    if constexpr (D == 3) {
      par[kSurfaceScale] = bits(float(g.surface_scale()));
      par[kSurfaceGradScale] = bits(float(g.surface_scale() * g.inverse_surface_cell()));
    }
    gl.Uniform1uiv(loc("hush_par"), kCount, par);
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

#endif  // HUSH_GLSL_GABOR_PROGRAM_HPP
