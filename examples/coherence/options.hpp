// hush — temporal-coherence metrics: the parameters every metric reads, with their defaults.
//
// Every threshold of docs/coherence.md is a member here, defined once; the CLI and the tests
// use these defaults unless they say otherwise.
#ifndef HUSH_COHERENCE_OPTIONS_HPP
#define HUSH_COHERENCE_OPTIONS_HPP

#include <cstddef>

namespace hush_tools {
namespace coherence {

struct options {
  // Reprojection (motion coherence, continuity): the previous frame's depth at the reprojected
  // position must be within depth_epsilon * (depth - dz) of depth - dz (relative, so the test
  // is scale free). 2% accepts bilinear interpolation of depth across one pixel of a plane
  // tilted up to ~60 degrees at typical depths, and rejects a jump to a surface 2% farther.
  double depth_epsilon = 0.02;
  // A pair of frames with fewer compared pixels has no coherence value (NaN, with a reason).
  std::size_t min_pixels = 64;
  // Popping: a pixel pops when its normalised change differs from the mean change of its
  // compared 4-neighbours by more than this many spatial standard deviations.
  double popping_threshold = 1.0;
  // Flatness: square analysis window (pixels, a power of two is fastest) and its stride.
  int window = 32;
  int window_stride = 16;
  // Flatness: windows of each object are split into this many depth quantile bins.
  int depth_bins = 3;
  // Flatness: a region (object, depth bin) needs this many windows to be measured.
  std::size_t min_windows = 4;
};

// Resolution of the change histogram (continuity percentiles): bins of 1 / kChangeBinsPerSigma
// spatial standard deviations up to kChangeHistogramSigmas; larger changes share the last bin.
constexpr int kChangeBinsPerSigma = 256;
constexpr int kChangeHistogramSigmas = 32;

// Motion following F is NaN when (1 - C) + (1 - S) is below this: nothing measurably moved
// (double rounding of the correlations is ~1e-15; 1e-9 leaves a wide guard).
constexpr double kFollowingMinLoss = 1e-9;

// Validates `o`; throws hush::invalid_argument naming the member and its valid range.
void validate(const options& o);

}  // namespace coherence
}  // namespace hush_tools

#endif  // HUSH_COHERENCE_OPTIONS_HPP
