// hush::glsl::anisotropic_frame (hush/glsl/anisotropic/frame.hpp) on llvmpipe: a frame
// rendered from caller-owned textures into a caller-owned R32F texture agrees pixel by pixel
// with the CPU's float sample at the same uv and Jacobian (given, or the central / one-sided
// differences of neighbouring uvs), with and without per-pixel surface maps; background pixels
// are 0; the CPU-image convenience gives the same image; a frame's read-backs, uploads and GL
// calls do not grow with the pixel count.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "glsl/glsl_test_util.hpp"
#include "glsl/readback_counter.hpp"
#include "hush/glsl/anisotropic/frame.hpp"

namespace {

using hush_glsl_test::headless;
using hush_glsl_test::readback_counter;

hush::anisotropic make_noise(int k, hush::fractal_kind kind) {
  hush::anisotropic::params p;
  p.seed = 5;
  p.orientations = k;
  p.scales = 4;
  p.base_scale = 1;
  p.octaves = 2;
  p.kind = kind;
  p.tile_size = 64;
  return hush::anisotropic(p);
}

// A receding plane's uvs and exact Jacobians (rows y down), a disc of background in the
// middle, and a per-pixel surface map that varies across the frame.
struct test_frame {
  int w = 0, h = 0;
  std::vector<hush::vec2> uv;
  std::vector<hush::vec4> jac;  // du/dx, du/dy, dv/dx, dv/dy
  std::vector<std::uint32_t> ids;
  std::vector<hush::surface_map> maps;
  std::vector<float> depth;  // the frame's size (hush::frame); not read
  hush::frame view() const {
    hush::frame f;
    f.depth = {depth.data(), std::size_t(w), std::size_t(h), std::size_t(w)};
    f.uv = {uv.data(), std::size_t(w), std::size_t(h), std::size_t(w)};
    f.uv_jacobian = {jac.data(), std::size_t(w), std::size_t(h), std::size_t(w)};
    f.object_id = {ids.data(), std::size_t(w), std::size_t(h), std::size_t(w)};
    return f;
  }
};

test_frame make_frame(int w, int h) {
  test_frame f;
  f.w = w;
  f.h = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // Plane seen in perspective: uv = (a (x - cx), b) / (y + d) scaled; exact derivatives.
      const double cx = w / 2.0, d = 4.0, a = 6.0, b = 40.0;
      const double px = x + 0.5, py = y + 0.5, z = py + d;
      f.uv.push_back({float(a * (px - cx) / z), float(b / z + 3.0)});
      f.jac.push_back({float(a / z), float(-a * (px - cx) / (z * z)), 0.0f, float(-b / (z * z))});
      const double rx = px - cx, ry = py - h / 2.0;
      f.depth.push_back(1.0f);
      f.ids.push_back(rx * rx + ry * ry < (h / 6.0) * (h / 6.0) ? 0u : 1u);
      const double t = 0.05 * x + 0.08 * y;
      f.maps.push_back(hush::surface_map::from_matrix(1.5 * std::cos(t), -0.7 * std::sin(t),
                                                      0.9 * std::sin(t), 1.2 * std::cos(t)));
    }
  return f;
}

// The bound texture complete without mipmaps (texelFetch of an incomplete texture reads 0).
void complete(const hush::glsl::detail::gl_api& gl) {
  using namespace hush::glsl::detail;
  gl.TexParameteri(kGlTexture2d, kGlTextureMinFilter, static_cast<gl_int>(kGlNearestFilter));
  gl.TexParameteri(kGlTexture2d, kGlTextureMagFilter, static_cast<gl_int>(kGlNearestFilter));
}

}  // namespace

TEST_CASE("anisotropic frame: given Jacobians and maps, every pixel within the kit's tolerance") {
  auto& h = headless();
  const test_frame f = make_frame(48, 40);
  double worst = 0;
  for (hush::fractal_kind kind : {hush::fractal_kind::fbm, hush::fractal_kind::turbulence})
    for (int k : {4, 6}) {
      const hush::anisotropic a = make_noise(k, kind);
      hush::glsl::anisotropic_frame fr(h.context.loader(), a);
      for (bool with_maps : {false, true}) {
        const std::vector<float> img =
            fr.render_image(f.view(), with_maps ? f.maps : std::vector<hush::surface_map>{});
        for (std::size_t q = 0; q < img.size(); ++q) {
          INFO("K " << k << " kind " << int(kind) << " maps " << with_maps << " pixel " << q);
          if (f.ids[q] == 0u) {
            CHECK(img[q] == 0.0f);
            continue;
          }
          const hush::vec2 dx{f.jac[q].x, f.jac[q].z}, dy{f.jac[q].y, f.jac[q].w};
          const auto fp = hush::footprint<2>::from_derivatives(dx, dy);
          const float cpu = with_maps ? a.sample(f.uv[q], fp, f.maps[q]) : a.sample(f.uv[q], fp);
          const double tol = hush::glsl::anisotropic_shader_tolerance(
              a, f.uv[q], dx, dy, with_maps ? &f.maps[q] : nullptr);
          const double e = std::fabs(double(img[q]) - cpu);
          CHECK(e <= tol);
          worst = std::max(worst, e / tol);
        }
      }
    }
  MESSAGE(h.device.renderer() << ", frame (given Jacobians): max error / tolerance = " << worst);
}

