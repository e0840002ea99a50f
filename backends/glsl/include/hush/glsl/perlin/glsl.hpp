// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The GLSL bodies of improved Perlin noise (include/hush/perlin.hpp), part of hush's
// function library (hush/glsl/library.hpp states their functions and contract): the
// CPU's float eval2 / eval3 operation by operation, from the generated constants
// (generator.hpp), the library's hashing and its lattice split.
#ifndef HUSH_GLSL_PERLIN_GLSL_HPP
#define HUSH_GLSL_PERLIN_GLSL_HPP

namespace hush {
namespace glsl {
namespace detail {

// Improved Perlin noise: include/hush/perlin.hpp eval2 / eval3.
constexpr const char* kPerlinBody = R"glsl(
// ---- Improved Perlin noise (Perlin 2002; include/hush/perlin.hpp).
float hush_fade(float t) {
  return t * t * t * (t * (t * HUSH_FADE5 + HUSH_FADE4) + HUSH_FADE3);
}
float hush_fade_derivative(float t) {
  return t * t * (t * (t * HUSH_FADE_DERIV4 + HUSH_FADE_DERIV3) + HUSH_FADE_DERIV2);
}
float hush_lerp(float a, float b, float t) { return a + t * (b - a); }
uint hush_perlin2_grad_index(uint h) { return h >> HUSH_PERLIN2_GRAD_SHIFT; }
uint hush_perlin3_grad_index(uint h) {
  return ((h >> HUSH_PERLIN3_INDEX_SHIFT) * HUSH_PERLIN3_GRAD_COUNT) >> HUSH_PERLIN3_INDEX_SHIFT;
}

// (value, d/dx, d/dy) from cells i0, i1 and fraction f; the value alone is .x
// (the compiler drops the gradient terms when only .x is used).
vec3 hush_perlin2_cells_gradient(uvec2 i0, uvec2 i1, vec2 f, uint key) {
  float fx = f.x, fy = f.y, fx1 = fx - 1.0, fy1 = fy - 1.0;
  uint g00 = hush_perlin2_grad_index(hush_lattice_hash(key, i0.x, i0.y));
  uint g10 = hush_perlin2_grad_index(hush_lattice_hash(key, i1.x, i0.y));
  uint g01 = hush_perlin2_grad_index(hush_lattice_hash(key, i0.x, i1.y));
  uint g11 = hush_perlin2_grad_index(hush_lattice_hash(key, i1.x, i1.y));
  float d00 = HUSH_PERLIN2_GRAD_X[g00] * fx + HUSH_PERLIN2_GRAD_Y[g00] * fy;
  float d10 = HUSH_PERLIN2_GRAD_X[g10] * fx1 + HUSH_PERLIN2_GRAD_Y[g10] * fy;
  float d01 = HUSH_PERLIN2_GRAD_X[g01] * fx + HUSH_PERLIN2_GRAD_Y[g01] * fy1;
  float d11 = HUSH_PERLIN2_GRAD_X[g11] * fx1 + HUSH_PERLIN2_GRAD_Y[g11] * fy1;
  float u = hush_fade(fx), v = hush_fade(fy);
  float x0 = hush_lerp(d00, d10, u), x1 = hush_lerp(d01, d11, u);
  float value = HUSH_PERLIN2_SCALE * hush_lerp(x0, x1, v);
  float du = hush_fade_derivative(fx), dv = hush_fade_derivative(fy);
  float gx = hush_lerp(hush_lerp(HUSH_PERLIN2_GRAD_X[g00], HUSH_PERLIN2_GRAD_X[g10], u),
                       hush_lerp(HUSH_PERLIN2_GRAD_X[g01], HUSH_PERLIN2_GRAD_X[g11], u), v) +
             du * hush_lerp(d10 - d00, d11 - d01, v);
  float gy = hush_lerp(hush_lerp(HUSH_PERLIN2_GRAD_Y[g00], HUSH_PERLIN2_GRAD_Y[g10], u),
                       hush_lerp(HUSH_PERLIN2_GRAD_Y[g01], HUSH_PERLIN2_GRAD_Y[g11], u), v) +
             dv * (x1 - x0);
  return vec3(value, HUSH_PERLIN2_SCALE * gx, HUSH_PERLIN2_SCALE * gy);
}
float hush_perlin2_cells(uvec2 i0, uvec2 i1, vec2 f, uint key) {
  return hush_perlin2_cells_gradient(i0, i1, f, key).x;
}

// Trilinear blend of eight corner quantities (corner n = a + 2b + 4c).
float hush_blend8(float q[8], float u, float v, float w) {
  return hush_lerp(hush_lerp(hush_lerp(q[0], q[1], u), hush_lerp(q[2], q[3], u), v),
                   hush_lerp(hush_lerp(q[4], q[5], u), hush_lerp(q[6], q[7], u), v), w);
}
// (value, d/dx, d/dy, d/dz); corner n = a + 2b + 4c sits at offset (a, b, c).
vec4 hush_perlin3_cells_gradient(uvec3 i0, uvec3 i1, vec3 f, uint key) {
  vec3 fo[2] = vec3[2](f, f - vec3(1.0));
  uvec3 io[2] = uvec3[2](i0, i1);
  float d[8], gxs[8], gys[8], gzs[8];
  for (int n = 0; n < 8; ++n) {
    int a = n & 1, b = (n >> 1) & 1, c = n >> 2;
    uint g = hush_perlin3_grad_index(hush_lattice_hash(key, io[a].x, io[b].y, io[c].z));
    gxs[n] = HUSH_PERLIN3_GRAD_X[g];
    gys[n] = HUSH_PERLIN3_GRAD_Y[g];
    gzs[n] = HUSH_PERLIN3_GRAD_Z[g];
    d[n] = gxs[n] * fo[a].x + gys[n] * fo[b].y + gzs[n] * fo[c].z;
  }
  float u = hush_fade(f.x), v = hush_fade(f.y), w = hush_fade(f.z);
  float x00 = hush_lerp(d[0], d[1], u), x10 = hush_lerp(d[2], d[3], u);
  float x01 = hush_lerp(d[4], d[5], u), x11 = hush_lerp(d[6], d[7], u);
  float y0 = hush_lerp(x00, x10, v), y1 = hush_lerp(x01, x11, v);
  float value = HUSH_PERLIN3_SCALE * hush_lerp(y0, y1, w);
  float du = hush_fade_derivative(f.x), dv = hush_fade_derivative(f.y);
  float dw = hush_fade_derivative(f.z);
  // d/dx of the lerp over x: du * (d[a=1] - d[a=0]), blended in y and z.
  float ex = hush_lerp(hush_lerp(d[1] - d[0], d[3] - d[2], v), hush_lerp(d[5] - d[4], d[7] - d[6], v), w);
  float ey = hush_lerp(x10 - x00, x11 - x01, w);
  float ez = y1 - y0;
  return vec4(value, HUSH_PERLIN3_SCALE * (hush_blend8(gxs, u, v, w) + du * ex),
              HUSH_PERLIN3_SCALE * (hush_blend8(gys, u, v, w) + dv * ey),
              HUSH_PERLIN3_SCALE * (hush_blend8(gzs, u, v, w) + dw * ez));
}
float hush_perlin3_cells(uvec3 i0, uvec3 i1, vec3 f, uint key) {
  return hush_perlin3_cells_gradient(i0, i1, f, key).x;
}

// Point evaluation: split each coordinate, then evaluate; NaN for non-finite input.
vec3 hush_perlin2_gradient(vec2 p, uint key, uvec2 period) {
  if (hush_is_nonfinite(p.x) || hush_is_nonfinite(p.y)) return vec3(hush_nan());
  hush_lattice_coord cx = hush_lattice_split(p.x, period.x);
  hush_lattice_coord cy = hush_lattice_split(p.y, period.y);
  return hush_perlin2_cells_gradient(uvec2(cx.i0, cy.i0), uvec2(cx.i1, cy.i1), vec2(cx.f, cy.f), key);
}
float hush_perlin2(vec2 p, uint key, uvec2 period) {
  return hush_perlin2_gradient(p, key, period).x;
}
vec4 hush_perlin3_gradient(vec3 p, uint key, uvec3 period) {
  if (hush_is_nonfinite(p.x) || hush_is_nonfinite(p.y) || hush_is_nonfinite(p.z))
    return vec4(hush_nan());
  hush_lattice_coord cx = hush_lattice_split(p.x, period.x);
  hush_lattice_coord cy = hush_lattice_split(p.y, period.y);
  hush_lattice_coord cz = hush_lattice_split(p.z, period.z);
  return hush_perlin3_cells_gradient(uvec3(cx.i0, cy.i0, cz.i0), uvec3(cx.i1, cy.i1, cz.i1),
                                     vec3(cx.f, cy.f, cz.f), key);
}
float hush_perlin3(vec3 p, uint key, uvec3 period) {
  return hush_perlin3_gradient(p, key, period).x;
}
)glsl";

}  // namespace detail
}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_PERLIN_GLSL_HPP
