// Coherent noise on the GLSL backend (backends/glsl/include/hush/glsl/coherent.hpp) against
// the scalar CPU pass, on a headless OSMesa (llvmpipe) context: the same disocclusions (fresh
// flags) every frame, and values within the tolerance derived below, measured as a function
// of the frame count; streams that switch backends, copies and serialised states; the
// time-symmetric filter; the generated constants and the pass's literals; GL limits.
#include <doctest/doctest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "coherent_scenes.hpp"
#include "glsl/glsl_test_util.hpp"
#include "hush/glsl/coherent/renderer.hpp"

namespace {

using hush_glsl_test::headless;
using hush_test::make_synthetic;
using hush_test::synthetic_frame;

hush::image_view<float> view_of(std::vector<float>& v, int w, int h) {
  return {v.data(), static_cast<std::size_t>(w), static_cast<std::size_t>(h)};
}

// Tolerance of GLSL against the scalar pass, in output units, for outputs of magnitude <= M:
//  - the blends: both sides round ~10 operations per step (GLSL may fuse them), the recursion
//    contracts by alpha: 2 (12 / (1 - alpha) + 1) 2^-24 M (coherent.hpp's float budget, twice);
//  - band-pass input: each Perlin value is within 2^-15 of the CPU's (library.hpp), times the
//    scale s; a step takes the input with weight beta and six refill values with weights
//    summing to at most 3 k alpha: gain s 2^-15 (beta + 3 k) / (1 - alpha) more.
double tolerance(const hush::coherent_params& p, double m) {
  const double alpha = static_cast<float>(p.alpha);
  const double k = hush::coherent_k(alpha), gain = 1 / k;
  double t = 2 * (12 / (1 - alpha) + 1) * std::ldexp(1.0, -24) * m;
  if (p.input == hush::coherent_input::bandpass)
    t += gain * hush::detail::coherent_bandpass_scale() * std::ldexp(1.0, -15) *
         ((1 - alpha) + 3 * k) / (1 - alpha);
  return t;
}

struct run_result {
  double worst = 0;  // max |glsl - scalar| over all frames
  std::vector<double> per_frame;
  bool same_fresh = true;
};

run_result compare_streams(const hush::coherent_params& prm, const std::string& kind, int w, int h,
                           int frames, bool ids = true) {
  hush::coherent_stream gpu(prm), cpu(prm);
  const std::size_t n = static_cast<std::size_t>(w) * h,
                    nc = static_cast<std::size_t>(prm.channels);
  std::vector<float> a(n * nc), b(n * nc);
  std::vector<hush::image_view<float>> va, vb;
  for (std::size_t c = 0; c < nc; ++c) {
    va.emplace_back(a.data() + n * c, w, h);
    vb.emplace_back(b.data() + n * c, w, h);
  }
  run_result r;
  for (int i = 0; i < frames; ++i) {
    const synthetic_frame s = make_synthetic(kind, 0.04, w, h, i);
    hush::frame f = s.view();
    if (!ids) f.object_id = {};
    gpu.advance(hush::exec::glsl{headless().device}, f,
                hush::span<const hush::image_view<float>>(va));
    cpu.advance(hush::exec::scalar, f, hush::span<const hush::image_view<float>>(vb));
    double worst = 0;
    for (std::size_t p = 0; p < a.size(); ++p)
      worst = std::max(worst, double(std::fabs(a[p] - b[p])));
    r.per_frame.push_back(worst);
    r.worst = std::max(r.worst, worst);
    r.same_fresh = r.same_fresh && gpu.fresh() == cpu.fresh();
  }
  return r;
}

}  // namespace

