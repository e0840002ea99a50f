// hush tests — synthetic frames for coherent noise: screen-space motions with exact
// per-pixel depth, backward and forward velocity and object ids (hush::frame), cheap
// enough for thousands of frames.
//
// Every scene is a disc (or a half plane) moving on a static background:
//  - translate: the left half moves by (vx, vy) pixels per frame;
//  - rotate:    a disc of radius 0.45 min(W, H) about the image centre turns by `amount`
//               radians per frame;
//  - zoom:      the same disc is magnified by `amount` per frame about the centre
//               (amount > 1 zooms in, < 1 out);
//  - occluder:  a square (depth 1) slides right by `amount` pixels per frame over a static
//               background (depth 2): background pixels it uncovers are disocclusions;
//  - still:     nothing moves.
// Motion is the same in every frame, so one frame describes the whole sequence
// (except the occluder, whose position depends on the frame index).
#ifndef HUSH_TESTS_COHERENT_SCENES_HPP
#define HUSH_TESTS_COHERENT_SCENES_HPP

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "hush/hush.hpp"

namespace hush_test {

struct synthetic_frame {
  int width = 0, height = 0;
  std::vector<float> depth, velocity, forward;
  std::vector<std::uint32_t> ids;

  hush::frame view() const {
    const std::size_t w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
    hush::frame f;
    f.depth = {depth.data(), w, h};
    f.velocity = {reinterpret_cast<const hush::vec3*>(velocity.data()), w, h};
    f.forward_velocity = {reinterpret_cast<const hush::vec3*>(forward.data()), w, h};
    f.object_id = {ids.data(), w, h};
    return f;
  }
  std::size_t pixels() const { return depth.size(); }
};

// kind: "still", "translate" (amount = vx; vy = 0.61 vx), "rotate", "zoom", "occluder".
inline synthetic_frame make_synthetic(const std::string& kind, double amount, int width, int height,
                                      int frame_index = 0) {
  synthetic_frame f;
  f.width = width;
  f.height = height;
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  f.depth.assign(n, 2.0f);
  f.velocity.assign(3 * n, 0.0f);
  f.forward.assign(3 * n, 0.0f);
  f.ids.assign(n, 2u);
  const double cx = width / 2.0, cy = height / 2.0, r = 0.45 * std::min(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                            static_cast<std::size_t>(x);
      const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
      double bx = 0, by = 0, fx = 0, fy = 0;  // backward and forward motion
      bool moving = false;
      if (kind == "translate" && x < width / 2) {
        moving = true;
        bx = fx = amount;
        by = fy = 0.61 * amount;
      } else if (kind == "rotate" && dx * dx + dy * dy < r * r) {
        moving = true;  // p_prev = R(-a) (p - c) + c, p_next = R(a) (p - c) + c
        const double c = std::cos(amount), s = std::sin(amount);
        bx = dx - (c * dx + s * dy);
        by = dy - (-s * dx + c * dy);
        fx = (c * dx - s * dy) - dx;
        fy = (s * dx + c * dy) - dy;
      } else if (kind == "zoom" && dx * dx + dy * dy < r * r) {
        moving = true;  // p_prev = c + (p - c) / s, p_next = c + (p - c) s
        bx = dx - dx / amount;
        by = dy - dy / amount;
        fx = dx * amount - dx;
        fy = dy * amount - dy;
      } else if (kind == "occluder") {
        const double left = 8 + amount * frame_index, size = 0.4 * std::min(width, height);
        if (x + 0.5 >= left && x + 0.5 < left + size && y + 0.5 >= cy - size / 2 &&
            y + 0.5 < cy + size / 2) {
          moving = true;
          bx = fx = amount;
        }
      }
      if (moving) {
        f.ids[p] = 1u;
        f.depth[p] = 1.0f;
      }
      f.velocity[3 * p] = static_cast<float>(bx);
      f.velocity[3 * p + 1] = static_cast<float>(by);
      f.forward[3 * p] = static_cast<float>(fx);
      f.forward[3 * p + 1] = static_cast<float>(fy);
    }
  return f;
}

// Variance and sharpness (mean squared difference of horizontally and vertically
// adjacent pixels over the variance; 2 for white noise) of `values` over the pixels of
// object `id` whose (2 r + 1)^2 neighbourhood is all that object (r = 0: every pixel).
struct region_stats {
  double sum_sq = 0, count = 0, diff_sq = 0, pairs = 0;
  void add(const std::vector<float>& values, const synthetic_frame& f, std::uint32_t id, int r) {
    const int w = f.width, h = f.height;
    auto inside = [&](int x, int y) {
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= w || yy >= h || f.ids[std::size_t(yy) * w + xx] != id)
            return false;
        }
      return true;
    };
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t p = std::size_t(y) * w + x;
        if (f.ids[p] != id || !inside(x, y)) continue;
        sum_sq += double(values[p]) * values[p];
        count += 1;
        if (x + 1 < w && f.ids[p + 1] == id) {
          const double d = double(values[p + 1]) - values[p];
          diff_sq += d * d;
          pairs += 1;
        }
        if (y + 1 < h && f.ids[p + w] == id) {
          const double d = double(values[p + w]) - values[p];
          diff_sq += d * d;
          pairs += 1;
        }
      }
  }
  double variance() const { return sum_sq / count; }  // the noise has mean 0
  double sharpness() const { return diff_sq / pairs / variance(); }
};

}  // namespace hush_test

#endif  // HUSH_TESTS_COHERENT_SCENES_HPP
