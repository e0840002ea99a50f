// hush — temporal-coherence metrics: flatness, the stationarity of the screen-space spectrum.
//
// Bénard et al. 2010 sec. 1: flatness is "the ability to convey the 2D aspect" of a pattern:
// its features keep one size, distribution and contrast on screen whatever the depth and the
// surface. A texture-mapped pattern shrinks with depth (perspective), a screen-space pattern
// does not. Their conclusion proposes "statistical texture measures to quantify flatness".
//
// Measure, per frame (definitions in docs/coherence.md):
//  1. Analysis windows: window x window squares on a grid of step window_stride, kept when all
//     their pixels are covered by one object (silhouettes would add the edge's spectrum).
//  2. Regions: each object's windows, sorted by mean depth, split into quantile bins of
//     (nearly) equal counts: depth_bins of them, or fewer so that each holds at least
//     min_windows windows; an object with fewer than min_windows windows has no region.
//  3. Per window: values minus the window's mean, times a separable Hann window w, 2D FFT
//     (Eigen), power P(k) = |F(k)|^2 with k the signed frequency in cycles per pixel. Per
//     region, with P summed over its windows: its RMS radial frequency
//       f = sqrt( sum |k|^2 P(k) / sum P(k)  -  m_w ),
//     m_w the same moment of the window's own spectrum |W|^2 (the expected windowed spectrum
//     is the true one convolved with |W|^2, and second moments add under convolution, so f
//     estimates the noise's RMS frequency free of the window's blur); its local variance:
//     the mean over its windows of the (unwindowed) variance.
//  4. Spread across the regions: coefficient of variation (population std / mean) and
//     max / min ratio of f and of the local variance. Ideal (flat): CV 0, ratio 1.
//  5. Over the sequence: the mean of the frames' spreads, and the pooled spread over every
//     region of every frame (a zoom keeps each frame flat but changes the feature size over
//     time; the pooled spread sees that).
#ifndef HUSH_COHERENCE_FLATNESS_HPP
#define HUSH_COHERENCE_FLATNESS_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "coherence/options.hpp"
#include "coherence/temporal.hpp"
#include "scene/gbuffer.hpp"

namespace hush_tools {
namespace coherence {

struct flatness_region {
  std::uint32_t object = 0;
  int depth_bin = 0;  // 0 = nearest
  std::size_t windows = 0;
  double mean_depth = 0;  // mean of the windows' mean depths (world units)
  double frequency = 0;   // RMS radial frequency f, cycles per pixel, 0 ... 0.71
  double variance = 0;    // noise units squared
};

struct flatness_frame {
  int frame = 0;
  std::vector<flatness_region> regions;
  std::size_t windows = 0;                       // windows kept (inside one object)
  std::size_t dropped_objects = 0;               // objects with fewer than min_windows windows
  double frequency_cv = 0, frequency_ratio = 0;  // NaN with `reason` when < 2 regions
  double variance_cv = 0, variance_ratio = 0;
  std::string reason;
};

struct flatness_metrics {
  std::vector<flatness_frame> frames;
  // Means over the frames that have values, and the worst (largest) frame.
  double frequency_cv = 0, frequency_ratio = 0, variance_cv = 0, variance_ratio = 0;
  double frequency_cv_max = 0, variance_cv_max = 0;
  // Spread over every region of every frame that has values.
  double pooled_frequency_cv = 0, pooled_frequency_ratio = 0;
  double pooled_variance_cv = 0, pooled_variance_ratio = 0;
  std::size_t frames_without_value = 0;
  std::string reason;  // set (aggregates NaN) when no frame has a value
};

// Flatness of every frame of the sequence (validated as in measure_temporal; N >= 1).
// Throws hush::invalid_argument on invalid options or sequences. Deterministic; the FFT
// plan and buffers are made once and reused for every window.
flatness_metrics measure_flatness(const std::vector<noise_frame>& frames,
                                  const std::vector<scene::gbuffer>& gbuffers,
                                  const options& o = {});

}  // namespace coherence
}  // namespace hush_tools

#endif  // HUSH_COHERENCE_FLATNESS_HPP
