// hush — test scenes: triangle meshes and their generators.
//
// A mesh is an indexed triangle list with per-vertex object-space positions,
// unit normals and texture coordinates. Front faces are counter-clockwise seen
// from outside (OpenGL's default), which is what back-face culling relies on
// for meshes marked `closed`. Example/test infrastructure (DESIGN.md), not a
// core header.
#ifndef HUSH_SCENE_MESH_HPP
#define HUSH_SCENE_MESH_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace hush_tools {
namespace scene {

struct mesh {
  std::vector<glm::vec3> positions;    // object space
  std::vector<glm::vec3> normals;      // unit, one per position
  std::vector<glm::vec2> uvs;          // one per position
  std::vector<std::uint32_t> indices;  // 3 per triangle, counter-clockwise from the front
  // True when the surface is closed (a solid's boundary): its back faces are never
  // visible, so rasterizers may cull them. Open surfaces (planes) are two-sided.
  bool closed = false;

  std::size_t triangles() const { return indices.size() / 3; }
  std::size_t vertices() const { return positions.size(); }
};

// Throws hush::invalid_argument unless `m` is well formed: one normal and one uv per
// position, a multiple of 3 indices, every index < vertices(). The rasterizers call it.
void validate(const mesh& m);

// Appends `part` to `m` (indices renumbered); `m.closed` stays as it was.
void append(mesh& m, const mesh& part);

// Sphere of `radius` at the origin, `slices` around the y axis (>= 3) and `stacks`
// from pole to pole (>= 2). uv = (longitude / 2 pi, colatitude / pi) in [0, 1]^2
// (seam and poles duplicated). Closed. 2 slices (stacks - 1) triangles.
mesh make_sphere(float radius, int slices, int stacks);

// Torus around the y axis: tube centre radius `major`, tube radius `minor` (< major),
// `rings` around y (>= 3), `sides` around the tube (>= 3). uv = (angle around y / 2 pi,
// angle around the tube / 2 pi). Closed. 2 rings sides triangles.
mesh make_torus(float major, float minor, int rings, int sides);

// Plane y = 0 over [-size_x/2, size_x/2] x [-size_z/2, size_z/2], `nx` x `nz` quads
// (>= 1), normal +y, planar uv = (x / size_x + 1/2, z / size_z + 1/2) * uv_scale.
// Open (two-sided). 2 nx nz triangles.
mesh make_plane(float size_x, float size_z, int nx, int nz, float uv_scale = 1.0f);

// Axis-aligned box centred at the origin with half extents `half`; flat face normals,
// each face mapped to uv [0, 1]^2. Closed. 12 triangles.
mesh make_box(const glm::vec3& half);

// Surface of revolution about the y axis of the polyline `profile` (points (r, y),
// r >= 0), `segments` around the axis (>= 3). uv = (angle / 2 pi, arc length along the
// profile / total length). Smooth normals (averaged over adjacent profile segments).
// Closed when the profile starts and ends on the axis (r = 0) and is traversed so that
// the solid is on its left (outward normals face right of the direction of travel).
mesh make_lathe(const std::vector<glm::vec2>& profile, int segments);

// A pitcher: a thick-walled lathe vessel (open at the top, so its inside shows)
// with a flared lip and a handle (a tube bent into a half ring) on its +x side.
// Height about 1.2, radius about 0.6. Self-occludes: the handle hides part of the
// body, the near wall hides the inside. Closed (the handle's ends are buried in the
// wall). `segments` >= 8 controls tessellation (about 60 segments triangles).
mesh make_pitcher(int segments);

// Wavefront OBJ file read with tinyobjloader (Debian libtinyobjloader-dev), faces
// triangulated. Normals and uvs from the file where it has them; otherwise smooth
// area-weighted vertex normals and spherical uv (longitude, colatitude about the
// bounding-box centre). Scaled and centred to fit the unit sphere. `closed` is false
// (nothing is known about the surface). Throws std::runtime_error naming the file.
mesh load_obj(const std::string& path);

}  // namespace scene
}  // namespace hush_tools

#endif  // HUSH_SCENE_MESH_HPP
