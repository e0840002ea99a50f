// The resident coherent-noise path (backends/glsl/include/hush/glsl/coherent/frame.hpp) on a
// headless OSMesa (llvmpipe) context: frames from G-buffer textures the test owns, the noise
// into the test's R32F textures; equal bit for bit to the CPU-image path (exec::glsl) frame by
// frame; no read-back through the stream's device (a counting loader); copy, reset and the
// state's way to and from a CPU stream; errors; host time per frame at two sizes (reported).
#include <doctest/doctest.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "coherent_scenes.hpp"
#include "glsl/glsl_test_util.hpp"
#include "glsl/readback_counter.hpp"
#include "hush/glsl/coherent/frame.hpp"
#include "hush/glsl/coherent/renderer.hpp"

namespace {

namespace gl = hush::glsl::detail;
using hush_glsl_test::counted_device;
using hush_glsl_test::headless;
using hush_glsl_test::readback_counter;
using hush_glsl_test::test_gl;
using hush_test::make_synthetic;
using hush_test::synthetic_frame;

// A G-buffer in textures the test owns, updated from a synthetic frame.
struct gbuffer {
  const test_gl& t;
  int w, h;
  gl::gl_uint depth, velocity, ids;
  gbuffer(const test_gl& g, int w_, int h_)
      : t(g),
        w(w_),
        h(h_),
        depth(g.texture(gl::kGlR32fFormat, w, h, gl::kGlRedChannel, gl::kGlFloat)),
        velocity(g.texture(gl::kGlRgb32fFormat, w, h, gl::kGlRgbChannels, gl::kGlFloat)),
        ids(g.texture(gl::kGlR32uiFormat, w, h, gl::kGlRedInteger, gl::kGlUnsignedInt)) {}
  ~gbuffer() {
    const gl::gl_uint names[3] = {depth, velocity, ids};
    t.api.DeleteTextures(3, names);
  }
  void put(const synthetic_frame& s) const {
    t.update(depth, w, h, gl::kGlRedChannel, gl::kGlFloat, s.depth.data());
    t.update(velocity, w, h, gl::kGlRgbChannels, gl::kGlFloat, s.velocity.data());
    t.update(ids, w, h, gl::kGlRedInteger, gl::kGlUnsignedInt, s.ids.data());
  }
  hush::glsl::coherent_gl_frame frame(bool with_ids) const {
    return {depth, velocity, with_ids ? ids : 0u, static_cast<std::uint32_t>(w),
            static_cast<std::uint32_t>(h)};
  }
};

struct outputs {
  const test_gl& t;
  std::vector<gl::gl_uint> tex;
  outputs(const test_gl& g, int channels, int w, int h) : t(g) {
    for (int c = 0; c < channels; ++c)
      tex.push_back(g.texture(gl::kGlR32fFormat, w, h, gl::kGlRedChannel, gl::kGlFloat));
  }
  ~outputs() { t.api.DeleteTextures(static_cast<gl::gl_sizei>(tex.size()), tex.data()); }
};

struct config {
  hush::coherent_filter filter;
  hush::coherent_input input;
  int channels;
  bool ids;
};

}  // namespace

TEST_CASE(
    "GL-resident coherent stream: outputs equal the CPU-image path bit for bit, frame by frame, "
    "with no read-back") {
  const test_gl g;
  const int w = 37, h = 29, frames = 12;
  for (const config& c :
       {config{hush::coherent_filter::stationary, hush::coherent_input::white, 1, true},
        config{hush::coherent_filter::paper, hush::coherent_input::white, 2, false},
        config{hush::coherent_filter::stationary, hush::coherent_input::bandpass, 2, true}}) {
    CAPTURE(static_cast<int>(c.filter));
    CAPTURE(static_cast<int>(c.input));
    hush::coherent_params prm;
    prm.filter = c.filter;
    prm.input = c.input;
    prm.channels = c.channels;
    prm.alpha = 0.9;
    hush::coherent_stream images(prm);
    hush::glsl::coherent_gl_stream resident(counted_device(), prm, w, h);
    const gbuffer gb(g, w, h);
    const outputs out(g, c.channels, w, h);
    const std::size_t n = std::size_t(w) * h;
    std::vector<float> a(n * std::size_t(c.channels));
    std::vector<hush::image_view<float>> va;
    for (int ch = 0; ch < c.channels; ++ch) va.emplace_back(a.data() + n * std::size_t(ch), w, h);
    int differing = 0;
    for (int i = 0; i < frames; ++i) {
      const synthetic_frame s = make_synthetic("rotate", 0.04, w, h, i);
      hush::frame f = s.view();
      if (!c.ids) f.object_id = {};
      images.advance(hush::exec::glsl{headless().device}, f,
                     hush::span<const hush::image_view<float>>(va));
      gb.put(s);
      const int before = readback_counter::count();
      resident.advance(gb.frame(c.ids), hush::span<const gl::gl_uint>(out.tex));
      CHECK(readback_counter::count() == before);
      for (int ch = 0; ch < c.channels; ++ch) {
        const std::vector<float> r = g.read(out.tex[std::size_t(ch)], w, h);
        if (std::memcmp(r.data(), a.data() + n * std::size_t(ch), n * 4) != 0) ++differing;
      }
    }
    CHECK(differing == 0);
    CHECK(resident.frame_index() == images.frame_index());
    const int before = readback_counter::count();
    const hush::coherent_stream back = resident.to_stream();
    CHECK(readback_counter::count() > before);  // the counter sees a read-back
    CHECK(back.fresh() == images.fresh());
    for (int ch = 0; ch < c.channels; ++ch) {
      const auto x = back.history(ch), y = images.history(ch);
      REQUIRE(x.size() == y.size());
      CHECK(std::memcmp(x.data(), y.data(), x.size() * 4) == 0);
    }
  }
}

