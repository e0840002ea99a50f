// Tests of the noise-frame files (examples/coherence/frame_io.hpp).
#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "coherence/frame_io.hpp"
#include "hush/core/error.hpp"

namespace {

namespace fs = std::filesystem;

std::string scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("hush_coherence_frame_io_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
}

}  // namespace

TEST_CASE("noise frames round-trip bit for bit through NNNN.npy files in index order") {
  const std::string dir = scratch("roundtrip");
  for (int i = 3; i < 6; ++i) {
    hush_tools::coherence::noise_frame f(12);
    for (std::size_t k = 0; k < f.size(); ++k)
      f[k] = static_cast<float>(i) + 0.1f * static_cast<float>(k) - 0.7f;
    hush_tools::coherence::save_noise_frame(hush_tools::coherence::noise_frame_path(dir, i), f, 4,
                                            3);
  }
  std::ofstream(dir + "/notes.txt") << "ignored";
  const auto s = hush_tools::coherence::load_noise_frames(dir);
  CHECK(s.first == 3);
  CHECK(s.width == 4);
  CHECK(s.height == 3);
  REQUIRE(s.frames.size() == 3);
  CHECK(s.frames[2][5] == 5.0f + 0.1f * 5 - 0.7f);
  // The header pads the data's start to a multiple of 64 bytes, as numpy does.
  CHECK((fs::file_size(hush_tools::coherence::noise_frame_path(dir, 3)) - 12 * 4) % 64 == 0);
  fs::remove_all(dir);
}

TEST_CASE("bad noise-frame directories and files throw with the path in the message") {
  const std::string dir = scratch("bad");
  CHECK_THROWS_AS(hush_tools::coherence::load_noise_frames(dir + "/missing"), std::runtime_error);
  CHECK_THROWS_AS(hush_tools::coherence::load_noise_frames(dir), std::runtime_error);  // empty
  const hush_tools::coherence::noise_frame f(6, 1.0f);
  hush_tools::coherence::save_noise_frame(hush_tools::coherence::noise_frame_path(dir, 0), f, 3, 2);
  hush_tools::coherence::save_noise_frame(hush_tools::coherence::noise_frame_path(dir, 2), f, 3, 2);
  CHECK_THROWS_WITH_AS(hush_tools::coherence::load_noise_frames(dir),
                       doctest::Contains("not consecutive"), std::runtime_error);
  std::ofstream(hush_tools::coherence::noise_frame_path(dir, 1)) << "not numpy";
  CHECK_THROWS_WITH_AS(hush_tools::coherence::load_noise_frames(dir), doctest::Contains("0001.npy"),
                       std::runtime_error);
  CHECK_THROWS_AS(hush_tools::coherence::save_noise_frame(dir + "/x.npy", f, 4, 2),
                  hush::invalid_argument);
  fs::remove_all(dir);
}
