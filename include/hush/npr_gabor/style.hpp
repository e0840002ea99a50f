// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Styles: turning unit-variance noise images into drawings (Benard, Lagae et
// al., "A dynamic noise primitive for coherent stylization", EGSR 2010,
// sec. 4, Figs. 2-3). Per-pixel functions of noise values (NPR Gabor noise,
// hush/npr_gabor.hpp, or any noise with mean 0 and variance 1) and of what a
// G-buffer gives (a tone from shading, a scene colour). Values are "paper":
// 1 = white paper, 0 = full ink.
//
//   hush::style::binary ink{0.5};                 // smooth-step width 0.5 sigma
//   double tone = hush::style::shading_tone(n, light, 0.1);  // N.L -> [0.1, 1]
//   double p = ink.paper(noise, tone);            // hatching (anisotropic noise)
//                                                 // or stippling (isotropic noise)
//   hush::style::crosshatch{0.5}.paper(n1, n2, tone);  // two orientations
//   hush::style::graphite{0.8, 0.6}.paper(n, n_fine, tone);
//   hush::style::watercolor{0.35}.colour(c, noise);    // overlay on scene colour
//   hush::style::projected_normal_field(frame, field, 1e-4);  // hatching direction
//   hush::style::curvature_field(frame, normals, field, 1e-3, 0.2, 1e-4);  // along curvature
//
// The thresholding (sec. 4, "binary styles"): the paper is white where the
// noise is above a threshold theta, with a smooth step of width w (in noise
// standard deviations) instead of a hard cut: paper = S((n - theta) / w + 1/2),
// S(s) = 3 s^2 - 2 s^3 on [0, 1] (0 below, 1 above). The position sets the
// tone: for a unit-variance Gaussian noise, theta = Phi^-1(1 - tone) makes the
// mean paper value tone (Phi the normal CDF), up to the smooth step's
// curvature term E[paper] = tone + theta phi(theta) w^2 / 40 + O(w^4)
// (integrating by parts, E[paper] = 1 - E[Phi(theta + u)] with u of density
// S'/w on [-w/2, w/2], variance w^2 / 20; |theta phi(theta)| <= phi(1) =
// 0.242, so the bias is below 0.0061 w^2). The width sets the edge softness:
// the fraction of pixels between ink and paper is
// Phi(theta + w/2) - Phi(theta - w/2). Gabor noise with many kernels per pixel
// (N' >= 16) is close to Gaussian (central limit), which is what makes the
// tone map hold for it (tests/style_test.cpp measures both).
#ifndef HUSH_NPR_GABOR_STYLE_HPP
#define HUSH_NPR_GABOR_STYLE_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "hush/core/error.hpp"
#include "hush/core/frame.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/detail/constants.hpp"

namespace hush {

namespace detail {
// The derivative of a field at a pixel from its neighbours' values (NaN where
// the neighbour is missing: another object, the border, no value): central
// where both exist, one-sided where one does, NaN where none does.
inline double field_difference(double lo, double mid, double hi) {
  if (!std::isnan(lo) && !std::isnan(hi)) return 0.5 * (hi - lo);
  if (!std::isnan(hi)) return hi - mid;
  if (!std::isnan(lo)) return mid - lo;
  return std::numeric_limits<double>::quiet_NaN();
}
}  // namespace detail

namespace style {

// Phi(x), the standard normal CDF. Phi(-inf) = 0, Phi(+inf) = 1, NaN -> NaN.
inline double normal_cdf(double x) {
  return 0.5 * std::erfc(-x * detail::constants::kInvSqrt2);
}

// Phi^-1(p): p <= 0 -> -inf, p >= 1 -> +inf, NaN -> NaN. Newton's method from
// 0: Phi is convex below 0 and concave above, so every step stays between 0
// and the root (no overshoot) and converges monotonically; stops when a step
// is below 1e-13 (to about 1e-13 absolute for p in [1e-300, 1 - 1e-16]).
inline double normal_quantile(double p) {
  if (std::isnan(p)) return p;
  if (p <= 0.0) return -std::numeric_limits<double>::infinity();
  if (p >= 1.0) return std::numeric_limits<double>::infinity();
  double x = 0.0;
  for (int k = 0; k < 200; ++k) {
    const double step =
        (p - normal_cdf(x)) / (detail::constants::kInvSqrt2Pi * std::exp(-0.5 * x * x));
    if (!std::isfinite(step)) break;  // density underflow: x is as far as doubles go
    x += step;
    if (std::fabs(step) < 1e-13) break;
  }
  return x;
}

// The smooth step's position for a tone: theta = Phi^-1(1 - tone) (tone
// clamped to [0, 1]; tone 1 -> -inf: all paper; tone 0 -> +inf: all ink;
// NaN -> all paper).
inline double threshold_of_tone(double tone) {
  if (std::isnan(tone)) return -std::numeric_limits<double>::infinity();
  return normal_quantile(1.0 - std::clamp(tone, 0.0, 1.0));
}

// Binary style: hatching with anisotropic noise, stippling with isotropic
// noise (the same thresholding, sec. 4).
class binary {
 public:
  // width: the smooth step's width in noise standard deviations, [0, 8]
  // (0: a hard step). Throws hush::invalid_argument naming "width".
  explicit binary(double width) : w_(width) {
    detail::require_in_range("hush::style::binary", "width", width, 0.0,
                             detail::constants::kStyleMaxWidth, "0 <= width <= 8 (noise sigmas)");
  }
  double width() const { return w_; }

