// The resident NPR Gabor path (backends/glsl/include/hush/glsl/npr_gabor/frame.hpp) on a
// headless OSMesa (llvmpipe) context: the G-buffer in textures and the triangles in buffers the
// test owns, the noise into the test's R32F texture; equal bit for bit to the CPU-image path
// (noise.render with exec::glsl) over frames of a moving scene; no read-back of any kind per
// frame through the renderer's device (a counting loader) once its capacities are set (the
// first resident frame of a device reads each level's totals back to set them, and maps its
// status buffer); a frame that needs more than the capacities: seen a frame later, the next
// frame equal to the CPU-image path again; the same triangles make the same GL calls per frame
// at two frame sizes; refusals; host time per frame at two sizes (reported).
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "glsl/glsl_test_util.hpp"
#include "glsl/readback_counter.hpp"
#include "hush/glsl/npr_gabor/frame.hpp"
#include "npr_gabor_scenes.hpp"

namespace {

namespace gl = hush::glsl::detail;
using hush_glsl_test::counted_device;
using hush_glsl_test::headless;
using hush_glsl_test::readback_counter;
using hush_glsl_test::test_gl;

// A shader storage buffer of `bytes` from `data`.
gl::gl_uint buffer_of(const test_gl& g, const void* data, std::size_t bytes) {
  gl::gl_uint b = 0;
  g.api.GenBuffers(1, &b);
  g.api.BindBuffer(gl::kGlShaderStorageBuffer, b);
  g.api.BufferData(gl::kGlShaderStorageBuffer, static_cast<gl::gl_sizeiptr>(bytes), data,
                   gl::kGlStaticDraw);
  g.api.BindBuffer(gl::kGlShaderStorageBuffer, 0);
  return b;
}

// A scene's G-buffer and triangles in GL objects the test owns.
struct gl_scene {
  const test_gl& t;
  gl::gl_uint depth, object, triangle, vertices, triangles;
  hush::glsl::npr_gabor_gl_frame f;
  gl_scene(const test_gl& g, const npr_test::grid_scene& sc) : t(g) {
    const int w = static_cast<int>(sc.width), h = static_cast<int>(sc.height);
    depth = g.texture(gl::kGlR32fFormat, w, h, gl::kGlRedChannel, gl::kGlFloat, sc.depth.data());
    object = g.texture(gl::kGlR32uiFormat, w, h, gl::kGlRedInteger, gl::kGlUnsignedInt,
                       sc.object.data());
    triangle = g.texture(gl::kGlR32uiFormat, w, h, gl::kGlRedInteger, gl::kGlUnsignedInt,
                         sc.triangle.data());
    std::vector<float> v;
    std::vector<std::uint32_t> tri;
    const hush::triangle_list list = sc.triangles();
    hush::glsl::npr_gabor_gl_pack(list, v, tri);
    vertices = buffer_of(g, v.data(), v.size() * 4);
    triangles = buffer_of(g, tri.data(), tri.size() * 4);
    f.depth = depth;
    f.object_id = object;
    f.triangle_id = triangle;
    f.width = static_cast<std::uint32_t>(w);
    f.height = static_cast<std::uint32_t>(h);
    f.vertices = vertices;
    f.triangles = triangles;
    f.vertex_count = static_cast<std::uint32_t>(list.vertices());
    f.triangle_count = static_cast<std::uint32_t>(list.triangles());
  }
  ~gl_scene() {
    const gl::gl_uint tex[3] = {depth, object, triangle}, buf[2] = {vertices, triangles};
    t.api.DeleteTextures(3, tex);
    t.api.DeleteBuffers(2, buf);
  }
};

// Frame i of a grid of 12-pixel cells sliding right by 1.75 pixels per frame, over a
// background (depth +inf, object 0): the G-buffer and triangles change every frame.
npr_test::grid_scene sliding(std::size_t w, std::size_t h, int i, double cell = 12.0) {
  const int nx = static_cast<int>(static_cast<double>(w) / cell) - 2,
            ny = static_cast<int>(static_cast<double>(h) / cell) - 2;
  return npr_test::grid_scene(w, h, 5.0 + 1.75 * i, 7.0, cell, nx, ny, 1.5f);
}

hush::npr_gabor::params base_params() {
  hush::npr_gabor::params p;
  p.frequency = 0.12;
  p.bandwidth = 0.2;
  p.impulses = 16;
  return p;
}

}  // namespace