TEST_CASE(
    "GLSL coherent pass: same disocclusions as the CPU, values within the derived "
    "tolerance, over the frame count") {
  struct config {
    hush::coherent_filter filter;
    hush::coherent_input input;
    int channels;
    bool ids;
  };
  for (const config& c :
       {config{hush::coherent_filter::stationary, hush::coherent_input::white, 1, true},
        config{hush::coherent_filter::paper, hush::coherent_input::white, 2, false},
        config{hush::coherent_filter::stationary, hush::coherent_input::bandpass, 2, true}}) {
    hush::coherent_params prm;
    prm.filter = c.filter;
    prm.input = c.input;
    prm.channels = c.channels;
    prm.alpha = 0.9;
    CAPTURE(static_cast<int>(c.filter));
    CAPTURE(static_cast<int>(c.input));
    const run_result r = compare_streams(prm, "rotate", 37, 29, 60, c.ids);
    CHECK(r.same_fresh);
    CHECK(r.worst <= tolerance(prm, 8));
    MESSAGE("GLSL vs scalar, max |difference| over 60 frames: " << r.worst << " (tolerance "
                                                                << tolerance(prm, 8) << ")");
  }
}

TEST_CASE("GLSL coherent tolerance as a function of the frame count (alpha 0.98)") {
  // The difference grows over the filter's memory (~1 / (1 - alpha) frames), then stays
  // bounded: the recursion contracts.
  for (auto input : {hush::coherent_input::white, hush::coherent_input::bandpass}) {
    hush::coherent_params prm;
    prm.input = input;
    const run_result r = compare_streams(prm, "rotate", 48, 36, 1000);
    CHECK(r.same_fresh);
    double upto[4] = {0, 0, 0, 0};
    for (std::size_t i = 0; i < r.per_frame.size(); ++i)
      for (int k = 0; k < 4; ++k)
        if (i < std::size_t(std::pow(10, k))) upto[k] = std::max(upto[k], r.per_frame[i]);
    const std::string name = input == hush::coherent_input::white ? "white" : "band-pass";
    MESSAGE(name << " input, max |glsl - scalar| over frames 1, 10, 100, 1000: " << upto[0] << ", "
                 << upto[1] << ", " << upto[2] << ", " << upto[3] << " (tolerance "
                 << tolerance(prm, 8) << ")");
    CHECK(r.worst <= tolerance(prm, 8));
  }
}

TEST_CASE("GLSL coherent streams switch backends, copy and serialise like CPU streams") {
  hush::coherent_params prm;
  prm.alpha = 0.8;
  const int w = 21, h = 17;
  const synthetic_frame s = make_synthetic("rotate", 0.05, w, h);
  hush::coherent_stream mixed(prm), cpu(prm);
  std::vector<float> a(w * h), b(w * h);
  double worst = 0;
  for (int i = 0; i < 12; ++i) {
    // GLSL, GLSL, scalar, GLSL, ...: the history moves between GPU and CPU as needed.
    if (i % 3 == 2)
      mixed.advance(hush::exec::scalar, s.view(), view_of(a, w, h));
    else
      mixed.advance(hush::exec::glsl{headless().device}, s.view(), view_of(a, w, h));
    cpu.advance(hush::exec::scalar, s.view(), view_of(b, w, h));
    REQUIRE(mixed.fresh() == cpu.fresh());
    for (std::size_t p = 0; p < a.size(); ++p)
      worst = std::max(worst, double(std::fabs(a[p] - b[p])));
    if (i == 6) {
      // A copy and a deserialised state of a GPU-held stream continue like it.
      hush::coherent_stream copy = mixed;
      hush::coherent_stream loaded = hush::coherent_stream::deserialize(mixed.serialize());
      std::vector<float> c(w * h), d(w * h), e(w * h);
      hush::coherent_stream ahead = mixed;
      ahead.advance(hush::exec::scalar, s.view(), view_of(c, w, h));
      copy.advance(hush::exec::scalar, s.view(), view_of(d, w, h));
      loaded.advance(hush::exec::scalar, s.view(), view_of(e, w, h));
      CHECK(std::memcmp(c.data(), d.data(), c.size() * 4) == 0);
      CHECK(std::memcmp(c.data(), e.data(), c.size() * 4) == 0);
    }
  }
  CHECK(worst <= tolerance(prm, 8));
}

