// hush — anisotropic noise experiments: the paper's figures and the measurements behind
// docs/anisotropic.md (Goldberg, Zwicker & Durand 2008, figs. 2/3, 6, 8, 9, 13), shared by
// `hush gallery`, `hush bench` and the tests (library hush_aniso_figures). Example/test
// infrastructure, not a core header.
#ifndef HUSH_ANISO_FIGURES_HPP
#define HUSH_ANISO_FIGURES_HPP

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hush/hush.hpp"

namespace hush_tools::aniso {

// A float image, row-major, row 0 at the top.
struct image {
  std::size_t width = 0, height = 0;
  std::vector<float> v;
  image() = default;
  image(std::size_t w, std::size_t h, float fill = 0.0f) : width(w), height(h), v(w * h, fill) {}
  float& at(std::size_t x, std::size_t y) { return v[y * width + x]; }
  float at(std::size_t x, std::size_t y) const { return v[y * width + x]; }
};

// ---- Figure 8: resampling a high-frequency test image under an affine map.

// A periodic n x n test image (n a power of two): `cosines` cosines with integer wave
// vectors of 1/16 ... 0.45 cycles per texel in every direction, random phases (hush::rng),
// total variance 1. The map takes output pixel centre (x + 1/2, y + 1/2) to texture
// position A (x + 1/2, y + 1/2) + (c0, c1) in texels; A shears and scales non-uniformly.
struct resampling_setup {
  std::size_t texture = 128;  // n
  std::size_t output = 128;   // output pixels per side
  double a00 = 2.0, a01 = 1.5, a10 = 0.0, a11 = 1.1;
  double c0 = 3.0, c1 = 5.0;
  int cosines = 96;
  int scales = 5;  // of the bank: centres 1/4, 1/8, ... cycles per texel
  std::uint32_t seed = 1;
};
struct resampling_result {
  std::string name;  // "gaussian reference", "least squares, K = 8", ...
  double mse = 0;    // against the reference (0 for the reference itself)
  image result;
};
// The Gaussian reference (exact: the cosines' filtered sum, sigma = kPixelFilterSigma)
// and, with the texture decomposed by steerable banks (residuals included) and looked up
// bilinearly: least squares with K = 8 and 4, the centre heuristic with K = 4 and 8, the
// three-point rule with K = 4, and plain bilinear lookups of the texture.
std::vector<resampling_result> figure8(const resampling_setup& setup = {});

// ---- Distortion compensation (figs. 4-6): the local spectrum in surface space.

// A noise on a surface, seen in local surface coordinates around a window centre.
using surface_noise = std::function<float(double s, double t)>;
// The power-weighted mean radial frequency (cycles per surface unit) of `noise` over a
// window of `size` x `size` surface units centred at (s0, t0), from a Hann-windowed FFT of
// n x n samples (n a power of two).
double radial_frequency(const surface_noise& noise, double s0, double t0, double size,
                        std::size_t n = 64);

struct distortion_result {
  std::string surface;
  double target = 0;  // the compensated noise's octave-0 frequency, cycles per surface unit
  // Over the windows: mean and coefficient of variation (std / mean) of the radial
  // frequency, each window's the mean over 4 seeds.
  double mean_none = 0, cv_none = 0;      // no compensation (texture-space noise)
  double mean_centre = 0, cv_centre = 0;  // the heuristic (centre rule)
  double mean_lsq = 0, cv_lsq = 0;        // least squares
  std::size_t windows = 0;
};
// The unit square of texture mapped onto a trapezoid (bottom width 2, top 0.5, height 1)
// as an n x n grid of triangles, T per triangle from its vertices; windows across it.
distortion_result trapezoid_distortion(std::uint32_t seed = 3);
// A sphere of radius 1 with the standard UV map (longitude / 2 pi, colatitude / pi),
// 64 x 32 quads as examples/scene's make_sphere; windows from 20 to 160 degrees colatitude.
distortion_result sphere_distortion(std::uint32_t seed = 4);
// The `walkthrough` scene's ground plane: 200 x 200 units, planar uv scaled by 50 / 200
// (examples/scene/scene.cpp): one T everywhere, so both stay uniform.
distortion_result ground_plane_distortion(std::uint32_t seed = 5);

// Figure 6: two octaves of fbm on the trapezoid, `width` x `height` pixels of surface
// space (background 0): no compensation, least squares, centre heuristic.
std::vector<image> figure6(std::size_t width = 384, std::size_t height = 192);

// ---- Figure 9 and the benchmark: a receding plane.

// A camera at height 1 over the plane y = 0, pitched down 0.5 rad, vertical field of view
// 0.9 rad: every pixel of a width x height image sees the plane, out to about 20 units.
// Texture coordinates are the plane's (x, z) in world units times `scale`.
struct receding_plane {
  std::size_t width = 0, height = 0;
  std::vector<hush::vec2> positions;           // per pixel, row-major
  std::vector<hush::footprint<2>> footprints;  // from the exact screen-to-plane Jacobian
  // The texture position seen at screen point (x, y) (pixel units, y down).
  hush::dvec2 at(double x, double y) const;
  double scale = 1;
};
receding_plane make_receding_plane(std::size_t width, std::size_t height, double scale = 1.0);

// The Gaussian (sigma 1/2 pixel) of the unfiltered noise over 9 x 9 point samples per
// pixel through the exact perspective map, at the given pixels (indices y * width + x):
// the reference filtered noise is compared with (double reference evaluation).
std::vector<double> supersampled(const hush::anisotropic& noise, const receding_plane& plane,
                                 const std::vector<std::size_t>& pixels);

// Figure 9: two octaves of fbm on the receding plane with K = 4 and K = 8 (centre
// heuristic), the same noises unfiltered, and their references: each pixel's Gaussian
// (sigma 1/2 pixel) over 9 x 9 point samples of the unfiltered noise through the exact
// perspective map. RMS errors against the reference of the same noise.
struct receding_result {
  image filtered4, filtered8, unfiltered4, reference4, reference8;
  double rms4 = 0, rms8 = 0, rms_unfiltered4 = 0, rms_unfiltered8 = 0;
};
receding_result figure9(std::size_t width = 512, std::size_t height = 256);

// ---- Figure 13: noise steered by an orientation field (targets per sample).

// Features stretched `stretch` times along the field direction theta(x, y): the vortex
// around the image centre (theta = angle + pi / 2), via surface maps A = R diag(s, 1) R^T.
image figure13(std::size_t size = 384, double stretch = 4.0);

// ---- Figures 2 and 3: the subbands of one scale and their isotropic sum.

// The tile's K orientation images (size x size texels) and their sum.
std::vector<image> figure2(int orientations = 4, int size = 256, std::uint32_t seed = 7);

}  // namespace hush_tools::aniso

#endif  // HUSH_ANISO_FIGURES_HPP