TEST_CASE("GL-resident coherent stream: copy, reset, and the state to and from a CPU stream") {
  const test_gl g;
  hush::coherent_params prm;
  prm.alpha = 0.8;
  const int w = 21, h = 17;
  const synthetic_frame s0 = make_synthetic("occluder", 0.6, w, h, 0);
  const gbuffer gb(g, w, h);
  const outputs out(g, 1, w, h), other(g, 1, w, h);
  hush::glsl::coherent_gl_stream resident(counted_device(), prm, w, h);
  hush::coherent_stream images(prm);
  std::vector<float> a(std::size_t(w) * h);
  const hush::image_view<float> va(a.data(), w, h);
  for (int i = 0; i < 5; ++i) {
    const synthetic_frame s = make_synthetic("occluder", 0.6, w, h, i);
    gb.put(s);
    resident.advance(gb.frame(true), out.tex[0]);
    images.advance(hush::exec::glsl{headless().device}, s.view(), va);
  }
  const synthetic_frame s5 = make_synthetic("occluder", 0.6, w, h, 5);
  gb.put(s5);
  images.advance(hush::exec::glsl{headless().device}, s5.view(), va);
  // A copy made on the GPU continues like the original, and like the CPU-image stream.
  {
    hush::glsl::coherent_gl_stream copy = resident.copy();
    const int before = readback_counter::count();
    copy.advance(gb.frame(true), other.tex[0]);
    resident.advance(gb.frame(true), out.tex[0]);
    CHECK(readback_counter::count() == before);
    const std::vector<float> x = g.read(out.tex[0], w, h), y = g.read(other.tex[0], w, h);
    CHECK(std::memcmp(x.data(), y.data(), x.size() * 4) == 0);
    CHECK(std::memcmp(x.data(), a.data(), x.size() * 4) == 0);
  }
  // A CPU stream continues on the GPU from its uploaded state, and the GPU's state continues
  // on the CPU.
  {
    const synthetic_frame s6 = make_synthetic("occluder", 0.6, w, h, 6);
    hush::glsl::coherent_gl_stream from(counted_device(), images, w, h);
    hush::coherent_stream cpu = resident.to_stream();
    gb.put(s6);
    from.advance(gb.frame(true), other.tex[0]);
    resident.advance(gb.frame(true), out.tex[0]);
    cpu.advance(hush::exec::glsl{headless().device}, s6.view(), va);
    const std::vector<float> x = g.read(out.tex[0], w, h), y = g.read(other.tex[0], w, h);
    CHECK(std::memcmp(x.data(), y.data(), x.size() * 4) == 0);
    CHECK(std::memcmp(x.data(), a.data(), x.size() * 4) == 0);
  }
  // reset(): the next frame is fresh everywhere, as a reset CPU stream's.
  resident.reset(40);
  images.reset(40);
  CHECK_FALSE(resident.has_history());
  gb.put(s0);
  resident.advance(gb.frame(true), out.tex[0]);
  images.advance(hush::exec::glsl{headless().device}, s0.view(), va);
  const std::vector<float> x = g.read(out.tex[0], w, h);
  CHECK(std::memcmp(x.data(), a.data(), x.size() * 4) == 0);
  const hush::coherent_stream back = resident.to_stream();
  CHECK(back.fresh() == std::vector<std::uint8_t>(std::size_t(w) * h, 1u));
  CHECK(back.frame_index() == 41);
}

TEST_CASE("GL-resident coherent stream: what it refuses") {
  const test_gl g;
  hush::coherent_params prm;
  const gbuffer gb(g, 8, 8);
  hush::glsl::coherent_gl_stream st(counted_device(), prm, 8, 8);
  const outputs out(g, 2, 8, 8);
  hush::glsl::coherent_gl_frame f = gb.frame(true);
  f.width = 9;
  CHECK_THROWS_AS(st.advance(f, out.tex[0]), hush::invalid_argument);
  f = gb.frame(true);
  f.velocity = 0;
  CHECK_THROWS_AS(st.advance(f, out.tex[0]), hush::invalid_argument);
  CHECK_THROWS_AS(st.advance(gb.frame(true), hush::span<const gl::gl_uint>(out.tex)),
                  hush::invalid_argument);  // two outputs, one channel
  CHECK(st.frame_index() == 0);
  hush::coherent_params smooth;
  smooth.smoothing = 1.0;
  CHECK_THROWS_AS(hush::glsl::coherent_gl_stream(counted_device(), smooth, 8, 8),
                  hush::invalid_argument);
  CHECK_THROWS_AS(hush::glsl::coherent_gl_stream(counted_device(), prm, 0, 8),
                  hush::invalid_argument);
}