  // Paper value in [0, 1] of noise n at tone in [0, 1] (1 = white): S((n -
  // theta(tone)) / w + 1/2). NaN noise -> paper (1): where there is no noise
  // (the background) nothing is drawn. Never throws.
  double paper(double n, double tone) const { return paper_at(n, threshold_of_tone(tone)); }

  // The same with theta given (theta_of_tone once per tone when many pixels
  // share it).
  double paper_at(double n, double theta) const {
    if (std::isnan(n) || std::isnan(theta)) return 1.0;
    if (w_ == 0.0) return n > theta ? 1.0 : 0.0;
    const double s = std::clamp((n - theta) / w_ + 0.5, 0.0, 1.0);
    return s * s * (3.0 - 2.0 * s);
  }

 private:
  double w_;
};

// Cross-hatching: the product of two binary layers (two noises, e.g. at
// orientations theta and theta + pi/2). Each layer is drawn at tone
// sqrt(tone), so for independent layers the mean paper is the product of the
// means, tone (up to the smooth step's bias of each layer, above).
class crosshatch {
 public:
  explicit crosshatch(double width) : layer_(width) {}
  double paper(double n1, double n2, double tone) const {
    const double t = std::isnan(tone) ? 1.0 : std::sqrt(std::clamp(tone, 0.0, 1.0));
    const double theta = threshold_of_tone(t);
    return layer_.paper_at(n1, theta) * layer_.paper_at(n2, theta);
  }

 private:
  binary layer_;
};

// Graphite: hatching whose strokes are broken by a high-frequency layer. The
// binary style thresholds the mix (n + grain n_fine) / sqrt(1 + grain^2):
// for independent unit-variance noises it has variance 1 again, so the tone
// map above still holds; grain sets how much of the fine layer shows (0:
// plain hatching). A wide smooth step gives the soft graphite edges.
class graphite {
 public:
  // width as binary's; grain in [0, 8]. Throws hush::invalid_argument naming
  // "width" or "grain".
  graphite(double width, double grain)
      : layer_(width), grain_(grain), norm_(1.0 / std::sqrt(1.0 + grain * grain)) {
    detail::require_in_range("hush::style::graphite", "grain", grain, 0.0,
                             detail::constants::kStyleMaxGrain, "0 <= grain <= 8");
  }
  // The mixed noise the layer thresholds (unit variance for independent inputs).
  double mix(double n, double n_fine) const { return (n + grain_ * n_fine) * norm_; }
  double paper(double n, double n_fine, double tone) const {
    return layer_.paper(mix(n, n_fine), tone);
  }

