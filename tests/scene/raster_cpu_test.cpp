// Tests of the CPU rasterizer (examples/scene/raster_cpu.hpp): the fill rule (no
// double coverage, no cracks, also across the near plane), exactness of depth, uv,
// position and the uv Jacobian against analytic ray casts, back-face culling that
// changes nothing on closed meshes, exact velocity (reprojection of frame i onto
// frame i-1 for every motion scene, and the analytic velocity of a translation; the
// forward velocity likewise onto frame i+1),
// and bit-for-bit determinism.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include "hush/core/error.hpp"
#include "raster_cpu.hpp"
#include "scene_test_util.hpp"

namespace {

namespace hs = hush_tools::scene;
using glm::dmat4;
using glm::dvec3;
using glm::dvec4;

constexpr double kFloatEps = 1.0 / (1 << 24);  // float32 unit roundoff

// The world-space ray through the centre of pixel (x, y).
struct ray {
  dvec3 origin, direction;
};
ray pixel_ray(const hs::camera_pose& pose, int width, int height, double x, double y) {
  const dmat4 inv =
      glm::inverse(hs::projection_matrix(pose, width, height) * hs::view_matrix(pose));
  const double nx = 2.0 * x / width - 1.0, ny = 1.0 - 2.0 * y / height;
  const dvec4 a = inv * dvec4(nx, ny, -1.0, 1.0), b = inv * dvec4(nx, ny, 0.5, 1.0);
  const dvec3 pa = dvec3(a) / a.w, pb = dvec3(b) / b.w;
  return {pa, glm::normalize(pb - pa)};
}

// A tilted, finely tessellated plane that fills the whole image.
hs::scene tilted_plane(double tilt_degrees, const hs::camera_pose& pose) {
  const dmat4 model = glm::rotate(dmat4(1.0), glm::radians(tilt_degrees), dvec3(1.0, 0.3, 0.0)) *
                      glm::rotate(dmat4(1.0), glm::radians(90.0), dvec3(1.0, 0.0, 0.0));
  return hush_scene_test::single(hs::make_plane(40.0f, 40.0f, 37, 41, 1.0f), model, pose);
}

TEST_CASE("fill rule: a tessellated plane filling the image covers every pixel exactly once") {
  hs::camera_pose pose;
  pose.eye = dvec3(0.0, 0.0, 3.0);
  for (double tilt : {0.0, 17.0, 40.0}) {
    const hs::scene s = tilted_plane(tilt, pose);
    std::vector<std::uint32_t> coverage;
    hs::raster_options o;
    o.coverage = &coverage;
    const hs::gbuffer g = hs::render_cpu(s, 0, 173, 131, o);
    std::size_t ones = 0;
    for (std::uint32_t c : coverage) ones += c == 1;
    CHECK(ones == coverage.size());
    for (std::size_t p = 0; p < g.pixels(); ++p) REQUIRE(g.covered(p));
  }
}

TEST_CASE("fill rule: triangle fans through pixel centres and edges along pixel rows") {
  // A 16-triangle fan whose centre vertex and many edges fall exactly on pixel
  // centres, rows and columns: the case the top-left rule exists for.
  hs::mesh fan;
  fan.positions.emplace_back(0.0f, 0.0f, 0.0f);
  const int spokes = 16;
  for (int k = 0; k < spokes; ++k) {
    const double a = 2.0 * 3.14159265358979 * k / spokes;
    // On a square, so the spokes end at exact coordinates.
    const double c = std::cos(a), s = std::sin(a), m = std::max(std::fabs(c), std::fabs(s));
    fan.positions.emplace_back(static_cast<float>(4.0 * c / m), static_cast<float>(4.0 * s / m),
                               0.0f);
  }
  for (std::size_t i = 0; i < fan.positions.size(); ++i) {
    fan.normals.emplace_back(0.0f, 0.0f, 1.0f);
    fan.uvs.emplace_back(0.0f, 0.0f);
  }
  for (int k = 0; k < spokes; ++k)
    fan.indices.insert(fan.indices.end(), {0u, static_cast<std::uint32_t>(1 + k),
                                           static_cast<std::uint32_t>(1 + (k + 1) % spokes)});
  // Orthographic-like: far camera, narrow field, so that world units map to whole pixels.
  hs::camera_pose pose;
  pose.eye = dvec3(0.0, 0.0, 100.0);
  pose.fov_y = 2.0 * std::atan(4.0 / 100.0);  // the square's half height fills half the image
  const hs::scene s = hush_scene_test::single(fan, dmat4(1.0), pose);
  std::vector<std::uint32_t> coverage;
  hs::raster_options o;
  o.coverage = &coverage;
  for (int size : {64, 65, 16}) {
    hs::render_cpu(s, 0, size, size, o);
    std::size_t ones = 0, over = 0;
    for (std::uint32_t c : coverage) {
      ones += c == 1;
      over += c > 1;
    }
    CHECK(over == 0u);
    CHECK(ones == coverage.size());  // the square fills the image
  }
}

TEST_CASE("near plane: a ground plane through the camera is clipped without cracks or garbage") {
  hs::camera_pose pose;
  pose.eye = dvec3(0.0, 0.4, 0.0);
  pose.target = dvec3(0.0, 0.3, -1.0);
  pose.near_depth = 0.05;
  // Triangles of 5 units: many cross the near plane and extend behind the camera.
  const hs::scene s =
      hush_scene_test::single(hs::make_plane(60.0f, 60.0f, 12, 12, 1.0f), dmat4(1.0), pose);
  std::vector<std::uint32_t> coverage;
  hs::raster_options o;
  o.coverage = &coverage;
  const int w = 160, h = 120;
  const hs::gbuffer g = hs::render_cpu(s, 0, w, h, o);
  std::size_t covered = 0;
  for (int x = 0; x < w; ++x) {
    bool seen = false;  // below the horizon every pixel is covered, exactly once
    for (int y = 0; y < h; ++y) {
      const std::size_t p =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
      CHECK(coverage[p] <= 1u);
      if (seen) CHECK(g.covered(p));
      if (!g.covered(p)) continue;
      seen = true;
      ++covered;
      CHECK(g.depth[p] >= pose.near_depth * (1.0 - 1e-6));
      CHECK(std::isfinite(g.uv[2 * p] + g.uv[2 * p + 1] + g.position[3 * p]));
      for (int c = 0; c < 3; ++c)
        CHECK(g.barycentric[3 * p + c] == doctest::Approx(0.5).epsilon(0.5 + 1e-3));
    }
  }
  CHECK(covered > static_cast<std::size_t>(w * h / 3));
}

TEST_CASE("depth, position, uv and the uv Jacobian equal analytic ray casts on a plane") {
  hs::camera_pose pose;
  pose.eye = dvec3(0.3, 0.2, 3.0);
  pose.target = dvec3(0.0, -0.1, 0.0);
  const hs::scene s = tilted_plane(35.0, pose);
  const int w = 96, h = 72;
  const hs::gbuffer g = hs::render_cpu(s, 0, w, h);
  const dmat4 model = s.objects[0].model(0), inv_model = glm::inverse(model);
  const dvec3 plane_point = dvec3(model * dvec4(0.0, 0.0, 0.0, 1.0));
  const dvec3 plane_normal =
      glm::normalize(dvec3(glm::transpose(inv_model) * dvec4(0.0, 1.0, 0.0, 0.0)));
  const dvec3 view_axis = glm::normalize(pose.target - pose.eye);
  // Object-space hit of the ray through screen point (x, y) (not just pixel centres).
  const auto hit = [&](double x, double y) {
    const ray r = pixel_ray(pose, w, h, x, y);
    const double t =
        glm::dot(plane_point - r.origin, plane_normal) / glm::dot(r.direction, plane_normal);
    return r.origin + t * r.direction;
  };
  double max_depth = 0.0, max_uv = 0.0, max_jacobian = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t p =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
      REQUIRE(g.covered(p));
      const dvec3 world = hit(x + 0.5, y + 0.5);
      const dvec3 object = dvec3(inv_model * dvec4(world, 1.0));
      const double depth = glm::dot(world - pose.eye, view_axis);
      max_depth = std::max(max_depth, std::fabs(g.depth[p] - depth) / depth);
      const auto uv_of = [](const dvec3& o) {
        return glm::dvec2(o.x / 40.0 + 0.5, o.z / 40.0 + 0.5);
      };
      const glm::dvec2 uv = uv_of(object);
      max_uv = std::max({max_uv, std::fabs(g.uv[2 * p] - uv.x), std::fabs(g.uv[2 * p + 1] - uv.y)});
      for (int c = 0; c < 3; ++c)
        CHECK(g.position[3 * p + c] == doctest::Approx(object[c]).epsilon(1e-5));
      // Central differences of the analytic uv, step 1/64 pixel: error ~ step^2 |uv'''|.
      const double d = 1.0 / 64.0;
      const glm::dvec2 ux = (uv_of(dvec3(inv_model * dvec4(hit(x + 0.5 + d, y + 0.5), 1.0))) -
                             uv_of(dvec3(inv_model * dvec4(hit(x + 0.5 - d, y + 0.5), 1.0)))) /
                            (2 * d);
      const glm::dvec2 uy = (uv_of(dvec3(inv_model * dvec4(hit(x + 0.5, y + 0.5 + d), 1.0))) -
                             uv_of(dvec3(inv_model * dvec4(hit(x + 0.5, y + 0.5 - d), 1.0)))) /
                            (2 * d);
      const double scale =
          std::max({std::fabs(ux.x), std::fabs(ux.y), std::fabs(uy.x), std::fabs(uy.y)});
      const double err = std::max(
          {std::fabs(g.uv_jacobian[4 * p] - ux.x), std::fabs(g.uv_jacobian[4 * p + 1] - uy.x),
           std::fabs(g.uv_jacobian[4 * p + 2] - ux.y), std::fabs(g.uv_jacobian[4 * p + 3] - uy.y)});
      max_jacobian = std::max(max_jacobian, err / scale);
    }
  MESSAGE("plane ray cast: max relative depth error " << max_depth << ", max uv error " << max_uv
                                                      << ", max relative Jacobian error "
                                                      << max_jacobian);
  // float32 storage: relative 2^-24 on depth; uv in [0, 1] within a few ulps; the
  // Jacobian differs from the central difference by O(d^2) relative (d = 1/64 pixel).
  CHECK(max_depth < 4 * kFloatEps);
  CHECK(max_uv < 1e-6);
  CHECK(max_jacobian < 1e-4);
}

