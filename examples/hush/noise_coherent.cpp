// hush — the `hush` program: `hush render coherent` (hush/coherent.hpp), its render_table
// entry: coherent noise over a G-buffer sequence, causal (one frame at a time) or
// time-symmetric (a forward pass whose records wait in scratch files, then a backward pass).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "glsl_device.hpp"
#include "hush/coherent.hpp"
#include "hush/detail/constants.hpp"
#include "hush/exec.hpp"
#include "noise_entries.hpp"
#include "scene_noises.hpp"

#if HUSH_CLI_HAVE_GLSL
#include "hush/glsl/coherent/renderer.hpp"
#endif

namespace hush_cli {
namespace {

// Coherent noise, causal or time-symmetric.
class coherent_noise final : public scene_noise {
 public:
  coherent_noise(const hush::coherent_params& prm, bool symmetric)
      : prm_(prm), symmetric_(symmetric) {
    hush::validate(prm_);
  }
  int channels() const override { return prm_.channels; }
  std::string unsupported_reason(backend b) const override { return backend_missing(b); }
  void render(gbuffer_sequence& frames, render_sink& sink, backend b) override {
    with_exec(b, [&](const auto& ex) { run(ex, frames, sink); });
  }

 private:
  template <class Exec>
  void run(const Exec& ex, gbuffer_sequence& frames, render_sink& sink) {
    const std::size_t n = frames.size();
    const std::size_t w = static_cast<std::size_t>(frames.width());
    const std::size_t h = static_cast<std::size_t>(frames.height());
    const std::size_t nc = static_cast<std::size_t>(prm_.channels);
    std::vector<float> planes(w * h * nc);
    std::vector<hush::image_view<float>> out;
    std::vector<hush::image_view<const float>> result;
    for (std::size_t c = 0; c < nc; ++c) {
      out.emplace_back(planes.data() + w * h * c, w, h);
      result.emplace_back(planes.data() + w * h * c, w, h);
    }
    if (!symmetric_) {
      hush::coherent_stream stream(prm_);
      for (std::size_t i = 0; i < n; ++i) {
        const hush::frame f = frames.frame(i, hush::frame_view::depth | hush::frame_view::velocity);
        stream.advance(ex, f, hush::span<const hush::image_view<float>>(out));
        sink.write(i, result);
        sink.progress("causal", i + 1, n);
      }
      return;
    }
    // Time-symmetric: the forward pass's records wait in scratch files, so no more than one
    // frame of the sequence is held.
    hush::coherent_sequence<float> io;
    io.frames = n;
    std::size_t forward_done = 0, backward_done = 0;
    io.frame_at = [&](std::size_t i) {
      return frames.frame(i, hush::frame_view::depth | hush::frame_view::velocity |
                                 hush::frame_view::forward_velocity);
    };
    io.keep = [&](std::size_t i, hush::span<const std::uint8_t> bytes) {
      std::ofstream f(sink.scratch(i), std::ios::binary | std::ios::trunc);
      f.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
      if (!f) throw run_error("cannot write scratch file '" + sink.scratch(i) + "'");
      sink.progress("forward pass", ++forward_done, n);
    };
    io.recall = [&](std::size_t i, hush::span<std::uint8_t> bytes) {
      {
        std::ifstream f(sink.scratch(i), std::ios::binary);
        f.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
        if (!f) throw run_error("cannot read scratch file '" + sink.scratch(i) + "'");
      }
      std::error_code ignored;
      std::filesystem::remove(sink.scratch(i), ignored);
    };
    io.write = [&](std::size_t i, hush::span<const hush::image_view<float>> r) {
      std::vector<hush::image_view<const float>> views;
      for (const hush::image_view<float>& v : r)
        views.emplace_back(v.data, v.width, v.height, v.stride);
      sink.write(i, views);
      sink.progress("backward pass", ++backward_done, n);
    };
    hush::coherent_symmetric(ex, prm_, io);
  }

  hush::coherent_params prm_;
  bool symmetric_;
};

std::unique_ptr<scene_noise> make_coherent(const render_setup& setup, const option_values& given,
                                           const std::vector<std::string>& flags) {
  namespace c = hush::detail::constants;
  hush::coherent_params p;
  p.seed = setup.seed;
  p.alpha = parse_range(given, "--alpha", 0, 1, true, "a number in [0, 1)", p.alpha);
  p.epsilon = parse_range(given, "--epsilon", 0, 1e30, false, "a number >= 0", p.epsilon);
  p.smoothing = parse_range(given, "--smoothing", 0, c::kCoherentMaxSmoothing, false,
                            "a number in 0 ... 2 (pixels)", p.smoothing);
  p.bandpass_pixels = parse_range(given, "--bandpass-pixels", 1, c::kCoherentMaxBandpassPixels,
                                  false, "a number in 1 ... 1024 (pixels)", p.bandpass_pixels);
  if (const std::string* v = find_value(given, "--channels"))
    p.channels = static_cast<int>(parse_integer("--channels", *v, 1, c::kCoherentMaxChannels));
  if (const std::string* v = find_value(given, "--input"))
    p.input = parse_choice<hush::coherent_input>(
        "--input", *v,
        {{"white", hush::coherent_input::white}, {"bandpass", hush::coherent_input::bandpass}});
  if (const std::string* v = find_value(given, "--filter"))
    p.filter =
        parse_choice<hush::coherent_filter>("--filter", *v,
                                            {{"stationary", hush::coherent_filter::stationary},
                                             {"paper", hush::coherent_filter::paper}});
  bool symmetric = false;
  for (const std::string& f : flags) symmetric = symmetric || f == "--symmetric";
  return std::make_unique<coherent_noise>(p, symmetric);
}

}  // namespace

void add_coherent_entries(program_entries& entries) {
  entries.render.push_back(
      {"coherent",
       "coherent noise (Kass & Pesare 2011): follows the scene's motion, each frame white or "
       "band-pass; needs depth and velocity (and forward velocity with --symmetric)",
       {
           {"--alpha", "a",
            "recursive filter weight in [0, 1): the noise renews over ~1/(1-a) "
            "frames (default 0.98)",
            "alpha"},
           {"--epsilon", "e", "disocclusion tolerance, relative to depth, >= 0 (default 0.02)",
            "epsilon"},
           {"--filter", "stationary|paper",
            "stationary: keeps variance and sharpness on moving surfaces (default); paper: "
            "Kass & Pesare eq. 7 exactly (fades under sub-pixel motion)",
            "filter"},
           {"--channels", "n", "independent noise channels per frame, 1 ... 4 (default 1)",
            "channels"},
           {"--input", "white|bandpass",
            "input noise: white per pixel (default) or band-pass (Perlin in screen space)",
            "input"},
           {"--bandpass-pixels", "p",
            "band-pass feature size (Perlin cell) in pixels, 1 ... 1024 "
            "(default 4)",
            "bandpass_pixels"},
           {"--smoothing", "s", "output Gaussian smoothing sigma in pixels, 0 ... 2 (default 0)",
            "smoothing"},
       },
       {
           {"--symmetric", "",
            "time-symmetric filter over the whole sequence (offline; needs "
            "forward_velocity.npy, written by hush scene render)"},
       },
       make_coherent});
}

}  // namespace hush_cli