TEST_CASE(
    "GL-resident NPR Gabor: output equals the CPU-image path bit for bit over frames, with no "
    "read-back per frame once the capacities are set") {
  const test_gl g;
  const std::size_t w = 96, h = 80;
  struct config {
    const char* name;
    hush::npr_gabor::params p;
  };
  std::vector<config> configs;
  configs.push_back({"defaults (object + depth tests)", base_params()});
  hush::npr_gabor::params q = base_params();
  q.triangle_test = true;
  q.soft_depth = true;
  q.isotropic = true;
  configs.push_back({"triangle test, soft depth, isotropic", q});
  q = base_params();
  q.depth_test = false;
  q.local_density = true;
  configs.push_back({"object test only, local density", q});
  const gl::gl_uint out =
      g.texture(gl::kGlR32fFormat, int(w), int(h), gl::kGlRedChannel, gl::kGlFloat);
  for (const config& c : configs) {
    const std::string name = c.name;
    CAPTURE(name);
    const hush::npr_gabor noise(c.p);
    int differing = 0, sizing_reads = 0, resident_frames = 0;
    double reached = 0;
    for (int i = 0; i < 4; ++i) {
      const npr_test::grid_scene sc = sliding(w, h, i);
      std::vector<float> a(w * h);
      noise.render(hush::exec::glsl{headless().device}, sc.frame(), sc.triangles(),
                   hush::image_view<float>(a.data(), w, h));
      const gl_scene gs(g, sc);
      const hush::glsl::detail::npr_gabor_gpu& state =
          hush::glsl::npr_gabor_state(counted_device());
      const bool sized = state.resident_sized();
      const int pixels = readback_counter::count(readback_counter::read_pixels_calls);
      const int tex = readback_counter::count(readback_counter::get_tex_calls);
      const int before = readback_counter::count();
      hush::glsl::npr_gabor_gl_render(counted_device(), noise, gs.f, out);
      CHECK(readback_counter::count(readback_counter::read_pixels_calls) == pixels);
      CHECK(readback_counter::count(readback_counter::get_tex_calls) == tex);
      if (sized) {
        // Stage 1 and 2 from the plan on the GPU: no glGetBufferSubData, glMapBufferRange,
        // glReadPixels or glGetTexImage at all.
        CHECK(readback_counter::count() == before);
        ++resident_frames;
      } else {
        // The device's first resident frame: each level's totals (8 bytes per scan) and the
        // status buffer's one persistent mapping.
        sizing_reads += readback_counter::count() - before;
        CHECK(state.resident_sized());
      }
      const std::vector<float> r = g.read(out, int(w), int(h));
      if (std::memcmp(r.data(), a.data(), a.size() * 4) != 0) ++differing;
      for (float v : a) reached += v != 0.0f ? 1 : 0;
    }
    CHECK(differing == 0);
    CHECK(reached > double(w * h));  // the noise covers over a third of each frame
    CHECK(resident_frames >= 3);
    MESSAGE(name << ": 4 frames, " << resident_frames << " with no read-back; " << sizing_reads
                 << " read-backs in the frame that set the capacities");
    CHECK(sizing_reads <= 2 * 24 + 1);
  }
  g.api.DeleteTextures(1, &out);
}