TEST_CASE("back-face culling leaves the G-buffer of closed meshes unchanged") {
  hs::raster_options no_cull;
  no_cull.cull_back_faces = false;
  for (const char* name : {"rotate", "zoom", "walkthrough"}) {
    const hs::scene s = hs::make_scene(name);
    for (int f : {0, 30}) {
      INFO(std::string(name) << " frame " << f);
      CHECK(hush_scene_test::same_bits(hs::render_cpu(s, f, 160, 120),
                                       hs::render_cpu(s, f, 160, 120, no_cull)));
    }
  }
}

TEST_CASE("determinism: rendering the same frame twice gives the same bits") {
  const hs::scene s = hs::make_scene("walkthrough");
  const hs::gbuffer a = hs::render_cpu(s, 12, 200, 150), b = hs::render_cpu(s, 12, 200, 150);
  CHECK(hush_scene_test::same_bits(a, b));
  const hs::gbuffer c = hs::render_cpu(hs::make_scene("walkthrough"), 12, 200, 150);
  CHECK(hush_scene_test::same_bits(a, c));
}

TEST_CASE("background pixels hold the documented values, IDs and barycentrics are consistent") {
  const hs::scene s = hs::make_scene("walkthrough");  // sky above the horizon
  const hs::gbuffer g = hs::render_cpu(s, 5, 120, 90);
  std::size_t background = 0;
  for (std::size_t p = 0; p < g.pixels(); ++p) {
    if (!g.covered(p)) {
      ++background;
      CHECK(std::isinf(g.depth[p]));
      CHECK(g.triangle_id[p] == 0xFFFFFFFFu);
      CHECK(g.velocity[3 * p] == 0.0f);
      continue;
    }
    REQUIRE(g.object_id[p] <= s.objects.size());
    CHECK(g.triangle_id[p] < s.objects[g.object_id[p] - 1].shape->triangles());
    const double sum = g.barycentric[3 * p] + g.barycentric[3 * p + 1] + g.barycentric[3 * p + 2];
    CHECK(sum == doctest::Approx(1.0).epsilon(1e-6));
    const double n = std::hypot(g.normal[3 * p], g.normal[3 * p + 1], g.normal[3 * p + 2]);
    CHECK(n == doctest::Approx(1.0).epsilon(1e-6));
  }
  CHECK(background > 0u);
}

