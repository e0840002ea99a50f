// hush — test scenes: the triangles of a frame, projected (what NPR Gabor noise reads
// beside the G-buffer: hush::triangle_list, include/hush/core/triangles.hpp).
//
// project_triangles(s, i, width, height): every triangle of every object of frame i,
// vertices projected with that frame's object and camera transforms exactly as the
// rasterizers do (raster_cpu.hpp): screen = ((X / W + 1) width / 2, (1 - Y / W) height / 2)
// in pixels (y down), depth = W (linear view depth). Objects are concatenated in scene
// order; triangle t of object k has triangle_id t (its index in the object's mesh, what
// the G-buffer's triangle_id shows) and object_id k + 1 (the G-buffer's object_id).
// Vertices behind the camera (W < 0) get the same formula (X / W with W < 0: W times the
// screen position, with W, is their clip (X, Y, W) through the viewport, so a triangle
// crossing the near plane can be clipped by its reader); W = 0 gets a NaN screen position.
// Back faces are listed too (noises cull by winding: front faces are clockwise on the
// y-down screen, counter-clockwise in GL's window coordinates).
//
// Files, beside the G-buffer channels of a frame directory (gbuffer_io.hpp), NPY 1.0:
// tri_screen.npy float32 (V, 2), tri_depth.npy float32 (V,), tri_indices.npy uint32
// (T, 3), tri_id.npy uint32 (T,), tri_object.npy uint32 (T,).
#ifndef HUSH_SCENE_TRIANGLES_HPP
#define HUSH_SCENE_TRIANGLES_HPP

#include <cstdint>
#include <string>
#include <vector>

#include "hush/core/triangles.hpp"
#include "hush/core/vec.hpp"
#include "scene.hpp"

namespace hush_tools {
namespace scene {

struct triangle_frame {
  std::vector<hush::vec2> screen;  // per vertex, pixels
  std::vector<float> depth;        // per vertex, linear view depth
  std::vector<std::uint32_t> indices;
  std::vector<std::uint32_t> triangle_id, object_id;  // per triangle

  // Views of the arrays (valid while this lives and is not resized).
  hush::triangle_list view() const {
    hush::triangle_list t;
    t.indices = indices;
    t.screen = screen;
    t.depth = depth;
    t.triangle_id = triangle_id;
    t.object_id = object_id;
    return t;
  }
};

// Frame `frame` of `s` for a width x height image (the arguments render_cpu takes;
// hush::invalid_argument for the same bad values).
triangle_frame project_triangles(const scene& s, int frame, int width, int height);

// Writes the five files into `frame_dir` (created if missing). Throws std::runtime_error
// naming a file that cannot be written.
void save_triangles(const triangle_frame& t, const std::string& frame_dir);
// Whether `frame_dir` holds them (G-buffers written before they existed have none).
bool has_triangles(const std::string& frame_dir);
// Reads them. Throws std::runtime_error naming the file when one is missing or malformed
// (wrong dtype or shape, arrays of disagreeing lengths, an index out of range).
triangle_frame load_triangles(const std::string& frame_dir);

}  // namespace scene
}  // namespace hush_tools

#endif  // HUSH_SCENE_TRIANGLES_HPP
