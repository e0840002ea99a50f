// hush — the `hush` program: the gallery's coherent-noise entries (see gallery_coherent.hpp).
#include "gallery_coherent.hpp"

#if HUSH_CLI_HAVE_SCENE
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "hush/coherent.hpp"
#include "hush/exec.hpp"
#include "raster_cpu.hpp"
#include "scene.hpp"
#endif

namespace hush_cli {

#if HUSH_CLI_HAVE_SCENE
namespace {

namespace hs = hush_tools::scene;

constexpr std::size_t kW = 128, kH = 96;  // one panel
constexpr int kFrames = 32;               // animations: 32 frames, 8 cs each (12.5 fps)
constexpr int kDelay = 8;
constexpr int kScanlineFrames = 192;  // Fig. 6: rows of the scanline image
constexpr double kShown = 2.5;        // unit-variance noise shown over +-2.5
// Flat shading (Fig. 3): a light from the upper right, three quantized levels.
constexpr double kLight[3] = {0.4, 0.8, 0.45};
constexpr double kLevels[3] = {0.15, 0.5, 0.85};
// Animations keep the top 5 bits of each gray level (32 levels): the noise compresses to
// about half (GIF's LZW finds few repeats in noise), and the eye sees no difference.
constexpr std::uint8_t kLevelMask = 0xf8;

std::vector<hs::gbuffer> render_frames(const std::string& scene, int frames) {
  const hs::scene s = hs::make_scene(scene);
  std::vector<hs::gbuffer> g;
  g.reserve(static_cast<std::size_t>(frames));
  for (int i = 0; i < frames; ++i) g.push_back(hs::render_cpu(s, i, int(kW), int(kH)));
  return g;
}

// The noise the animations show: band-pass (Perlin cells of 4 pixels), as Kass & Pesare
// smooth their white noise for display.
hush::coherent_params shown_params(double alpha, int channels = 1) {
  hush::coherent_params p;
  p.alpha = alpha;
  p.seed = 5;
  p.input = hush::coherent_input::bandpass;
  p.channels = channels;
  return p;
}

// Causal coherent noise of every frame (channel planes of kW x kH, concatenated).
std::vector<std::vector<float>> causal(const std::vector<hs::gbuffer>& g,
                                       const hush::coherent_params& p) {
  hush::coherent_stream st(p);
  const std::size_t n = kW * kH, nc = static_cast<std::size_t>(p.channels);
  std::vector<std::vector<float>> out(g.size(), std::vector<float>(n * nc));
  for (std::size_t i = 0; i < g.size(); ++i) {
    std::vector<hush::image_view<float>> v;
    for (std::size_t c = 0; c < nc; ++c) v.emplace_back(out[i].data() + n * c, kW, kH);
    st.advance(hush::exec::simd, hs::as_frame(g[i]), hush::span<const hush::image_view<float>>(v));
  }
  return out;
}

std::vector<std::vector<float>> symmetric(const std::vector<hs::gbuffer>& g,
                                          const hush::coherent_params& p) {
  const std::size_t n = kW * kH;
  std::vector<std::vector<float>> out(g.size(), std::vector<float>(n));
  hush::coherent_sequence<float> io;
  io.frames = g.size();
  io.frame_at = [&](std::size_t i) { return hs::as_frame(g[i]); };
  io.write = [&](std::size_t i, hush::span<const hush::image_view<float>> r) {
    std::copy(r[0].data, r[0].data + n, out[i].begin());
  };
  hush::coherent_symmetric(hush::exec::simd, p, io);
  return out;
}

gray_image shown(const std::vector<float>& v, const hs::gbuffer& g) {
  return noise_on_surfaces(v, g, kShown);
}

// Quantized Lambert shading of the G-buffer's normals (white sky).
std::vector<float> flat_shading(const hs::gbuffer& g) {
  const double len =
      std::sqrt(kLight[0] * kLight[0] + kLight[1] * kLight[1] + kLight[2] * kLight[2]);
  std::vector<float> s(kW * kH, 1.0f);
  for (std::size_t p = 0; p < kW * kH; ++p) {
    if (!g.covered(p)) continue;
    double d = 0;
    for (int c = 0; c < 3; ++c) d += g.normal[3 * p + std::size_t(c)] * kLight[c] / len;
    const double lit = std::max(d, 0.0);
    s[p] = static_cast<float>(lit < 0.33 ? kLevels[0] : lit < 0.66 ? kLevels[1] : kLevels[2]);
  }
  return s;
}

gray_image grid2x2(const gray_image& a, const gray_image& b, const gray_image& c,
                   const gray_image& d) {
  gray_image top = side_by_side(a, b), bottom = side_by_side(c, d);
  gray_image img(top.width, top.height + bottom.height);
  std::copy(top.pixels.begin(), top.pixels.end(), img.pixels.begin());
  std::copy(bottom.pixels.begin(), bottom.pixels.end(),
            img.pixels.begin() + static_cast<std::ptrdiff_t>(top.pixels.size()));
  return img;
}

// The four noises of the paper's video, side by side: independent per frame (alpha 0),
// constant (frame 0 of it, kept), causal and time-symmetric coherent noise (alpha 0.98).
std::vector<gray_image> four_noises(const std::string& scene) {
  const std::vector<hs::gbuffer> g = render_frames(scene, kFrames);
  const auto white = causal(g, shown_params(0.0));
  const auto coherent = causal(g, shown_params(0.98));
  const auto both_ways = symmetric(g, shown_params(0.98));
  std::vector<gray_image> frames;
  for (std::size_t i = 0; i < g.size(); ++i)
    frames.push_back(grid2x2(shown(white[i], g[i]), shown(white[0], g[i]), shown(coherent[i], g[i]),
                             shown(both_ways[i], g[i])));
  for (gray_image& f : frames)
    for (std::uint8_t& v : f.pixels) v &= kLevelMask;
  return frames;
}

// Fig. 2: the scene, two consecutive frames of coherent noise, and their difference (shown
// over 4 of its standard deviations): the frames look unrelated, the difference shows the
// motion.
std::vector<gray_image> figure2() {
  const std::vector<hs::gbuffer> g = render_frames("rotate", 31);
  const auto noise = causal(g, shown_params(0.98));
  const std::vector<float>& a = noise[29];
  const std::vector<float>& b = noise[30];
  std::vector<float> diff(kW * kH);
  double sum_sq = 0, count = 0;
  for (std::size_t p = 0; p < diff.size(); ++p) {
    diff[p] = std::fabs(b[p] - a[p]);
    if (g[30].covered(p)) {
      sum_sq += double(diff[p]) * diff[p];
      count += 1;
    }
  }
  const double sd = std::sqrt(sum_sq / std::max(count, 1.0));
  gray_image d(kW, kH);
  for (std::size_t p = 0; p < diff.size(); ++p)
    d.pixels[p] = g[30].covered(p) ? to_gray(diff[p], 0, 4 * sd) : 0;
  return {
      side_by_side(side_by_side(to_gray_image(flat_shading(g[30]), kW, kH, 0, 1), shown(a, g[29])),
                   side_by_side(shown(b, g[30]), d))};
}

// Fig. 6: one scanline (the middle row) through time, time running down: the flat-shaded
// scene, causal coherent noise (it streaks along the motion, like a line-integral
// convolution of the velocity field), and independent per-frame noise.
std::vector<gray_image> figure6() {
  const std::vector<hs::gbuffer> g = render_frames("rotate", kScanlineFrames);
  const auto coherent = causal(g, shown_params(0.98));
  const auto white = causal(g, shown_params(0.0));
  gray_image shade(kW, std::size_t(kScanlineFrames)), c(kW, std::size_t(kScanlineFrames)),
      w(kW, std::size_t(kScanlineFrames));
  const std::size_t row = kH / 2;
  for (std::size_t i = 0; i < g.size(); ++i) {
    const std::vector<float> s = flat_shading(g[i]);
    for (std::size_t x = 0; x < kW; ++x) {
      const std::size_t p = row * kW + x;
      shade.at(x, i) = to_gray(s[p], 0, 1);
      c.at(x, i) = g[i].covered(p) ? to_gray(coherent[i][p], -kShown, kShown) : 0;
      w.at(x, i) = g[i].covered(p) ? to_gray(white[i][p], -kShown, kShown) : 0;
    }
  }
  return {side_by_side(side_by_side(shade, c), w)};
}

double bilinear(const std::vector<float>& img, double x, double y) {
  x = std::clamp(x, 0.0, double(kW - 1));
  y = std::clamp(y, 0.0, double(kH - 1));
  const std::size_t x0 = std::min(std::size_t(x), kW - 2), y0 = std::min(std::size_t(y), kH - 2);
  const double fx = x - double(x0), fy = y - double(y0);
  const auto at = [&](std::size_t xx, std::size_t yy) { return double(img[yy * kW + xx]); };
  return (1 - fx) * (1 - fy) * at(x0, y0) + fx * (1 - fy) * at(x0 + 1, y0) +
         (1 - fx) * fy * at(x0, y0 + 1) + fx * fy * at(x0 + 1, y0 + 1);
}

// 3 x 3 grey-level dilation (max) or erosion (min).
std::vector<float> morphology(const std::vector<float>& img, bool dilate) {
  std::vector<float> out(img.size());
  for (std::size_t y = 0; y < kH; ++y)
    for (std::size_t x = 0; x < kW; ++x) {
      float v = img[y * kW + x];
      for (std::size_t yy = y ? y - 1 : 0; yy <= std::min(y + 1, kH - 1); ++yy)
        for (std::size_t xx = x ? x - 1 : 0; xx <= std::min(x + 1, kW - 1); ++xx)
          v = dilate ? std::max(v, img[yy * kW + xx]) : std::min(v, img[yy * kW + xx]);
      out[y * kW + x] = v;
    }
  return out;
}

// Fig. 3(a): the flat-shaded rotate scene, plus smoothed coherent noise, dilated then eroded
// (a painterly texture), then warped in the image plane by two more channels of the noise.
std::vector<gray_image> figure3a() {
  const std::vector<hs::gbuffer> g = render_frames("rotate", kFrames);
  hush::coherent_params p = shown_params(0.98, 3);
  p.smoothing = 1.0;
  const auto noise = causal(g, p);
  const std::size_t n = kW * kH;
  std::vector<gray_image> frames;
  for (std::size_t i = 0; i < g.size(); ++i) {
    std::vector<float> s = flat_shading(g[i]);
    for (std::size_t q = 0; q < n; ++q) s[q] += 0.04f * noise[i][q];
    s = morphology(morphology(s, true), false);
    std::vector<float> warped(n);
    for (std::size_t y = 0; y < kH; ++y)
      for (std::size_t x = 0; x < kW; ++x) {
        const std::size_t q = y * kW + x;
        warped[q] = static_cast<float>(
            bilinear(s, double(x) + 0.8 * noise[i][n + q], double(y) + 0.8 * noise[i][2 * n + q]));
      }
    frames.push_back(to_gray_image(warped, kW, kH, 0, 1));
  }
  return frames;
}

// Fig. 3(b): object-ID boundaries drawn as dots displaced by two channels of coherent noise
// (read on the nearer side of the boundary, so the wiggle belongs to the front object).
std::vector<gray_image> figure3b() {
  const std::vector<hs::gbuffer> g = render_frames("rotate", kFrames);
  const auto noise = causal(g, shown_params(0.98, 2));
  const std::size_t n = kW * kH;
  std::vector<gray_image> frames;
  for (std::size_t i = 0; i < g.size(); ++i) {
    gray_image img(kW, kH);
    std::fill(img.pixels.begin(), img.pixels.end(), std::uint8_t{255});
    for (std::size_t y = 0; y + 1 < kH; ++y)
      for (std::size_t x = 0; x + 1 < kW; ++x) {
        const std::size_t p = y * kW + x;
        for (const std::size_t q : {p + 1, p + kW}) {
          if (g[i].object_id[p] == g[i].object_id[q]) continue;
          const std::size_t front = g[i].depth[p] <= g[i].depth[q] ? p : q;
          // A 2 x 2 dot at the displaced point: the dots of a boundary join into a line.
          const double px = double(x) + 0.5 + 1.5 * noise[i][front];
          const double py = double(y) + 0.5 + 1.5 * noise[i][n + front];
          for (double dy : {0.0, 1.0})
            for (double dx : {0.0, 1.0})
              if (px + dx >= 0 && py + dy >= 0 && px + dx < double(kW) && py + dy < double(kH))
                img.at(std::size_t(px + dx), std::size_t(py + dy)) = 0;
        }
      }
    frames.push_back(img);
  }
  return frames;
}

}  // namespace

gray_image noise_on_surfaces(const std::vector<float>& v, const hs::gbuffer& g, double range) {
  const std::size_t w = static_cast<std::size_t>(g.width), h = static_cast<std::size_t>(g.height);
  gray_image img(w, h);
  for (std::size_t p = 0; p < w * h; ++p)
    img.pixels[p] = g.covered(p) ? to_gray(v[p], -range, range) : 0;
  return img;
}

std::vector<gallery_item> coherent_gallery_items() {
  return {
      {"coherent_rotate.gif",
       "rotate scene, 32 frames: independent per-frame noise | constant (shower door) noise; "
       "causal | time-symmetric coherent noise (band-pass 4 px, alpha 0.98)",
       [] { return four_noises("rotate"); }, kDelay},
      {"coherent_walkthrough.gif",
       "walkthrough scene, the same four noises (top: independent, constant; bottom: causal, "
       "time-symmetric coherent)",
       [] { return four_noises("walkthrough"); }, kDelay},
      {"coherent_fig2.png",
       "Kass & Pesare Fig. 2: the rotate scene (flat shaded) | coherent noise, frame 29 | frame 30 "
       "| their difference",
       figure2},
      {"coherent_fig6.png",
       "Kass & Pesare Fig. 6: the middle row of the rotate scene through 192 frames (time down): "
       "flat shading | causal coherent noise | independent noise",
       figure6},
      {"coherent_fig3a.gif",
       "Kass & Pesare Fig. 3(a): the flat-shaded rotate scene + smoothed coherent noise, dilated "
       "and eroded, warped by two more noise channels",
       figure3a, kDelay},
      {"coherent_fig3b.gif",
       "Kass & Pesare Fig. 3(b): object-ID boundaries wiggled by two channels of coherent noise",
       figure3b, kDelay},
  };
}

#else
std::vector<gallery_item> coherent_gallery_items() { return {}; }
#endif

}  // namespace hush_cli
