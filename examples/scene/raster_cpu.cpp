// hush — test scenes: the CPU rasterizer (see raster_cpu.hpp).
#include "raster_cpu.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include "hush/core/error.hpp"

namespace hush_tools {
namespace scene {
namespace {

using glm::dmat3;
using glm::dmat4;
using glm::dvec3;
using glm::dvec4;

constexpr int kSubpixelBits = 8;  // vertices snap to 1/256 pixel, as GPUs do
constexpr std::int64_t kSubpixel = std::int64_t(1) << kSubpixelBits;
constexpr double kGuardBand = 2.0;  // clip to |x_ndc|, |y_ndc| <= 2 (off screen)
constexpr int kPlanes = 5;          // near + 4 guard-band planes
constexpr std::size_t kMaxPolygon = 3 + kPlanes;
constexpr std::uint32_t kNoTriangle = 0xFFFFFFFFu;

// Signed distances of a clip-space point (X, Y, W) to the clip planes; inside >= 0.
std::array<double, kPlanes> plane_distances(const dvec3& p, double near_depth) {
  return {p.z - near_depth, kGuardBand * p.z - p.x, kGuardBand * p.z + p.x, kGuardBand * p.z - p.y,
          kGuardBand * p.z + p.y};
}

double plane_distance(const dvec3& p, int plane, double near_depth) {
  return plane_distances(p, near_depth)[static_cast<std::size_t>(plane)];
}

struct polygon {
  std::array<dvec3, kMaxPolygon + kPlanes> v;
  std::size_t n = 0;
};

// Sutherland-Hodgman against one plane. The intersection on an edge is always
// computed from its inside end to its outside end, so an edge shared by two
// triangles is cut at bit-identical points in both (no cracks along clipped edges).
polygon clip_polygon(const polygon& in, int plane, double near_depth) {
  polygon out;
  for (std::size_t i = 0; i < in.n; ++i) {
    const dvec3& a = in.v[i];
    const dvec3& b = in.v[(i + 1) % in.n];
    const double da = plane_distance(a, plane, near_depth);
    const double db = plane_distance(b, plane, near_depth);
    if (da >= 0.0) out.v[out.n++] = a;
    if ((da >= 0.0) != (db >= 0.0)) {
      const dvec3& p = da >= 0.0 ? a : b;  // inside end
      const dvec3& q = da >= 0.0 ? b : a;
      const double dp = da >= 0.0 ? da : db, dq = da >= 0.0 ? db : da;
      out.v[out.n++] = p + (dp / (dp - dq)) * (q - p);
    }
  }
  return out;
}

struct fixed_point {
  std::int64_t x, y;
};

std::int64_t floor_div(std::int64_t a, std::int64_t b) {  // b > 0
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

// What the shading pass needs of a visible triangle: which one it is and the affine
// functions f_k(x, y) = a_k x + b_k y + c_k of the pixel position (x, y) that equal
// barycentric_k / depth (2D homogeneous rasterization).
struct triangle_setup {
  std::uint32_t object;
  std::uint32_t triangle;
  dvec3 a, b, c;
};

struct object_frame {
  dmat4 clip_from_object;       // frame i
  dmat4 prev_clip_from_object;  // frame i - 1
  dmat4 next_clip_from_object;  // frame i + 1
  dmat3 normal_to_world;        // inverse transpose of the model's linear part
};

struct rasterizer {
  int width = 0, height = 0;
  const raster_options* options = nullptr;
  std::vector<double> inv_depth;       // the depth buffer holds 1 / depth (0: nothing)
  std::vector<std::uint32_t> visible;  // index into setups, or kNoTriangle
  std::vector<triangle_setup> setups;
  std::vector<dvec3> clip_xyw;  // one object's vertices in clip space (X, Y, W)

  void reset(int w, int h, const raster_options* o) {
    width = w;
    height = h;
    options = o;
    inv_depth.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0.0);
    visible.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), kNoTriangle);
    setups.clear();
  }

  fixed_point snap(const dvec3& clip) const {
    const double x = (clip.x / clip.z + 1.0) * 0.5 * width;
    const double y = (1.0 - clip.y / clip.z) * 0.5 * height;
    return {std::llround(x * kSubpixel), std::llround(y * kSubpixel)};
  }