 private:
  binary layer_;
  double grain_, norm_;
};

// Watercolour-like colour style: the scene colour c (each channel in [0, 1])
// overlay-blended with a noise texture b = clamp(1/2 + gain n, 0, 1):
// overlay(c, b) = 2 c b for c < 1/2, 1 - 2 (1 - c)(1 - b) otherwise. n = 0
// leaves c unchanged; the result stays in [0, 1] and increases with n; for a
// noise symmetric about 0, E[b] = 1/2 (the clamp is symmetric) and overlay is
// affine in b, so the mean colour is c exactly: the texture modulates the
// pigment density without shifting the hue on average.
class watercolor {
 public:
  // gain in [0, 4]. Throws hush::invalid_argument naming "gain".
  explicit watercolor(double gain) : gain_(gain) {
    detail::require_in_range("hush::style::watercolor", "gain", gain, 0.0,
                             detail::constants::kStyleMaxGain, "0 <= gain <= 4");
  }
  // One channel. NaN noise -> c (no texture); c clamped to [0, 1].
  double channel(double c, double n) const {
    c = std::clamp(c, 0.0, 1.0);
    if (std::isnan(n)) return c;
    const double b = std::clamp(0.5 + gain_ * n, 0.0, 1.0);
    return c < 0.5 ? 2.0 * c * b : 1.0 - 2.0 * (1.0 - c) * (1.0 - b);
  }
  dvec3 colour(const dvec3& c, double n) const {
    return {channel(c.x, n), channel(c.y, n), channel(c.z, n)};
  }

