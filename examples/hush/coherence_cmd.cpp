// hush — the `hush` program: `hush coherence`, objective temporal-coherence metrics of a
// noise sequence over its scene's G-buffers, and `hush coherence baseline`, which writes the
// calibration baselines (examples/coherence, docs/coherence.md).
//
//   hush coherence --frames DIR --gbuffer DIR [--json FILE] [metric options]
//   hush coherence baseline --kind white|shower-door|texture --gbuffer DIR --out DIR
//                           [--seed n] [--feature-pixels f]
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "args.hpp"
#include "commands.hpp"
#include "hush/core/error.hpp"
#include "output_file.hpp"

#if HUSH_CLI_HAVE_COHERENCE && HUSH_CLI_HAVE_SCENE
#include "coherence/baselines.hpp"
#include "coherence/frame_io.hpp"
#include "coherence/report.hpp"
#include "gbuffer_io.hpp"
#endif

namespace hush_cli {

const std::vector<option_spec>& coherence_options() {
  static const std::vector<option_spec> options = {
      {"--frames", "DIR", "directory of noise frames NNNN.npy, float32 (H, W) (required)"},
      {"--gbuffer", "DIR",
       "the scene's G-buffers DIR/frame_NNNN/ as written by hush scene (required); frame "
       "NNNN.npy is measured against frame_NNNN"},
      {"--json", "FILE", "also write every number, per frame too, as JSON"},
      {"--depth-epsilon", "e", "relative depth tolerance of reprojection, 0 ... 1 (default 0.02)"},
      {"--popping-threshold", "t",
       "isolated-jump threshold in spatial standard deviations, >= 0 (default 1)"},
      {"--window", "n", "flatness analysis window in pixels, 4 ... 4096 (default 32)"},
      {"--stride", "n", "flatness window stride in pixels, 1 ... 4096 (default window / 2)"},
      {"--depth-bins", "n", "flatness depth bins per object, 1 ... 64 (default 3)"},
  };
  return options;
}

const std::vector<option_spec>& coherence_baseline_options() {
  static const std::vector<option_spec> options = {
      {"--kind", "white|shower-door|texture", "which baseline (required)"},
      {"--gbuffer", "DIR", "the scene's G-buffers DIR/frame_NNNN/ (required)"},
      {"--out", "DIR", "directory for the frames NNNN.npy (created; required)"},
      {"--seed", "n", "random seed, 0 ... 4294967295 (default 1)"},
      {"--feature-pixels", "f", "Perlin cell size on screen in pixels, 1 ... 4096 (default 8)"},
  };
  return options;
}

#if HUSH_CLI_HAVE_COHERENCE && HUSH_CLI_HAVE_SCENE
namespace {

namespace fs = std::filesystem;
namespace hc = hush_tools::coherence;

option_values read_options(const std::vector<std::string>& args,
                           const std::vector<option_spec>& specs) {
  option_values given;
  arg_reader in(args);
  while (!in.done()) {
    const option_spec& o = in.option(specs);
    given[o.name] = in.value();
  }
  return given;
}

const std::string& required(const option_values& given, const char* name, const char* what) {
  const std::string* v = find_value(given, name);
  if (!v) throw usage_error(std::string(name) + " is required: " + what);
  return *v;
}

// frame_NNNN directories `first`, first + 1, ... (count of them, or all consecutive ones
// from `first` when count < 0).
std::vector<hush_tools::scene::gbuffer> load_gbuffers(const std::string& dir, int first,
                                                      int count) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw usage_error("--gbuffer '" + dir + "' is not a directory");
  std::vector<hush_tools::scene::gbuffer> g;
  for (int i = first; count < 0 || i < first + count; ++i) {
    const std::string frame = hush_tools::scene::frame_directory(dir, i);
    if (!fs::is_directory(frame, ec)) {
      if (count < 0) break;
      throw usage_error("--gbuffer '" + dir + "' has no " + fs::path(frame).filename().string() +
                        " for noise frame " + std::to_string(i));
    }
    try {
      g.push_back(hush_tools::scene::load_gbuffer(frame));
    } catch (const std::runtime_error& e) {
      throw usage_error(std::string("--gbuffer: ") + e.what());
    }
  }
  if (g.empty())
    throw usage_error("--gbuffer '" + dir + "' holds no frame_" + std::string(4, 'N') +
                      " directory from frame " + std::to_string(first));
  return g;
}

int run_baseline(const std::vector<std::string>& args) {
  const option_values given = read_options(args, coherence_baseline_options());
  const std::string& kind_name = required(given, "--kind", "white, shower-door or texture");
  const std::string& gdir = required(given, "--gbuffer", "a directory of frame_NNNN/");
  const std::string& out = required(given, "--out", "a directory for the noise frames");
  const hc::baseline_kind kind =
      parse_choice<hc::baseline_kind>("--kind", kind_name,
                                      {{"white", hc::baseline_kind::white},
                                       {"shower-door", hc::baseline_kind::shower_door},
                                       {"texture", hc::baseline_kind::texture}});
  hc::baseline_options o;
  if (const std::string* v = find_value(given, "--seed"))
    o.seed = static_cast<std::uint32_t>(parse_integer("--seed", *v, 0, 4294967295LL));
  if (const std::string* v = find_value(given, "--feature-pixels")) {
    o.feature_pixels = parse_finite("--feature-pixels", *v, "a number in 1 ... 4096");
    if (!(o.feature_pixels >= 1 && o.feature_pixels <= 4096))
      throw_bad_value("--feature-pixels", *v, "a number in 1 ... 4096");
  }
  const std::vector<hush_tools::scene::gbuffer> g = load_gbuffers(gdir, 0, -1);
  std::vector<hc::noise_frame> frames;
  try {
    frames = hc::make_baseline(kind, g, o);
  } catch (const hush::invalid_argument& e) {
    throw usage_error(std::string("--gbuffer: ") + e.what());
  }
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw run_error("cannot create directory '" + out + "': " + ec.message());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    try {
      hc::save_noise_frame(hc::noise_frame_path(out, static_cast<int>(i)), frames[i], g[i].width,
                           g[i].height);
    } catch (const std::runtime_error& e) {
      throw run_error(e.what());
    }
  }
  std::cout << "wrote " << frames.size() << " " << hc::baseline_name(kind) << " frames ("
            << g[0].width << "x" << g[0].height << ") to " << out << "\n";
  return 0;
}

}  // namespace

