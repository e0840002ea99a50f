// hush — temporal-coherence metrics: noise frames as files.
//
// A noise sequence is a directory of NNNN.npy files (NNNN = the frame index, at least 4
// digits, the index of the matching G-buffer frame_NNNN/ directory), each a NumPy NPY 1.0
// array of little-endian float32 ('<f4'), C order, shape (H, W), row 0 at the top. This is
// what `hush sample` and numpy.save(path, a.astype('<f4')) write (examples/npy/npy.hpp).
#ifndef HUSH_COHERENCE_FRAME_IO_HPP
#define HUSH_COHERENCE_FRAME_IO_HPP

#include <string>
#include <vector>

#include "coherence/temporal.hpp"

namespace hush_tools {
namespace coherence {

struct noise_sequence {
  int first = 0;  // index of frames[0] (NNNN of its file)
  int width = 0, height = 0;
  std::vector<noise_frame> frames;  // consecutive indices first, first + 1, ...
};

// Reads one (H, W) float32 NPY file (hush_tools::npy::load). Throws std::runtime_error
// "'<path>': <what>" when it cannot be read, is not NPY 1.0 '<f4' C-order 2D with
// 1 <= H, W <= 2^20, or its data size disagrees with its shape.
noise_frame load_noise_frame(const std::string& path, int& width, int& height);

// Every NNNN.npy in `dir` (other files are ignored), in index order. Throws
// std::runtime_error when `dir` is not a directory, holds no NNNN.npy, the indices are not
// consecutive, or the frames differ in size.
noise_sequence load_noise_frames(const std::string& dir);

// "DIR/NNNN.npy" for frame `index` (>= 0), at least 4 digits.
std::string noise_frame_path(const std::string& dir, int index);

// Writes `f` (width * height values) as an (H, W) '<f4' NPY 1.0 file (hush_tools::npy::save);
// throws std::runtime_error naming the file when it cannot be written completely (the file
// is then removed), hush::invalid_argument when f.size() != width * height.
void save_noise_frame(const std::string& path, const noise_frame& f, int width, int height);

}  // namespace coherence
}  // namespace hush_tools

#endif  // HUSH_COHERENCE_FRAME_IO_HPP