 private:
  double gain_;
};

// Tone from shading: ambient + (1 - ambient) max(0, N.L) with N and L
// normalised (Lambert; any space, the same for both). A zero or non-finite
// normal (the background) gives 1 (white paper). ambient is clamped to [0, 1].
inline double shading_tone(const dvec3& normal, const dvec3& light, double ambient) {
  auto dot = [](const dvec3& a, const dvec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
  const double nn = std::sqrt(dot(normal, normal)), ll = std::sqrt(dot(light, light));
  if (!(nn > 0.0) || !std::isfinite(nn) || !(ll > 0.0) || !std::isfinite(ll)) return 1.0;
  const double k = std::clamp(ambient, 0.0, 1.0);
  return k + (1.0 - k) * std::max(0.0, dot(normal, light) / (nn * ll));
}

// Orientation from the G-buffer: the screen direction of the projected normal
// at every pixel, in radians from +x towards +y (down), written to `out`
// (frame-sized). It is the direction of grad(1/z): for a plane n.X = d seen
// through a pinhole, 1/z = (n_x x / f + n_y y / f + n_z) / d, so grad(1/z) is
// parallel to (n_x, n_y). By differences of the frame's depth within one
// object (central where both neighbours show the object, one-sided at its
// edges; exact on a plane). NaN on the background (object 0 or unusable
// depth), at isolated pixels, and where the surface faces the camera:
// |grad(1/z)| z < min_slope (relative depth change per pixel), where the
// direction is noise; NPR Gabor noise then takes its constant orientation
// (param_source: NaN pixels). Throws hush::invalid_argument when the frame
// lacks depth or object ids, or out's size differs from the frame's.
inline void projected_normal_field(const frame& f, const image_view<float>& out,
                                   double min_slope) {
  const char* where = "hush::style::projected_normal_field";
  f.validate(where, frame_view::depth | frame_view::object_id,
             detail::constants::kNprGaborMaxImageSide);
  const std::size_t w = f.width(), h = f.height();
  if (out.width != w || out.height != h || !out.data)
    detail::throw_out_of_range(where, "out size",
                               std::to_string(out.width) + "x" + std::to_string(out.height),
                               "the frame's size (non-null)");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // 1/z of pixel (x, y) if it shows object o with a usable depth, else NaN.
  auto inv = [&](std::size_t x, std::size_t y, std::uint32_t o) {
    const double z = static_cast<double>(f.depth(x, y));
    if (f.object_id(x, y) != o || !(z > 0.0) || !std::isfinite(z)) return nan;
    return 1.0 / z;
  };
  const auto diff = detail::field_difference;
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      out(x, y) = std::numeric_limits<float>::quiet_NaN();
      const std::uint32_t o = f.object_id(x, y);
      const double mid = inv(x, y, o);
      if (o == 0 || std::isnan(mid)) continue;
      const double gx = diff(x > 0 ? inv(x - 1, y, o) : nan, mid, x + 1 < w ? inv(x + 1, y, o) : nan);
      const double gy = diff(y > 0 ? inv(x, y - 1, o) : nan, mid, y + 1 < h ? inv(x, y + 1, o) : nan);
      if (!(std::hypot(gx, gy) / mid >= min_slope)) continue;  // also NaN
      out(x, y) = static_cast<float>(std::atan2(gy, gx));
    }
}

// Orientation along the principal curvature (paper sec. 4: "an orientation
// field along the principal curvature"), an image-space estimate from the
// G-buffer's normals: at every pixel the screen direction in which the unit
// normal turns fastest, in radians from +x towards +y (down), written to `out`
// (frame-sized); elsewhere projected_normal_field's value (the fallback).
// `normals`: per pixel, any space (world or view: the estimate is invariant
// under rotations), any length. *Derivation:* with J = [dN/dx dN/dy] the
// screen Jacobian of the unit normal (3 x 2, by differences within one object
// as projected_normal_field) and P = [dX/dx dX/dy] that of the surface point,
// J = S P (S the shape operator, symmetric), so G = J^T J = P^T S^2 P. Where
// the screen map is a similarity (P^T P = s^2 I: the surface seen face-on), the
// eigenvectors of G are the principal directions (S^2 has S's eigenvectors and
// eigenvalues kappa^2), the larger eigenvalue belonging to the larger
// |curvature|; under foreshortening G is the image-space version (a direction
// the screen compresses weighs more). The eigenvector of the larger eigenvalue
// of G = [[a, b], [b, c]] is at angle atan2(2b, a - c) / 2 (mod pi: a Gabor
// kernel's F and -F are the same kernel). Fallback where the estimate is
// unusable: the normal turns by less than min_turn radians per pixel (sqrt of
// the larger eigenvalue: flat), the anisotropy (l1 - l2) / (l1 + l2) is below
// min_anisotropy (umbilic, e.g. a sphere: no principal direction), a normal is
// zero or not finite, or no neighbour shows the object along x or y. Throws
// as projected_normal_field, and names "normals size" when normals is not the
// frame's size. min_turn, min_anisotropy and min_slope are thresholds (NaN:
// always fall back).
inline void curvature_field(const frame& f, const image_view<const vec3>& normals,
                            const image_view<float>& out, double min_turn, double min_anisotropy,
                            double min_slope) {
  projected_normal_field(f, out, min_slope);
  const std::size_t w = f.width(), h = f.height();
  if (normals.width != w || normals.height != h || !normals.data)
    detail::throw_out_of_range("hush::style::curvature_field", "normals size",
                               std::to_string(normals.width) + "x" + std::to_string(normals.height),
                               "the frame's size (non-null)");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Component c of the unit normal at (x, y) if it shows object o, else NaN.
  auto unit = [&](std::size_t x, std::size_t y, std::uint32_t o, int c) {
    const vec3 n = normals(x, y);
    const double nx = n.x, ny = n.y, nz = n.z;
    const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (f.object_id(x, y) != o || !(len > 0.0) || !std::isfinite(len)) return nan;
    return (c == 0 ? nx : (c == 1 ? ny : nz)) / len;
  };
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const std::uint32_t o = f.object_id(x, y);
      if (o == 0) continue;
      double a = 0, b = 0, c = 0;
      for (int k = 0; k < 3; ++k) {
        const double mid = unit(x, y, o, k);
        const double dx = detail::field_difference(x > 0 ? unit(x - 1, y, o, k) : nan, mid,
                                                   x + 1 < w ? unit(x + 1, y, o, k) : nan);
        const double dy = detail::field_difference(y > 0 ? unit(x, y - 1, o, k) : nan, mid,
                                                   y + 1 < h ? unit(x, y + 1, o, k) : nan);
        a += dx * dx;
        b += dx * dy;
        c += dy * dy;
      }
      const double half_gap = std::hypot(0.5 * (a - c), b);
      const double larger = 0.5 * (a + c) + half_gap;
      if (!(std::sqrt(larger) >= min_turn) || !(2.0 * half_gap >= min_anisotropy * (a + c)))
        continue;  // also NaN: keep the fallback
      out(x, y) = static_cast<float>(0.5 * std::atan2(2.0 * b, a - c));
    }
}

}  // namespace style
}  // namespace hush

#endif  // HUSH_NPR_GABOR_STYLE_HPP
