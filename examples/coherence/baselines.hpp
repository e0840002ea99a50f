// hush — temporal-coherence metrics: the calibration baselines of Bénard et al. 2010, Table 1.
//
// Three ways to put noise on an animated scene, whose places in Table 1 the metrics must
// reproduce (tests/coherence):
//  - white:       independent uniform values in [-1, 1) per pixel and frame (hush::rng, stream
//                 = frame index): neither coherent nor continuous (the worst case).
//  - shower_door: one 2D Perlin image in screen space, the same in every frame: perfectly flat,
//                 continuous in screen space, but it does not follow the motion ("shower door",
//                 Meier 1996; Bénard et al. sec. 1).
//  - texture:     3D Perlin of the object-space position (solid texturing, so UV seams do not
//                 matter): attached to the surfaces, so coherent, but it shrinks with depth and
//                 follows perspective, so not flat. Where a lattice cell covers fewer than 2
//                 pixels the noise fades out (frequency clamping, the procedural mipmap):
//                 unfiltered, distant and grazing surfaces alias into flickering noise.
// Background pixels (object_id 0) are 0 in every baseline.
#ifndef HUSH_COHERENCE_BASELINES_HPP
#define HUSH_COHERENCE_BASELINES_HPP

#include <cstdint>
#include <string>
#include <vector>

#include "coherence/temporal.hpp"
#include "scene/gbuffer.hpp"

namespace hush_tools {
namespace coherence {

enum class baseline_kind { white, shower_door, texture };

struct baseline_options {
  std::uint32_t seed = 1;
  // Perlin lattice spacing on screen, in pixels: shower_door's lattice cell is this many
  // pixels; texture's object-space scale is chosen so that in the first frame showing any
  // surface the median screen footprint of one lattice cell is this many pixels (one scale
  // for every object, as a texture authored in object units would be). Range 1 ... 4096.
  double feature_pixels = 8;
  // texture: fade the noise out linearly from 2 to 1 pixels per lattice cell (the cell's
  // screen size from the object-space distance to the neighbouring pixels). Off: aliasing.
  bool antialias = true;
};

// "white", "shower-door", "texture"; and back (throws hush::invalid_argument naming `kind`).
const char* baseline_name(baseline_kind kind);
baseline_kind parse_baseline(const std::string& name);

// The baseline's noise frames for `gbuffers` (one per G-buffer, same size; the G-buffers'
// object_id, and for texture their position, must be sized for width * height). Throws
// hush::invalid_argument on invalid options or G-buffers; texture also when no frame has two
// horizontally adjacent pixels of one object at distinct positions (no scale to calibrate).
std::vector<noise_frame> make_baseline(baseline_kind kind,
                                       const std::vector<scene::gbuffer>& gbuffers,
                                       const baseline_options& o = {});

}  // namespace coherence
}  // namespace hush_tools

#endif  // HUSH_COHERENCE_BASELINES_HPP
