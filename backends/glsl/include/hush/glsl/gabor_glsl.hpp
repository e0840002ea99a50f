// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Gabor noise (include/hush/gabor.hpp) in GLSL: the library bodies every
// Gabor-type noise can reuse (hush's own exp and sin/cos, the cell streams,
// the word fields, the kernel's taper and separable factors) and
// noise_program<gabor<D>>, the runner's part (uniforms and the cell loop).
//
// Library functions (hush/glsl/detail/gabor_body.hpp, part of library();
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
//                                            gabor_kernel.hpp's separable kernel
//
// The runner (noise_program<gabor<D>> below) is a one-band banded program
// (noise_program.hpp): the CPU splits p / r into cell and fraction in double
// (as gabor<D>::eval does), the shader walks the 3^D cells around it. Its
// contract:
//  - the same integer path as the CPU: lattice_hash of the noise's key, the
//    cell's hush::rng stream, the Poisson count from the first word by the
//    same thresholds (a uniform array), the impulses' words and fields; the
//    fields become floats exactly ((2m + 1) 2^-9 or 2^-17), so every count,
//    position, weight and frequency mark equals the CPU's;
//  - the float arithmetic follows the CPU's order; GLSL may fuse a * b + c
//    and asks only for correctly rounded +, -, * (library.hpp), so values
//    differ from the CPU float result within twice gabor.hpp's float budget
//    (each op's error is bounded the same way), measured in
//    tests/glsl/glsl_gabor_test.cpp;
//  - samples with footprints (hush::samples): the filter of gabor_filter
//    (gabor_kernel.hpp) computed per sample in float (cyclic Jacobi on the
//    footprint matrix instead of the CPU's double Jacobi): within a stated
//    tolerance of the CPU (the test); degenerate footprints stay finite;
//  - 3D samples with a non-zero normal (surface noise, gabor.hpp sec. 4.3)
//    are not evaluated on GLSL: the result is NaN (documented limitation;
//    docs/gabor.md). A zero normal is the solid noise, as on the CPU;
//  - NaN or +-Inf in a coordinate gives NaN.
#ifndef HUSH_GLSL_GABOR_GLSL_HPP
#define HUSH_GLSL_GABOR_GLSL_HPP

#include <cstdint>
#include <cstring>
#include <string>

#include "hush/detail/constants.hpp"
#include "hush/gabor.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/noise_program.hpp"

namespace hush {
namespace glsl {
// Gabor noise, 2D and 3D, as a one-band banded program: band 0's position is
// p / r (cell units), split on the CPU in double. Uniforms: hush_key
// (seed_key(seed)), hush_kind (0 isotropic, 1 anisotropic, 2 hybrid),
// hush_words (words per impulse), hush_table_size and hush_table[] (the
// Poisson thresholds), hush_par[] (float bits of the float constants the CPU
// uses, indices below).
template <int D>
struct noise_program<gabor<D>> {
  static constexpr int dimension = D;
  static constexpr const char* name = D == 2 ? "gabor2" : "gabor3";
  static constexpr bool banded = true;

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
    kCount
  };

