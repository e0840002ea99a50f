// Tests of the OpenGL G-buffer rasterizer (examples/scene/raster_gl.hpp, OSMesa llvmpipe)
// against the CPU rasterizer: the same IDs on interior pixels (all 8 neighbours show the
// same triangle), values within derived float32 tolerances there, and only a small
// fraction of pixels (along triangle edges) with different IDs.
//
// Tolerance for a quantity q at a pixel, derived from how GL computes it:
//   tol_q = G_q * delta + kappa * eps * a * M_q
//  - G_q * delta: llvmpipe snaps vertices to 1/256 pixel (the CPU rasterizer uses the
//    exact vertices for attributes), which moves q by at most its screen gradient G_q
//    (|dq/dx| + |dq/dy| from the CPU's central differences) times delta = 1/256 pixel.
//  - kappa * eps * a * M_q: float32 arithmetic (eps = 2^-24) in the transforms,
//    interpolation and shading, kappa = 32 roundings of condition <= 2 on the way.
//    Perspective-correct interpolation sums q_k / w_k over the (clipped) vertices
//    k and divides by 1/w, so rounding is relative to the largest term: the
//    amplification a = depth / min_k max(w_k, near) (w_k: the vertices' view depths;
//    a vertex clipped away is replaced by one on the near plane). M_q is the size of
//    the values summed: max |q_k| of the vertices for position and uv, 1 for unit
//    normals and barycentrics, the depth for depth, (width + height) pixels for
//    velocity (a difference of screen positions), and 6 max |uv_k| for the uv
//    Jacobian: GL differences uv/w and 1/w between neighbouring pixels, each built
//    from the interpolated uv and depth (relative errors <= kappa eps a (max |uv_k|
//    + |uv|) / |uv|), so (uv/w)_x / (1/w) errs by 2 kappa eps a (max |uv_k| + |uv|)
//    and the (1/w)_x term by 2 kappa eps a |uv|: at most 6 kappa eps a max |uv_k|.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "raster_cpu.hpp"
#include "raster_gl.hpp"
#include "scene_test_util.hpp"

