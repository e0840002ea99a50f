// NPR Gabor noise tests: synthetic scenes whose G-buffers are known exactly.
//
// grid_scene: a fronto-parallel plane at depth `depth`, tessellated into nx x ny
// square quads of `cell` pixels whose top-left corner is at `origin`, two front-facing
// triangles per quad (clockwise on the y-down screen): triangle 2 q = (v00, v01, v10),
// 2 q + 1 = (v10, v01, v11), q = j nx + i. Its G-buffer (object 1, triangle ids, depth)
// is computed analytically per pixel centre; pixels off the plane are background
// (object 0, triangle 0xFFFFFFFF, depth +inf).
#ifndef HUSH_TESTS_NPR_GABOR_SCENES_HPP
#define HUSH_TESTS_NPR_GABOR_SCENES_HPP

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "hush/hush.hpp"  // the umbrella: tests/simd builds against the single header too

namespace npr_test {

struct grid_scene {
  std::size_t width = 0, height = 0;
  std::vector<hush::vec2> screen;
  std::vector<float> vdepth;
  std::vector<std::uint32_t> indices, tri_id, obj_id;
  std::vector<float> depth;
  std::vector<std::uint32_t> object, triangle;

  grid_scene(std::size_t w, std::size_t h, double ox, double oy, double cell, int nx, int ny,
             float z = 1.0f)
      : width(w), height(h) {
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        screen.push_back({static_cast<float>(ox + cell * i), static_cast<float>(oy + cell * j)});
        vdepth.push_back(z);
      }
    auto v = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::uint32_t q = static_cast<std::uint32_t>(j * nx + i);
        indices.insert(indices.end(), {v(i, j), v(i, j + 1), v(i + 1, j)});
        indices.insert(indices.end(), {v(i + 1, j), v(i, j + 1), v(i + 1, j + 1)});
        tri_id.insert(tri_id.end(), {2 * q, 2 * q + 1});
        obj_id.insert(obj_id.end(), {1u, 1u});
      }
    depth.assign(w * h, std::numeric_limits<float>::infinity());
    object.assign(w * h, 0u);
    triangle.assign(w * h, 0xFFFFFFFFu);
    for (std::size_t y = 0; y < h; ++y)
      for (std::size_t x = 0; x < w; ++x) {
        const double fx = (static_cast<double>(x) + 0.5 - ox) / cell;
        const double fy = (static_cast<double>(y) + 0.5 - oy) / cell;
        if (!(fx >= 0 && fy >= 0 && fx < nx && fy < ny)) continue;
        const int i = static_cast<int>(fx), j = static_cast<int>(fy);
        const std::uint32_t q = static_cast<std::uint32_t>(j * nx + i);
        depth[y * w + x] = z;
        object[y * w + x] = 1u;
        triangle[y * w + x] = (fx - i) + (fy - j) < 1.0 ? 2 * q : 2 * q + 1;
      }
  }

  hush::frame frame() const {
    hush::frame f;
    f.depth = {depth.data(), width, height};
    f.object_id = {object.data(), width, height};
    f.triangle_id = {triangle.data(), width, height};
    return f;
  }
  hush::triangle_list triangles() const {
    hush::triangle_list t;
    t.indices = indices;
    t.screen = screen;
    t.depth = vdepth;
    t.triangle_id = tri_id;
    t.object_id = obj_id;
    return t;
  }
};

// A grid_scene covering a w x h image (and `margin` pixels beyond each side) with
// cells of `cell` pixels, anchored so that the image centre is a grid vertex: scaling
// `cell` zooms the same surface about the image centre.
inline grid_scene covering(std::size_t w, std::size_t h, double cell, double margin) {
  const double cx = 0.5 * static_cast<double>(w), cy = 0.5 * static_cast<double>(h);
  const int kx = static_cast<int>(std::ceil((cx + margin) / cell));
  const int ky = static_cast<int>(std::ceil((cy + margin) / cell));
  return grid_scene(w, h, cx - kx * cell, cy - ky * cell, cell, 2 * kx, 2 * ky);
}

// The discrete normalised autocorrelation of the kernel on the pixel lattice,
// rho(d) = sum_x g(x) g(x + d) / sum_x g(x)^2 (g sampled at integer offsets plus a
// fractional shift averaged away by using several shifts), and sum_d rho(d)^2: what
// the variance of a sample variance over n pixels needs,
// Var(s^2) = (2 sum_d rho(d)^2 + kappa) / n for a field of unit variance with
// fourth-cumulant integral kappa.
template <class Kernel>
double rho_at(const Kernel& k, const hush::dvec2& F, int dx, int dy) {
  const int r = static_cast<int>(std::ceil(k.radius())) + 1;
  double num = 0, den = 0;
  for (int sy = 0; sy < 4; ++sy)
    for (int sx = 0; sx < 4; ++sx) {
      const double ox = 0.25 * sx + 0.125, oy = 0.25 * sy + 0.125;
      for (int y = -r; y <= r; ++y)
        for (int x = -r; x <= r; ++x) {
          const double g = k.template value<double>(hush::dvec2{x + ox, y + oy}, F);
          const double g2 = k.template value<double>(hush::dvec2{x + dx + ox, y + dy + oy}, F);
          num += g * g2;
          den += g * g;
        }
    }
  return num / den;
}

// sum_d |rho(d)|^power over the lags within two kernel radii (beyond, the
// kernels do not overlap and rho = 0): power 2 for the standard error of sample
// variances and autocorrelations, power 1 for that of sample means of functions
// of the noise (tests/style_test.cpp).
template <class Kernel>
double sum_rho_power(const Kernel& k, const hush::dvec2& F, int power) {
  const int reach = 2 * static_cast<int>(std::ceil(k.radius()));
  double sum = 0;
  for (int dy = -reach; dy <= reach; ++dy)
    for (int dx = -reach; dx <= reach; ++dx)
      sum += std::pow(std::fabs(rho_at(k, F, dx, dy)), power);
  return sum;
}

// A ground plane y = -1 (view space) under a camera at the origin looking along +Z, focal
// f = 80 px, the horizon at screen row -40 (above the 160 x 160 image, whose rows show depths
// 2 (top) to 0.4 (bottom)): the quad X in [-4, 4], Z in [back, 3]. A surface point (X, Z)
// is at screen (80 + 80 X / Z, -40 + 80 / Z), the scene's clip xy / w for any w != 0, so a
// vertex behind the camera (back < 0) has its (z s, z) = clip (x, w) through the viewport.
// The G-buffer is exact: depth 80 / (y + 40) at pixel row y (1/z affine in screen), object
// 1 everywhere (the plane covers the image for back < 0.4).
inline grid_scene ground_under_camera(float back) {
  const std::size_t w = 160, h = 160;
  grid_scene sc(w, h, 0.0, 0.0, 1.0, 1, 1);
  const auto at = [](double x, double z) {
    return hush::vec2{static_cast<float>(80.0 + 80.0 * x / z),
                      static_cast<float>(-40.0 + 80.0 / z)};
  };
  // Vertices (0,0), (1,0) far; (0,1), (1,1) near (behind the camera for back < 0).
  sc.screen = {at(-4, 3), at(4, 3), at(-4, back), at(4, back)};
  sc.vdepth = {3.0f, 3.0f, back, back};
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      sc.depth[y * w + x] = static_cast<float>(80.0 / (static_cast<double>(y) + 0.5 + 40.0));
      sc.object[y * w + x] = 1u;
    }
  return sc;
}

}  // namespace npr_test

#endif  // HUSH_TESTS_NPR_GABOR_SCENES_HPP