// Without a Jacobian texture the frame differentiates neighbouring uvs: central differences
// (hi - lo) / 2, one-sided next to background and at the frame's edges; the CPU forms the same
// float differences and samples there.
TEST_CASE("anisotropic frame: Jacobians from neighbouring uvs, one-sided at edges") {
  auto& h = headless();
  const test_frame f = make_frame(40, 32);
  const hush::anisotropic a = make_noise(4, hush::fractal_kind::fbm);
  hush::glsl::anisotropic_frame fr(h.context.loader(), a);
  const hush::glsl::detail::gl_api& gl = h.device.gl();
  const std::size_t n = f.uv.size();
  std::vector<float> uv(4 * n);
  for (std::size_t q = 0; q < n; ++q) {
    uv[4 * q] = f.uv[q].x;
    uv[4 * q + 1] = f.uv[q].y;
    uv[4 * q + 3] = f.ids[q] ? 1.0f : 0.0f;
  }
  using namespace hush::glsl::detail;
  gl_uint tex[2] = {0, 0};
  gl.GenTextures(2, tex);
  gl.BindTexture(kGlTexture2d, tex[0]);
  gl.TexImage2D(kGlTexture2d, 0, static_cast<gl_int>(kGlRgba32f), f.w, f.h, 0, kGlRgba, kGlFloat,
                uv.data());
  complete(gl);
  gl.BindTexture(kGlTexture2d, tex[1]);
  gl.TexImage2D(kGlTexture2d, 0, static_cast<gl_int>(kGlR32fFormat), f.w, f.h, 0, kGlRedFormat,
                kGlFloat, nullptr);
  gl.BindTexture(kGlTexture2d, 0u);
  fr.render({tex[0], 0u, 0u}, tex[1], f.w, f.h);
  // Read back through render_image's path would re-render; read this output directly.
  std::vector<float> img(n);
  {
    void(HUSH_GLAPI * gen)(gl_sizei, gl_uint*) = nullptr;
    void(HUSH_GLAPI * bind)(gl_enum, gl_uint) = nullptr;
    void(HUSH_GLAPI * attach)(gl_enum, gl_enum, gl_enum, gl_uint, gl_int) = nullptr;
    void(HUSH_GLAPI * del)(gl_sizei, const gl_uint*) = nullptr;
    void(HUSH_GLAPI * read)(gl_int, gl_int, gl_sizei, gl_sizei, gl_enum, gl_enum, void*) = nullptr;
    gl_api::load(gl.loader, gen, "glGenFramebuffers");
    gl_api::load(gl.loader, bind, "glBindFramebuffer");
    gl_api::load(gl.loader, attach, "glFramebufferTexture2D");
    gl_api::load(gl.loader, del, "glDeleteFramebuffers");
    gl_api::load(gl.loader, read, "glReadPixels");
    gl_uint fbo = 0;
    gen(1, &fbo);
    bind(0x8D40, fbo);
    attach(0x8D40, 0x8CE0, kGlTexture2d, tex[1], 0);
    read(0, 0, f.w, f.h, kGlRedFormat, kGlFloat, img.data());
    bind(0x8D40, 0u);
    del(1, &fbo);
  }
  gl.DeleteTextures(2, tex);
  gl.check("frame test read-back");
  auto covered = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < f.w && y < f.h && f.ids[std::size_t(y * f.w + x)] != 0u;
  };
  auto at = [&](int x, int y) { return f.uv[std::size_t(y * f.w + x)]; };
  auto diff = [&](int x, int y, int sx, int sy) {
    const bool lo = covered(x - sx, y - sy), hi = covered(x + sx, y + sy);
    const hush::vec2 c = at(x, y);
    if (lo && hi) {
      const hush::vec2 l = at(x - sx, y - sy), r = at(x + sx, y + sy);
      return hush::vec2{(r.x - l.x) / 2.0f, (r.y - l.y) / 2.0f};
    }
    if (hi) return hush::vec2{at(x + sx, y + sy).x - c.x, at(x + sx, y + sy).y - c.y};
    if (lo) return hush::vec2{c.x - at(x - sx, y - sy).x, c.y - at(x - sx, y - sy).y};
    return hush::vec2{0, 0};
  };
  double worst = 0;
  int one_sided = 0;
  for (int y = 0; y < f.h; ++y)
    for (int x = 0; x < f.w; ++x) {
      const std::size_t q = std::size_t(y * f.w + x);
      if (!covered(x, y)) {
        CHECK(img[q] == 0.0f);
        continue;
      }
      one_sided += !(covered(x - 1, y) && covered(x + 1, y)) ? 1 : 0;
      const hush::vec2 dx = diff(x, y, 1, 0), dy = diff(x, y, 0, 1);
      const float cpu = a.sample(f.uv[q], hush::footprint<2>::from_derivatives(dx, dy));
      const double tol = hush::glsl::anisotropic_shader_tolerance(a, f.uv[q], dx, dy, nullptr);
      INFO("pixel " << x << ", " << y << ": cpu " << cpu << " gpu " << img[q]);
      CHECK(std::fabs(double(img[q]) - cpu) <= tol);
      worst = std::max(worst, std::fabs(double(img[q]) - cpu) / tol);
    }
  CHECK(one_sided > 40);  // the frame's sides and the disc's rim
  MESSAGE(h.device.renderer() << ", frame (neighbour differences): max error / tolerance = "
                              << worst);
}