namespace {

namespace hs = hush_tools::scene;

constexpr double kEps = 1.0 / (1 << 24);
constexpr double kKappa = 32.0;
constexpr double kSnap = 1.0 / 256.0;  // llvmpipe's subpixel precision (8 bits)

hs::gl_rasterizer& gl() {
  static hs::gl_rasterizer r;
  return r;
}

struct agreement {
  std::size_t pixels = 0, id_differ = 0, edge = 0, interior = 0, interior_id_differ = 0;
  // Largest |cpu - gl| on interior pixels, and largest ratio to the tolerance.
  double depth = 0, uv = 0, normal = 0, velocity = 0, forward_velocity = 0, position = 0,
         barycentric = 0, jacobian = 0;
  double worst_ratio = 0;
  std::string worst;
};

agreement compare(const hs::scene& s, int frame, int w, int h) {
  const hs::gbuffer c = hs::render_cpu(s, frame, w, h);
  const hs::gbuffer g = gl().render(s, frame, w, h);
  agreement r;
  r.pixels = c.pixels();
  const hs::camera_pose pose = s.camera(frame);
  const glm::dmat4 view = hs::view_matrix(pose);
  const auto at = [w](int x, int y) {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t p = at(x, y);
      const bool same_id = c.object_id[p] == g.object_id[p] && c.triangle_id[p] == g.triangle_id[p];
      r.id_differ += !same_id;
      if (!c.covered(p)) continue;
      bool interior = x > 0 && y > 0 && x + 1 < w && y + 1 < h;
      for (int dy = -1; dy <= 1 && interior; ++dy)
        for (int dx = -1; dx <= 1 && interior; ++dx) {
          const std::size_t q = at(x + dx, y + dy);
          interior = c.object_id[q] == c.object_id[p] && c.triangle_id[q] == c.triangle_id[p];
        }
      if (!interior) {
        ++r.edge;
        continue;
      }
      ++r.interior;
      if (!same_id) {
        ++r.interior_id_differ;
        continue;
      }
      // The triangle's vertices: their view depths and value sizes.
      const hs::object& o = s.objects[c.object_id[p] - 1];
      const hs::mesh& m = *o.shape;
      const glm::dmat4 view_model = view * o.model(frame);
      double min_w = INFINITY, max_pos = 0, max_uv = 0;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v =
            m.indices[3 * static_cast<std::size_t>(c.triangle_id[p]) + static_cast<std::size_t>(k)];
        const glm::dvec4 e = view_model * glm::dvec4(glm::dvec3(m.positions[v]), 1.0);
        min_w = std::min(min_w, std::max(-e.z, pose.near_depth));
        for (int i = 0; i < 3; ++i)
          max_pos = std::max(max_pos, static_cast<double>(std::fabs(m.positions[v][i])));
        for (int i = 0; i < 2; ++i)
          max_uv = std::max(max_uv, static_cast<double>(std::fabs(m.uvs[v][i])));
      }
      const double a = std::max(1.0, c.depth[p] / min_w);
      const auto check = [&](const char* name, const std::vector<float>& cc,
                             const std::vector<float>& gg, std::size_t comps, double size,
                             double& worst_abs) {
        for (std::size_t k = 0; k < comps; ++k) {
          const auto v = [&](int xx, int yy) {
            return static_cast<double>(cc[comps * at(xx, yy) + k]);
          };
          const double grad =
              0.5 * (std::fabs(v(x + 1, y) - v(x - 1, y)) + std::fabs(v(x, y + 1) - v(x, y - 1)));
          const double tol = grad * kSnap + kKappa * kEps * a * size;
          const double err = std::fabs(static_cast<double>(cc[comps * p + k]) - gg[comps * p + k]);
          worst_abs = std::max(worst_abs, err);
          const double ratio = err == 0.0 ? 0.0 : err / tol;  // NaN (never expected) fails below
          if (!(ratio <= r.worst_ratio)) {
            r.worst_ratio = ratio;
            r.worst =
                std::string(name) + " at (" + std::to_string(x) + ", " + std::to_string(y) + ")";
          }
        }
      };
      check("depth", c.depth, g.depth, 1, c.depth[p], r.depth);
      check("uv", c.uv, g.uv, 2, max_uv, r.uv);
      check("normal", c.normal, g.normal, 3, 1.0, r.normal);
      check("velocity", c.velocity, g.velocity, 3, w + h, r.velocity);
      check("forward_velocity", c.forward_velocity, g.forward_velocity, 3, w + h,
            r.forward_velocity);
      check("position", c.position, g.position, 3, max_pos, r.position);
      check("barycentric", c.barycentric, g.barycentric, 3, 1.0, r.barycentric);
      check("uv_jacobian", c.uv_jacobian, g.uv_jacobian, 4, 6.0 * max_uv, r.jacobian);
    }
  return r;
}

TEST_CASE(
    "GL and CPU G-buffers agree: equal IDs and values within derived tolerances on interior "
    "pixels") {
  const int w = 320, h = 240;
  for (const char* name : {"translate", "rotate", "zoom", "walkthrough", "dense:20000"}) {
    const hs::scene s = hs::make_scene(name);
    for (int frame : {0, 5}) {
      const agreement r = compare(s, frame, w, h);
      MESSAGE(std::string(name)
              << " frame " << frame << ": IDs differ on " << r.id_differ << " of " << r.pixels
              << " pixels ("
              << 100.0 * static_cast<double>(r.id_differ) / static_cast<double>(r.pixels) << "%), "
              << r.interior << " interior pixels, max |cpu - gl| there: depth " << r.depth
              << ", uv " << r.uv << ", normal " << r.normal << ", velocity " << r.velocity
              << " px, forward velocity " << r.forward_velocity << " px, position " << r.position
              << ", barycentric " << r.barycentric << ", uv Jacobian " << r.jacobian
              << "; worst error / tolerance " << r.worst_ratio << " (" << r.worst << ")");
      CHECK(r.interior > r.pixels / 4);
      CHECK(r.interior_id_differ == 0u);
      // Only pixel centres within the snapping distance of an edge can change hands:
      // at most 4 * delta of each edge pixel's neighbourhood (edge length <= 2 pixels).
      CHECK(static_cast<double>(r.id_differ) <= 4.0 * kSnap * static_cast<double>(r.edge) + 1.0);
      CHECK(r.worst_ratio <= 1.0);
    }
  }
}

TEST_CASE("GL rendering is deterministic and names its renderer") {
  const hs::scene s = hs::make_scene("walkthrough");
  CHECK(hush_scene_test::same_bits(gl().render(s, 3, 96, 64), gl().render(s, 3, 96, 64)));
  CHECK_FALSE(gl().renderer().empty());
}

}  // namespace