int run_coherence(const std::vector<std::string>& args) {
  if (!args.empty() && args[0] == "baseline")
    return run_baseline(std::vector<std::string>(args.begin() + 1, args.end()));
  const option_values given = read_options(args, coherence_options());
  const std::string& fdir = required(given, "--frames", "a directory of NNNN.npy noise frames");
  const std::string& gdir = required(given, "--gbuffer", "a directory of frame_NNNN/");
  hc::options o;
  if (const std::string* v = find_value(given, "--depth-epsilon")) {
    o.depth_epsilon = parse_finite("--depth-epsilon", *v, "a number in 0 ... 1");
    if (!(o.depth_epsilon >= 0 && o.depth_epsilon <= 1))
      throw_bad_value("--depth-epsilon", *v, "a number in 0 ... 1");
  }
  if (const std::string* v = find_value(given, "--popping-threshold")) {
    o.popping_threshold = parse_finite("--popping-threshold", *v, "a number >= 0");
    if (!(o.popping_threshold >= 0)) throw_bad_value("--popping-threshold", *v, "a number >= 0");
  }
  if (const std::string* v = find_value(given, "--window")) {
    o.window = static_cast<int>(parse_integer("--window", *v, 4, 4096));
    o.window_stride = o.window / 2;
  }
  if (const std::string* v = find_value(given, "--stride"))
    o.window_stride = static_cast<int>(parse_integer("--stride", *v, 1, 4096));
  if (const std::string* v = find_value(given, "--depth-bins"))
    o.depth_bins = static_cast<int>(parse_integer("--depth-bins", *v, 1, 64));

  hc::noise_sequence noise;
  try {
    noise = hc::load_noise_frames(fdir);
  } catch (const std::runtime_error& e) {
    throw usage_error(std::string("--frames ") + e.what());
  }
  if (noise.frames.size() < 2)
    throw usage_error("--frames '" + fdir + "' holds 1 frame; the metrics need at least 2");
  const std::vector<hush_tools::scene::gbuffer> g =
      load_gbuffers(gdir, noise.first, static_cast<int>(noise.frames.size()));
  if (g[0].width != noise.width || g[0].height != noise.height)
    throw usage_error("--frames are " + std::to_string(noise.width) + "x" +
                      std::to_string(noise.height) + " but --gbuffer frames are " +
                      std::to_string(g[0].width) + "x" + std::to_string(g[0].height));
  hc::report r;
  try {
    r = hc::measure(noise.frames, g, o);
  } catch (const hush::invalid_argument& e) {
    throw usage_error(std::string("--frames/--gbuffer: ") + e.what());
  }
  std::cout << hc::to_markdown(r);
  if (const std::string* path = find_value(given, "--json")) {
    const std::string json = hc::to_json(r);
    output_file f(*path);
    f.write(json.data(), json.size());
    f.close();
  }
  return 0;
}
#else
int run_coherence(const std::vector<std::string>&) {
  throw usage_error(
      "not available in this build: it needs Eigen3 (libeigen3-dev) for the metrics and the "
      "scene library (libtinyobjloader-dev, libglm-dev) for G-buffer files; install them and "
      "re-run cmake");
}
#endif

}  // namespace hush_cli