// What render() sends between host and GPU at 256 x 256 and at 1920 x 1080 (32 times the
// pixels): no read-back, the same uploads (calls, buffer bytes, texels) and the same GL calls
// at both sizes, so no per-pixel data is formed on the CPU and no command is issued per row,
// tile or pixel. The host's time per frame is the benchmark's row (`hush bench --filter
// resident`, docs/gpu.md).
TEST_CASE(
    "anisotropic frame: a frame reads nothing back, uploads the same and makes the same GL calls "
    "at 256 x 256 and 1920 x 1080 (no per-pixel or per-tile host work)") {
  auto& h = headless();
  const hush::anisotropic a = make_noise(4, hush::fractal_kind::fbm);
  hush::glsl::anisotropic_frame fr(&readback_counter::loader, a);
  const hush::glsl::detail::gl_api& gl = h.device.gl();
  using namespace hush::glsl::detail;
  readback_counter::uploads sent[2];
  int read_back[2] = {-1, -1};
  hush_glsl_test::frame_calls calls[2];
  const int sizes[2][2] = {{256, 256}, {1920, 1080}};
  for (int s = 0; s < 2; ++s) {
    const int w = sizes[s][0], ht = sizes[s][1];
    std::vector<float> uv(std::size_t(w) * std::size_t(ht) * 2);
    for (int y = 0; y < ht; ++y)
      for (int x = 0; x < w; ++x) {
        uv[2 * std::size_t(y * w + x)] = 0.01f * float(x);
        uv[2 * std::size_t(y * w + x) + 1] = 0.013f * float(y);
      }
    gl_uint tex[2] = {0, 0};
    gl.GenTextures(2, tex);
    gl.BindTexture(kGlTexture2d, tex[0]);
    gl.TexImage2D(kGlTexture2d, 0, static_cast<gl_int>(kGlRg32fFormat), w, ht, 0, kGlRgFormat,
                  kGlFloat, uv.data());
    complete(gl);
    gl.BindTexture(kGlTexture2d, tex[1]);
    gl.TexImage2D(kGlTexture2d, 0, static_cast<gl_int>(kGlR32fFormat), w, ht, 0, kGlRedFormat,
                  kGlFloat, nullptr);
    gl.BindTexture(kGlTexture2d, 0u);
    if (s == 0) fr.render({tex[0], 0u, 0u}, tex[1], w, ht);  // first use: program and kit set up
    gl.Finish();
    const int before = readback_counter::count();
    readback_counter::uploaded() = {};
    const auto frame = [&] { fr.render({tex[0], 0u, 0u}, tex[1], w, ht); };
    calls[s].real = hush_glsl_test::gl_calls_of(frame);
    gl.Finish();
    read_back[s] = readback_counter::count() - before;
    sent[s] = readback_counter::uploaded();
    {
      const hush_glsl_test::skipping_gpu_work skip;  // the same calls without the draw's work
      calls[s].skipped = hush_glsl_test::gl_calls_of(frame);
    }
    gl.DeleteTextures(2, tex);
  }
  MESSAGE(h.device.renderer() << ": per frame, 256x256 then 1920x1080: read-backs " << read_back[0]
                              << ", " << read_back[1] << "; uploads " << sent[0].calls << " calls, "
                              << sent[0].buffer_bytes << " buffer bytes, " << sent[0].texels
                              << " texels; " << sent[1].calls << ", " << sent[1].buffer_bytes
                              << ", " << sent[1].texels << "; GL calls " << calls[0].real << ", "
                              << calls[1].real);
  CHECK(read_back[0] == 0);
  CHECK(read_back[1] == 0);
  CHECK(sent[0] == sent[1]);
  CHECK(sent[1].texels < 256);  // nothing image-sized
  CHECK(sent[1].buffer_bytes < 65536);
  CHECK(calls[0].real == calls[1].real);
  CHECK(calls[0].skipped == calls[0].real);
  CHECK(calls[1].skipped == calls[1].real);
  CHECK(hush_glsl_test::unwrapped_names() == "");
  // The counters see host traffic: render_image uploads the frame's uvs and reads the image back.
  const test_frame small = make_frame(24, 20);
  const int before = readback_counter::count();
  readback_counter::uploaded() = {};
  (void)fr.render_image(small.view());
  CHECK(readback_counter::count() - before >= 1);
  CHECK(readback_counter::uploaded().texels >= 24 * 20);
}
