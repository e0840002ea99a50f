// hush — temporal-coherence metrics: calibration baselines (see baselines.hpp).
#include "coherence/baselines.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "hush/core/error.hpp"
#include "hush/core/rng.hpp"
#include "hush/exec.hpp"
#include "hush/perlin.hpp"

namespace hush_tools {
namespace coherence {
namespace {

constexpr const char* kWhere = "hush_tools::coherence::make_baseline";

void check_size(std::size_t got, std::size_t want, std::size_t frame, const char* channel) {
  if (got != want)
    throw hush::invalid_argument(std::string(kWhere) + ": gbuffer " + std::to_string(frame) +
                                 " channel " + channel + " has " + std::to_string(got) +
                                 " values; expected " + std::to_string(want));
}

// Object-space length per screen pixel: the median distance between the positions of
// horizontally adjacent pixels of one object, in the first frame that has such pairs.
double object_units_per_pixel(const std::vector<scene::gbuffer>& gbuffers) {
  std::vector<double> d;
  for (const scene::gbuffer& g : gbuffers) {
    const std::size_t w = static_cast<std::size_t>(g.width);
    for (std::size_t p = 0; p + 1 < g.pixels(); ++p) {
      if ((p + 1) % w == 0 || !g.covered(p) || g.object_id[p + 1] != g.object_id[p]) continue;
      const double dx = g.position[3 * p + 3] - g.position[3 * p];
      const double dy = g.position[3 * p + 4] - g.position[3 * p + 1];
      const double dz = g.position[3 * p + 5] - g.position[3 * p + 2];
      const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
      if (len > 0 && std::isfinite(len)) d.push_back(len);
    }
    if (!d.empty()) break;
  }
  if (d.empty())
    throw hush::invalid_argument(std::string(kWhere) +
                                 ": texture needs two adjacent pixels of one object at distinct "
                                 "object-space positions in some frame; none found");
  auto mid = d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2);
  std::nth_element(d.begin(), mid, d.end());
  return *mid;
}

// Object-space distance from pixel p to its neighbour at offset (dx, dy) on the same object
// (the forward neighbour, else the backward one); 0 when neither is on p's object.
double neighbour_distance(const scene::gbuffer& g, std::size_t p, int dx, int dy) {
  const int w = g.width, h = g.height;
  const int x = static_cast<int>(p % static_cast<std::size_t>(w));
  const int y = static_cast<int>(p / static_cast<std::size_t>(w));
  for (int sign : {1, -1}) {
    const int nx = x + sign * dx, ny = y + sign * dy;
    if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
    const std::size_t q =
        static_cast<std::size_t>(ny) * static_cast<std::size_t>(w) + static_cast<std::size_t>(nx);
    if (g.object_id[q] != g.object_id[p]) continue;
    double d2 = 0;
    for (std::size_t c = 0; c < 3; ++c) {
      const double d = static_cast<double>(g.position[3 * q + c]) - g.position[3 * p + c];
      d2 += d * d;
    }
    return std::sqrt(d2);
  }
  return 0;
}

// Frequency clamping (Norton, Rockwood & Skolmoski 1982), the procedural counterpart of
// mipmapping: the noise fades out where one lattice cell covers fewer than 2 pixels (its
// highest frequencies would alias) and is gone at 1 pixel per cell. Linear in the cell's
// screen size c = 1 / (scale * object units per pixel): weight clamp(c - 1, 0, 1).
float clamp_weight(const scene::gbuffer& g, std::size_t p, double scale) {
  const double footprint =
      std::max(neighbour_distance(g, p, 1, 0), neighbour_distance(g, p, 0, 1)) * scale;
  if (!(footprint > 0)) return 1.0f;  // no neighbour on this object: nothing to measure
  return static_cast<float>(std::clamp(1 / footprint - 1, 0.0, 1.0));
}

}  // namespace

const char* baseline_name(baseline_kind kind) {
  switch (kind) {
    case baseline_kind::white:
      return "white";
    case baseline_kind::shower_door:
      return "shower-door";
    case baseline_kind::texture:
      return "texture";
  }
  return "?";
}

baseline_kind parse_baseline(const std::string& name) {
  for (baseline_kind k : {baseline_kind::white, baseline_kind::shower_door, baseline_kind::texture})
    if (name == baseline_name(k)) return k;
  throw hush::invalid_argument("hush_tools::coherence: kind '" + name +
                               "' is invalid; valid: white, shower-door, texture");
}

std::vector<noise_frame> make_baseline(baseline_kind kind,
                                       const std::vector<scene::gbuffer>& gbuffers,
                                       const baseline_options& o) {
  hush::detail::require_in_range(kWhere, "feature_pixels", o.feature_pixels, 1.0, 4096.0,
                                 "1 ... 4096");
  for (std::size_t i = 0; i < gbuffers.size(); ++i) {
    const scene::gbuffer& g = gbuffers[i];
    if (g.width <= 0 || g.height <= 0)
      throw hush::invalid_argument(std::string(kWhere) + ": gbuffer " + std::to_string(i) +
                                   " has no pixels");
    check_size(g.object_id.size(), g.pixels(), i, "object_id");
    if (kind == baseline_kind::texture)
      check_size(g.position.size(), 3 * g.pixels(), i, "position");
  }
  std::vector<noise_frame> frames;
  frames.reserve(gbuffers.size());

  if (kind == baseline_kind::white) {
    for (std::size_t i = 0; i < gbuffers.size(); ++i) {
      const scene::gbuffer& g = gbuffers[i];
      hush::rng r(o.seed, static_cast<std::uint32_t>(i));
      noise_frame f(g.pixels());
      for (std::size_t p = 0; p < g.pixels(); ++p) {
        const float u = r.uniform(-1.0f, 1.0f);  // drawn for every pixel: frames align
        f[p] = g.covered(p) ? u : 0.0f;
      }
      frames.push_back(std::move(f));
    }
    return frames;
  }

  if (kind == baseline_kind::shower_door) {
    const hush::perlin<2> noise(o.seed);
    std::map<std::pair<int, int>, noise_frame> screen;  // one image per size (usually one)
    for (const scene::gbuffer& g : gbuffers) {
      noise_frame& image = screen[{g.width, g.height}];
      if (image.empty()) {
        image.resize(g.pixels());
        hush::grid<2> grid;
        // Pixel centres (x + 0.5, y + 0.5), feature_pixels pixels per lattice cell.
        grid.origin = {0.5 / o.feature_pixels, 0.5 / o.feature_pixels};
        grid.step = {1 / o.feature_pixels, 1 / o.feature_pixels};
        grid.size = {static_cast<std::size_t>(g.width), static_cast<std::size_t>(g.height)};
        hush::evaluate_grid(noise, hush::exec::scalar, grid, hush::span<float>(image));
      }
      noise_frame f(image);
      for (std::size_t p = 0; p < g.pixels(); ++p)
        if (!g.covered(p)) f[p] = 0;
      frames.push_back(std::move(f));
    }
    return frames;
  }

  // texture: one Perlin per object (seed + object id) so objects sharing object-space
  // coordinates (instances) still differ.
  const double scale = 1 / (o.feature_pixels * object_units_per_pixel(gbuffers));
  std::map<std::uint32_t, hush::perlin<3>> noises;
  for (const scene::gbuffer& g : gbuffers) {
    noise_frame f(g.pixels(), 0.0f);
    for (std::size_t p = 0; p < g.pixels(); ++p) {
      const std::uint32_t id = g.object_id[p];
      if (id == 0) continue;
      auto it = noises.find(id);
      if (it == noises.end()) it = noises.emplace(id, hush::perlin<3>(o.seed + id)).first;
      const hush::vec3 x{static_cast<float>(g.position[3 * p] * scale),
                         static_cast<float>(g.position[3 * p + 1] * scale),
                         static_cast<float>(g.position[3 * p + 2] * scale)};
      f[p] = it->second(x) * (o.antialias ? clamp_weight(g, p, scale) : 1.0f);
    }
    frames.push_back(std::move(f));
  }
  return frames;
}

}  // namespace coherence
}  // namespace hush_tools
