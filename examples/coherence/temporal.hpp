// hush — temporal-coherence metrics: motion coherence and temporal continuity of a sequence.
//
// Bénard et al. 2010 (NPR Gabor noise, sec. 1 and Table 1) name three goals: flatness,
// coherent motion and temporal continuity, judged there by a user study; their conclusion
// names "optical flow to quantify motion coherence and temporal continuity" as future work.
// These are those measures, with the renderer's exact motion (G-buffer velocity) in place of
// optical flow. Definitions, units and ideal values: docs/coherence.md.
//
// For frames i = 1 ... N-1 and every pixel p visible in both i-1 and i (reprojection.hpp):
//   m(p)  = n_{i-1}(p - v(p)), bilinear        (motion-compensated previous noise)
//   C_i   = Pearson correlation of n_i(p) and m(p) over those pixels   (motion coherence)
//   S_i   = the same with n_{i-1}(p), no motion compensation            (screen coherence)
//   F_i   = (C_i - S_i) / ((1 - C_i) + (1 - S_i))                        (motion following)
//   s_i   = standard deviation of n_i over all covered pixels of frame i
//   D(p)  = (n_i(p) - m(p)) / s_i                               (normalised change)
//   pop   = |D(p) - mean of D over p's visible 4-neighbours| > popping_threshold, for pixels
//           with at least 2 visible 4-neighbours                 (isolated jump)
#ifndef HUSH_COHERENCE_TEMPORAL_HPP
#define HUSH_COHERENCE_TEMPORAL_HPP

#include <cstddef>
#include <string>
#include <vector>

#include "coherence/options.hpp"
#include "scene/gbuffer.hpp"

namespace hush_tools {
namespace coherence {

// One noise frame: gbuffer.width * gbuffer.height values, row-major, row 0 at the top (the
// G-buffer's layout). Values at background pixels are ignored.
using noise_frame = std::vector<float>;

// Frame pair (i-1, i).
struct pair_metrics {
  int frame = 0;                // i
  double coherence = 0;         // C_i in [-1, 1]; NaN when `reason` is set
  double screen_coherence = 0;  // S_i in [-1, 1]; NaN also when frame i-1 is constant there
  double following = 0;         // F_i in [-1, 1]; NaN also when C_i = S_i = 1 (no motion)
  std::size_t covered = 0;      // pixels covered in frame i
  std::size_t compared = 0;     // of those, visible in both frames
  std::size_t offscreen = 0;    // excluded: reprojection leaves the image
  std::size_t disoccluded = 0;  // excluded: another surface or depth mismatch
  double sigma = 0;             // s_i
  std::string reason;           // why coherence is NaN ("" when it is not)
};

struct temporal_metrics {
  std::vector<pair_metrics> pairs;  // frames 1 ... N-1
  // Motion coherence over the pairs that have one (ideal 1; independent frames 0).
  double coherence_mean = 0, coherence_min = 0;
  // Mean S_i over the same pairs (NaN if any is NaN). Not a goal in itself: it tells whether
  // the noise follows the surfaces (C > S, texture mapping) or stays on the screen (C < S,
  // shower door: S = 1), independently of how fast the scene moves.
  double screen_coherence_mean = 0;
  // Motion following, mean F_i over the pairs that have one: +1 when the noise moves exactly
  // with the surfaces (C = 1 < S), -1 when it stays exactly on the screen (S = 1 > C), ~0
  // for independent frames (C ~ S ~ 0). Scale free: C and S both approach 1 as the motion
  // per frame shrinks, F does not. Ideal 1.
  double following_mean = 0;
  std::size_t pairs_without_following = 0;
  std::size_t pairs_without_coherence = 0;
  // Continuity: |D| over every compared pixel of every pair (ideal 0; independent Gaussian
  // frames moved by whole pixels: mean 2 / sqrt(pi) = 1.128, p50 0.954, p95 2.772, p99 3.643,
  // p99.9 4.654; sub-pixel motion averages the previous frame and lowers these).
  // Percentiles come from a histogram with bins of 1 / kChangeBinsPerSigma (error <= half a
  // bin); changes beyond kChangeHistogramSigmas count in the last bin.
  std::size_t changes = 0;
  double change_mean = 0;
  double change_p50 = 0, change_p95 = 0, change_p99 = 0, change_p999 = 0;
  // Popping: fraction of the pixels with >= 2 visible 4-neighbours whose change is an isolated
  // jump (ideal 0; independent frames about 0.5, see docs/coherence.md).
  std::size_t popping_candidates = 0;
  double popping = 0;
  std::string reason;  // set (and every aggregate NaN) when no pair could be measured
};

// Motion coherence and continuity of `frames` (N >= 2) over their G-buffers (same N, same
// size, each G-buffer's depth, velocity and object_id sized for its width * height). Throws
// hush::invalid_argument on mismatched sizes, invalid options or a non-finite noise value at
// a covered pixel. Deterministic; O(N * pixels) time, one pixel-sized buffer.
temporal_metrics measure_temporal(const std::vector<noise_frame>& frames,
                                  const std::vector<scene::gbuffer>& gbuffers,
                                  const options& o = {});

// Checks that `frames` and `gbuffers` describe one sequence (sizes as above, N >= 1); throws
// hush::invalid_argument naming the frame and channel that do not fit.
void validate_sequence(const std::vector<noise_frame>& frames,
                       const std::vector<scene::gbuffer>& gbuffers);

}  // namespace coherence
}  // namespace hush_tools

#endif  // HUSH_COHERENCE_TEMPORAL_HPP
