// hush — the `hush` program: `hush render NOISE --gbuffer DIR --out DIR [options]`, the
// scene-driven noises (scene_noises.hpp) over a G-buffer sequence written by `hush scene
// render` (DIR/frame_NNNN/, examples/scene/gbuffer_io.hpp).
//
// Frames are read one at a time (at most two G-buffers are held), and each result is written
// as soon as it is made: OUT/NNNN.npy, float32 (H, W) for one channel or (H, W, C), the layout
// `hush coherence --frames` reads. Progress goes to stderr, one line per 10% of each pass
// (or a percentage rewritten in place on a terminal), and a summary to stdout.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "args.hpp"
#include "commands.hpp"
#include "scene_noises.hpp"

#if HUSH_CLI_HAVE_SCENE
#include "gbuffer_io.hpp"
#include "npy/npy.hpp"
#include "output_file.hpp"
#include "png_write.hpp"
#include "progress.hpp"
#include "triangles.hpp"
#endif

namespace hush_cli {

const std::vector<option_spec>& render_options() {
  static const std::vector<option_spec> options = {
      {"--gbuffer", "DIR", "G-buffers DIR/frame_NNNN/ as written by hush scene render (required)"},
      {"--out", "DIR", "directory for the noise frames OUT/NNNN.npy (created; required)"},
      {"--frames", "N", "render frames 0 ... N-1 (default: every consecutive frame_NNNN)"},
      {"--seed", "n", "random seed, 0 ... 4294967295 (default 0)"},
      {"--backend", "scalar|simd|glsl", "where the noise is computed (default scalar)"},
  };
  return options;
}

#if HUSH_CLI_HAVE_SCENE
namespace {

namespace fs = std::filesystem;

// DIR/frame_NNNN/ loaded on demand; the last frame loaded is kept.
class directory_sequence final : public gbuffer_sequence {
 public:
  directory_sequence(std::string dir, long long frames) : dir_(std::move(dir)) {
    std::error_code ec;
    if (!fs::is_directory(dir_, ec))
      throw usage_error("--gbuffer '" + dir_ + "' is not a directory");
    if (frames > 0) {
      size_ = static_cast<std::size_t>(frames);
      for (std::size_t i = 0; i < size_; ++i)
        if (!fs::is_directory(hush_tools::scene::frame_directory(dir_, static_cast<int>(i)), ec))
          throw usage_error("--gbuffer '" + dir_ + "' has no frame_" + four(i) + " (--frames " +
                            std::to_string(frames) + ")");
    } else {
      while (
          fs::is_directory(hush_tools::scene::frame_directory(dir_, static_cast<int>(size_)), ec))
        ++size_;
      if (size_ == 0) throw usage_error("--gbuffer '" + dir_ + "' holds no frame_0000 directory");
    }
    load(0);
    width_ = current_.width;
    height_ = current_.height;
  }
  std::size_t size() const override { return size_; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  hush::frame frame(std::size_t i, hush::frame_view needs) override {
    load(i);
    if (current_.width != width_ || current_.height != height_)
      throw usage_error("--gbuffer frame_" + four(i) + " is " + std::to_string(current_.width) +
                        "x" + std::to_string(current_.height) + "; frame_0000 is " +
                        std::to_string(width_) + "x" + std::to_string(height_));
    if (hush::has_view(needs, hush::frame_view::forward_velocity) &&
        current_.forward_velocity.empty())
      throw usage_error("--gbuffer frame_" + four(i) +
                        " has no forward_velocity.npy (render the scene again with this hush)");
    return hush_tools::scene::as_frame(current_);
  }
  hush::triangle_list triangles(std::size_t i) override {
    if (triangles_loaded_ != static_cast<long long>(i)) {
      const std::string dir = hush_tools::scene::frame_directory(dir_, static_cast<int>(i));
      if (!hush_tools::scene::has_triangles(dir))
        throw usage_error("--gbuffer frame_" + four(i) +
                          " has no tri_*.npy triangle files (render the scene again with this "
                          "hush)");
      try {
        triangles_ = hush_tools::scene::load_triangles(dir);
      } catch (const std::runtime_error& e) {
        throw run_error(e.what());
      }
      triangles_loaded_ = static_cast<long long>(i);
    }
    return triangles_.view();
  }
  hush::image_view<const hush::vec3> normals(std::size_t i) override {
    load(i);
    return {reinterpret_cast<const hush::vec3*>(current_.normal.data()),
            static_cast<std::size_t>(current_.width), static_cast<std::size_t>(current_.height)};
  }
  field_file field(std::size_t i, const std::string& name) override {
    const fs::path path =
        fs::path(hush_tools::scene::frame_directory(dir_, static_cast<int>(i))) / (name + ".npy");
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
      throw usage_error("--gbuffer frame_" + four(i) + " has no " + name + ".npy");
    try {
      hush_tools::npy::array<float> a = hush_tools::npy::load<float>(path.string());
      return {std::move(a.shape), std::move(a.values)};
    } catch (const std::runtime_error& e) {
      throw run_error(e.what());
    }
  }

 private:
  static std::string four(std::size_t i) {
    char b[16];
    std::snprintf(b, sizeof b, "%04zu", i);
    return b;
  }
  void load(std::size_t i) {
    if (loaded_ == static_cast<long long>(i)) return;
    try {
      current_ = hush_tools::scene::load_gbuffer(
          hush_tools::scene::frame_directory(dir_, static_cast<int>(i)));
    } catch (const std::runtime_error& e) {
      throw run_error(e.what());
    }
    loaded_ = static_cast<long long>(i);
  }

  std::string dir_;
  std::size_t size_ = 0;
  int width_ = 0, height_ = 0;
  hush_tools::scene::gbuffer current_;
  long long loaded_ = -1;
  hush_tools::scene::triangle_frame triangles_;
  long long triangles_loaded_ = -1;
};

class directory_sink final : public render_sink {
 public:
  explicit directory_sink(std::string dir) : dir_(std::move(dir)) {
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec) throw run_error("cannot create directory '" + dir_ + "': " + ec.message());
  }
  void write(std::size_t i, const std::vector<hush::image_view<const float>>& channels) override {
    const hush::image_view<const float>& first = channels.at(0);
    const std::size_t w = first.width, h = first.height, nc = channels.size();
    std::vector<std::size_t> shape = {h, w};
    if (nc > 1) shape.push_back(nc);
    std::vector<float> row(w * nc);
    char name[32];
    std::snprintf(name, sizeof name, "%04zu.npy", i);
    const std::string path = (fs::path(dir_) / name).string();
    as_run_error([&] {
      hush_tools::npy::writer out(path, hush_tools::npy::dtype::float32, shape);
      for (std::size_t y = 0; y < h; ++y) {
        for (std::size_t x = 0; x < w; ++x)
          for (std::size_t c = 0; c < nc; ++c) row[x * nc + c] = channels[c](x, y);
        out.write(row.data(), row.size());
      }
      out.close();
    });
    ++written_;
  }
  void write_png(std::size_t i, const std::vector<std::uint8_t>& rgb, std::size_t width,
                 std::size_t height) override {
    char name[32];
    std::snprintf(name, sizeof name, "%04zu.png", i);
    const std::string path = (fs::path(dir_) / name).string();
    if (!hush_tools::scene::detail::png_available())
      throw run_error("cannot write '" + path + "': this build has no PNG output (libstb-dev)");
    if (!hush_tools::scene::detail::write_png(path, static_cast<int>(width),
                                              static_cast<int>(height), 3, rgb))
      throw run_error("cannot write '" + path + "'");
    ++written_;
  }
  std::string scratch(std::size_t i) const override {
    char name[48];
    std::snprintf(name, sizeof name, ".forward_%04zu.tmp", i);
    return (fs::path(dir_) / name).string();
  }
  void progress(const std::string& pass, std::size_t done, std::size_t total) override {
    if (!bar_ || pass != pass_) {
      bar_.reset();
      pass_ = pass;
      bar_ = std::make_unique<hush_cli::progress>("render: " + pass, total);
    }
    bar_->update(done);
  }
  std::size_t written() const { return written_; }

