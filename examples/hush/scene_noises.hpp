// hush — the `hush` program: what the scene-driven noises `hush render` runs share.
//
// A render_entry names a noise, lists its own options (and flags, options without a value)
// and builds a scene_noise from them. `hush render NOISE` looks NOISE up in render_table();
// usage text and option errors come from the entries. Each noise's entry is in its own file,
// noise_<noise>.cpp (noise_entries.hpp), so adding a scene-driven noise to the program is that
// file: its entry plus the class that renders it.
//
// A scene_noise renders a sequence of G-buffer frames (hush scene render's layout,
// examples/scene/gbuffer_io.hpp) into noise frames. It reads frames through
// gbuffer_sequence, which loads them from disk on demand (a sequence is never held whole),
// and hands each result to render_sink, which writes DIR/NNNN.npy.
#ifndef HUSH_CLI_SCENE_NOISES_HPP
#define HUSH_CLI_SCENE_NOISES_HPP

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "args.hpp"
#include "glsl_device.hpp"
#include "hush/exec.hpp"
#include "hush/core/frame.hpp"
#include "hush/core/triangles.hpp"
#include "hush/core/views.hpp"
#include "noises.hpp"
#include "npr_fields.hpp"

namespace hush_cli {

// Frames 0 ... size() - 1 of a G-buffer directory DIR/frame_NNNN/, as hush::frame views.
class gbuffer_sequence {
 public:
  virtual ~gbuffer_sequence() = default;
  virtual std::size_t size() const = 0;
  virtual int width() const = 0;
  virtual int height() const = 0;
  // Frame i's views, valid until the next call. Throws run_error when the frame's files
  // cannot be read, usage_error when its size differs from frame 0's or a channel the noise
  // needs is missing (`needs`, hush::frame_view flags).
  virtual hush::frame frame(std::size_t i, hush::frame_view needs) = 0;
  // Frame i's projected triangles (examples/scene/triangles.hpp), valid until the next
  // call. Throws run_error when the files cannot be read, usage_error when the frame has
  // none (G-buffers written before hush scene render wrote them).
  virtual hush::triangle_list triangles(std::size_t i) = 0;
  // Frame i's unit world-space shading normals (0 on the background; what the styles'
  // tone from shading reads), valid until the next call.
  virtual hush::image_view<const hush::vec3> normals(std::size_t i) = 0;
  // DIR/frame_NNNN/NAME.npy of frame i, float32 of any shape (user fields beside the
  // G-buffer's channels). Throws usage_error when it is missing, run_error when it cannot be
  // read or is not a float32 NPY file.
  virtual field_file field(std::size_t i, const std::string& name) = 0;
};

// Where results go.
class render_sink {
 public:
  virtual ~render_sink() = default;
  // Writes frame i's channels (one view per channel) as DIR/NNNN.npy: float32 (H, W) for one
  // channel, (H, W, C) for more. Throws run_error when the file cannot be written.
  virtual void write(std::size_t i, const std::vector<hush::image_view<const float>>& channels) = 0;
  // Writes frame i as DIR/NNNN.png, 8-bit RGB (`rgb`: width * height * 3 bytes, rows top to
  // bottom). Throws run_error when it cannot be written or this build has no PNG output.
  virtual void write_png(std::size_t i, const std::vector<std::uint8_t>& rgb, std::size_t width,
                         std::size_t height) = 0;
  // A scratch file path for pass data of frame i (removed by the caller when done).
  virtual std::string scratch(std::size_t i) const = 0;
  // Reports progress of a pass ("forward pass", ...) on stderr.
  virtual void progress(const std::string& pass, std::size_t done, std::size_t total) = 0;
};

class scene_noise {
 public:
  virtual ~scene_noise() = default;
  virtual int channels() const = 0;
  // Empty when this noise runs on backend `b` in this build, else why not.
  virtual std::string unsupported_reason(backend b) const = 0;
  // Renders every frame of `frames` into `sink` on backend `b`.
  virtual void render(gbuffer_sequence& frames, render_sink& sink, backend b) = 0;
};

struct render_setup {
  std::uint32_t seed = 0;
};

struct render_entry {
  const char* name;
  const char* summary;
  std::vector<option_spec> options;  // each takes a value
  std::vector<option_spec> flags;    // options without a value
  // Builds the noise; throws usage_error for a value it cannot parse and lets
  // hush::invalid_argument through (make_scene_noise reports it against the option).
  std::unique_ptr<scene_noise> (*make)(const render_setup& setup, const option_values& given,
                                       const std::vector<std::string>& flags);
};

// Every noise's `hush render` entry, as usage lists them (noise_entries.cpp).
const std::vector<render_entry>& render_table();
std::string render_names();
const render_entry& find_render(const std::string& name);
// entry.make(...), with a hush::invalid_argument turned into a usage_error naming the option
// that carries the refused library parameter.
std::unique_ptr<scene_noise> make_scene_noise(const render_entry& entry, const render_setup& setup,
                                              const option_values& given,
                                              const std::vector<std::string>& flags);

// Option `name` as a finite number in [lo, hi] ([lo, hi) with hi_open), `fallback` when not
// given. Throws usage_error naming `valid` otherwise.
double parse_range(const option_values& given, const char* name, double lo, double hi, bool hi_open,
                   const char* valid, double fallback);

}  // namespace hush_cli

#endif  // HUSH_CLI_SCENE_NOISES_HPP