TEST_CASE("GL-resident coherent stream: host time per frame at two sizes (reported)") {
  // Host wall time of the advance() calls alone (glFinish after the loop, timed apart): the
  // host sets uniforms and dispatches, whatever the pixel count. On llvmpipe the driver itself
  // may run work inside the calls; on a hardware GPU the host time stays flat.
  const test_gl g;
  hush::coherent_params prm;
  const int frames = 20;
  for (const int side : {64, 512}) {
    const synthetic_frame s = make_synthetic("rotate", 0.04, side, side);
    const gbuffer gb(g, side, side);
    gb.put(s);
    const outputs out(g, 1, side, side);
    hush::glsl::coherent_gl_stream st(counted_device(), prm, side, side);
    st.advance(gb.frame(true), out.tex[0]);  // compiles the program
    g.api.Finish();
    const int before = readback_counter::count();
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < frames; ++i) st.advance(gb.frame(true), out.tex[0]);
    const auto t1 = std::chrono::steady_clock::now();
    g.api.Finish();
    const auto t2 = std::chrono::steady_clock::now();
    CHECK(readback_counter::count() == before);
    MESSAGE(side << "x" << side << ": host "
                 << std::chrono::duration<double, std::milli>(t1 - t0).count() / frames
                 << " ms/frame in advance(), then glFinish "
                 << std::chrono::duration<double, std::milli>(t2 - t1).count() << " ms for "
                 << frames << " frames");
  }
}

TEST_CASE(
    "GL-resident coherent stream: a frame makes the same GL calls at 64 x 64 and at 1920 x 1080 "
    "(no per-pixel or per-tile host work)") {
  // The command sequence of advance() is set by the parameters, not by the pixel count: white
  // input (uniforms and one dispatch) and band-pass input (its lattice tables are uploaded in
  // one call each, O(width + height) bytes). A frame that issued calls per row, per tile or
  // per pixel would differ between the sizes (1920 x 1080 is 506 times 64 x 64).
  const test_gl g;
  for (const hush::coherent_input input :
       {hush::coherent_input::white, hush::coherent_input::bandpass}) {
    CAPTURE(static_cast<int>(input));
    hush::coherent_params prm;
    prm.input = input;
    prm.channels = 2;
    hush_glsl_test::frame_calls calls[2];
    const int sizes[2][2] = {{64, 64}, {1920, 1080}};
    for (int k = 0; k < 2; ++k) {
      const int w = sizes[k][0], h = sizes[k][1];
      const gbuffer gb(g, w, h);
      gb.put(make_synthetic("rotate", 0.04, w, h));
      const outputs out(g, 2, w, h);
      hush::glsl::coherent_gl_stream st(counted_device(), prm, w, h);
      const auto frame = [&] {
        st.advance(gb.frame(true), hush::span<const gl::gl_uint>(out.tex));
      };
      frame();  // the program compiled, the history begun
      calls[k] = hush_glsl_test::calls_per_frame(frame);
    }
    MESSAGE("GL calls per advance(), 64x64 then 1920x1080: " << calls[0].real << ", "
                                                             << calls[1].real);
    CHECK(calls[0].real == calls[1].real);
    CHECK(calls[0].skipped == calls[0].real);
    CHECK(calls[1].skipped == calls[1].real);
  }
  CHECK(hush_glsl_test::unwrapped_names() == "");
}

TEST_CASE("GL-resident coherent stream: the caller's active unit, samplers and program stay") {
  const test_gl g;
  constexpr gl::gl_enum kSamplerBinding = 0x8919;  // GL_SAMPLER_BINDING
  const gbuffer gb(g, 8, 8);
  const outputs out(g, 1, 8, 8);
  hush::glsl::coherent_gl_stream st(counted_device(), hush::coherent_params{}, 8, 8);
  g.api.ActiveTexture(gl::kGlTexture0 + 5);
  st.advance(gb.frame(true), out.tex[0]);
  gl::gl_int active = 0, program = -1;
  g.api.GetIntegerv(gl::kGlActiveTexture, &active);
  g.api.GetIntegerv(gl::kGlCurrentProgram, &program);
  CHECK(active == static_cast<gl::gl_int>(gl::kGlTexture0 + 5));
  CHECK(program == 0);
  for (gl::gl_uint u = 0; u < 3; ++u) {
    g.api.ActiveTexture(gl::kGlTexture0 + u);
    gl::gl_int sampler = -1;
    g.api.GetIntegerv(kSamplerBinding, &sampler);
    CHECK(sampler == 0);  // the caller's textures filter as they did
  }
  g.api.ActiveTexture(gl::kGlTexture0);
}
