// hush — temporal-coherence metrics: motion coherence and continuity (see temporal.hpp).
#include "coherence/temporal.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "coherence/reprojection.hpp"
#include "hush/core/error.hpp"

namespace hush_tools {
namespace coherence {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

[[noreturn]] void throw_sequence(const std::string& what) {
  throw hush::invalid_argument("hush_tools::coherence: " + what);
}

void check_channel(std::size_t got, std::size_t want, std::size_t frame, const char* name) {
  if (got != want)
    throw_sequence("gbuffer " + std::to_string(frame) + " channel " + name + " has " +
                   std::to_string(got) + " values; expected " + std::to_string(want));
}

// The value at `fraction` of the sorted |D| values, from the histogram: the centre of the bin
// holding the rank ceil(fraction * n) value.
double percentile(const std::vector<std::uint64_t>& histogram, std::size_t n, double fraction) {
  const double rank = std::ceil(fraction * static_cast<double>(n));
  double seen = 0;
  for (std::size_t b = 0; b < histogram.size(); ++b) {
    seen += static_cast<double>(histogram[b]);
    if (seen >= rank) return (static_cast<double>(b) + 0.5) / kChangeBinsPerSigma;
  }
  return static_cast<double>(histogram.size()) / kChangeBinsPerSigma;
}

// Mean and standard deviation of `values` over the covered pixels of `g` (two passes).
void covered_stats(const noise_frame& values, const scene::gbuffer& g, double& mean, double& sigma,
                   std::size_t& count) {
  double sum = 0;
  count = 0;
  for (std::size_t p = 0; p < g.pixels(); ++p)
    if (g.covered(p)) {
      sum += values[p];
      ++count;
    }
  mean = count ? sum / static_cast<double>(count) : kNaN;
  double sq = 0;
  for (std::size_t p = 0; p < g.pixels(); ++p)
    if (g.covered(p)) sq += (values[p] - mean) * (values[p] - mean);
  sigma = count ? std::sqrt(sq / static_cast<double>(count)) : kNaN;
}

}  // namespace

void validate_sequence(const std::vector<noise_frame>& frames,
                       const std::vector<scene::gbuffer>& gbuffers) {
  if (frames.empty()) throw_sequence("no frames");
  if (frames.size() != gbuffers.size())
    throw_sequence(std::to_string(frames.size()) + " noise frames but " +
                   std::to_string(gbuffers.size()) + " gbuffers");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const scene::gbuffer& g = gbuffers[i];
    if (g.width <= 0 || g.height <= 0 || g.width != gbuffers[0].width ||
        g.height != gbuffers[0].height)
      throw_sequence("gbuffer " + std::to_string(i) + " is " + std::to_string(g.width) + "x" +
                     std::to_string(g.height) + "; every frame must have the first frame's " +
                     "positive size");
    const std::size_t n = g.pixels();
    check_channel(frames[i].size(), n, i, "noise");
    check_channel(g.depth.size(), n, i, "depth");
    check_channel(g.velocity.size(), 3 * n, i, "velocity");
    check_channel(g.object_id.size(), n, i, "object_id");
    for (std::size_t p = 0; p < n; ++p)
      if (g.covered(p) && !std::isfinite(frames[i][p]))
        throw_sequence("noise frame " + std::to_string(i) + " has a non-finite value at pixel (" +
                       std::to_string(p % static_cast<std::size_t>(g.width)) + ", " +
                       std::to_string(p / static_cast<std::size_t>(g.width)) + ")");
  }
}