TEST_CASE("GLSL coherent time-symmetric filter agrees with the CPU") {
  hush::coherent_params prm;
  prm.alpha = 0.85;
  prm.channels = 2;
  const int w = 26, h = 19, frames = 8;
  std::vector<synthetic_frame> seq;
  std::vector<hush::frame> views;
  for (int i = 0; i < frames; ++i) seq.push_back(make_synthetic("occluder", 0.6, w, h, i));
  for (const synthetic_frame& s : seq) views.push_back(s.view());
  const std::size_t n = std::size_t(w) * h;
  std::vector<float> a(n * 2 * frames), b(n * 2 * frames);
  std::vector<hush::image_view<float>> va, vb;
  for (int k = 0; k < 2 * frames; ++k) {
    va.emplace_back(a.data() + n * k, w, h);
    vb.emplace_back(b.data() + n * k, w, h);
  }
  hush::coherent_symmetric(hush::exec::glsl{headless().device}, prm,
                           hush::span<const hush::frame>(views),
                           hush::span<const hush::image_view<float>>(va));
  hush::coherent_symmetric(hush::exec::scalar, prm, hush::span<const hush::frame>(views),
                           hush::span<const hush::image_view<float>>(vb));
  double worst = 0;
  for (std::size_t p = 0; p < a.size(); ++p)
    worst = std::max(worst, double(std::fabs(a[p] - b[p])));
  MESSAGE("symmetric, GLSL vs scalar: max |difference| " << worst);
  // The sum of two passes and the input: twice a pass's tolerance (in the symmetric gain).
  CHECK(worst <= 2 * tolerance(prm, 8));
}

TEST_CASE("GLSL coherent: a frame larger than one storage block is refused by name") {
  headless();  // the context the small device runs on
  hush::glsl::device small(hush_glsl_test::headless().context.loader(), {0, 4096});
  const synthetic_frame s = make_synthetic("still", 0, 40, 30);  // velocity: 14400 bytes
  hush::coherent_stream st;
  std::vector<float> out(40 * 30);
  try {
    st.advance(hush::exec::glsl{small}, s.view(), view_of(out, 40, 30));
    FAIL("expected hush::invalid_argument");
  } catch (const hush::invalid_argument& e) {
    CHECK(std::string(e.what()).find("GL_MAX_SHADER_STORAGE_BLOCK_SIZE") != std::string::npos);
  }
}

TEST_CASE("GLSL coherent constants read back from the C++ table; the pass holds no other number") {
  // Every generated constant appears in the source as its literal.
  const std::string src = hush::glsl::coherent_source();
  for (const hush::glsl::glsl_constant& k : hush::glsl::coherent_constant_table())
    CHECK(
        src.find("const " +
                 std::string(k.kind == hush::glsl::glsl_constant::type::u32 ? "uint " : "float ") +
                 k.name + " = " + hush::glsl::glsl_literal(k.kind, k.bits[0]) + ";") !=
        std::string::npos);
  // The hand-written body: numeric literals outside comments are structural only.
  const std::string body = hush::glsl::detail::kCoherentBody;
  std::vector<std::string> stray;
  bool comment = false;
  for (std::size_t i = 0; i < body.size(); ++i) {
    const char ch = body[i];
    if (comment) {
      comment = ch != '\n';
      continue;
    }
    if (ch == '/' && i + 1 < body.size() && body[i + 1] == '/') {
      comment = true;
      continue;
    }
    const bool ident =
        i > 0 && (std::isalnum(static_cast<unsigned char>(body[i - 1])) || body[i - 1] == '_');
    if (!std::isdigit(static_cast<unsigned char>(ch)) || ident) continue;
    std::size_t j = i;
    while (j < body.size() && (std::isalnum(static_cast<unsigned char>(body[j])) || body[j] == '.'))
      ++j;
    const std::string lit = body.substr(i, j - i);
    // Structural: indices and strides of 4 taps, 3 fields, 3 motion components, binding
    // points 0 ... 7, flag bits 1, 2, 4, and 0.0 / 1.0.
    const char* const allowed[] = {"0",  "1",  "2",  "3",  "4",  "5",   "6",  "7",
                                   "0u", "1u", "2u", "3u", "4u", "0.0", "1.0"};
    if (std::find_if(std::begin(allowed), std::end(allowed),
                     [&](const char* a) { return lit == a; }) == std::end(allowed))
      stray.push_back(lit);
    i = j - 1;
  }
  CHECK_MESSAGE(stray.empty(), "literal in the pass: " << (stray.empty() ? "" : stray[0]));
}