  // Scan-converts the snapped triangle (p0, p1, p2) for setup `index`.
  void scan(fixed_point p0, fixed_point p1, fixed_point p2, std::uint32_t index) {
    // Orient so that E_ab(p) = (b - a) x (p - a) >= 0 inside (y down).
    std::int64_t area = (p1.x - p0.x) * (p2.y - p0.y) - (p1.y - p0.y) * (p2.x - p0.x);
    if (area == 0) return;
    if (area < 0) std::swap(p1, p2);
    const std::int64_t min_x = std::min({p0.x, p1.x, p2.x}), max_x = std::max({p0.x, p1.x, p2.x});
    const std::int64_t min_y = std::min({p0.y, p1.y, p2.y}), max_y = std::max({p0.y, p1.y, p2.y});
    // Pixel centres (256 x + 128) inside the bounding box, clamped to the image.
    const std::int64_t half = kSubpixel / 2;
    const std::int64_t x0 = std::max<std::int64_t>(0, -floor_div(-(min_x - half), kSubpixel));
    const std::int64_t x1 = std::min<std::int64_t>(width - 1, floor_div(max_x - half, kSubpixel));
    const std::int64_t y0 = std::max<std::int64_t>(0, -floor_div(-(min_y - half), kSubpixel));
    const std::int64_t y1 = std::min<std::int64_t>(height - 1, floor_div(max_y - half, kSubpixel));
    if (x0 > x1 || y0 > y1) return;
    const fixed_point v[3] = {p0, p1, p2};
    std::int64_t row[3], step_x[3], step_y[3];
    const std::int64_t cx = x0 * kSubpixel + half, cy = y0 * kSubpixel + half;
    for (int e = 0; e < 3; ++e) {
      const fixed_point& a = v[e];
      const fixed_point& b = v[(e + 1) % 3];
      const std::int64_t dx = b.x - a.x, dy = b.y - a.y;
      // Top-left rule: a centre exactly on an edge is inside only for top edges
      // (horizontal, interior below) and left edges (going up). Reversing an edge
      // flips the verdict, so of two triangles sharing it exactly one owns it.
      const bool top_left = dy < 0 || (dy == 0 && dx > 0);
      row[e] = dx * (cy - a.y) - dy * (cx - a.x) - (top_left ? 0 : 1);
      step_x[e] = -dy * kSubpixel;
      step_y[e] = dx * kSubpixel;
    }
    const triangle_setup& t = setups[index];
    const double inv_a = t.a.x + t.a.y + t.a.z, inv_b = t.b.x + t.b.y + t.b.z,
                 inv_c = t.c.x + t.c.y + t.c.z;  // 1 / depth = sum of f_k
    for (std::int64_t y = y0; y <= y1; ++y) {
      std::int64_t e0 = row[0], e1 = row[1], e2 = row[2];
      const double py = static_cast<double>(y) + 0.5;
      for (std::int64_t x = x0; x <= x1; ++x) {
        if ((e0 | e1 | e2) >= 0) {
          const std::size_t pixel = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                    static_cast<std::size_t>(x);
          if (options->coverage) ++(*options->coverage)[pixel];
          const double inv = inv_a * (static_cast<double>(x) + 0.5) + inv_b * py + inv_c;
          if (inv > inv_depth[pixel]) {
            inv_depth[pixel] = inv;
            visible[pixel] = index;
          }
        }
        e0 += step_x[0];
        e1 += step_x[1];
        e2 += step_x[2];
      }
      row[0] += step_y[0];
      row[1] += step_y[1];
      row[2] += step_y[2];
    }
  }

