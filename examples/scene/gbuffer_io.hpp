// hush — test scenes: G-buffer files.
//
// One frame is a directory holding one NumPy .npy file per channel of gbuffer.hpp,
// named after the field: depth.npy, velocity.npy, object_id.npy, triangle_id.npy,
// barycentric.npy, uv.npy, uv_jacobian.npy, normal.npy, position.npy, and
// forward_velocity.npy when the G-buffer has that channel (it is optional: written
// when non-empty, read when the file exists, else left empty). Each is NPY
// format 1.0, little-endian float32 ('<f4') or uint32 ('<u4', the IDs), C order,
// shape (H, W) for one channel and (H, W, C) otherwise, row 0 at the top of the
// image (numpy.load gives arrays indexed [y, x, c]). Beside them, PNG previews for
// looking at (not read back): preview_depth.png (near bright), preview_normal.png
// ((n + 1) / 2 as RGB), preview_uv.png (fract(u), fract(v), 0),
// preview_velocity.png (0.5 + v / (2 max |v|) per channel), preview_object_id.png
// (one colour per object). A sequence is DIR/frame_NNNN/ (frame_directory).
#ifndef HUSH_SCENE_GBUFFER_IO_HPP
#define HUSH_SCENE_GBUFFER_IO_HPP

#include <string>

#include "gbuffer.hpp"

namespace hush_tools {
namespace scene {

// Writes `g` into `frame_dir` (created with its parents if missing; existing channel
// files are replaced). Throws std::runtime_error naming the file that could not be
// written, hush::invalid_argument if `g`'s channel sizes do not match its width and
// height.
void save_gbuffer(const gbuffer& g, const std::string& frame_dir);

// Reads the channel files written by save_gbuffer. Throws std::runtime_error naming
// the file when one is missing, is not a little-endian NPY 1.0 array of the expected
// type, or has a shape that disagrees with depth.npy's (H, W) or the channel count.
gbuffer load_gbuffer(const std::string& frame_dir);

// "DIR/frame_NNNN": frame index `frame` (>= 0) with at least 4 digits.
std::string frame_directory(const std::string& dir, int frame);

// Whether save_gbuffer writes the PNG previews (stb_image_write was found at configure time).
bool previews_supported();

}  // namespace scene
}  // namespace hush_tools

#endif  // HUSH_SCENE_GBUFFER_IO_HPP
