// hush — test scenes: mesh generators (see mesh.hpp).
#include "mesh.hpp"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>
#include <tuple>

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include "hush/core/error.hpp"

namespace hush_tools {
namespace scene {
namespace {

constexpr float kPi = glm::pi<float>();
constexpr float kTwoPi = 2.0f * kPi;

struct vertex {
  glm::vec3 position, normal;
  glm::vec2 uv;
};

std::uint32_t add_vertex(mesh& m, const vertex& v) {
  m.positions.push_back(v.position);
  m.normals.push_back(glm::normalize(v.normal));
  m.uvs.push_back(v.uv);
  return static_cast<std::uint32_t>(m.positions.size() - 1);
}

// Adds triangle (a, b, c) wound counter-clockwise seen from the side its vertex
// normals point to (so the generators cannot get a winding wrong); degenerate
// triangles (zero area: poles, lathe points on the axis) are skipped.
void add_triangle(mesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const glm::vec3 face =
      glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
  if (glm::dot(face, face) == 0.0f) return;
  const glm::vec3 n = m.normals[a] + m.normals[b] + m.normals[c];
  if (glm::dot(face, n) < 0.0f) std::swap(b, c);
  m.indices.insert(m.indices.end(), {a, b, c});
}

// A (nu + 1) x (nv + 1) vertex grid from f(i, j), two triangles per cell.
void add_grid(mesh& m, int nu, int nv, const std::function<vertex(int, int)>& f) {
  const std::uint32_t base = static_cast<std::uint32_t>(m.positions.size());
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) add_vertex(m, f(i, j));
  const auto at = [&](int i, int j) { return base + static_cast<std::uint32_t>(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      add_triangle(m, at(i, j), at(i + 1, j), at(i, j + 1));
      add_triangle(m, at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
}

void require(bool ok, const char* what) {
  if (!ok) throw hush::invalid_argument(what);
}

}  // namespace

void validate(const mesh& m) {
  require(m.normals.size() == m.positions.size() && m.uvs.size() == m.positions.size(),
          "mesh: needs one normal and one uv per position");
  require(m.indices.size() % 3 == 0, "mesh: the index count must be a multiple of 3");
  for (std::uint32_t i : m.indices)
    require(i < m.positions.size(), "mesh: an index is out of range (>= the vertex count)");
}

void append(mesh& m, const mesh& part) {
  const std::uint32_t base = static_cast<std::uint32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), part.positions.begin(), part.positions.end());
  m.normals.insert(m.normals.end(), part.normals.begin(), part.normals.end());
  m.uvs.insert(m.uvs.end(), part.uvs.begin(), part.uvs.end());
  for (std::uint32_t i : part.indices) m.indices.push_back(base + i);
}

mesh make_sphere(float radius, int slices, int stacks) {
  require(radius > 0.0f, "make_sphere: radius must be > 0");
  require(slices >= 3 && stacks >= 2, "make_sphere: slices must be >= 3 and stacks >= 2");
  mesh m;
  m.closed = true;
  add_grid(m, slices, stacks, [&](int i, int j) {
    const float u = static_cast<float>(i) / static_cast<float>(slices);
    const float v = static_cast<float>(j) / static_cast<float>(stacks);
    const float phi = kTwoPi * u, theta = kPi * v;
    // Exactly on the axis at the poles, so that their degenerate triangles are dropped.
    const bool pole = j == 0 || j == stacks;
    const float sin_theta = pole ? 0.0f : std::sin(theta);
    const float cos_theta = pole ? (j == 0 ? 1.0f : -1.0f) : std::cos(theta);
    const glm::vec3 n(sin_theta * std::cos(phi), cos_theta, -sin_theta * std::sin(phi));
    return vertex{radius * n, n, glm::vec2(u, v)};
  });
  return m;
}

mesh make_torus(float major, float minor, int rings, int sides) {
  require(minor > 0.0f && major > minor, "make_torus: need 0 < minor < major");
  require(rings >= 3 && sides >= 3, "make_torus: rings and sides must be >= 3");
  mesh m;
  m.closed = true;
  add_grid(m, rings, sides, [&](int i, int j) {
    const float u = static_cast<float>(i) / static_cast<float>(rings);
    const float v = static_cast<float>(j) / static_cast<float>(sides);
    const float a = kTwoPi * u, b = kTwoPi * v;
    const glm::vec3 n(std::cos(b) * std::cos(a), std::sin(b), -std::cos(b) * std::sin(a));
    const glm::vec3 centre(major * std::cos(a), 0.0f, -major * std::sin(a));
    return vertex{centre + minor * n, n, glm::vec2(u, v)};
  });
  return m;
}

mesh make_plane(float size_x, float size_z, int nx, int nz, float uv_scale) {
  require(size_x > 0.0f && size_z > 0.0f, "make_plane: sizes must be > 0");
  require(nx >= 1 && nz >= 1, "make_plane: nx and nz must be >= 1");
  mesh m;
  add_grid(m, nx, nz, [&](int i, int j) {
    const float u = static_cast<float>(i) / static_cast<float>(nx);
    const float v = static_cast<float>(j) / static_cast<float>(nz);
    return vertex{glm::vec3((u - 0.5f) * size_x, 0.0f, (v - 0.5f) * size_z),
                  glm::vec3(0.0f, 1.0f, 0.0f), uv_scale * glm::vec2(u, v)};
  });
  return m;
}

mesh make_box(const glm::vec3& half) {
  require(half.x > 0.0f && half.y > 0.0f && half.z > 0.0f, "make_box: half extents must be > 0");
  mesh m;
  m.closed = true;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      glm::vec3 n(0.0f);
      n[axis] = static_cast<float>(sign);
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
      add_grid(m, 1, 1, [&](int i, int j) {
        glm::vec3 p(0.0f);
        p[axis] = static_cast<float>(sign) * half[axis];
        p[a1] = (2.0f * static_cast<float>(i) - 1.0f) * half[a1];
        p[a2] = (2.0f * static_cast<float>(j) - 1.0f) * half[a2];
        return vertex{p, n, glm::vec2(static_cast<float>(i), static_cast<float>(j))};
      });
    }
  return m;
}

mesh make_lathe(const std::vector<glm::vec2>& profile, int segments) {
  require(profile.size() >= 2, "make_lathe: the profile needs >= 2 points");
  require(segments >= 3, "make_lathe: segments must be >= 3");
  const std::size_t n = profile.size();
  // Outward profile normals: right of the direction of travel, averaged at points.
  std::vector<glm::vec2> seg_normal(n - 1);
  std::vector<float> arc(n, 0.0f);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const glm::vec2 d = profile[k + 1] - profile[k];
    require(glm::dot(d, d) > 0.0f, "make_lathe: repeated profile point");
    seg_normal[k] = glm::normalize(glm::vec2(d.y, -d.x));
    arc[k + 1] = arc[k] + glm::length(d);
  }
  mesh m;
  m.closed = profile.front().x == 0.0f && profile.back().x == 0.0f;
  add_grid(m, segments, static_cast<int>(n) - 1, [&](int i, int j) {
    const std::size_t k = static_cast<std::size_t>(j);
    glm::vec2 pn = k == 0       ? seg_normal[0]
                   : k == n - 1 ? seg_normal[n - 2]
                                : seg_normal[k - 1] + seg_normal[k];
    pn = glm::normalize(pn);
    const float u = static_cast<float>(i) / static_cast<float>(segments);
    const float a = kTwoPi * u, c = std::cos(a), s = -std::sin(a);
    const glm::vec2 p = profile[k];
    return vertex{glm::vec3(p.x * c, p.y, p.x * s), glm::vec3(pn.x * c, pn.y, pn.x * s),
                  glm::vec2(u, arc[k] / arc[n - 1])};
  });
  return m;
}