  void draw(const scene& s, std::uint32_t object_index, const object_frame& of, double near_depth) {
    const mesh& m = *s.objects[object_index].shape;
    clip_xyw.resize(m.vertices());  // (X, Y, W): the rasterizer never needs Z
    for (std::size_t i = 0; i < m.vertices(); ++i) {
      const dvec4 c = of.clip_from_object * dvec4(dvec3(m.positions[i]), 1.0);
      clip_xyw[i] = dvec3(c.x, c.y, c.w);
    }
    const bool cull = options->cull_back_faces && m.closed;
    const double sx = 2.0 / width, sy = -2.0 / height;  // d(ndc)/d(pixel)
    for (std::size_t t = 0; t < m.triangles(); ++t) {
      const dvec3& c0 = clip_xyw[m.indices[3 * t]];
      const dvec3& c1 = clip_xyw[m.indices[3 * t + 1]];
      const dvec3& c2 = clip_xyw[m.indices[3 * t + 2]];
      const dmat3 mc(c0, c1, c2);  // columns: the vertices' (X, Y, W)
      // det > 0: counter-clockwise on screen, the front face (the projection's
      // determinant is negative and the view-space triple product of a front face is).
      const double det = glm::determinant(mc);
      if (det == 0.0 || !std::isfinite(det)) continue;  // seen edge-on: covers nothing
      if (cull && det < 0.0) continue;
      const std::array<double, kPlanes> d0 = plane_distances(c0, near_depth),
                                        d1 = plane_distances(c1, near_depth),
                                        d2 = plane_distances(c2, near_depth);
      bool outside = false, inside = true;
      for (std::size_t p = 0; p < static_cast<std::size_t>(kPlanes); ++p) {
        if (d0[p] < 0.0 && d1[p] < 0.0 && d2[p] < 0.0) outside = true;
        if (d0[p] < 0.0 || d1[p] < 0.0 || d2[p] < 0.0) inside = false;
      }
      if (outside) continue;
      // f = M^-1 (x_ndc, y_ndc, 1) with x_ndc = sx x - 1, y_ndc = sy y + 1.
      const dmat3 inv = glm::inverse(mc);  // inv[col][row]; row k gives f_k
      triangle_setup setup{object_index, static_cast<std::uint32_t>(t), dvec3(), dvec3(), dvec3()};
      for (int k = 0; k < 3; ++k) {
        setup.a[k] = inv[0][k] * sx;
        setup.b[k] = inv[1][k] * sy;
        setup.c[k] = -inv[0][k] + inv[1][k] + inv[2][k];
      }
      const std::uint32_t index = static_cast<std::uint32_t>(setups.size());
      setups.push_back(setup);
      if (inside) {
        scan(snap(c0), snap(c1), snap(c2), index);
        continue;
      }
      polygon poly;
      poly.v[0] = c0;
      poly.v[1] = c1;
      poly.v[2] = c2;
      poly.n = 3;
      for (int p = 0; p < kPlanes && poly.n >= 3; ++p) poly = clip_polygon(poly, p, near_depth);
      if (poly.n < 3) continue;
      std::array<fixed_point, kMaxPolygon + kPlanes> snapped{};
      for (std::size_t i = 0; i < poly.n; ++i) snapped[i] = snap(poly.v[i]);
      for (std::size_t i = 1; i + 1 < poly.n; ++i)
        scan(snapped[0], snapped[i], snapped[i + 1], index);
    }
  }
};

}  // namespace

void check_scene(const scene& s, const camera_pose& pose) {
  if (!(pose.near_depth > 0.0) || !std::isfinite(pose.near_depth))
    throw hush::invalid_argument("render: camera near_depth must be finite and > 0");
  if (!(pose.fov_y > 0.0 && pose.fov_y < glm::pi<double>()))
    throw hush::invalid_argument("render: camera fov_y must be in (0, pi) radians");
  for (const object& o : s.objects) {
    if (!o.shape || !o.model)
      throw hush::invalid_argument("render: an object has no mesh or no transform");
    validate(*o.shape);
  }
  if (!s.camera) throw hush::invalid_argument("render: the scene has no camera");
}

void check_render_arguments(int frame, int width, int height) {
  if (width < 1 || width > kMaxImageSize || height < 1 || height > kMaxImageSize)
    throw hush::invalid_argument("render: size " + std::to_string(width) + "x" +
                                 std::to_string(height) + " is out of range; valid: 1 ... " +
                                 std::to_string(kMaxImageSize) + " in each dimension");
  if (frame < 0)
    throw hush::invalid_argument("render: frame = " + std::to_string(frame) +
                                 " is out of range; valid: >= 0");
}

