// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The impulse walk of Gabor noise in GLSL (gabor<D>::eval, filtered_eval, surface_eval):
// the cell loop, the Poisson count, the marks, the filtered pair and the surface slab, as
// one text that hush's batch runner (hush/glsl/gabor/program.hpp) and the kit for the user's
// shader (hush/glsl/gabor/shader.hpp) both compile, and the data both read: the float
// constants (gabor_par_words, indices gabor_par) and the Poisson thresholds
// (gabor_table_words). The text reads them through names its includer declares:
//   uint hush_gabor_key, hush_gabor_kind, hush_gabor_words, hush_gabor_table_size
//   (3D also hush_gabor_surface_table_size): seed_key(seed), the kind (0 isotropic,
//   1 anisotropic, 2 hybrid), stream words per impulse, the solid table's length;
//   float hush_gp(uint i): the float constant at index i (gabor_par);
//   uint hush_gabor_threshold(uint i): gabor_table_words()[i].
// The runner declares them as plain uniforms, the kit as members of its std140 block.
// Functions it defines (after library(): hashing, the lattice split, kGaborBody):
//   vec4 hush_gabor_eval(uvec3 i0, vec3 f, bool separable, bool filtered, mat3 fp, bool grad)
//   vec4 hush_gabor_surface_eval(uvec3 i0, vec3 f, vec3 n, mat3 fp, bool grad)   (3D)
// (value, gradient) at cell i0 + fraction f (cell units); their contract is program.hpp's.
#ifndef HUSH_GLSL_GABOR_WALK_HPP
#define HUSH_GLSL_GABOR_WALK_HPP

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>

#include "hush/detail/constants.hpp"
#include "hush/gabor.hpp"