TEST_CASE("velocity of a translation parallel to the image plane is the projected step") {
  const hs::scene s = hs::make_scene("translate");
  const int w = 200, h = 150;
  const hs::gbuffer g = hs::render_cpu(s, 10, w, h);
  const hs::camera_pose pose = s.camera(10);
  const double focal_px = 0.5 * h / std::tan(0.5 * pose.fov_y);  // pixels per unit at depth 1
  const double step = s.objects[0].model(10)[3][0] - s.objects[0].model(9)[3][0];
  double max_err = 0.0;
  std::size_t n = 0;
  for (std::size_t p = 0; p < g.pixels(); ++p) {
    if (g.object_id[p] != 1) continue;
    ++n;
    // The camera's x axis is the world's x axis: dx = focal step / depth, dy = dz = 0.
    const double dx = focal_px * step / g.depth[p];
    max_err = std::max({max_err, std::fabs(g.velocity[3 * p] - dx) / dx,
                        std::fabs(g.velocity[3 * p + 1]) / dx,
                        std::fabs(static_cast<double>(g.velocity[3 * p + 2]))});
  }
  MESSAGE("translate: " << n << " pixels, max relative velocity error " << max_err);
  CHECK(n > 1000u);
  CHECK(max_err < 1e-5);  // float32 depth and velocity
}