TEST_CASE(
    "GL-resident NPR Gabor: a frame beyond the capacities is seen a frame later; the next "
    "frame sets them again and equals the CPU-image path") {
  // A device of its own: its capacities set by a sparse frame (1 impulse per kernel area), then
  // a dense one (256) needs far more nodes per level. That frame keeps the nodes that fit (the
  // GPU writes nothing beyond the buffers); the renderer reads its status once the GPU has
  // finished it (here after glFinish, through the persistent mapping), and the next frame
  // walks with read-backs as the first did, setting the capacities: exact, as those after.
  const test_gl g;
  hush::glsl::device dev(&readback_counter::loader);
  const hush::glsl::detail::npr_gabor_gpu& state = hush::glsl::npr_gabor_state(dev);
  const std::size_t w = 160, h = 128;
  const npr_test::grid_scene sc = sliding(w, h, 0, 20.0);
  const gl_scene gs(g, sc);
  const gl::gl_uint out =
      g.texture(gl::kGlR32fFormat, int(w), int(h), gl::kGlRedChannel, gl::kGlFloat);
  hush::npr_gabor::params p = base_params();
  p.impulses = 1;
  hush::glsl::npr_gabor_gl_render(dev, hush::npr_gabor(p), gs.f, out);
  REQUIRE(state.resident_sized());
  std::size_t before = 0;
  for (std::size_t k = 0; k < 22; ++k) before = std::max(before, state.resident_capacity(k));
  p.impulses = 256;
  const hush::npr_gabor dense(p);
  std::vector<float> a(w * h);
  dense.render(hush::exec::glsl{headless().device}, sc.frame(), sc.triangles(),
               hush::image_view<float>(a.data(), w, h));
  auto differs = [&] {
    const std::vector<float> r = g.read(out, int(w), int(h));
    return std::memcmp(r.data(), a.data(), a.size() * 4) != 0;
  };
  int reads = readback_counter::count();
  hush::glsl::npr_gabor_gl_render(dev, dense, gs.f, out);  // beyond the capacities
  CHECK(readback_counter::count() == reads);
  const std::string beyond = differs() ? "differed" : "was equal";
  g.api.Finish();
  CHECK(state.resident_overflows() == 0);  // not seen yet: nothing was read
  reads = readback_counter::count();
  hush::glsl::npr_gabor_gl_render(dev, dense, gs.f, out);  // seen: the capacities set again
  const int sizing = readback_counter::count() - reads;
  CHECK(state.resident_overflows() > 0);
  std::size_t after = 0;
  for (std::size_t k = 0; k < 22; ++k) after = std::max(after, state.resident_capacity(k));
  CHECK(after > before);
  CHECK_FALSE(differs());
  for (int i = 0; i < 2; ++i) {
    reads = readback_counter::count();
    hush::glsl::npr_gabor_gl_render(dev, dense, gs.f, out);
    CHECK(readback_counter::count() == reads);
    CHECK_FALSE(differs());
  }
  MESSAGE("capacity (most nodes of a level) "
          << before << " -> " << after << "; the frame beyond it " << beyond << "; " << sizing
          << " read-backs setting them again");
  g.api.DeleteTextures(1, &out);
}

TEST_CASE(
    "GL-resident NPR Gabor: capacity reserved at every level keeps a growing scene's frames "
    "exact, with no frame beyond the capacities; a reserve beyond a storage block is refused") {
  // Devices size their capacities on a frame of 16 impulses per kernel area, then render one of
  // 64, whose walk needs more nodes per level and a deeper level. Without a reserve that frame
  // is beyond the capacities (seen a frame later, as the test above); with a reserve of the
  // most nodes any level of the dense frame needs (measured on a third device sized by it)
  // every frame equals the CPU-image path and no overflow is ever seen.
  const test_gl g;
  const std::size_t w = 320, h = 256;
  const npr_test::grid_scene sc = sliding(w, h, 0, 20.0);
  const gl_scene gs(g, sc);
  const gl::gl_uint out =
      g.texture(gl::kGlR32fFormat, int(w), int(h), gl::kGlRedChannel, gl::kGlFloat);
  hush::npr_gabor::params p = base_params();
  const hush::npr_gabor sparse(p);
  p.impulses = 64;
  const hush::npr_gabor dense(p);
  std::vector<float> a(w * h);
  dense.render(hush::exec::glsl{headless().device}, sc.frame(), sc.triangles(),
               hush::image_view<float>(a.data(), w, h));
  std::size_t need = 0;  // twice the most nodes a level of the dense frame needs
  {
    hush::glsl::device dev(&readback_counter::loader);
    hush::glsl::npr_gabor_gl_render(dev, dense, gs.f, out);
    for (std::size_t k = 0; k < hush::glsl::kNprGaborPlanLevels; ++k)
      need = std::max(need, hush::glsl::npr_gabor_state(dev).resident_capacity(k));
  }
  std::size_t overflows[2] = {0, 0};
  bool exact[2] = {true, true};
  for (int i = 0; i < 2; ++i) {
    hush::glsl::device dev(&readback_counter::loader);
    hush::glsl::detail::npr_gabor_gpu& state = hush::glsl::npr_gabor_state(dev);
    if (i == 1) state.reserve_resident(need / 2);
    hush::glsl::npr_gabor_gl_render(dev, sparse, gs.f, out);
    for (int frame = 0; frame < 3; ++frame) {
      hush::glsl::npr_gabor_gl_render(dev, dense, gs.f, out);
      const std::vector<float> r = g.read(out, int(w), int(h));
      exact[i] = exact[i] && std::memcmp(r.data(), a.data(), a.size() * 4) == 0;
      g.api.Finish();
    }
    overflows[i] = state.resident_overflows();
    if (i == 1) CHECK(state.resident_reserved() == need / 2);
  }
  MESSAGE("the dense frame's most nodes at a level: " << need / 2);
  CHECK(overflows[0] > 0);  // the growth is beyond the capacities the sparse frame set
  CHECK_FALSE(exact[0]);
  CHECK(overflows[1] == 0);
  CHECK(exact[1]);
  hush::glsl::detail::npr_gabor_gpu& state = hush::glsl::npr_gabor_state(headless().device);
  const std::size_t reserved = state.resident_reserved();
  CHECK_THROWS_WITH_AS(state.reserve_resident(std::size_t{1} << 40),
                       doctest::Contains("nodes = 1099511627776 is out of range"),
                       hush::invalid_argument);
  CHECK(state.resident_reserved() == reserved);
  g.api.DeleteTextures(1, &out);
}