mesh make_pitcher(int segments) {
  require(segments >= 8, "make_pitcher: segments must be >= 8");
  // Outside up from the base, a flared lip, inside down to the inner floor: the
  // solid (a wall about 0.06 thick) is on the left of the direction of travel.
  const std::vector<glm::vec2> profile = {
      {0.0f, 0.0f},  {0.45f, 0.0f}, {0.55f, 0.1f},  {0.62f, 0.35f}, {0.6f, 0.6f},
      {0.48f, 0.9f}, {0.5f, 1.05f}, {0.58f, 1.15f}, {0.56f, 1.18f}, {0.46f, 1.08f},
      {0.42f, 0.9f}, {0.54f, 0.6f}, {0.56f, 0.35f}, {0.48f, 0.12f}, {0.0f, 0.08f}};
  mesh m = make_lathe(profile, segments);
  // Handle: a tube of radius 0.04 along a C from the middle of the wall at y = 0.35
  // (r = 0.59) to the middle of the wall at y = 0.85 (r = 0.47), bulging out 0.35.
  // Its open ends lie inside the wall, so the pitcher stays a closed surface.
  constexpr float kTube = 0.04f, kBulge = 0.35f, kY0 = 0.35f, kY1 = 0.85f;
  constexpr float kR0 = 0.59f, kR1 = 0.47f;
  const int along = std::max(8, segments / 2), around = std::max(6, segments / 4);
  const auto centre = [&](float t) {  // t in [-pi/2, pi/2]
    const float y = 0.5f * (kY0 + kY1) + 0.5f * (kY1 - kY0) * std::sin(t);
    const float r_mid = kR0 + (kR1 - kR0) * (y - kY0) / (kY1 - kY0);
    return glm::vec3(r_mid + kBulge * std::cos(t), y, 0.0f);
  };
  mesh handle;
  add_grid(handle, along, around, [&](int i, int j) {
    const float t = kPi * (static_cast<float>(i) / static_cast<float>(along) - 0.5f);
    const float dt = 1e-3f;
    const glm::vec3 tangent = glm::normalize(centre(t + dt) - centre(t - dt));
    const glm::vec3 side(tangent.y, -tangent.x, 0.0f);  // in-plane, perpendicular
    const float s = kTwoPi * static_cast<float>(j) / static_cast<float>(around);
    const glm::vec3 n = std::cos(s) * side + std::sin(s) * glm::vec3(0.0f, 0.0f, 1.0f);
    return vertex{centre(t) + kTube * n, n,
                  glm::vec2(static_cast<float>(i) / static_cast<float>(along),
                            static_cast<float>(j) / static_cast<float>(around))};
  });
  append(m, handle);
  return m;
}