TEST_CASE("velocity is zero in frame 0 and on static objects under a static camera") {
  const hs::scene s = hs::make_scene("translate");  // the wall (object 2) is static
  const hs::gbuffer g0 = hs::render_cpu(s, 0, 120, 90), g = hs::render_cpu(s, 7, 120, 90);
  for (std::size_t p = 0; p < g0.pixels(); ++p) {
    for (int c = 0; c < 3; ++c) REQUIRE(g0.velocity[3 * p + c] == 0.0f);
    if (g.object_id[p] == 2)
      for (int c = 0; c < 3; ++c) CHECK(std::fabs(g.velocity[3 * p + c]) < 1e-9f);
  }
}

// Reprojection (Kass & Pesare 2011 sec. 3): for every pixel p of frame i whose previous
// position q = p - v falls where frame i-1 shows the same triangle (all four pixel
// centres around q), the object-space position stored at p equals frame i-1's
// positions bilinearly interpolated at q, and depth - dz equals the interpolated depth.
// Tolerance, derived: position and depth are ratios A(x)/S(x) of affine functions of
// the screen position (S = 1/depth), so g'' = -2 g' S'/S, and bilinear interpolation
// on a unit cell errs by at most (1/8)(max|g_xx| + max|g_yy|) =
// (1/4)(|g_x||d_x| + |g_y||d_y|)/d. The derivatives come from the cell's differences
// (x2 for their variation over the cell), plus float32 rounding of the stored values
// and of the velocity.
// Exactly, too: the ray through q of frame i-1's camera meets the triangle, placed
// by frame i-1's model transform, at the object-space point stored at p (tolerance:
// float32 rounding of the stored position, 4 eps |position|, and of the velocity,
// 2 eps (|v| + width + height) pixels times the position's change per pixel).
struct reprojection_result {
  std::size_t checked = 0, covered = 0;
  double max_position_error = 0.0, max_depth_error = 0.0, max_ratio = 0.0;
  double max_exact_error = 0.0, max_exact_ratio = 0.0;
};