 private:
  std::string dir_;
  std::size_t written_ = 0;
  std::string pass_;
  std::unique_ptr<hush_cli::progress> bar_;
};

}  // namespace

int run_render_noise(const std::vector<std::string>& args) {
  if (args.empty() || args[0].rfind("--", 0) == 0)
    throw usage_error("expected NOISE first (" + render_names() + ")");
  const render_entry& entry = find_render(args[0]);
  // Flags (options without a value) are taken out first; every other option has a value.
  std::vector<std::string> rest, flags;
  for (std::size_t k = 1; k < args.size(); ++k) {
    bool flag = false;
    for (const option_spec& f : entry.flags)
      if (args[k] == f.name) {
        for (const std::string& seen : flags)
          if (seen == f.name) throw usage_error(std::string(f.name) + " is given twice");
        flags.push_back(f.name);
        flag = true;
      } else if (args[k].rfind(std::string(f.name) + "=", 0) == 0) {
        throw usage_error(std::string(f.name) + " is a flag and takes no value; got '" + args[k] +
                          "'");
      }
    if (!flag) rest.push_back(args[k]);
  }
  std::vector<option_spec> options = render_options();
  options.insert(options.end(), entry.options.begin(), entry.options.end());
  option_values given;
  arg_reader in(rest);
  while (!in.done()) {
    const option_spec& o = in.option(options);
    given[o.name] = in.value();
  }
  const std::string* gdir = find_value(given, "--gbuffer");
  const std::string* out = find_value(given, "--out");
  if (!gdir) throw usage_error("--gbuffer DIR is required (hush scene render writes one)");
  if (!out) throw usage_error("--out DIR is required");
  render_setup setup;
  if (const std::string* v = find_value(given, "--seed"))
    setup.seed = static_cast<std::uint32_t>(parse_integer("--seed", *v, 0, 4294967295LL));
  backend where = backend::scalar;
  if (const std::string* v = find_value(given, "--backend"))
    where = parse_choice<backend>(
        "--backend", *v,
        {{"scalar", backend::scalar}, {"simd", backend::simd}, {"glsl", backend::glsl}});
  long long frames = 0;
  if (const std::string* v = find_value(given, "--frames"))
    frames = parse_integer("--frames", *v, 1, 10000);
  const std::unique_ptr<scene_noise> noise = make_scene_noise(entry, setup, given, flags);
  const std::string why = noise->unsupported_reason(where);
  if (!why.empty())
    throw usage_error("--backend '" + std::string(backend_name(where)) + "': " + why);

  directory_sequence seq(*gdir, frames);
  directory_sink sink(*out);
  const auto start = std::chrono::steady_clock::now();
  noise->render(seq, sink, where);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("wrote %zu %s frame%s (%dx%d, %d channel%s, %s) to %s in %.2f s\n", sink.written(),
              entry.name, sink.written() == 1 ? "" : "s", seq.width(), seq.height(),
              noise->channels(), noise->channels() == 1 ? "" : "s", backend_name(where),
              out->c_str(), seconds);
  return 0;
}

#else  // !HUSH_CLI_HAVE_SCENE

int run_render_noise(const std::vector<std::string>&) {
  throw usage_error(
      "not available in this build: G-buffer files need the scene library "
      "(libtinyobjloader-dev, libglm-dev); install them and re-run cmake");
}

#endif

}  // namespace hush_cli
