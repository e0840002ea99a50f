// hush tests — analytic G-buffers for the coherence metrics: fronto-parallel planes seen by a
// pinhole camera, moving with known motion, so every channel has a closed form.
//
// Camera: focal length `focal` pixels, principal point at the image centre, looking along +z.
// The screen is split at column `split`: pixels x < split see plane A, the others plane B
// (a fixed screen-space split, like two windows). Plane P in frame i lies at depth
// z_i = depth + i * dz and is translated by i * (tx, ty) in world units; the world point seen
// at pixel centre p is X = (p - c) z_i / focal, its object-space position X - i (tx, ty).
#ifndef HUSH_TESTS_COHERENCE_ANALYTIC_SCENE_HPP
#define HUSH_TESTS_COHERENCE_ANALYTIC_SCENE_HPP

#include <cstdint>
#include <limits>
#include <vector>

#include "scene/gbuffer.hpp"

namespace hush_test {

struct moving_plane {
  std::uint32_t id = 1;
  double depth = 4;       // z at frame 0
  double dz = 0;          // per frame
  double tx = 0, ty = 0;  // world translation per frame
};

struct plane_scene {
  int width = 160, height = 120;
  double focal = 160;
  moving_plane a, b;
  int split = 1 << 30;  // column where plane B starts (default: only A)
  int frames = 2;
};

inline hush_tools::scene::gbuffer plane_frame(const plane_scene& s, int i) {
  hush_tools::scene::gbuffer g;
  g.width = s.width;
  g.height = s.height;
  const std::size_t n = g.pixels();
  g.depth.assign(n, std::numeric_limits<float>::infinity());
  g.velocity.assign(3 * n, 0.0f);
  g.object_id.assign(n, 0);
  g.triangle_id.assign(n, 0);
  g.barycentric.assign(3 * n, 0.0f);
  g.uv.assign(2 * n, 0.0f);
  g.uv_jacobian.assign(4 * n, 0.0f);
  g.normal.assign(3 * n, 0.0f);
  g.position.assign(3 * n, 0.0f);
  const double cx = s.width / 2.0, cy = s.height / 2.0;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const moving_plane& pl = x < s.split ? s.a : s.b;
      const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(s.width) +
                            static_cast<std::size_t>(x);
      const double px = x + 0.5, py = y + 0.5, z = pl.depth + i * pl.dz;
      const double ox = (px - cx) * z / s.focal - i * pl.tx;
      const double oy = (py - cy) * z / s.focal - i * pl.ty;
      g.object_id[p] = pl.id;
      g.depth[p] = static_cast<float>(z);
      g.position[3 * p] = static_cast<float>(ox);
      g.position[3 * p + 1] = static_cast<float>(oy);
      g.uv[2 * p] = static_cast<float>(ox);
      g.uv[2 * p + 1] = static_cast<float>(oy);
      g.uv_jacobian[4 * p] = g.uv_jacobian[4 * p + 3] = static_cast<float>(z / s.focal);
      g.normal[3 * p + 2] = -1.0f;
      g.barycentric[3 * p] = 1.0f;
      if (i == 0) continue;  // frame 0: velocity 0 (gbuffer.hpp)
      // The same object point in frame i-1, projected.
      const double zp = z - pl.dz;
      const double qx = cx + (ox + (i - 1) * pl.tx) * s.focal / zp;
      const double qy = cy + (oy + (i - 1) * pl.ty) * s.focal / zp;
      g.velocity[3 * p] = static_cast<float>(px - qx);
      g.velocity[3 * p + 1] = static_cast<float>(py - qy);
      g.velocity[3 * p + 2] = static_cast<float>(pl.dz);
    }
  return g;
}

inline std::vector<hush_tools::scene::gbuffer> plane_sequence(const plane_scene& s) {
  std::vector<hush_tools::scene::gbuffer> seq;
  for (int i = 0; i < s.frames; ++i) seq.push_back(plane_frame(s, i));
  return seq;
}

}  // namespace hush_test

#endif  // HUSH_TESTS_COHERENCE_ANALYTIC_SCENE_HPP