TEST_CASE(
    "GL-resident NPR Gabor: the same triangles make the same GL calls per frame at 128 x 128 and "
    "1920 x 1080 once the capacities are set (no per-pixel or per-tile host work)") {
  // The command sequence follows the capacities (levels, storage blocks of records), which
  // follow the triangles' kernels, not the frame's pixel count: the same 8 x 8 cells of 12
  // pixels in a frame of 128 x 128 and of 1920 x 1080 (126 times the pixels). A device of its
  // own, its capacities set by the first frame; the larger frame must leave them as they are.
  const test_gl g;
  hush::glsl::device dev(&readback_counter::loader);
  const hush::glsl::detail::npr_gabor_gpu& state = hush::glsl::npr_gabor_state(dev);
  const hush::npr_gabor noise(base_params());
  const std::size_t sizes[2][2] = {{128, 128}, {1920, 1080}};
  std::vector<npr_test::grid_scene> scenes;
  for (const auto& wh : sizes) scenes.emplace_back(wh[0], wh[1], 5.0, 7.0, 12.0, 8, 8, 1.5f);
  hush_glsl_test::frame_calls calls[2];
  std::vector<std::size_t> capacities;
  for (int pass = 0; pass < 2; ++pass)  // pass 0 sets the capacities, pass 1 counts
    for (std::size_t k = 0; k < 2; ++k) {
      const gl_scene gs(g, scenes[k]);
      const int w = int(sizes[k][0]), h = int(sizes[k][1]);
      const gl::gl_uint out = g.texture(gl::kGlR32fFormat, w, h, gl::kGlRedChannel, gl::kGlFloat);
      // Each frame after a glFinish (the test's own, uncounted): the renderer polls the fences
      // of earlier frames' status entries, one call per entry it finds finished and one for the
      // first unfinished, so the count follows the GPU's progress; finished, it is the same.
      const auto frame = [&] {
        g.api.Finish();
        hush::glsl::npr_gabor_gl_render(dev, noise, gs.f, out);
      };
      if (pass == 0) {
        frame();  // programs, capacities, framebuffer at this size
      } else {
        const int reads = readback_counter::count();
        calls[k] = hush_glsl_test::calls_per_frame(frame);
        CHECK(readback_counter::count() == reads);
      }
      g.api.DeleteTextures(1, &out);
      std::vector<std::size_t> now;
      for (std::size_t level = 0; level < 22; ++level)
        now.push_back(state.resident_capacity(level));
      if (pass == 0 && k == 0) capacities = now;
      CHECK(now == capacities);
    }
  MESSAGE("GL calls per npr_gabor_gl_render, 128x128 then 1920x1080 ("
          << scenes[0].triangles().triangles() << " triangles): " << calls[0].real << ", "
          << calls[1].real);
  CHECK(state.resident_overflows() == 0);
  CHECK(calls[0].real == calls[1].real);
  CHECK(calls[0].skipped == calls[0].real);
  CHECK(calls[1].skipped == calls[1].real);
  CHECK(hush_glsl_test::unwrapped_names() == "");
}