  static std::string uniforms() {
    namespace c = hush::detail::constants;
    const std::string d = std::to_string(D);
    std::string s =
        "uniform uint hush_key;         // seed_key(seed)\n"
        "uniform uint hush_kind;        // 0 isotropic, 1 anisotropic, 2 hybrid\n"
        "uniform uint hush_words;       // stream words per impulse\n"
        "uniform uint hush_table_size;  // Poisson thresholds used\n"
        "uniform uint hush_table[" +
        std::to_string(c::kGaborMaxThresholds) +
        "];  // poisson_table::thresholds()\n"
        "uniform uint hush_par[" +
        std::to_string(kCount) + "];  // float bits of the CPU's float constants\n";
    s += "const uint hush_gabor_dim = " + d + "u;\n";
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
                               {"FILTER_M", kFilterM}})
      s += std::string("const uint hush_gp_") + n + " = " + std::to_string(i) + "u;\n";
    s += R"glsl(float hush_gp(uint i) { return uintBitsToFloat(hush_par[i]); }
// poisson_table::count: the number of thresholds <= u (sorted: stop at the first above).
uint hush_gabor_count(uint u) {
  uint n = 0u;
  for (uint k = 0u; k < hush_table_size; ++k) {
    if (hush_table[k] > u) break;
    ++n;
  }
  return n;
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
    float ct = 1.0 - hush_gp(hush_gp_ONE_MINUS_CAP) * hush_gabor_half(w1, 0u);
    float st = sqrt((1.0 - ct) * (1.0 + ct));
    vec2 sc = hush_sincos_turns(hush_gabor_half(w1, 1u));
    float lx = st * sc.y, ly = st * sc.x;
    for (uint i = 0u; i < 3u; ++i)
      phi[i] = f * ((hush_gp(hush_gp_FRAME_T + i) * lx + hush_gp(hush_gp_FRAME_B + i) * ly) +
                    hush_gp(hush_gp_FRAME_AXIS + i) * ct);
  }
  return w;
}
// The solid noise's unscaled sum and gradient sum at cell i0 + fraction f
// (gabor<D>::eval, or filtered_eval with filter q, m, amp when `filtered`).
vec4 hush_gabor_sum(uvec3 i0, vec3 f, bool filtered, mat3 q, mat3 m, float amp, bool grad) {
  float neg_a = hush_gp(hush_gp_NEG_A), a = hush_gp(hush_gp_A), tk = hush_gp(hush_gp_TAPER_K);
  float sum = 0.0;
  vec3 g = vec3(0.0);
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
    uint count = hush_gabor_count(hush_stream_word(key, 0u));
    for (uint k = 0u; k < count; ++k) {
      uint counter = 1u + k * hush_words;
      uint w0 = hush_stream_word(key, counter);
      float d[3], d2[3];
      for (uint ax = 0u; ax < 3u; ++ax) {
        d[ax] = ax < hush_gabor_dim ? (f[ax] - float(o[ax])) - hush_gabor_byte(w0, ax) : 0.0;
        d2[ax] = d[ax] * d[ax];
      }
      float s = hush_gabor_dim == 2u ? d2[0] + d2[1] : d2[0] + (d2[1] + d2[2]);
      if (!(s < 1.0)) continue;
      uint w1 = hush_words > 1u ? hush_stream_word(key, counter + 1u) : 0u;
      uint w2 = hush_words > 2u ? hush_stream_word(key, counter + 2u) : 0u;
      vec3 phi;
      float w = hush_gabor_marks(w0, w1, w2, phi);
      if (!filtered) {
        hush_gabor_axis ax0 = hush_gabor_axis_factors(d[0], neg_a, phi[0]);
        hush_gabor_axis ax1 = hush_gabor_axis_factors(d[1], neg_a, phi[1]);
        hush_gabor_row row;
        if (hush_gabor_dim == 2u) {
          row = hush_gabor_row_of(w, ax1);
        } else {
          row = hush_gabor_row_of(w, ax1, hush_gabor_axis_factors(d[2], neg_a, phi[2]));
        }
        if (grad) {
          vec3 pg = hush_gabor_pair_gradient(ax0, row, tk, a);
          sum += pg.x;
          for (uint i = 0u; i < hush_gabor_dim; ++i) g[i] += pg.y * d[i] - pg.z * phi[i];
        } else {
          sum += hush_gabor_pair(ax0, row, tk);
        }
        continue;
      }
      // filtered_pair: w amp e^{-Phi^T M Phi} e^{-A d^T Q d} cos(2 pi <Q Phi, d>) tau(s).
      float mu[3], qd[3];
      float att = 0.0, dqd = 0.0, theta = 0.0;
      for (uint i = 0u; i < hush_gabor_dim; ++i) {
        float x = 0.0, y = 0.0, z = 0.0;
        for (uint j = 0u; j < hush_gabor_dim; ++j) {
          x += q[j][i] * phi[j];
          y += m[j][i] * phi[j];
          z += q[j][i] * d[j];
        }
        mu[i] = x;
        att += phi[i] * y;
        qd[i] = z;
        dqd += d[i] * z;
      }
      for (uint i = 0u; i < hush_gabor_dim; ++i) theta += mu[i] * d[i];
      float p = ((w * amp) * hush_exp_neg(-att)) * hush_exp_neg(neg_a * dqd);
      vec2 sc = hush_sincos_turns(theta);
      if (grad) {
        vec2 tw = hush_gabor_taper_derivative(s, tk);
        float pc = p * sc.y, ps = HUSH_TWO_PI * ((p * tw.x) * sc.x);
        sum += pc * tw.x;
        for (uint i = 0u; i < hush_gabor_dim; ++i)
          g[i] += pc * ((tw.y + tw.y) * d[i] - (a + a) * (tw.x * qd[i])) - ps * mu[i];
      } else {
        sum += (p * sc.y) * hush_gabor_taper(s, tk);
      }
    }
  }
  return vec4(sum, g);
}
// The noise (value, gradient) at cell i0 + fraction f, filtered over footprint fp.
vec4 hush_gabor_eval(uvec3 i0, vec3 f, bool filtered, mat3 fp, bool grad) {
  mat3 q = mat3(1.0), m = mat3(0.0);
  float amp = 1.0;
  if (filtered)
    amp = hush_gabor_filter(fp, hush_gabor_dim, hush_gp(hush_gp_FILTER_K), hush_gp(hush_gp_FILTER_M),
                            q, m);
  vec4 r = hush_gabor_sum(i0, f, filtered, q, m, amp, grad);
  return vec4(r.x * hush_gp(hush_gp_SCALE), r.yzw * hush_gp(hush_gp_GRAD_SCALE));
}
)glsl";
    return s;
  }

  static int band_count(const gabor<D>&) { return 1; }
  static std::uint32_t band_period(const gabor<D>&, int, int) { return 0; }
  // p / r in double: gabor<D>::for_each_pair's split.
  static vec<double, D> band_position(const gabor<D>& g, int, const vec<double, D>& p) {
    vec<double, D> q;
    for (int a = 0; a < D; ++a) q[a] = p[a] * g.inverse_cell();
    return q;
  }
  // Samples (compute_source.hpp defines HUSH_SAMPLES) filter over fp and
  // refuse surface noise (NaN); points and grids evaluate the plain noise.
  static std::string band_begin(bool) {
    return "  vec4 acc = vec4(0.0);\n  bool bad = false;\n"
           "#ifdef HUSH_SAMPLES\n"
           "  mat3 fp3 = mat3(fp);\n  bool filtered = true;\n" +
           std::string(D == 3 ? "  bad = has_nrm && nrm != vec3(0.0);\n" : "") +
           "#else\n"
           "  mat3 fp3 = mat3(0.0);\n  bool filtered = false;\n"
           "#endif\n";
  }
  static std::string band_step(bool gradient) {
    const std::string widen_i = D == 2 ? "uvec3(i0, 0u)" : "i0";
    const std::string widen_f = D == 2 ? "vec3(f, 0.0)" : "f";
    return "    bad = bad || hush_any_nonfinite(f);\n    if (!bad) acc = hush_gabor_eval(" +
           widen_i + ", " + widen_f + ", filtered, fp3, " + (gradient ? "true" : "false") + ");\n";
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
    if (!t.empty())
      gl.Uniform1uiv(loc("hush_table"), static_cast<hush::glsl::detail::gl_sizei>(t.size()),
                     t.data());
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

#endif  // HUSH_GLSL_GABOR_GLSL_HPP
