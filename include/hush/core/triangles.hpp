// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::triangle_list: the triangles a renderer drew in one frame, as views of
// arrays the caller owns (valid for the call), beside hush::frame
// (core/frame.hpp) for the noises that attach primitives to surfaces (NPR
// Gabor noise, Benard et al. 2010 sec. 3.3). Nothing but this frame's data:
//  - indices: 3 per triangle, into the vertex arrays;
//  - screen: each vertex's screen position in pixels for this frame (the
//    frame's conventions: x right, y down, pixel (x, y) centred at
//    (x + 0.5, y + 0.5)), i.e. clip (X, Y) / W through the viewport;
//  - depth: each vertex's linear view depth for this frame (clip W; the
//    frame's depth units). A vertex behind the camera has depth < 0 and as
//    screen position clip (X, Y) / W with that negative W, so that (depth *
//    screen, depth) is its clip (X, Y, W) through the viewport; noises clip or
//    skip such triangles, and those with a vertex at depth 0 or a non-finite
//    value (documented per noise);
//  - triangle_id: per triangle, a stable id: the same surface triangle has
//    the same id in every frame, and it is the id the frame's triangle_id
//    view shows where the triangle is visible;
//  - object_id: per triangle, the object id the frame's object_id view shows
//    where it is visible. Optional (empty: every triangle is object 0).
// A triangle is keyed by (object_id, triangle_id): noises seed their
// per-triangle random streams with that pair, so a triangle's primitives are
// the same in every frame whatever the order or number of triangles.
//
// Perspective: a surface point of barycentric coordinates b (object space)
// projects to s = sum b_i z_i s_i / sum b_i z_i at depth sum b_i z_i (clip
// coordinates are linear in object space), which is why depth comes with
// the screen positions.
#ifndef HUSH_CORE_TRIANGLES_HPP
#define HUSH_CORE_TRIANGLES_HPP

#include <cstddef>
#include <cstdint>
#include <string>

#include "hush/core/error.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"

namespace hush {

struct triangle_list {
  span<const std::uint32_t> indices;      // 3 per triangle
  span<const vec2> screen;                // per vertex: pixels
  span<const float> depth;                // per vertex: linear view depth
  span<const std::uint32_t> triangle_id;  // per triangle: stable id
  span<const std::uint32_t> object_id;    // per triangle, optional

  std::size_t triangles() const { return indices.size() / 3; }
  std::size_t vertices() const { return screen.size(); }
  std::uint32_t object_of(std::size_t t) const { return object_id.empty() ? 0u : object_id[t]; }

  // Throws hush::invalid_argument naming `where` and the array when the index
  // count is not a multiple of 3, there are more than max_triangles
  // triangles, depth and screen differ in length, triangle_id (or a non-empty
  // object_id) does not hold one id per triangle, or an index is not below
  // vertices(). Reads every index (O(triangles)), never a vertex value.
  void validate(const char* where, std::size_t max_triangles) const {
    if (indices.size() % 3 != 0)
      detail::throw_out_of_range(where, "triangles.indices size", indices.size(),
                                 "a multiple of 3 (3 indices per triangle)");
    if (triangles() > max_triangles)
      detail::throw_out_of_range(where, "triangles.indices size", indices.size(),
                                 ("at most 3 x " + std::to_string(max_triangles)).c_str());
    if (depth.size() != screen.size())
      detail::throw_out_of_range(where, "triangles.depth size", depth.size(),
                                 ("one per vertex: " + std::to_string(screen.size())).c_str());
    if (triangle_id.size() != triangles())
      detail::throw_out_of_range(where, "triangles.triangle_id size", triangle_id.size(),
                                 ("one per triangle: " + std::to_string(triangles())).c_str());
    if (!object_id.empty() && object_id.size() != triangles())
      detail::throw_out_of_range(
          where, "triangles.object_id size", object_id.size(),
          ("0 (absent) or one per triangle: " + std::to_string(triangles())).c_str());
    for (std::size_t i = 0; i < indices.size(); ++i)
      if (indices[i] >= vertices())
        detail::throw_out_of_range(
            where, "triangles.indices[" + std::to_string(i) + "]", indices[i],
            ("below the vertex count, " + std::to_string(vertices())).c_str());
  }
};

}  // namespace hush

#endif  // HUSH_CORE_TRIANGLES_HPP
