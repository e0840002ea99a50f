// Tests of `hush coherence` and `hush coherence baseline` (examples/hush/coherence_cmd.cpp):
// each runs the built program on G-buffer files written here, then checks its files and
// numbers against the library, and that every bad input fails with exit code 2 and one line
// naming the option.
#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/run_hush.hpp"
#include "coherence/baselines.hpp"
#include "coherence/frame_io.hpp"
#include "coherence/report.hpp"
#include "gbuffer_io.hpp"
#include "raster_cpu.hpp"
#include "scene.hpp"

namespace {

namespace fs = std::filesystem;
namespace hc = hush_tools::coherence;

using hush_cli_test::result;
using hush_cli_test::run_hush;
using hush_cli_test::scratch;
using hush_cli_test::slurp;

// Frames 0 ... 3 of the translate scene at 96x72, written as G-buffer files and read back.
std::vector<hush_tools::scene::gbuffer> write_gbuffers(const fs::path& dir) {
  const hush_tools::scene::scene s = hush_tools::scene::make_scene("translate");
  std::vector<hush_tools::scene::gbuffer> g;
  for (int i = 0; i < 4; ++i) {
    const std::string frame = hush_tools::scene::frame_directory(dir.string(), i);
    hush_tools::scene::save_gbuffer(hush_tools::scene::render_cpu(s, i, 96, 72), frame);
    g.push_back(hush_tools::scene::load_gbuffer(frame));
  }
  return g;
}

std::string json_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// One line on stderr naming `option`, exit code 2.
void check_usage_error(const result& r, const std::string& option) {
  CHECK(r.exit_code == 2);
  CHECK(r.err.find(option) != std::string::npos);
  CHECK(r.err.find('\n') == r.err.size() - 1);
  CHECK(r.out.empty());
}

}  // namespace

TEST_CASE("hush coherence baseline writes the library's baseline frames bit for bit") {
  const fs::path dir = scratch("baseline");
  const auto g = write_gbuffers(dir / "g");
  for (auto kind :
       {hc::baseline_kind::white, hc::baseline_kind::shower_door, hc::baseline_kind::texture}) {
    const fs::path out = dir / hc::baseline_name(kind);
    const result r = run_hush(std::string("coherence baseline --kind ") + hc::baseline_name(kind) +
                                  " --gbuffer '" + (dir / "g").string() + "' --out '" +
                                  out.string() + "' --seed 5",
                              dir);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.empty());
    const hc::noise_sequence s = hc::load_noise_frames(out.string());
    hc::baseline_options o;
    o.seed = 5;
    CHECK(s.first == 0);
    CHECK(s.width == 96);
    CHECK(s.height == 72);
    CHECK(s.frames == hc::make_baseline(kind, g, o));
  }
}

TEST_CASE("hush coherence prints the library's metrics and writes them as JSON") {
  const fs::path dir = scratch("measure");
  const auto g = write_gbuffers(dir / "g");
  const auto frames = hc::make_baseline(hc::baseline_kind::texture, g);
  fs::create_directories(dir / "f");
  for (std::size_t i = 0; i < frames.size(); ++i)
    hc::save_noise_frame(hc::noise_frame_path((dir / "f").string(), static_cast<int>(i)), frames[i],
                         96, 72);
  const result r = run_hush("coherence --frames '" + (dir / "f").string() + "' --gbuffer '" +
                                (dir / "g").string() + "' --json '" + (dir / "m.json").string() +
                                "' --window 16",
                            dir);
  REQUIRE(r.exit_code == 0);
  hc::options o;
  o.window = 16;
  o.window_stride = 8;
  const hc::report want = hc::measure(frames, g, o);
  CHECK(r.out == hc::to_markdown(want));
  CHECK(r.out.find("| motion coherence (mean) |") != std::string::npos);
  const std::string json = slurp(dir / "m.json");
  CHECK(json == hc::to_json(want));
  CHECK(json.find("\"mean\": " + json_number(want.temporal.coherence_mean)) != std::string::npos);
}

TEST_CASE("hush coherence refuses bad input with exit code 2 and one line naming the option") {
  const fs::path dir = scratch("errors");
  const auto g = write_gbuffers(dir / "g");
  const std::string gdir = "'" + (dir / "g").string() + "'";
  check_usage_error(run_hush("coherence --gbuffer " + gdir, dir), "--frames");
  check_usage_error(
      run_hush("coherence --frames '" + (dir / "none").string() + "' --gbuffer " + gdir, dir),
      "--frames");
  check_usage_error(run_hush("coherence baseline --kind grey --gbuffer " + gdir + " --out x", dir),
                    "--kind");
  check_usage_error(run_hush("coherence baseline --kind white --gbuffer '" +
                                 (dir / "none").string() + "' --out x",
                             dir),
                    "--gbuffer");
  check_usage_error(run_hush("coherence baseline --kind white --gbuffer " + gdir, dir), "--out");
  check_usage_error(
      run_hush("coherence baseline --kind white --gbuffer " + gdir + " --out x --feature-pixels 0",
               dir),
      "--feature-pixels");
  // Frames of another size than the G-buffers.
  const hc::noise_frame small(12, 0.5f);
  fs::create_directories(dir / "small");
  fs::create_directories(dir / "long");
  hc::save_noise_frame(hc::noise_frame_path((dir / "small").string(), 0), small, 4, 3);
  hc::save_noise_frame(hc::noise_frame_path((dir / "small").string(), 1), small, 4, 3);
  check_usage_error(
      run_hush("coherence --frames '" + (dir / "small").string() + "' --gbuffer " + gdir, dir),
      "--frames");
  // More noise frames than G-buffer frames.
  for (int i = 0; i < 6; ++i)
    hc::save_noise_frame(hc::noise_frame_path((dir / "long").string(), i),
                         hc::noise_frame(96 * 72, 0.25f), 96, 72);
  check_usage_error(
      run_hush("coherence --frames '" + (dir / "long").string() + "' --gbuffer " + gdir, dir),
      "--gbuffer");
  check_usage_error(run_hush("coherence --frames '" + (dir / "long").string() + "' --gbuffer " +
                                 gdir + " --window 2",
                             dir),
                    "--window");
  check_usage_error(run_hush("coherence --frames x --gbuffer " + gdir + " --bogus 1", dir),
                    "--bogus");
}

TEST_CASE("hush --help describes hush coherence and its baseline subcommand") {
  const fs::path dir = scratch("help");
  const result r = run_hush("--help", dir);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("hush coherence --frames DIR --gbuffer DIR") != std::string::npos);
  CHECK(r.out.find("hush coherence baseline --kind K") != std::string::npos);
}