reprojection_result reproject(const hs::scene& s, int frame, const hs::gbuffer& cur,
                              const hs::gbuffer& prev) {
  reprojection_result r;
  const hs::camera_pose prev_pose = s.camera(frame - 1);
  const int w = cur.width, h = cur.height;
  const auto at = [w](int x, int y) {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t p = at(x, y);
      if (!cur.covered(p)) continue;
      ++r.covered;
      const double vx = cur.velocity[3 * p], vy = cur.velocity[3 * p + 1],
                   vz = cur.velocity[3 * p + 2];
      if (!std::isfinite(vx + vy + vz)) continue;
      const double qx = x + 0.5 - vx - 0.5, qy = y + 0.5 - vy - 0.5;  // in pixel-centre units
      const double fx0 = std::floor(qx), fy0 = std::floor(qy);
      if (fx0 < 0 || fy0 < 0 || fx0 + 1 >= w || fy0 + 1 >= h) continue;
      const int x0 = static_cast<int>(fx0), y0 = static_cast<int>(fy0);
      const std::size_t c[4] = {at(x0, y0), at(x0 + 1, y0), at(x0, y0 + 1), at(x0 + 1, y0 + 1)};
      bool same = true;
      for (std::size_t k : c)
        same = same && prev.object_id[k] == cur.object_id[p] &&
               prev.triangle_id[k] == cur.triangle_id[p];
      if (!same) continue;
      ++r.checked;
      const double fx = qx - fx0, fy = qy - fy0;
      const double wgt[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
      const auto lerp = [&](const std::vector<float>& ch, int comps, int comp) {
        double v = 0.0;
        for (int k = 0; k < 4; ++k)
          v += wgt[k] * ch[static_cast<std::size_t>(comps) * c[k] + static_cast<std::size_t>(comp)];
        return v;
      };
      const auto diff = [&](const std::vector<float>& ch, int comps, int comp, int a, int b) {
        return std::fabs(
            static_cast<double>(
                ch[static_cast<std::size_t>(comps) * c[a] + static_cast<std::size_t>(comp)]) -
            ch[static_cast<std::size_t>(comps) * c[b] + static_cast<std::size_t>(comp)]);
      };
      const double d = lerp(prev.depth, 1, 0);
      const double dx = std::max(diff(prev.depth, 1, 0, 1, 0), diff(prev.depth, 1, 0, 3, 2));
      const double dy = std::max(diff(prev.depth, 1, 0, 2, 0), diff(prev.depth, 1, 0, 3, 1));
      const double speed = std::hypot(vx, vy);
      double position_error = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double gx =
            std::max(diff(prev.position, 3, k, 1, 0), diff(prev.position, 3, k, 3, 2));
        const double gy =
            std::max(diff(prev.position, 3, k, 2, 0), diff(prev.position, 3, k, 3, 1));
        const double magnitude = std::fabs(lerp(prev.position, 3, k)) + gx + gy;
        const double tol = 2.0 * 0.25 * (gx * dx + gy * dy) / d + 4 * kFloatEps * magnitude +
                           (gx + gy) * 2 * kFloatEps * (speed + w + h);
        const double err = std::fabs(cur.position[3 * p + static_cast<std::size_t>(k)] -
                                     lerp(prev.position, 3, k));
        position_error = std::max(position_error, err);
        r.max_ratio = std::max(r.max_ratio, err / tol);
      }
      const double depth_tol = 2.0 * 0.25 * (dx * dx + dy * dy) / d +
                               4 * kFloatEps * (cur.depth[p] + std::fabs(vz)) +
                               (dx + dy) * 2 * kFloatEps * (speed + w + h);
      const double depth_error = std::fabs(cur.depth[p] - vz - d);
      r.max_ratio = std::max(r.max_ratio, depth_error / depth_tol);
      r.max_position_error = std::max(r.max_position_error, position_error);
      r.max_depth_error = std::max(r.max_depth_error, depth_error);

      const hs::object& o = s.objects[cur.object_id[p] - 1];
      const glm::dmat4 model = o.model(frame - 1);
      dvec3 corner[3];
      double size = 0.0, change = 0.0;
      for (std::size_t k = 0; k < 3; ++k) {
        const glm::vec3& v =
            o.shape
                ->positions[o.shape->indices[3 * static_cast<std::size_t>(cur.triangle_id[p]) + k]];
        corner[k] = dvec3(model * dvec4(dvec3(v), 1.0));
        size = std::max(size, static_cast<double>(std::fabs(cur.position[3 * p + k])));
        change = std::max(change, diff(prev.position, 3, static_cast<int>(k), 1, 0) +
                                      diff(prev.position, 3, static_cast<int>(k), 2, 0));
      }
      const ray q = pixel_ray(prev_pose, w, h, x + 0.5 - vx, y + 0.5 - vy);
      const dvec3 n = glm::cross(corner[1] - corner[0], corner[2] - corner[0]);
      const dvec3 hit =
          q.origin + (glm::dot(corner[0] - q.origin, n) / glm::dot(q.direction, n)) * q.direction;
      const dvec3 object = dvec3(glm::inverse(model) * dvec4(hit, 1.0));
      double exact_error = 0.0;
      for (std::size_t k = 0; k < 3; ++k)
        exact_error =
            std::max(exact_error, std::fabs(cur.position[3 * p + k] - object[static_cast<int>(k)]));
      const double exact_tol = 4 * kFloatEps * size + change * 2 * kFloatEps * (speed + w + h);
      r.max_exact_error = std::max(r.max_exact_error, exact_error);
      r.max_exact_ratio = std::max(r.max_exact_ratio, exact_error / exact_tol);
    }
  return r;
}