TEST_CASE("GL-resident NPR Gabor: what it refuses") {
  const test_gl g;
  const npr_test::grid_scene sc = sliding(64, 64, 0);
  const gl_scene gs(g, sc);
  REQUIRE(gs.f.triangle_count > 0);
  const gl::gl_uint out = g.texture(gl::kGlR32fFormat, 64, 64, gl::kGlRedChannel, gl::kGlFloat);
  const hush::npr_gabor noise(base_params());
  hush::glsl::npr_gabor_gl_frame f = gs.f;
  f.depth = 0;  // the depth test reads it
  CHECK_THROWS_AS(hush::glsl::npr_gabor_gl_render(counted_device(), noise, f, out),
                  hush::invalid_argument);
  f = gs.f;
  f.vertex_count += 1;  // more than the buffer holds
  CHECK_THROWS_AS(hush::glsl::npr_gabor_gl_render(counted_device(), noise, f, out),
                  hush::invalid_argument);
  f = gs.f;
  f.triangles = 0;
  CHECK_THROWS_AS(hush::glsl::npr_gabor_gl_render(counted_device(), noise, f, out),
                  hush::invalid_argument);
  CHECK_THROWS_AS(hush::glsl::npr_gabor_gl_render(counted_device(), noise, gs.f, 0u),
                  hush::invalid_argument);
  const std::vector<float> per_pixel(64 * 64, 0.1f);
  hush::npr_gabor::sources src;
  src.frequency = hush::param_source::per_pixel({per_pixel.data(), 64, 64});
  CHECK_THROWS_AS(hush::glsl::npr_gabor_gl_render(counted_device(), noise, gs.f, out, src),
                  hush::invalid_argument);
  // Without the tests that read them, no texture is needed.
  hush::npr_gabor::params p = base_params();
  p.depth_test = p.object_test = false;
  f = gs.f;
  f.depth = f.object_id = f.triangle_id = 0;
  CHECK_NOTHROW(hush::glsl::npr_gabor_gl_render(counted_device(), hush::npr_gabor(p), f, out));
  g.api.DeleteTextures(1, &out);
}

TEST_CASE("GL-resident NPR Gabor: host time per frame at two sizes (reported)") {
  // The same triangles (cells scaled with the frame) at 128 x 128 and 256 x 256: host wall
  // time of the render calls alone (glFinish after the loop, timed apart). On llvmpipe the
  // driver may run work inside the calls; on a hardware GPU the host part stays flat.
  const test_gl g;
  const hush::npr_gabor noise(base_params());
  const int frames = 3;
  for (const std::size_t side : {std::size_t(128), std::size_t(256)}) {
    const npr_test::grid_scene sc = sliding(side, side, 0, double(side) / 10.0);
    const gl_scene gs(g, sc);
    const gl::gl_uint out =
        g.texture(gl::kGlR32fFormat, int(side), int(side), gl::kGlRedChannel, gl::kGlFloat);
    hush::glsl::npr_gabor_gl_render(counted_device(), noise, gs.f, out);  // programs made
    g.api.Finish();
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < frames; ++i)
      hush::glsl::npr_gabor_gl_render(counted_device(), noise, gs.f, out);
    const auto t1 = std::chrono::steady_clock::now();
    g.api.Finish();
    const auto t2 = std::chrono::steady_clock::now();
    MESSAGE(side << "x" << side << " (" << gs.f.triangle_count << " triangles): host "
                 << std::chrono::duration<double, std::milli>(t1 - t0).count() / frames
                 << " ms/frame in npr_gabor_gl_render, then glFinish "
                 << std::chrono::duration<double, std::milli>(t2 - t1).count() << " ms for "
                 << frames << " frames");
    g.api.DeleteTextures(1, &out);
  }
}
