// hush — the `hush` program: `hush scene list` and `hush scene render`, the test scenes
// of examples/scene rendered to G-buffer files (examples/scene/gbuffer_io.hpp):
//
//   hush scene list
//   hush scene render --scene NAME [--frames N] [--size WxH] [--backend cpu|gl] --out DIR
//
// render writes DIR/frame_0000 ... frame_{N-1} (one .npy per channel plus PNG previews, and
// the projected triangles NPR Gabor noise reads: examples/scene/triangles.hpp),
// one progress line per frame on stderr, and a summary with the median render time per
// frame (rasterization only, not file writing; wall clock and this thread's CPU time) on
// stdout.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "args.hpp"
#include "commands.hpp"

#if HUSH_CLI_HAVE_SCENE
#include "gbuffer_io.hpp"
#include "hush/core/error.hpp"
#include "raster_cpu.hpp"
#include "scene.hpp"
#include "triangles.hpp"
#if HUSH_SCENE_HAVE_GL
#include "raster_gl.hpp"
#endif
#endif

namespace hush_cli {

const std::vector<option_spec>& scene_options() {
  static const std::vector<option_spec> options = {
      {"--scene", "NAME", "the scene (hush scene list shows them); required"},
      {"--frames", "N", "render frames 0 ... N-1; 1 ... 10000, default 1"},
      {"--size", "WxH", "image width x height in pixels, each 1 ... 16384; default 640x360"},
      {"--backend", "cpu|gl",
       "cpu: the deterministic CPU rasterizer (default); gl: OpenGL 4.5 through OSMesa"},
      {"--out", "DIR", "output directory (DIR/frame_NNNN/<channel>.npy); required"},
  };
  return options;
}

#if HUSH_CLI_HAVE_SCENE
namespace {

constexpr long long kMaxFrames = 10000;  // frame directories have 4 digits
const char* const kDefaultSize = "640x360";

// CPU time of the calling thread in ms: on a shared machine the wall clock also counts
// time other processes held the core; the CPU rasterizer runs on this thread only.
double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

int run_list() {
  for (const hush_tools::scene::scene_info& s : hush_tools::scene::scene_list()) {
    std::string name = s.name;
    name.resize(std::max<std::size_t>(name.size() + 2, 14), ' ');
    std::cout << name << s.description << '\n';
  }
  return 0;
}

void parse_size(const std::string& token, int& width, int& height) {
  const std::string valid =
      "WxH, width and height integers in 1 ... " + std::to_string(hush_tools::scene::kMaxImageSize);
  const std::vector<std::string> parts = split(token, 'x');
  long long w = 0, h = 0;
  if (parts.size() != 2 || !to_integer(parts[0], w) || !to_integer(parts[1], h) || w < 1 || h < 1 ||
      w > hush_tools::scene::kMaxImageSize || h > hush_tools::scene::kMaxImageSize)
    throw_bad_value("--size", token, valid);
  width = static_cast<int>(w);
  height = static_cast<int>(h);
}

hush_tools::scene::scene load_scene(const std::string& name) {
  try {
    return hush_tools::scene::make_scene(name);
  } catch (const hush::invalid_argument&) {
    std::string valid;
    for (const hush_tools::scene::scene_info& s : hush_tools::scene::scene_list())
      valid += (valid.empty() ? "" : ", ") + s.name;
    throw_bad_value("--scene", name, valid + ", dense:N (N in 1000 ... 10000000)");
  } catch (const std::exception& e) {  // an OBJ file that cannot be read
    throw run_error(e.what());
  }
}

int run_render(const std::vector<std::string>& args) {
  option_values given;
  arg_reader in(args);
  while (!in.done()) {
    const option_spec& o = in.option(scene_options());
    given[o.name] = in.value();
  }
  const std::string* scene_name = find_value(given, "--scene");
  const std::string* out = find_value(given, "--out");
  if (!scene_name) throw usage_error("--scene NAME is required (hush scene list shows them)");
  if (!out) throw usage_error("--out DIR is required");
  const int frames = static_cast<int>(
      find_value(given, "--frames")
          ? parse_integer("--frames", *find_value(given, "--frames"), 1, kMaxFrames)
          : 1);
  int width = 0, height = 0;
  parse_size(find_value(given, "--size") ? *find_value(given, "--size") : kDefaultSize, width,
             height);
  const bool gl = find_value(given, "--backend") &&
                  parse_choice<bool>("--backend", *find_value(given, "--backend"),
                                     {{"cpu", false}, {"gl", true}});
#if !HUSH_SCENE_HAVE_GL
  if (gl)
    throw usage_error(
        "--backend 'gl' is unavailable: this build has no OSMesa (apt-get install "
        "libosmesa6-dev, then re-run cmake); valid: cpu");
#endif
  const hush_tools::scene::scene s = load_scene(*scene_name);

#if HUSH_SCENE_HAVE_GL
  std::unique_ptr<hush_tools::scene::gl_rasterizer> gl_raster;
  if (gl) {
    try {
      gl_raster = std::make_unique<hush_tools::scene::gl_rasterizer>();
    } catch (const std::runtime_error& e) {
      throw run_error(e.what());
    }
  }
#endif
  std::vector<double> times, cpu_times;
  hush_tools::scene::gbuffer g;
  for (int f = 0; f < frames; ++f) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = thread_cpu_ms();
#if HUSH_SCENE_HAVE_GL
    if (gl)
      g = gl_raster->render(s, f, width, height);
    else
#endif
      hush_tools::scene::render_cpu(s, f, width, height, hush_tools::scene::raster_options{}, g);
    cpu_times.push_back(thread_cpu_ms() - cpu_start);
    const auto stop = std::chrono::steady_clock::now();
    times.push_back(std::chrono::duration<double, std::milli>(stop - start).count());
    const std::string dir = hush_tools::scene::frame_directory(*out, f);
    try {
      hush_tools::scene::save_gbuffer(g, dir);
      hush_tools::scene::save_triangles(hush_tools::scene::project_triangles(s, f, width, height),
                                        dir);
    } catch (const std::runtime_error& e) {
      throw run_error(e.what());
    }
    std::fprintf(stderr, "scene: [%d/%d] %s rendered in %.1f ms (%s)\n", f + 1, frames, dir.c_str(),
                 times.back(), gl ? "gl" : "cpu");
  }
  std::sort(times.begin(), times.end());
  std::sort(cpu_times.begin(), cpu_times.end());
  std::printf(
      "wrote %d frame%s of '%s' (%zu triangles, %dx%d, %s) to %s; median render time %.2f ms "
      "per frame (wall clock), %.2f ms thread CPU time\n",
      frames, frames == 1 ? "" : "s", s.name.c_str(), s.triangles(), width, height,
      gl ? "gl" : "cpu", out->c_str(), times[times.size() / 2], cpu_times[cpu_times.size() / 2]);
  return 0;
}

}  // namespace

int run_scene(const std::vector<std::string>& args) {
  const std::string sub = args.empty() ? "" : args[0];
  const std::vector<std::string> rest(args.empty() ? args.begin() : args.begin() + 1, args.end());
  if (sub == "list") {
    if (!rest.empty()) throw usage_error("'list' takes no arguments; got '" + rest[0] + "'");
    return run_list();
  }
  if (sub == "render") return run_render(rest);
  throw usage_error("expected 'list' or 'render'" +
                    (sub.empty() ? std::string() : ", got '" + sub + "'"));
}

#else  // !HUSH_CLI_HAVE_SCENE

int run_scene(const std::vector<std::string>&) {
  throw usage_error(
      "scenes are not available in this build: libtinyobjloader-dev or libglm-dev was not "
      "found when hush was configured (apt-get install them, then re-run cmake)");
}

#endif

}  // namespace hush_cli