TEST_CASE("velocity reprojection: frame i seen through its velocity matches frame i-1") {
  const int w = 320, h = 240;
  for (const char* name : {"translate", "rotate", "zoom", "walkthrough"}) {
    const hs::scene s = hs::make_scene(name);
    for (int f : {1, 25}) {
      const reprojection_result r =
          reproject(s, f, hs::render_cpu(s, f, w, h), hs::render_cpu(s, f - 1, w, h));
      MESSAGE(std::string(name) << " frame " << f << ": checked " << r.checked << " of "
                                << r.covered << " covered pixels; against frame i-1's G-buffer "
                                << "(bilinear): max position error " << r.max_position_error
                                << ", max depth error " << r.max_depth_error
                                << ", max error / tolerance " << r.max_ratio
                                << "; against frame i-1's exact surface: max position error "
                                << r.max_exact_error << ", max error / tolerance "
                                << r.max_exact_ratio);
      CHECK(r.checked > r.covered / 2);
      CHECK(r.max_ratio <= 1.0);
      CHECK(r.max_exact_ratio <= 1.0);
    }
  }
}

TEST_CASE(
    "forward velocity reprojection: frame i seen through its forward velocity matches "
    "frame i+1") {
  // The same check as the backward one, run forwards: frame i with velocity -forward is a
  // frame whose "previous" frame is i+1 (reproject() reads the pose and transforms of
  // frame f - 1, so it is given f = i + 2).
  const int w = 320, h = 240;
  for (const char* name : {"translate", "rotate", "zoom", "walkthrough"}) {
    const hs::scene s = hs::make_scene(name);
    for (int f : {0, 24}) {
      hs::gbuffer cur = hs::render_cpu(s, f, w, h);
      REQUIRE(cur.forward_velocity.size() == cur.velocity.size());
      for (std::size_t k = 0; k < cur.velocity.size(); ++k)
        cur.velocity[k] = -cur.forward_velocity[k];
      const reprojection_result r = reproject(s, f + 2, cur, hs::render_cpu(s, f + 1, w, h));
      MESSAGE(std::string(name) << " frame " << f << " -> " << f + 1 << ": checked " << r.checked
                                << " of " << r.covered << " covered pixels; max position error "
                                << r.max_position_error << ", max depth error " << r.max_depth_error
                                << ", max error / tolerance " << r.max_ratio
                                << "; against frame i+1's exact surface: max error / tolerance "
                                << r.max_exact_ratio);
      CHECK(r.checked > r.covered / 2);
      CHECK(r.max_ratio <= 1.0);
      CHECK(r.max_exact_ratio <= 1.0);
    }
  }
}

TEST_CASE("out-of-range sizes and frames throw hush::invalid_argument") {
  const hs::scene s = hs::make_scene("translate");
  CHECK_THROWS_AS(hs::render_cpu(s, 0, 0, 10), hush::invalid_argument);
  CHECK_THROWS_AS(hs::render_cpu(s, 0, 10, hs::kMaxImageSize + 1), hush::invalid_argument);
  CHECK_THROWS_AS(hs::render_cpu(s, -1, 10, 10), hush::invalid_argument);
}

TEST_CASE(
    "malformed meshes and cameras throw hush::invalid_argument instead of reading out of bounds") {
  hs::mesh m = hs::make_box(glm::vec3(1.0f));
  m.indices.back() = static_cast<std::uint32_t>(m.vertices());
  hs::camera_pose pose;
  CHECK_THROWS_AS(hs::render_cpu(hush_scene_test::single(m, dmat4(1.0), pose), 0, 8, 8),
                  hush::invalid_argument);
  hs::mesh short_normals = hs::make_box(glm::vec3(1.0f));
  short_normals.normals.pop_back();
  CHECK_THROWS_AS(hs::render_cpu(hush_scene_test::single(short_normals, dmat4(1.0), pose), 0, 8, 8),
                  hush::invalid_argument);
  for (double fov : {0.0, 3.2}) {
    pose.fov_y = fov;
    CHECK_THROWS_AS(
        hs::render_cpu(hush_scene_test::single(hs::make_box(glm::vec3(1.0f)), dmat4(1.0), pose), 0,
                       8, 8),
        hush::invalid_argument);
  }
  pose = hs::camera_pose();
  pose.near_depth = 0.0;
  CHECK_THROWS_AS(
      hs::render_cpu(hush_scene_test::single(hs::make_box(glm::vec3(1.0f)), dmat4(1.0), pose), 0, 8,
                     8),
      hush::invalid_argument);
}

}  // namespace
