// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The GLSL bodies of fractal sums (include/hush/fractal.hpp), part of hush's function
// library (hush/glsl/library.hpp states their functions and contract): one band's term
// in the CPU's order; the runner (hush/glsl/fractal/program.hpp) loops over the bands.
#ifndef HUSH_GLSL_FRACTAL_GLSL_HPP
#define HUSH_GLSL_FRACTAL_GLSL_HPP

namespace hush {
namespace glsl {
namespace detail {

// Fractal sums: include/hush/fractal.hpp value / value_and_gradient, one band at a time.
constexpr const char* kFractalBody = R"glsl(
// ---- Fractal sums (include/hush/fractal.hpp): one band's term, in the CPU's order.
bool hush_any_nonfinite(vec2 v) { return hush_is_nonfinite(v.x) || hush_is_nonfinite(v.y); }
bool hush_any_nonfinite(vec3 v) {
  return hush_is_nonfinite(v.x) || hush_is_nonfinite(v.y) || hush_is_nonfinite(v.z);
}
// sum + w * n (fBm) or sum + w * |n| (turbulence), as fractal::value.
float hush_fractal_add(float sum, float n, float weight, bool turbulence) {
  return sum + weight * (turbulence ? abs(n) : n);
}
// (value, gradient) + the band's (w n, chain g), chain = w f; turbulence
// negates a band whose value is negative (the CPU's sign -1: exact).
vec3 hush_fractal_add_gradient(vec3 acc, vec3 ng, float weight, float chain, bool turbulence) {
  if (turbulence && ng.x < 0.0) ng = -ng;
  return vec3(acc.x + weight * ng.x, acc.yz + chain * ng.yz);
}
vec4 hush_fractal_add_gradient(vec4 acc, vec4 ng, float weight, float chain, bool turbulence) {
  if (turbulence && ng.x < 0.0) ng = -ng;
  return vec4(acc.x + weight * ng.x, acc.yzw + chain * ng.yzw);
}
)glsl";

}  // namespace detail
}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_FRACTAL_GLSL_HPP
