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

#include <cstdint>
#include <string>

#include "hush/detail/constants.hpp"
#include "hush/gabor.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/noise_program.hpp"
#include "hush/glsl/gabor/walk.hpp"

namespace hush {
namespace glsl {
// Gabor noise, 2D and 3D, as a banded program: band 0's position is p / r
// (cell units), band 1's (3D: surface noise) p / (r sqrt(3/2)), split on the
// CPU in double. Uniforms: hush_gabor_key (seed_key(seed)), hush_gabor_kind (0 isotropic,
// 1 anisotropic, 2 hybrid), hush_gabor_words (words per impulse), hush_gabor_table_size
// and hush_table[] (the Poisson thresholds; 3D: hush_gabor_surface_table_size and
// the surface table at kGaborMaxThresholds), hush_par[] (float bits of the
// float constants the CPU uses, detail::gabor_par). The cell walk is gabor/walk.hpp, shared
// with the kit for the user's shader (gabor/shader.hpp). In 3D that is about 430 uniform
// components with the runner's, within the 512 that GL 4.3 guarantees a
// compute shader (GL_MAX_COMPUTE_UNIFORM_COMPONENTS).
template <int D>
struct noise_program<gabor<D>> {
  static constexpr int dimension = D;
  static constexpr const char* name = D == 2 ? "gabor2" : "gabor3";
  static constexpr bool banded = true;
  // hush_table's entries: the solid table, and in 3D the surface table after it.
  static constexpr int kTableEntries = detail::gabor_table_entries<D>();

  static constexpr int kCount = detail::gabor_par::kCount;

  static std::string uniforms() {
    namespace c = hush::detail::constants;
    const std::string d = std::to_string(D);
    std::string s =
        "uniform uint hush_gabor_key;         // seed_key(seed)\n"
        "uniform uint hush_gabor_kind;        // 0 isotropic, 1 anisotropic, 2 hybrid\n"
        "uniform uint hush_gabor_words;       // stream words per impulse\n"
        "uniform uint hush_gabor_table_size;  // Poisson thresholds used (solid)\n" +
        std::string(D == 3 ? "uniform uint hush_gabor_surface_table_size;  // (surface process)\n"
                           : "") +
        "uniform uint hush_table[" + std::to_string(kTableEntries) +
        "];  // poisson_table::thresholds(): solid" +
        (D == 3 ? ", then the surface table's at " + std::to_string(c::kGaborMaxThresholds)
                : std::string()) +
        "\n"
        "uniform uint hush_par[" +
        std::to_string(kCount) + "];  // float bits of the CPU's float constants\n";
    s += "float hush_gp(uint i) { return uintBitsToFloat(hush_par[i]); }\n"
         "uint hush_gabor_threshold(uint i) { return hush_table[i]; }\n";
    s += detail::gabor_walk_body(D);
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
    auto loc = [&](const char* n) { return gl.GetUniformLocation(program, n); };
    gl.Uniform1ui(loc("hush_gabor_key"), g.key());
    gl.Uniform1ui(loc("hush_gabor_kind"), static_cast<std::uint32_t>(g.marks().kind()));
    gl.Uniform1ui(loc("hush_gabor_words"), static_cast<std::uint32_t>(g.words_per_impulse()));
    gl.Uniform1ui(loc("hush_gabor_table_size"),
                  static_cast<std::uint32_t>(g.table().thresholds().size()));
    if constexpr (D == 3)
      gl.Uniform1ui(loc("hush_gabor_surface_table_size"),
                    static_cast<std::uint32_t>(g.surface_table().thresholds().size()));
    // The same words as the kit's block (hush/glsl/gabor/shader.hpp): gabor/walk.hpp.
    const auto table = detail::gabor_table_words(g);
    gl.Uniform1uiv(loc("hush_table"), kTableEntries, table.data());
    const auto par = detail::gabor_par_words(g);
    gl.Uniform1uiv(loc("hush_par"), kCount, par.data());
  }
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_GABOR_PROGRAM_HPP