mesh load_obj(const std::string& path) {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, path.c_str(), nullptr, true))
    throw std::runtime_error("cannot read OBJ file '" + path + "': " + (err.empty() ? warn : err));
  mesh m;
  bool all_normals = true, all_uvs = true;
  std::map<std::tuple<int, int, int>, std::uint32_t> seen;  // (v, n, t) -> vertex
  for (const tinyobj::shape_t& shape : shapes)
    for (const tinyobj::index_t& idx : shape.mesh.indices) {
      const auto key = std::make_tuple(idx.vertex_index, idx.normal_index, idx.texcoord_index);
      auto it = seen.find(key);
      if (it == seen.end()) {
        if (idx.vertex_index < 0 ||
            3 * static_cast<std::size_t>(idx.vertex_index) + 2 >= attrib.vertices.size())
          throw std::runtime_error("OBJ file '" + path + "': vertex index out of range");
        const std::size_t v = 3 * static_cast<std::size_t>(idx.vertex_index);
        m.positions.emplace_back(attrib.vertices[v], attrib.vertices[v + 1],
                                 attrib.vertices[v + 2]);
        if (idx.normal_index >= 0) {
          const std::size_t q = 3 * static_cast<std::size_t>(idx.normal_index);
          if (q + 2 >= attrib.normals.size())
            throw std::runtime_error("OBJ file '" + path + "': normal index out of range");
          m.normals.emplace_back(attrib.normals[q], attrib.normals[q + 1], attrib.normals[q + 2]);
        } else {
          all_normals = false;
          m.normals.emplace_back(0.0f);
        }
        if (idx.texcoord_index >= 0) {
          const std::size_t q = 2 * static_cast<std::size_t>(idx.texcoord_index);
          if (q + 1 >= attrib.texcoords.size())
            throw std::runtime_error("OBJ file '" + path + "': texture coordinate index out of range");
          m.uvs.emplace_back(attrib.texcoords[q], attrib.texcoords[q + 1]);
        } else {
          all_uvs = false;
          m.uvs.emplace_back(0.0f);
        }
        it = seen.emplace(key, static_cast<std::uint32_t>(m.positions.size() - 1)).first;
      }
      m.indices.push_back(it->second);
    }
  if (m.indices.empty()) throw std::runtime_error("OBJ file '" + path + "' has no faces");
  // Fit the unit sphere around the bounding-box centre.
  glm::vec3 lo = m.positions[0], hi = m.positions[0];
  for (const glm::vec3& p : m.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::vec3 mid = 0.5f * (lo + hi);
  float radius = 0.0f;
  for (const glm::vec3& p : m.positions) radius = std::max(radius, glm::length(p - mid));
  if (!(radius > 0.0f)) throw std::runtime_error("OBJ file '" + path + "' has no extent");
  for (glm::vec3& p : m.positions) p = (p - mid) / radius;
  if (!all_normals) {  // smooth, area weighted (the cross product's length)
    std::fill(m.normals.begin(), m.normals.end(), glm::vec3(0.0f));
    for (std::size_t t = 0; t < m.triangles(); ++t) {
      const std::uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1], c = m.indices[3 * t + 2];
      const glm::vec3 face =
          glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
      m.normals[a] += face;
      m.normals[b] += face;
      m.normals[c] += face;
    }
  }
  for (std::size_t i = 0; i < m.vertices(); ++i) {
    const float len = glm::length(m.normals[i]);
    m.normals[i] = len > 0.0f ? m.normals[i] / len : glm::vec3(0.0f, 1.0f, 0.0f);
    if (!all_uvs) {
      const glm::vec3 d = glm::normalize(m.positions[i] + glm::vec3(0.0f, 0.0f, 1e-30f));
      m.uvs[i] = glm::vec2(std::atan2(-d.z, d.x) / kTwoPi + 0.5f,
                           std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi);
    }
  }
  return m;
}

}  // namespace scene
}  // namespace hush_tools
