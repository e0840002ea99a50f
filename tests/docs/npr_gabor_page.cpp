// NPR Gabor noise (docs/npr-gabor.md): one frame of a square made of two triangles, drawn by a
// renderer into a 128 x 96 G-buffer. The renderer hands over views of its own buffers: the
// depth and object ids per pixel, and the frame's triangles with their vertices' screen
// positions and depths. Quoted in docs/npr-gabor.md.
#include <hush/hush.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

int main() {
  const std::size_t w = 128, h = 96;
  // The G-buffer: the square covers pixels x in [16, 112), y in [8, 88) at depth 4, object 1.
  std::vector<float> depth(w * h, 0.0f);
  std::vector<std::uint32_t> object(w * h, 0u);
  for (std::size_t y = 8; y < 88; ++y)
    for (std::size_t x = 16; x < 112; ++x) {
      depth[y * w + x] = 4.0f;
      object[y * w + x] = 1u;
    }
  hush::frame f;
  f.depth = {depth.data(), w, h};
  f.object_id = {object.data(), w, h};

  // The triangles drawn this frame: screen positions in pixels (y down), linear view depths,
  // a stable id per triangle (the same in every frame) and its object. Front faces are
  // counter-clockwise as displayed (params::front_face, GL's default); in these y-down pixel
  // coordinates that is (v1 - v0) x (v2 - v0) < 0. Back faces emit nothing unless
  // cull_back_faces is off; render() returns how many it culled.
  const std::vector<hush::vec2> screen = {{16, 8}, {112, 8}, {112, 88}, {16, 88}};
  const std::vector<float> vertex_depth = {4, 4, 4, 4};
  const std::vector<std::uint32_t> indices = {0, 2, 1, 0, 3, 2};
  const std::vector<std::uint32_t> ids = {0, 1}, objects = {1, 1};
  hush::triangle_list t;
  t.indices = indices;
  t.screen = screen;
  t.depth = vertex_depth;
  t.triangle_id = ids;
  t.object_id = objects;

  hush::npr_gabor::params prm;  // F0 = 1/8 cycle per pixel, a = 0.08 per pixel, N' = 16
  prm.orientation = 0.5;        // radians from +x towards +y (screen y points down)
  prm.seed = 7;
  const hush::npr_gabor noise{prm};
  std::vector<float> out(w * h);
  noise.render(hush::exec::simd, f, t, hush::image_view<float>{out.data(), w, h});

  double sum_sq = 0;  // unit variance inside the square (mean 0), 0 outside
  std::size_t n = 0;
  for (std::size_t y = 24; y < 72; ++y)
    for (std::size_t x = 32; x < 96; ++x, ++n) sum_sq += double(out[y * w + x]) * out[y * w + x];
  std::printf("standard deviation inside the square: %.2f\n", std::sqrt(sum_sq / double(n)));
  return std::isfinite(sum_sq) && out[0] == 0.0f ? 0 : 1;
}