namespace {

void write_background(gbuffer& g, std::size_t pixel) {
  g.depth[pixel] = std::numeric_limits<float>::infinity();
  g.object_id[pixel] = 0u;
  g.triangle_id[pixel] = kNoTriangle;
  for (std::size_t c = 0; c < 3; ++c) {
    g.velocity[3 * pixel + c] = 0.0f;
    g.forward_velocity[3 * pixel + c] = 0.0f;
    g.barycentric[3 * pixel + c] = 0.0f;
    g.normal[3 * pixel + c] = 0.0f;
    g.position[3 * pixel + c] = 0.0f;
  }
  g.uv[2 * pixel] = g.uv[2 * pixel + 1] = 0.0f;
  for (std::size_t c = 0; c < 4; ++c) g.uv_jacobian[4 * pixel + c] = 0.0f;
}

}  // namespace

gbuffer make_background(int width, int height) {
  gbuffer g;
  g.width = width;
  g.height = height;
  const std::size_t n = g.pixels();
  g.depth.assign(n, std::numeric_limits<float>::infinity());
  g.velocity.assign(3 * n, 0.0f);
  g.forward_velocity.assign(3 * n, 0.0f);
  g.object_id.assign(n, 0u);
  g.triangle_id.assign(n, kNoTriangle);
  g.barycentric.assign(3 * n, 0.0f);
  g.uv.assign(2 * n, 0.0f);
  g.uv_jacobian.assign(4 * n, 0.0f);
  g.normal.assign(3 * n, 0.0f);
  g.position.assign(3 * n, 0.0f);
  return g;
}

gbuffer render_cpu(const scene& s, int frame, int width, int height) {
  return render_cpu(s, frame, width, height, raster_options{});
}

gbuffer render_cpu(const scene& s, int frame, int width, int height,
                   const raster_options& options) {
  gbuffer g;
  render_cpu(s, frame, width, height, options, g);
  return g;
}