temporal_metrics measure_temporal(const std::vector<noise_frame>& frames,
                                  const std::vector<scene::gbuffer>& gbuffers, const options& o) {
  validate(o);
  validate_sequence(frames, gbuffers);
  temporal_metrics t;
  if (frames.size() < 2) throw_sequence("motion needs at least 2 frames, got 1");

  const int w = gbuffers[0].width, h = gbuffers[0].height;
  const std::size_t n = gbuffers[0].pixels();
  std::vector<float> change(n);  // D(p), valid where `visible`
  std::vector<std::uint8_t> visible(n);
  std::vector<std::uint64_t> histogram(static_cast<std::size_t>(kChangeBinsPerSigma) *
                                       kChangeHistogramSigmas);
  double change_sum = 0, coherence_sum = 0, screen_sum = 0, following_sum = 0;
  std::size_t pops = 0, coherent_pairs = 0, screen_nan = 0, following_pairs = 0;
  t.coherence_min = kNaN;

  for (std::size_t i = 1; i < frames.size(); ++i) {
    const scene::gbuffer& prev = gbuffers[i - 1];
    const scene::gbuffer& cur = gbuffers[i];
    pair_metrics pm;
    pm.frame = static_cast<int>(i);
    double mean_cur = 0;
    covered_stats(frames[i], cur, mean_cur, pm.sigma, pm.covered);

    // Pass 1: visibility, the motion-compensated value and the correlation sums.
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, sz = 0, szz = 0, sxz = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t p =
            static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
        const reprojection r = reproject(prev, cur, x, y, o.depth_epsilon);
        visible[p] = r.status == visibility::visible;
        if (r.status == visibility::offscreen) ++pm.offscreen;
        if (r.status == visibility::disoccluded) ++pm.disoccluded;
        if (!visible[p]) continue;
        ++pm.compared;
        // Centred on frame i's mean so the one-pass sums do not cancel.
        const double a = frames[i][p] - mean_cur, b = sample(frames[i - 1].data(), r) - mean_cur;
        sx += a;
        sy += b;
        sxx += a * a;
        syy += b * b;
        sxy += a * b;
        const double z = frames[i - 1][p] - mean_cur;  // same pixel, no motion compensation
        sz += z;
        szz += z * z;
        sxz += a * z;
        change[p] = static_cast<float>((a - b) / pm.sigma);  // inf/NaN when sigma is 0
      }

    const double c = static_cast<double>(pm.compared);
    const double vx = sxx - sx * sx / c, vy = syy - sy * sy / c;
    if (pm.compared < o.min_pixels) {
      pm.reason = std::to_string(pm.compared) + " pixels visible in both frames (< min_pixels " +
                  std::to_string(o.min_pixels) + ")";
    } else if (!(pm.sigma > 0) || !(vx > 0) || !(vy > 0)) {
      pm.reason = "constant noise over the compared pixels (zero variance)";
    }
    if (!pm.reason.empty()) {
      pm.coherence = pm.screen_coherence = pm.following = kNaN;
      ++t.pairs_without_coherence;
      ++t.pairs_without_following;
      t.pairs.push_back(pm);
      continue;
    }
    pm.coherence = (sxy - sx * sy / c) / std::sqrt(vx * vy);
    const double vz = szz - sz * sz / c;
    pm.screen_coherence = vz > 0 ? (sxz - sx * sz / c) / std::sqrt(vx * vz) : kNaN;
    coherence_sum += pm.coherence;
    if (std::isnan(pm.screen_coherence)) {
      ++screen_nan;
    } else {
      screen_sum += pm.screen_coherence;
    }
    // F_i = (C - S) / ((1 - C) + (1 - S)); undefined when both are 1 (nothing moved, or
    // constant-in-time noise on a static scene): then NaN.
    const double loss = (1 - pm.coherence) + (1 - pm.screen_coherence);
    pm.following = loss > kFollowingMinLoss ? (pm.coherence - pm.screen_coherence) / loss : kNaN;
    if (std::isnan(pm.following)) {
      ++t.pairs_without_following;
    } else {
      following_sum += pm.following;
      ++following_pairs;
    }
    ++coherent_pairs;
    if (!(pm.coherence >= t.coherence_min)) t.coherence_min = pm.coherence;  // NaN start

    // Pass 2: the change distribution and isolated jumps (needs every D of the frame).
    const std::size_t last_bin = histogram.size() - 1;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t p =
            static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
        if (!visible[p]) continue;
        const double d = std::abs(static_cast<double>(change[p]));
        change_sum += d;
        ++t.changes;
        const double bin = std::floor(d * kChangeBinsPerSigma);
        ++histogram[bin < static_cast<double>(last_bin) ? static_cast<std::size_t>(bin) : last_bin];
        double neighbours = 0;
        int count = 0;
        auto add = [&](int nx, int ny) {
          if (nx < 0 || ny < 0 || nx >= w || ny >= h) return;
          const std::size_t q = static_cast<std::size_t>(ny) * static_cast<std::size_t>(w) +
                                static_cast<std::size_t>(nx);
          if (!visible[q]) return;
          neighbours += change[q];
          ++count;
        };
        add(x - 1, y);
        add(x + 1, y);
        add(x, y - 1);
        add(x, y + 1);
        if (count < 2) continue;
        ++t.popping_candidates;
        if (std::abs(change[p] - neighbours / count) > o.popping_threshold) ++pops;
      }
    t.pairs.push_back(pm);
  }

  if (coherent_pairs == 0) {
    t.reason = "no frame pair has a coherence value (see pairs[].reason)";
    t.coherence_mean = t.coherence_min = t.screen_coherence_mean = kNaN;
  } else {
    t.coherence_mean = coherence_sum / static_cast<double>(coherent_pairs);
    t.screen_coherence_mean = screen_nan ? kNaN : screen_sum / static_cast<double>(coherent_pairs);
  }
  t.following_mean = following_pairs ? following_sum / static_cast<double>(following_pairs) : kNaN;
  if (t.changes == 0) {
    t.change_mean = t.change_p50 = t.change_p95 = t.change_p99 = t.change_p999 = kNaN;
  } else {
    t.change_mean = change_sum / static_cast<double>(t.changes);
    t.change_p50 = percentile(histogram, t.changes, 0.5);
    t.change_p95 = percentile(histogram, t.changes, 0.95);
    t.change_p99 = percentile(histogram, t.changes, 0.99);
    t.change_p999 = percentile(histogram, t.changes, 0.999);
  }
  t.popping = t.popping_candidates
                  ? static_cast<double>(pops) / static_cast<double>(t.popping_candidates)
                  : kNaN;
  return t;
}

}  // namespace coherence
}  // namespace hush_tools
