#include <cmath>
#include <cstdio>
#include <hush/hush.hpp>
#include <vector>

// Coherent noise on a 320 x 240 G-buffer: a plane at depth 4 sliding right by 0.3 pixels per
// frame. A renderer passes views of its own depth, velocity and object-id buffers.
int main() {
  const std::size_t w = 320, h = 240, n = w * h;
  std::vector<float> depth(n, 4.0f), velocity(3 * n, 0.0f), out(n);
  std::vector<std::uint32_t> ids(n, 1u);
  for (std::size_t p = 0; p < n; ++p) velocity[3 * p] = 0.3f;  // dx, dy (pixels), dz
  hush::frame f;
  f.depth = {depth.data(), w, h};
  f.velocity = {reinterpret_cast<const hush::vec3*>(velocity.data()), w, h};
  f.object_id = {ids.data(), w, h};

  hush::coherent_params prm;  // alpha 0.98, stationary filter, white input, 1 channel
  hush::coherent_stream stream{prm};
  for (int frame = 0; frame < 100; ++frame)
    stream.advance(hush::exec::scalar, f, hush::image_view<float>{out.data(), w, h});

  double sum_sq = 0;
  for (float v : out) sum_sq += double(v) * v;
  std::printf("frame %u: standard deviation %.3f (1 on still and moving surfaces alike)\n",
              stream.frame_index() - 1, std::sqrt(sum_sq / double(n)));
}