void render_cpu(const scene& s, int frame, int width, int height, const raster_options& options,
                gbuffer& g) {
  check_render_arguments(frame, width, height);
  const int prev_frame = frame > 0 ? frame - 1 : frame;
  if (!s.camera) throw hush::invalid_argument("render: the scene has no camera");
  const camera_pose pose = s.camera(frame), prev_pose = s.camera(prev_frame),
                    next_pose = s.camera(frame + 1);
  check_scene(s, pose);
  check_scene(s, prev_pose);
  check_scene(s, next_pose);
  const dmat4 clip_from_world = projection_matrix(pose, width, height) * view_matrix(pose);
  const dmat4 prev_clip_from_world =
      projection_matrix(prev_pose, width, height) * view_matrix(prev_pose);
  const dmat4 next_clip_from_world =
      projection_matrix(next_pose, width, height) * view_matrix(next_pose);
  std::vector<object_frame> frames;
  for (const object& o : s.objects) {
    const dmat4 model = o.model(frame), prev_model = o.model(prev_frame),
                next_model = o.model(frame + 1);
    frames.push_back({clip_from_world * model, prev_clip_from_world * prev_model,
                      next_clip_from_world * next_model,
                      glm::transpose(glm::inverse(dmat3(model)))});
  }
  if (options.coverage)
    options.coverage->assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                             0u);

  // The visibility buffers are kept per thread between calls: allocating and
  // page-faulting them anew would cost as much as rasterizing a dense frame.
  thread_local rasterizer r;
  r.reset(width, height, &options);
  for (std::size_t o = 0; o < s.objects.size(); ++o)
    r.draw(s, static_cast<std::uint32_t>(o), frames[o], pose.near_depth);

  // Shading: once per covered pixel; background values elsewhere.
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  g.width = width;
  g.height = height;
  g.depth.resize(n);
  g.velocity.resize(3 * n);
  g.forward_velocity.resize(3 * n);
  g.object_id.resize(n);
  g.triangle_id.resize(n);
  g.barycentric.resize(3 * n);
  g.uv.resize(2 * n);
  g.uv_jacobian.resize(4 * n);
  g.normal.resize(3 * n);
  g.position.resize(3 * n);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t pixel = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                static_cast<std::size_t>(x);
      if (r.visible[pixel] == kNoTriangle) {
        write_background(g, pixel);
        continue;
      }
      const triangle_setup& t = r.setups[r.visible[pixel]];
      const mesh& m = *s.objects[t.object].shape;
      const object_frame& of = frames[t.object];
      const double px = x + 0.5, py = y + 0.5;
      const dvec3 f = t.a * px + t.b * py + t.c;
      const double sum = f.x + f.y + f.z, sum_x = t.a.x + t.a.y + t.a.z,
                   sum_y = t.b.x + t.b.y + t.b.z;
      // One division per pixel (they dominate the shading time): the reciprocals.
      const double inv_sum = 1.0 / sum, inv_sum2 = inv_sum * inv_sum;
      const dvec3 bary = f * inv_sum;
      // d(f_k / S)/dx = (a_k S - f_k S_x) / S^2, and likewise in y.
      const dvec3 dbary_dx = (t.a * sum - f * sum_x) * inv_sum2;
      const dvec3 dbary_dy = (t.b * sum - f * sum_y) * inv_sum2;
      const std::size_t first = 3 * static_cast<std::size_t>(t.triangle);
      const std::uint32_t i0 = m.indices[first], i1 = m.indices[first + 1],
                          i2 = m.indices[first + 2];
      const dvec3 position = bary.x * dvec3(m.positions[i0]) + bary.y * dvec3(m.positions[i1]) +
                             bary.z * dvec3(m.positions[i2]);
      dvec3 normal =
          of.normal_to_world * (bary.x * dvec3(m.normals[i0]) + bary.y * dvec3(m.normals[i1]) +
                                bary.z * dvec3(m.normals[i2]));
      const double normal_length2 = glm::dot(normal, normal);
      if (normal_length2 > 0.0) normal *= 1.0 / std::sqrt(normal_length2);
      const glm::dvec2 uv0(m.uvs[i0]), uv1(m.uvs[i1]), uv2(m.uvs[i2]);
      const glm::dvec2 uv = bary.x * uv0 + bary.y * uv1 + bary.z * uv2;
      const glm::dvec2 duv_dx = dbary_dx.x * uv0 + dbary_dx.y * uv1 + dbary_dx.z * uv2;
      const glm::dvec2 duv_dy = dbary_dy.x * uv0 + dbary_dy.y * uv1 + dbary_dy.z * uv2;
      const double depth = inv_sum;
      dvec3 velocity(0.0);
      if (frame > 0) {
        const dvec4 prev = of.prev_clip_from_object * dvec4(position, 1.0);
        if (prev.w > 0.0) {
          const double inv_w = 1.0 / prev.w;
          const double prev_x = (prev.x * inv_w + 1.0) * 0.5 * width;
          const double prev_y = (1.0 - prev.y * inv_w) * 0.5 * height;
          velocity = dvec3(px - prev_x, py - prev_y, depth - prev.w);
        } else {
          velocity = dvec3(nan);
        }
      }
      // Forward: where the point is in frame i + 1 (the same projection, next transforms).
      dvec3 forward(nan);
      const dvec4 next = of.next_clip_from_object * dvec4(position, 1.0);
      if (next.w > 0.0) {
        const double inv_w = 1.0 / next.w;
        const double next_x = (next.x * inv_w + 1.0) * 0.5 * width;
        const double next_y = (1.0 - next.y * inv_w) * 0.5 * height;
        forward = dvec3(next_x - px, next_y - py, next.w - depth);
      }
      g.depth[pixel] = static_cast<float>(depth);
      g.object_id[pixel] = t.object + 1;
      g.triangle_id[pixel] = t.triangle;
      for (int c = 0; c < 3; ++c) {
        g.velocity[3 * pixel + c] = static_cast<float>(velocity[c]);
        g.forward_velocity[3 * pixel + c] = static_cast<float>(forward[c]);
        g.barycentric[3 * pixel + c] = static_cast<float>(bary[c]);
        g.normal[3 * pixel + c] = static_cast<float>(normal[c]);
        g.position[3 * pixel + c] = static_cast<float>(position[c]);
      }
      g.uv[2 * pixel] = static_cast<float>(uv.x);
      g.uv[2 * pixel + 1] = static_cast<float>(uv.y);
      g.uv_jacobian[4 * pixel] = static_cast<float>(duv_dx.x);
      g.uv_jacobian[4 * pixel + 1] = static_cast<float>(duv_dy.x);
      g.uv_jacobian[4 * pixel + 2] = static_cast<float>(duv_dx.y);
      g.uv_jacobian[4 * pixel + 3] = static_cast<float>(duv_dy.y);
    }
}

}  // namespace scene
}  // namespace hush_tools
