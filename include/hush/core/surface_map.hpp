// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::surface_map: a per-sample input of 2D texture-space noises on
// surfaces (DESIGN.md "Per-sample inputs": the texture-to-surface map of a
// triangle). It is the 2 x 2 matrix T of Goldberg, Zwicker & Durand 2008,
// sec. 3.1, that takes local coordinates (s, t) on the surface (orthonormal,
// in surface length units) to texture coordinates (u, v):
//
//   (u, v)^T = T (s, t)^T,   T = [m00 m01; m10 m11].
//
// A noise that takes it (anisotropic noise) shapes its texture-space spectrum
// so that the noise looks as intended in (s, t), whatever the UV mapping does:
// with target spectrum E in surface space, the texture-space target is
// sqrt|det T| E(T^T w) (derived in docs/anisotropic.md: the power spectrum of
// g(T^{-1} u) is |det T| P(T^T w)). Identity: texture space is surface space.
//
// It also carries user-chosen target spectra (the paper's fig. 13): a target
// E(A^T xi) that is an isotropic E seen through a 2 x 2 matrix A (stretched by
// A's singular values, rotated by its singular vectors) is T replaced by T A
// (with_target(A)).
//
// Robustness (per-sample data: nothing here throws):
//  - from_triangle: a triangle with zero 3D area, or non-finite input, gives
//    the zero map; zero UV area gives a rank-1 (or zero) map; mirrored UVs a
//    map with negative determinant. Noises document what they do with those
//    (anisotropic noise: its mean, 0, where det T = 0; |det T| otherwise).
//  - from_matrix with a NaN or infinite entry gives the zero map.
// Layout: four floats, row by row (m00, m01, m10, m11), the same on every
// backend (GLSL: SSBO binding 4, compute_source.hpp).
#ifndef HUSH_CORE_SURFACE_MAP_HPP
#define HUSH_CORE_SURFACE_MAP_HPP

#include <cmath>

#include "hush/core/vec.hpp"

namespace hush {

struct surface_map {
  float m00 = 1, m01 = 0, m10 = 0, m11 = 1;  // identity by default

  static constexpr surface_map identity() { return {}; }
  static constexpr surface_map zero() { return {0, 0, 0, 0}; }

  // T = [a b; c d]; a non-finite entry gives zero().
  static surface_map from_matrix(double a, double b, double c, double d) {
    if (!(std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && std::isfinite(d)))
      return zero();
    const surface_map m{static_cast<float>(a), static_cast<float>(b), static_cast<float>(c),
                        static_cast<float>(d)};
    return m.finite() ? m : zero();  // entries beyond float range
  }

  // The map of a triangle from its vertices' positions p0, p1, p2 (any 3D
  // space with the surface's length unit) and texture coordinates uv0, uv1,
  // uv2. The local frame is e1 along p1 - p0 and e2 = n x e1 in the
  // triangle's plane (n its normal), so (s, t) is a right-handed orthonormal
  // frame seen from the front; T solves T [a1 a2] = [uv1 - uv0, uv2 - uv0]
  // with a1, a2 the edges in that frame. Degenerate input: see the file comment.
  static surface_map from_triangle(const dvec3& p0, const dvec3& p1, const dvec3& p2,
                                   const dvec2& uv0, const dvec2& uv1, const dvec2& uv2) {
    const dvec3 e1{p1.x - p0.x, p1.y - p0.y, p1.z - p0.z};
    const dvec3 e2{p2.x - p0.x, p2.y - p0.y, p2.z - p0.z};
    const double l1 = std::sqrt(dot(e1, e1));
    const dvec3 n = cross(e1, e2);
    const double ln = std::sqrt(dot(n, n));
    // Zero area (or NaN): nothing to map; also guards the divisions below.
    if (!(l1 > 0.0 && ln > 0.0 && std::isfinite(l1) && std::isfinite(ln))) return zero();
    const dvec3 x = scale(e1, 1.0 / l1);
    const dvec3 y = scale(cross(n, e1), 1.0 / (ln * l1));
    // Edges in the local frame: a1 = (l1, 0), a2 = (e2.x, e2.y).
    const double a2x = dot(e2, x), a2y = dot(e2, y);  // a2y = 2 area / l1 > 0
    const double du1 = uv1.x - uv0.x, dv1 = uv1.y - uv0.y;
    const double du2 = uv2.x - uv0.x, dv2 = uv2.y - uv0.y;
    // [a1 a2]^{-1} = [1/l1, -a2x / (l1 a2y); 0, 1 / a2y].
    const double i00 = 1.0 / l1, i01 = -a2x / (l1 * a2y), i11 = 1.0 / a2y;
    return from_matrix(du1 * i00, du1 * i01 + du2 * i11, dv1 * i00, dv1 * i01 + dv2 * i11);
  }

  // T A: the map for the target E(A^T xi) in surface space instead of E(xi)
  // (see the file comment), A = [a00 a01; a10 a11].
  surface_map with_target(double a00, double a01, double a10, double a11) const {
    return from_matrix(double(m00) * a00 + double(m01) * a10, double(m00) * a01 + double(m01) * a11,
                       double(m10) * a00 + double(m11) * a10,
                       double(m10) * a01 + double(m11) * a11);
  }

  double determinant() const { return double(m00) * m11 - double(m01) * m10; }
  bool finite() const {
    return std::isfinite(m00) && std::isfinite(m01) && std::isfinite(m10) && std::isfinite(m11);
  }
  friend bool operator==(const surface_map& a, const surface_map& b) {
    return a.m00 == b.m00 && a.m01 == b.m01 && a.m10 == b.m10 && a.m11 == b.m11;
  }
  friend bool operator!=(const surface_map& a, const surface_map& b) { return !(a == b); }

 private:
  static double dot(const dvec3& a, const dvec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
  static dvec3 cross(const dvec3& a, const dvec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  }
  static dvec3 scale(const dvec3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
};

}  // namespace hush

#endif  // HUSH_CORE_SURFACE_MAP_HPP