namespace hush {
namespace glsl {
namespace detail {

// Indices of the float constants (hush_gp(i)), gabor_par_words.
struct gabor_par {
  enum : int {
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
};

// The thresholds' entries: the solid table, and in 3D the surface table after it, at
// kGaborMaxThresholds.
template <int D>
constexpr int gabor_table_entries() {
  return hush::detail::constants::kGaborMaxThresholds * (D == 3 ? 2 : 1);
}

inline std::uint32_t gabor_float_bits(float f) {
  std::uint32_t u = 0;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

// The float constants exactly as the CPU's float path rounds them (gabor<D>::eval and
// filtered_eval take each as T(double value)).
template <int D>
std::array<std::uint32_t, gabor_par::kCount> gabor_par_words(const gabor<D>& g) {
  namespace c = hush::detail::constants;
  using P = gabor_par;
  std::array<std::uint32_t, P::kCount> par{};
  auto bits = gabor_float_bits;
  const gabor_marks<D>& m = g.marks();
  const double a = g.kernel().envelope_exponent();
  par[P::kNegA] = bits(float(-a));
  par[P::kA] = bits(float(a));
  par[P::kTaperK] = bits(float(1.0 / (1.0 - c::kGaborTaperStart)));
  par[P::kScale] = bits(float(g.scale()));
  par[P::kGradScale] = bits(float(g.scale() * g.inverse_cell()));
  par[P::kTheta0] = bits(float(m.theta0()));
  par[P::kSpread] = bits(float(m.spread_turns()));
  par[P::kPhi0] = bits(float(m.phi0()));
  par[P::kDPhi] = bits(float(m.dphi()));
  if constexpr (D == 3) par[P::kOneMinusCap] = bits(float(1.0 - m.cos_cap()));
  for (std::size_t i = 0; i < 3; ++i) {
    const int axis = static_cast<int>(i);
    par[static_cast<std::size_t>(P::kFixed) + i] =
        bits(axis < D ? float(m.fixed_frequency()[axis]) : 0.0f);
    if constexpr (D == 3) {
      par[static_cast<std::size_t>(P::kFrameT) + i] = bits(float(m.frame_t()[axis]));
      par[static_cast<std::size_t>(P::kFrameB) + i] = bits(float(m.frame_b()[axis]));
      par[static_cast<std::size_t>(P::kFrameAxis) + i] = bits(float(m.frame_axis()[axis]));
    }
  }
  // gabor_filter's k = 2 A sigma^2 / r^2 and pi^2 / A.
  par[P::kFilterK] = bits(float(2.0 * a * c::kPixelFilterSigma * c::kPixelFilterSigma *
                                g.inverse_cell() * g.inverse_cell()));
  par[P::kFilterM] = bits(float(c::kPi * c::kPi / a));
  if constexpr (D == 3) {
    par[P::kSurfaceScale] = bits(float(g.surface_scale()));
    par[P::kSurfaceGradScale] = bits(float(g.surface_scale() * g.inverse_surface_cell()));
  }
  return par;
}

// poisson_table::thresholds() of the solid table, then (3D) the surface table's at
// kGaborMaxThresholds; unused entries 0 (the walk reads only the tables' lengths).
template <int D>
std::array<std::uint32_t, gabor_table_entries<D>()> gabor_table_words(const gabor<D>& g) {
  std::array<std::uint32_t, gabor_table_entries<D>()> table{};
  const auto& t = g.table().thresholds();
  std::copy(t.begin(), t.end(), table.begin());
  if constexpr (D == 3) {
    const auto& st = g.surface_table().thresholds();
    std::copy(st.begin(), st.end(), table.begin() + hush::detail::constants::kGaborMaxThresholds);
  }
  return table;
}

// The walk's GLSL for dimension dim (2 or 3): it depends on dim only.
inline std::string gabor_walk_body(int dim) {
  namespace c = hush::detail::constants;
  using P = gabor_par;
  std::string s = "const uint hush_gabor_dim = " + std::to_string(dim) + "u;\n";
  if (dim == 3)
    s += "const uint hush_surface_table = " + std::to_string(c::kGaborMaxThresholds) + "u;\n";
  for (const auto& [n, i] : {std::pair<const char*, int>{"NEG_A", P::kNegA},
                             {"A", P::kA},
                             {"TAPER_K", P::kTaperK},
                             {"SCALE", P::kScale},
                             {"GRAD_SCALE", P::kGradScale},
                             {"THETA0", P::kTheta0},
                             {"SPREAD", P::kSpread},
                             {"PHI0", P::kPhi0},
                             {"DPHI", P::kDPhi},
                             {"ONE_MINUS_CAP", P::kOneMinusCap},
                             {"FIXED", P::kFixed},
                             {"FRAME_T", P::kFrameT},
                             {"FRAME_B", P::kFrameB},
                             {"FRAME_AXIS", P::kFrameAxis},
                             {"FILTER_K", P::kFilterK},
                             {"FILTER_M", P::kFilterM},
                             {"SURFACE_SCALE", P::kSurfaceScale},
                             {"SURFACE_GRAD_SCALE", P::kSurfaceGradScale}})
    s += std::string("const uint hush_gp_") + n + " = " + std::to_string(i) + "u;\n";
  s +=
      R"glsl(// poisson_table::count: the number of thresholds <= u (sorted: stop at the first above),
// of the table at hush_gabor_threshold(base), `size` entries.
uint hush_gabor_count(uint u, uint base, uint size) {
  uint n = 0u;
  for (uint k = 0u; k < size; ++k) {
    if (hush_gabor_threshold(base + k) > u) break;
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
  if (hush_gabor_kind == 1u) {
    phi = vec3(hush_gp(hush_gp_FIXED), hush_gp(hush_gp_FIXED + 1u), hush_gp(hush_gp_FIXED + 2u));
    return w;
  }
  bool hybrid = hush_gabor_kind == 2u;
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
    uint key =
        hush_gabor_cell_stream(hush_gabor_key, uvec3(cell[0], cell[1], cell[2]), hush_gabor_dim);
    uint count = hush_gabor_count(hush_stream_word(key, 0u), 0u, hush_gabor_table_size);
    for (uint k = 0u; k < count; ++k) {
      uint counter = 1u + k * hush_gabor_words;
      uint w0 = hush_stream_word(key, counter);
      float d[3], d2[3];
      for (uint ax = 0u; ax < 3u; ++ax) {
        d[ax] = ax < hush_gabor_dim ? f[ax] - (float(o[ax]) + hush_gabor_byte(w0, ax)) : 0.0;
        d2[ax] = d[ax] * d[ax];
      }
      float s = hush_gabor_dim == 2u ? d2[0] + d2[1] : d2[0] + (d2[1] + d2[2]);
      if (!(s < 1.0)) continue;
      uint w1 = hush_gabor_words > 1u ? hush_stream_word(key, counter + 1u) : 0u;
      uint w2 = hush_gabor_words > 2u ? hush_stream_word(key, counter + 2u) : 0u;
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
  if (dim == 3)
    s += R"glsl(// ---- Surface noise (3D; gabor<3>::sample_eval with a normal, surface_eval).
// The surface process's unscaled sum and gradient sum at surface cell i0 + fraction f
// for unit normal n, tangents t, b and the plane's filter q, m without its amplitude
// (gabor<3>::surface_eval, operation by operation).
vec4 hush_gabor_surface_sum(uvec3 i0, vec3 f, vec3 n, vec3 t, vec3 b, mat3 q, mat3 m, bool grad) {
  float tk = hush_gp(hush_gp_TAPER_K);
  bool normalise = hush_gabor_kind != 1u;
  bool hybrid = hush_gabor_kind == 2u;
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
    uint key = hush_gabor_surface_stream(hush_gabor_key, uvec3(cell[0], cell[1], cell[2]));
    uint count =
        hush_gabor_count(hush_stream_word(key, 0u), hush_surface_table,
                         hush_gabor_surface_table_size);
    for (uint k = 0u; k < count; ++k) {
      uint counter = 1u + k * hush_gabor_words;
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
      if (hush_gabor_kind == 1u) {
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

}  // namespace detail
}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_GABOR_WALK_HPP
