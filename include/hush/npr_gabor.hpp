// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// NPR Gabor noise (Benard, Lagae, Vangorp, Lefebvre, Drettakis, Thollot, "A
// dynamic noise primitive for coherent stylization", EGSR 2010): Gabor
// kernels (hush/gabor/kernel.hpp) defined and evaluated in 2D screen space
// (a 2D look, like a shower door) at points attached to the surface (they move
// with it, like a texture). A scene-driven noise: per frame it reads the
// visibility G-buffer (hush::frame) and the triangles drawn (hush::triangle_list)
// and splats every point's kernel into an image.
//
//   hush::npr_gabor::params prm;             // F0 = 1/8 cycle/px, a = 0.08 /px, N' = 16
//   prm.orientation = 0.5;                   // radians, from +x towards +y (down)
//   hush::npr_gabor noise{prm};
//   noise.render(frame, triangles, out);     // out: frame-sized image_view<float>
//
// The noise (paper eq. 1, sec. 3.2-3.4), n(x) = scale sum_i w_i v_i g_{F_i}(x - x_i):
//  - points (sec. 3.3): triangle t (key hash32(hash32(seed_key(seed),
//    object), triangle)) has a hierarchical point sequence
//    (npr_gabor/tree.hpp): subdivided at its edge midpoints (object
//    space) into four children, recursively, each node holding its own point
//    (uniform in the node: local barycentrics (1 - sqrt u, sqrt u (1 - v),
//    sqrt u v)) and a random order of its children; point J is the root's own
//    point for J = 0, else point (J - 1) / 4 of the child at slot (J - 1) mod 4
//    (point_of). So point J is the same surface point in every frame, the
//    points for M are a prefix of those for 2M, every point is uniform on the
//    triangle (all the variance and spectrum see: only the diagonal of the
//    double sum survives, the amplitudes being independent and zero-mean),
//    and a subtree whose screen triangle misses the image holds no point near
//    it: stage 1 walks the tree depth first, skipping those, so its work is
//    bounded by the image, not by the triangle's area. Screen position
//    sum b_i z_i s_i / sum b_i z_i (core/triangles.hpp).
//  - count and LOD weights (eqs. 2, 4): N = lambda A, A the triangle's screen
//    area, lambda = N' / (pi r^2) (r the kernel radius in pixels). For
//    N >= 1: M = 2^floor(log2 N), 2M points, the first M weighted 1 and the
//    second M weighted alpha(N) = sqrt(N / M - 1). For 0 < N < 1 one point
//    weighted sqrt(N), not N as the paper writes: what the variance and the
//    power spectrum see is the sum of the squared weights (Campbell's
//    theorem; paper eqs. 5-8 with M replaced by the weights), which is N for
//    N unit-weight Poisson points; M (1 + alpha^2) = N above, and sqrt(N)^2 = N
//    below. Weighting by N gives N^2: the variance of small triangles falls
//    by a factor N (tests/npr_gabor/npr_gabor_test.cpp shows both). Every weight is
//    continuous in N: alpha -> 1 as N -> 2M from below, where the next level
//    starts with the same 2M points at weight 1; sqrt(N) -> 1 = the weight
//    of the single point at N = 1 (alpha(1) = 0). No pops at the switches.
//    N is clamped to kNprGaborMaxPoints = 2^40 (constants.hpp: the float input's
//    limit, not a work bound). With params::thinning
//    the N < 1 point is kept only for the triangle's own uniform u < 2N (N <=
//    1/2), with a weight fading in continuously (npr_gabor_lod::thinned_square:
//    E[w^2] = N as above, so the same variance and spectrum, without pops), so
//    dense meshes cost min(1, 2N) points per triangle instead of 1.
//  - with params::local_density, a count per tree node instead (local_walk,
//    npr_gabor_lod::local_square): node P's own point has squared weight
//    n_P h(n_P), n_P = lambda_P A_P (its projected sub-triangle's area), h a hat
//    in log4 summing to 1 over the levels, so the screen density of squared
//    weights is lambda across foreshortened triangles too (docs/npr-gabor.md
//    "Local density"); continuous in n_P, so no pops.
//  - two stages (hush/npr_gabor/splat.hpp): make_splats lists one
//    record per point (position, F, radius, weight, plane, ids, pixel range);
//    splat adds the records' kernels, on exec::scalar or exec::simd (screen
//    tiles, hush/npr_gabor/simd-inl.h, bit for bit scalar under HUSH_STRICT_FP).
//  - amplitudes v_i uniform in (-1, 1) (16-bit symmetric, E[v^2] =
//    (1 - 2^-32) / 3); kernel g of gabor_kernel<2> (bandwidth a, truncation
//    t, C1 taper) with F_i = F0 (cos theta, sin theta), theta = orientation
//    (anisotropic) or uniform (isotropic), theta measured from +x towards +y
//    (screen y points down: clockwise on screen).
//  - scale = 1 / sqrt(lambda E[v^2] int g^2) (kernel energy by quadrature):
//    where the surface covers the kernel's disc with unclipped points, the
//    noise has mean 0 and variance 1, independent of the triangles' sizes and
//    of zoom, with power spectrum scale^2 lambda E[v^2] |g^(f)|^2 (two blobs
//    at +-F0 omega0; isotropic: a ring at F0): the frequency is in pixels, so
//    it does not change with depth (the 2D aspect).
//  - visibility (sec. 3.4, each switchable, per pixel of a kernel's disc):
//    object test (the pixel shows the point's object), triangle test (the
//    pixel shows the point's triangle), depth test (the pixel's depth is within
//    a relative tolerance of the depth the triangle's plane has at that pixel:
//    1/z is affine in screen space on a plane, so the test follows slanted
//    surfaces and cuts kernels at depth discontinuities); soft depth test: the
//    kernel fades out linearly between 1 and 2 tolerances instead of a cut.
//  - skipped triangles (emit nothing): back faces when cull_back_faces
//    (front_face: counter-clockwise by default, GL's front face, as seen on the
//    displayed image; npr_gabor_front_face states the sign in these y-down pixel
//    coordinates; with a vertex behind the camera, by the homogeneous
//    orientation z0 z1 z2 cross; render returns how many), degenerate ones, those with a vertex at depth
//    exactly 0 or a non-finite value, those entirely behind the camera, and
//    those whose bounding box grown by r misses the image. Hidden triangles
//    emit points whose fragments fail the tests (nothing is added).
//  - the near plane and strong perspective (docs/npr-gabor.md "Triangles crossing
//    the near plane"): a vertex behind the camera (depth < 0) gives its screen
//    position as clip xy / w with w < 0, so (z s, z) is its clip (x, y, w): a
//    triangle whose nearest vertex is below w_near = far / 1024 is clipped per
//    tree node (nodes behind w_near dropped, nodes crossing it weight 0 and culled
//    by their part in front) and uses the count per node; one of depth ratio
//    far / near above 4 blends the count per node in by squared weight (all of
//    it from ratio 8), whatever params::local_density: the per-triangle N is
//    unbounded as a vertex nears depth 0, and every weight stays continuous.
//  - pixels no kernel reaches, or where every fragment fails, are 0 (the mean).
//  - parameter sources (sec. 4; render's `sources`, hush/core/param_source.hpp):
//    F0, omega0, a and N' each a constant (params), a per-object table (indexed
//    by the G-buffer's object id), a per-pixel field (e.g. an orientation field
//    along the projected normal, a frequency driven by shading) or per-vertex
//    values (interpolated with the point's own barycentric coordinates). Each
//    point reads F0, omega0 and a once, at the pixel under its own screen
//    position in this frame (or its barycentric position), not per fragment: a
//    splat is one Gabor kernel (its own frequency and radius), and a point
//    keeps its parameters while it moves exactly as far as the field is
//    attached to the surface (a field computed from the surface, like the
//    projected normal, changes only as the surface's view changes); reading per
//    fragment would make the kernel change shape as it slides over the pixels.
//    The point count N = lambda A needs one density per triangle: lambda_T =
//    N'_T / (pi r(a_T)^2) with a_T and N'_T read at the triangle's object-space
//    centroid (per pixel: its pixel, clamped into the image; per vertex: the
//    mean). Non-finite field pixels and vertex values, point positions outside
//    the image and objects past a table's end take the params' constant; finite
//    field values are clamped to their ranges (F0 [0, 0.5], a [0.01, 10], N'
//    [0, 256]; N'_T = 0: no points). A hidden point reads the pixel of what
//    hides it (its fragments then mostly fail the visibility tests). With
//    `isotropic` the orientation source is ignored (each point has its random
//    angle). Each point is weighted by 1 / sqrt(lambda_T E[v^2] int g_{F,a}^2)
//    for its own F and a and its triangle's lambda_T (interpolated_energy:
//    linear between exact energies at steps of 1/64 in F r, computed on demand,
//    relative error below 1e-3), so the noise has variance 1 wherever F and a
//    are constant over a kernel's disc, whatever N' does; where F or a vary
//    linearly the first-order change cancels (the kernel is even), see
//    docs/npr-gabor.md.
//  - float render is within 2^-21 (1 + 2 pi F0 r) per kernel of the double
//    reference times sum |w_i v_i| scale (the kernel's float budget,
//    gabor/kernel.hpp); tests/npr_gabor/npr_gabor_test.cpp measures it.
//  - GLSL: render on exec::glsl{device} (include hush/glsl/npr_gabor.hpp): stage 1 in
//    compute passes (counts, prefix sum, one invocation per point, the CPU's record order)
//    where every source is constant or per object, else on the CPU; the records drawn as
//    point sprites (geometry shader), the kernel and the tests per fragment, additive
//    blending into a float target.
#ifndef HUSH_NPR_GABOR_HPP
#define HUSH_NPR_GABOR_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "hush/config.hpp"
#include "hush/core/error.hpp"
#include "hush/core/frame.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/param_source.hpp"
#include "hush/core/rng.hpp"
#include "hush/core/triangles.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/detail/constants.hpp"
#include "hush/npr_gabor/splat.hpp"
#include "hush/npr_gabor/tree.hpp"
#include "hush/exec.hpp"
#include "hush/gabor.hpp"
#include "hush/gabor/kernel.hpp"
#include "hush/npr_gabor/simd_kernel.hpp"

namespace hush {

namespace detail {
// Whether Exec is exec::glsl{device} (splat hands stage 2 to hush/glsl/npr_gabor.hpp).
template <class Exec>
struct is_glsl_exec : std::false_type {};
template <class Device>
struct is_glsl_exec<exec::glsl<Device>> : std::true_type {};
}  // namespace detail

// Which winding faces the camera (npr_gabor::params::front_face), as the triangle is seen on
// the displayed image: counter_clockwise is GL's default front face (counter-clockwise in GL's
// y-up window coordinates, and on the displayed image). In hush's y-down pixel coordinates
// (row 0 at the top) a counter-clockwise triangle has e1.x e2.y - e1.y e2.x < 0 (e1, e2 its
// edges from vertex 0): the formula's sign flips with the y axis, the picture does not.
enum class npr_gabor_front_face { counter_clockwise, clockwise };

// What one render did with the triangle list (npr_gabor::render's result).
struct npr_gabor_render_stats {
  std::size_t triangles = 0;  // in the list
  // Skipped as back faces (params::cull_back_faces, params::front_face): triangles of non-zero
  // finite screen area, every vertex at a finite non-zero depth, whose winding is not the front
  // one. Equal to `triangles` when every triangle is wound the other way: the image is 0.
  std::size_t back_faces_culled = 0;
};

// The LOD of one triangle (paper sec. 3.3, eqs. 2 and 4, and the N < 1 case
// derived above): points 0 ... first - 1 weigh first_weight, points first ...
// count - 1 weigh second_weight. sum of squared weights = N (for 0 <= N <=
// kNprGaborMaxPoints; N clamped above, 0 points for N <= 0 or NaN).
struct npr_gabor_lod {
  std::uint64_t first = 0, count = 0;
  double first_weight = 0, second_weight = 0;

  static npr_gabor_lod of(double n) {
    npr_gabor_lod l;
    if (!(n > 0.0)) return l;  // also NaN
    n = std::min(n, detail::constants::kNprGaborMaxPoints);
    if (n < 1.0) {
      l.first = l.count = 1;
      l.first_weight = std::sqrt(n);
      return l;
    }
    int e = 0;
    (void)std::frexp(n, &e);  // n = f 2^e, f in [0.5, 1): floor(log2 n) = e - 1
    const double m = std::ldexp(1.0, e - 1);
    l.first = static_cast<std::uint64_t>(m);
    l.first_weight = 1.0;
    l.second_weight = std::sqrt(n / m - 1.0);  // alpha(N), eq. 4
    l.count = l.second_weight > 0.0 ? 2 * l.first : l.first;
    return l;
  }
  double weight(std::uint64_t j) const { return j < first ? first_weight : second_weight; }

  // Thinning of the N < 1 point (npr_gabor::params::thinning): its squared
  // weight g(N, u) for the triangle's own uniform u in [0, 1):
  //   g = max(0, 1 - u / (2N))   for 0 < N <= 1/2 (a point for u < 2N only),
  //   g = 1 - 2 (1 - N) u        for 1/2 <= N <= 1 (always a point),
  // 0 for N <= 0 or NaN, 1 for N >= 1. E_u[g] = N on both pieces (the area
  // under a ramp from 1 to 0 over [0, 2N] is N; 1 - (1 - N) = N), which is
  // all the variance and the spectrum see (Campbell's theorem: the density of
  // sum w^2 per area, amplitudes independent of u), as the unthinned weight
  // sqrt(N) has it. For fixed u, g is continuous in N (both pieces are 1 - u
  // at N = 1/2, and 1 at N = 1, the weight the single point keeps above), so
  // a point fades in as its triangle grows: no pops. Expected points per
  // triangle min(1, 2N) instead of 1.
  static double thinned_square(double n, double u) {
    if (!(n > 0.0)) return 0.0;
    if (n >= 1.0) return 1.0;
    if (n <= 0.5) return std::max(0.0, 1.0 - u / (2.0 * n));
    return 1.0 - 2.0 * (1.0 - n) * u;
  }

  // Local density (npr_gabor::params::local_density, docs/npr-gabor.md "Local density"):
  // the squared weight f(n) = n h(n) of a tree node's own point, n = lambda_P A_P the
  // node's expected count, h the hat in log base 4, h(n) = max(0, 1 - |log4 n|). The hat
  // is a partition of unity in log4 (sum over integer k of h(n 4^-k) = 1), and the tree
  // has no levels above the root and none below the deepest one walked: `coarsest` adds
  // the missing coarser levels' hats (h = 1 for n <= 1: f = n, the squared weight
  // sqrt(N)^2 of the paper's N < 1 point), `finest` the missing finer ones (h = 1 for
  // n >= 1). So the root-to-finest sum of h(n 4^-k) is 1 for every n > 0 (exact to
  // rounding where the levels' counts are n 4^-k). 0 for n <= 0 or NaN; n clamped to
  // kNprGaborMaxPoints. Continuous in n (h is 0 at n = 1/4 and 4, 1 at n = 1).
  static double local_square(double n, bool coarsest, bool finest) {
    if (!(n > 0.0)) return 0.0;
    n = std::min(n, detail::constants::kNprGaborMaxPoints);
    const double l = std::log(n) / std::log(4.0);
    double h = 1.0 - std::fabs(l);
    if ((coarsest && l <= 0.0) || (finest && l >= 0.0)) h = 1.0;
    return h > 0.0 ? n * h : 0.0;
  }
};

class npr_gabor {
 public:
  struct params {
    double frequency = detail::constants::kNprGaborDefaultFrequency;  // F0, cycles per pixel
    double bandwidth = detail::constants::kNprGaborDefaultBandwidth;  // a, 1/pixel
    double truncation = detail::constants::kGaborDefaultTruncation;   // t
    double impulses = detail::constants::kNprGaborDefaultImpulses;    // N'
    double orientation = 0.0;  // omega0, radians from +x towards +y (anisotropic)
    bool isotropic = false;    // random orientation per point
    std::uint32_t seed = 0;
    bool object_test = true;
    bool triangle_test = false;
    bool depth_test = true;
    bool soft_depth = false;
    double depth_tolerance = detail::constants::kNprGaborDefaultDepthTolerance;
    bool cull_back_faces = true;
    // The winding of the triangles facing the camera, as seen on the displayed image
    // (npr_gabor_front_face); the other winding is culled when cull_back_faces.
    npr_gabor_front_face front_face = npr_gabor_front_face::counter_clockwise;
    // Thin the points of triangles with N < 1 (npr_gabor_lod::thinned_square):
    // same variance and spectrum, min(1, 2N) points per triangle instead of 1,
    // so that the cost follows N' and the covered pixels, not the triangle count.
    bool thinning = false;
    // Local density (docs/npr-gabor.md "Local density"): every node P of a triangle's point
    // tree gets its own count n_P = lambda_P A_P (A_P the screen area of its projected
    // sub-triangle, lambda_P the density at its centroid) and its own point the squared
    // weight npr_gabor_lod::local_square(n_P): the screen density of squared weights is then
    // lambda wherever the perspective within a node is small, so the variance stays 1 across
    // strongly foreshortened triangles, where the paper's one N = lambda A per triangle makes
    // the near part too sparse and the far part too dense. false: the paper's per-triangle
    // LOD (eqs. 2, 4), except for triangles crossing the near plane (always a count per node)
    // and of depth ratio above 4 (blended in; see the header comment). thinning applies to the
    // root's point when n_root < 1.
    bool local_density = false;
  };

  // Throws hush::invalid_argument naming the parameter and its range:
  // frequency in [0, 0.5], bandwidth in [0.01, 10], truncation in [1e-9, 0.5],
  // impulses in (0, 256], finite orientation, depth_tolerance in [0, 1].
  explicit npr_gabor(const params& p) : p_(p), kernel_(checked(p).bandwidth, p.truncation) {
    const double r = kernel_.radius();
    lambda_ = p_.impulses / (detail::constants::kPi * r * r);
    scale_ = 1.0 / std::sqrt(lambda_ * weight_moment() * kernel_.energy(p_.frequency));
  }

  const params& parameters() const { return p_; }
  const gabor_kernel<2>& kernel() const { return kernel_; }
  // lambda = N' / (pi r^2): points per square pixel.
  double density() const { return lambda_; }
  // The factor making the variance 1: 1 / sqrt(lambda E[v^2] int g^2).
  double scale() const { return scale_; }
  // E[v^2] of the 16-bit symmetric amplitudes: (1 - 2^-32) / 3.
  static constexpr double weight_moment() { return (1.0 - 1.0 / 4294967296.0) / 3.0; }
  // The deepest level of a triangle's point tree that stage 1 walks (21: J < 2^41 for the
  // paper's LOD; params::local_density's finest level, whose hat carries the levels below).
  // GPU stage 1 (hush/glsl/npr_gabor.hpp) walks the same levels.
  static constexpr int max_depth() { return kMaxDepth; }
  // The frame views render reads.
  frame_view needs() const {
    frame_view v = frame_view::depth;
    if (p_.object_test) v = v | frame_view::object_id;
    if (p_.triangle_test) v = v | frame_view::triangle_id;
    return v;
  }

  // A point of a triangle in barycentric coordinates, its amplitude v in
  // (-1, 1) and its orientation word's angle in radians (isotropic).
  struct point {
    double b[3];
    double amplitude;
    double angle;
  };
  // The point J of a triangle (the hierarchical sequence of
  // npr_gabor/tree.hpp, J < 2^64) in the triangle's (object-space)
  // barycentric coordinates: the own point of the node reached from
  // the root by slots d = (J - 1) mod 4 with local index q = (J - 1) / 4, until
  // q = 0 (J = 0: the root's own point, words 0 and 1 of the triangle's stream).
  point point_of(std::uint32_t object, std::uint32_t triangle, std::uint64_t j) const {
    detail::npr_tree_node nd;
    nd.seed = triangle_key(object, triangle);
    detail::npr_tree_words w = detail::npr_tree_words_of(nd.seed);
    for (; j > 0; j = (j - 1) / 4) {
      nd = detail::npr_tree_child(nd, w, static_cast<unsigned>((j - 1) % 4));
      w = detail::npr_tree_words_of(nd.seed);
    }
    return node_point(nd, w);
  }

  // Where F0, omega0, a and N' come from in one frame (see the header
  // comment): a default-constructed source is the params' constant. Views,
  // valid for the render call. Per-object frequencies in [0, 0.5],
  // orientations finite, bandwidths in [0.01, 10], impulses in (0, 256].
  struct sources {
    param_source frequency;    // cycles per pixel
    param_source orientation;  // radians from +x towards +y
    param_source bandwidth;    // 1/pixel: per point, and per triangle for its density
    param_source impulses;     // N': per triangle (its density)
  };

  // Overwrites `out` (frame-sized; float, or double for the reference) with
  // the noise of this frame: stage 1 (make_splats) then stage 2 (the kernels
  // added per pixel in record order). `ex` picks stage 2's backend:
  // exec::scalar, or exec::simd (float only; screen tiles, lanes along x,
  // hush/npr_gabor/simd-inl.h: bit for bit exec::scalar under HUSH_STRICT_FP;
  // the scalar loop where the build has no SIMD), or exec::glsl{device}
  // (float only; include hush/glsl/npr_gabor.hpp: both stages on the GPU where
  // every source is constant or per object, stage 1 here otherwise; within the
  // tolerance stated there). Throws
  // hush::invalid_argument when the frame lacks a view needs() lists or is
  // malformed (frame::validate), when the triangle list is malformed
  // (triangle_list::validate), when out's size differs from the frame's, or
  // when a source is malformed (param_source::validate: "frequency[i]",
  // "orientation[i]", "bandwidth[i]", "impulses[i]", a field's size).
  // Never reads outside the views. Returns the triangle count and how many were culled as
  // back faces (the same on every backend: counted here from the triangle list).
  template <class Exec, class T>
  npr_gabor_render_stats render(const Exec& ex, const frame& f, const triangle_list& tris,
                                const image_view<T>& out, const sources& src = {}) const {
    validate(f, tris, src);
    check_out(f, out);
    const npr_gabor_render_stats stats = count_culled(tris);
    if constexpr (detail::is_glsl_exec<Exec>::value) {
      static_assert(std::is_same<T, float>::value, "exec::glsl renders into float images");
      // exec::glsl{device}: both stages on the GPU where the sources allow, else stage 1 here
      // (hush/glsl/npr_gabor.hpp, found by argument-dependent lookup).
      npr_gabor_glsl_render(ex.device, *this, f, tris, src, out);
    } else {
      std::vector<npr_gabor_splat> splats;
      splats_of(f, tris, splats, src);  // validated above
      splat(ex, f, splats.data(), splats.size(), out);
    }
    return stats;
  }
  template <class T>
  npr_gabor_render_stats render(const frame& f, const triangle_list& tris,
                                const image_view<T>& out, const sources& src = {}) const {
    return render(exec::scalar, f, tris, out, src);
  }

  // The triangles of `tris` (validated) that render skips as back faces (render's stats).
  npr_gabor_render_stats count_culled(const triangle_list& tris) const {
    npr_gabor_render_stats st;
    st.triangles = tris.triangles();
    if (!p_.cull_back_faces) return st;
    for (std::size_t t = 0; t < st.triangles; ++t) {
      dvec2 s[3];
      double z[3], cross = 0, facing = 0;
      if (orientation(tris, t, s, z, cross, facing) && cross != 0.0 && std::isfinite(cross) &&
          !is_front(facing))
        ++st.back_faces_culled;
    }
    return st;
  }

  // Stage 1: replaces `splats` with this frame's records (npr_gabor_splat),
  // triangle by triangle in list order, each triangle's points in J order
  // (npr_gabor_splat::index), each point with its own kernel parameters from
  // `src`; points whose pixel range misses the image are left out, and so are
  // the subtrees of the point sequence whose screen triangle (grown by the
  // largest radius an off-image point can have) misses it: exactly the records
  // of generating every point and leaving out each one that misses, with work
  // bounded by the image, not by the triangles' areas. `nodes`, if given, gets
  // the number of sequence nodes examined added. Throws as render does for
  // the frame, the triangles and the sources.
  void make_splats(const frame& f, const triangle_list& tris, std::vector<npr_gabor_splat>& splats,
                   const sources& src = {}, std::uint64_t* nodes = nullptr) const {
    validate(f, tris, src);
    splats_of(f, tris, splats, src, nodes);
  }

  // Stage 2: overwrites `out` (frame-sized) with the sum of the `count`
  // records' kernels at `splats`, each fragment passing this noise's
  // visibility tests against frame f (validated by make_splats; records with
  // a pixel range outside the frame are the caller's error). Backends as
  // for render.
  template <class Exec, class T>
  void splat(const Exec& ex, const frame& f, const npr_gabor_splat* splats, std::size_t count,
             const image_view<T>& out) const {
    check_out(f, out);
    for (std::size_t y = 0; y < out.height; ++y)
      std::fill(out.row(y), out.row(y) + out.width, T(0));
    const detail::npr_gabor_splat_job job = splat_job(f, splats, count);
    if constexpr (detail::is_glsl_exec<Exec>::value) {
      static_assert(std::is_same<T, float>::value, "exec::glsl splats into float images");
      // exec::glsl{device}: hush/glsl/npr_gabor.hpp (found by argument-dependent lookup).
      npr_gabor_glsl_splat(ex.device, job, out);
    } else {
#if HUSH_CONFIG_SIMD
      if constexpr (std::is_same<Exec, exec::simd_t>::value && std::is_same<T, float>::value) {
        simd::npr_gabor_splat(job, out);
        return;
      }
#endif
      (void)ex;
      std::vector<detail::gabor_axis<T>> columns;
      detail::npr_gabor_splat_scalar(job, out, columns);
    }
  }

  // What stage 2 reads for `count` records at `splats` in frame f: the views and this
  // noise's visibility tests (for the backends; splat builds it).
  detail::npr_gabor_splat_job splat_job(const frame& f, const npr_gabor_splat* splats,
                                        std::size_t count) const {
    detail::npr_gabor_splat_job job;
    job.splats = splats;
    job.count = count;
    job.depth = f.depth;
    job.object_id = f.object_id;
    job.triangle_id = f.triangle_id;
    job.object_test = p_.object_test;
    job.triangle_test = p_.triangle_test;
    job.depth_test = p_.depth_test;
    job.soft_depth = p_.soft_depth;
    job.depth_tolerance = p_.depth_tolerance;
    job.envelope_exponent = kernel_.envelope_exponent();
    return job;
  }

  // The kernel every point of an object's triangles has when no source is per pixel or per
  // vertex (each constant or per object): F (for isotropic the angle 0, i.e. (F0, 0)), a, r,
  // the triangles' density lambda_T and the weight factor, computed as stage 1 computes them
  // (for GPU backends that generate the points themselves). Other sources: not meaningful.
  struct object_kernel {
    dvec2 F;
    double bandwidth, radius, density, scale;
  };
  object_kernel kernel_of_object(std::uint32_t object, const sources& src) const {
    const point_parameters pp(*this, src);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const param_source::site at{object, nan, nan, nullptr, {nan, nan, nan}};
    const double lambda = pp.density(at, 1.0, 1.0);
    const point_parameters::kernel k = pp.at(at, 0.0, lambda);
    return {k.F, k.bandwidth, k.radius, lambda, k.scale};
  }
  // Whether stage 1 walks a triangle of `tris` (validated) with a count per node even
  // without params::local_density: a vertex in front of the camera and one behind it, or a
  // depth ratio far / near above kNprGaborPerNodeRatioLow (docs/npr-gabor.md "Triangles
  // crossing the near plane"; conservative: back faces and triangles off the image count too). GPU
  // backends whose stage 1 has one count per triangle run such frames' stage 1 on the CPU.
  // O(triangles).
  static bool walks_per_node(const triangle_list& tris) {
    for (std::size_t t = 0; t < tris.triangles(); ++t) {
      double near = std::numeric_limits<double>::infinity(), far = -near;
      for (std::size_t i = 0; i < 3; ++i) {
        const double z = tris.depth[tris.indices[3 * t + i]];
        near = std::min(near, z);
        far = std::max(far, z);
      }
      if (far > 0.0 && far > detail::constants::kNprGaborPerNodeRatioLow * near) return true;
    }
    return false;
  }
  // Whether every source is constant or per object (kernel_of_object applies).
  static bool per_object_at_most(const sources& src) {
    for (const param_source* s : {&src.frequency, &src.orientation, &src.bandwidth, &src.impulses})
      if (!s->is_constant() && s->which() != param_source::kind::per_object) return false;
    return true;
  }

  // int g_F^2 for |F| = frequency and a kernel of radius `radius` (default:
  // this noise's), as render normalises a point whose F or a is not the
  // constant: the energy is r^2 E(F r) (substitute x = r u; E for a unit
  // radius and this truncation), E interpolated linearly between the nodes
  // F r = k kNprGaborEnergyStep, computed as kernel().energy at the nodes.
  // Exact at the nodes; relative error below 1e-3 (tests/npr_gabor/npr_gabor_sources_test.cpp
  // measures it). `cache`: node energies (NaN = not computed yet), filled on
  // demand (one quadrature, ~0.5 ms, per node used).
  double interpolated_energy(double frequency, std::vector<double>& cache) const {
    return interpolated_energy(frequency, kernel_.radius(), cache);
  }
  double interpolated_energy(double frequency, double radius, std::vector<double>& cache) const {
    const double r0 = kernel_.radius();
    const double h = detail::constants::kNprGaborEnergyStep / radius;
    const double u = std::max(frequency, 0.0) / h;
    const std::size_t i = static_cast<std::size_t>(u);
    const double t = u - static_cast<double>(i);
    if (cache.size() < i + 2) cache.resize(i + 2, std::numeric_limits<double>::quiet_NaN());
    const double h0 = detail::constants::kNprGaborEnergyStep / r0;
    for (std::size_t k = i; k <= i + 1; ++k)
      if (std::isnan(cache[k])) cache[k] = kernel_.energy(static_cast<double>(k) * h0);
    const double ratio = radius / r0;  // exactly 1 for this noise's radius
    return (cache[i] * (1.0 - t) + cache[i + 1] * t) * (ratio * ratio);
  }

 private:
  // make_splats without the validation (render validates once, before it).
  void splats_of(const frame& f, const triangle_list& tris, std::vector<npr_gabor_splat>& splats,
                 const sources& src, std::uint64_t* nodes = nullptr) const {
    splats.clear();
    const point_parameters pp(*this, src);
    for (std::size_t t = 0; t < tris.triangles(); ++t)
      triangle_splats(f, tris, t, splats, pp, nodes);
  }

  static const params& checked(const params& p) {
    namespace c = detail::constants;
    const char* w = "hush::npr_gabor";
    detail::require_in_range(w, "frequency", p.frequency, 0.0, c::kNprGaborMaxFrequency,
                             "0 <= frequency <= 0.5 (cycles per pixel)");
    detail::require_in_range(w, "bandwidth", p.bandwidth, c::kNprGaborMinBandwidth,
                             c::kNprGaborMaxBandwidth, "0.01 <= bandwidth <= 10 (1/pixel)");
    detail::require_in_range(w, "truncation", p.truncation, c::kGaborMinTruncation,
                             c::kGaborMaxTruncation, "1e-09 <= truncation <= 0.5");
    if (!(p.impulses > 0.0 && p.impulses <= c::kGaborMaxImpulses))
      detail::throw_out_of_range(w, "impulses", p.impulses, "0 < impulses <= 256");
    if (!std::isfinite(p.orientation))
      detail::throw_out_of_range(w, "orientation", p.orientation, "finite (radians)");
    detail::require_in_range(w, "depth_tolerance", p.depth_tolerance, 0.0,
                             c::kNprGaborMaxDepthTolerance, "0 <= depth_tolerance <= 1");
    return p;
  }

  // The kernel radius for bandwidth a: gabor_kernel's r = sqrt(ln(1/t) / pi) / a.
  double radius_of(double a) const {
    return a == p_.bandwidth ? kernel_.radius()
                             : std::sqrt(kernel_.envelope_exponent() / detail::constants::kPi) / a;
  }

  // The kernel parameters from the sources (the params' constants where a
  // source is constant: bit for bit the renderer without sources). One per
  // render call (it caches node energies).
  //  - Per triangle, its density lambda_T = N'_T / (pi r(a_T)^2) (eq. 2), a_T
  //    and N'_T read where the triangle is: at its object-space centroid
  //    (per pixel: its pixel, clamped into the image, so that a triangle whose
  //    centroid leaves the image keeps the border pixel's value, continuously:
  //    no pop; per vertex: the mean of the three values).
  //  - Per point, its own F, omega and a read at its own pixel or barycentric
  //    position (as render's contract says), and the weight factor 1 / sqrt(lambda_T E[v^2]
  //    int g_{F,a}^2) with its triangle's lambda_T, the density its points
  //    actually have (Campbell: the variance at x is then the integral over
  //    the surface of g_y(x - y)^2 / int g_y^2, 1 where F and a are constant
  //    over the kernel's disc, whatever N' does; see docs/npr-gabor.md).
  class point_parameters {
   public:
    point_parameters(const npr_gabor& n, const sources& src) : n_(n), src_(src) {}
    struct kernel {
      dvec2 F;
      double bandwidth, radius, scale;
    };
    static double clamp_bandwidth(double a) {
      return std::clamp(a, detail::constants::kNprGaborMinBandwidth,
                        detail::constants::kNprGaborMaxBandwidth);
    }
    // a at a site: finite values clamped to [0.01, 10].
    double bandwidth(const param_source::site& at) const {
      return clamp_bandwidth(src_.bandwidth.value(at, n_.p_.bandwidth));
    }
    // The largest radius of a point of a triangle of `object` with vertices
    // `v` that lies off the image (per pixel: the constant's; per object: the
    // table's; per vertex: that of the smallest a of its vertices, which
    // bounds their convex combinations): culls triangles whose bounding box
    // grown by it misses the image (their points are all off it).
    double off_image_radius(std::uint32_t object, const std::uint32_t* v) const {
      const param_source& s = src_.bandwidth;
      if (s.is_constant()) return n_.kernel_.radius();
      const double nan = std::numeric_limits<double>::quiet_NaN(), c = n_.p_.bandwidth;
      if (s.which() != param_source::kind::per_vertex)
        return n_.radius_of(bandwidth({object, nan, nan, nullptr, {0, 0, 0}}));
      return n_.radius_of(clamp_bandwidth(
          std::min({s.vertex_value(v[0], c), s.vertex_value(v[1], c), s.vertex_value(v[2], c)})));
    }
    // lambda_T for the triangle whose object-space centroid is `centre` (its
    // pixel clamped here into the w x h image); N'_T clamped to [0, 256]
    // (0: no points).
    // Whether density() is the params' lambda everywhere (a and N' constant).
    bool constant_density() const {
      return src_.bandwidth.is_constant() && src_.impulses.is_constant();
    }
    double density(param_source::site centre, double w, double h) const {
      const params& p = n_.p_;
      if (constant_density()) return n_.lambda_;
      centre.x = std::clamp(centre.x, 0.5, w - 0.5);
      centre.y = std::clamp(centre.y, 0.5, h - 0.5);
      const double a = bandwidth(centre);
      const double np = std::clamp(src_.impulses.value(centre, p.impulses), 0.0,
                                   detail::constants::kGaborMaxImpulses);
      if (a == p.bandwidth && np == p.impulses) return n_.lambda_;
      const double r = n_.radius_of(a);
      return np / (detail::constants::kPi * r * r);
    }
    // The kernel of the point at `at` (its pixel and barycentric coordinates)
    // of a triangle of density `lambda`.
    kernel at(const param_source::site& at, double random_angle, double lambda) const {
      const params& p = n_.p_;
      double f = p.frequency, scale = n_.scale_;
      const double a = src_.bandwidth.is_constant() ? p.bandwidth : bandwidth(at);
      const double r = n_.radius_of(a);
      if (!src_.frequency.is_constant())
        f = std::clamp(src_.frequency.value(at, p.frequency), 0.0,
                       detail::constants::kNprGaborMaxFrequency);
      if (!src_.frequency.is_constant() || a != p.bandwidth || lambda != n_.lambda_)
        scale = 1.0 / std::sqrt(lambda * weight_moment() * n_.interpolated_energy(f, r, energy_));
      const double theta = p.isotropic ? random_angle : src_.orientation.value(at, p.orientation);
      return {{f * std::cos(theta), f * std::sin(theta)}, a, r, scale};
    }

   private:
    const npr_gabor& n_;
    const sources& src_;
    mutable std::vector<double> energy_;
  };

  // A node's own point: local barycentrics (1 - sqrt u, sqrt u (1 - v), sqrt u v)
  // of its corners from its point word (uniform in the node), mapped to the
  // root's barycentrics; amplitude and angle from its value word. The root's
  // corners are the identity, so its point is b = l exactly.
  static point node_point(const detail::npr_tree_node& nd, const detail::npr_tree_words& w) {
    const double u = detail::gabor_half<double>(w.point, 0),
                 v = detail::gabor_half<double>(w.point, 1);
    const double su = std::sqrt(u);
    const double l[3] = {1.0 - su, su * (1.0 - v), su * v};
    point pt{{0.0, 0.0, 0.0},
             2.0 * detail::gabor_half<double>(w.value, 0) - 1.0,
             detail::constants::kTwoPi * detail::gabor_half<double>(w.value, 1)};
    for (unsigned k = 0; k < 3; ++k)
      pt.b[k] = l[0] * nd.corner[0][k] + l[1] * nd.corner[1][k] + l[2] * nd.corner[2][k];
    return pt;
  }

  std::uint32_t triangle_key(std::uint32_t object, std::uint32_t triangle) const {
    return hash32(hash32(seed_key(p_.seed), object), triangle);
  }

  // The triangle's thinning uniform in [0, 1): the last two words of its root's stream
  // (2^32 - 2 and 2^32 - 1), which no node reads (a node takes words 0 ... 2 of its own
  // stream), so it is independent of every point's position and amplitude.
  double thinning_uniform(std::uint32_t object, std::uint32_t triangle) const {
    rng r(triangle_key(object, triangle), detail::constants::kNprGaborStream);
    r.skip(0xFFFFFFFEu);
    return r.uniform<double>();
  }

  void validate(const frame& f, const triangle_list& tris, const sources& src) const {
    namespace c = detail::constants;
    const char* where = "hush::npr_gabor::render";
    f.validate(where, needs(), c::kNprGaborMaxImageSide);
    tris.validate(where, c::kNprGaborMaxTriangles);
    src.frequency.validate(where, "frequency", 0.0, c::kNprGaborMaxFrequency,
                           "0 <= frequency <= 0.5 (cycles per pixel)", f.width(), f.height(),
                           tris.vertices());
    src.orientation.validate(where, "orientation", -std::numeric_limits<double>::max(),
                             std::numeric_limits<double>::max(), "finite (radians)", f.width(),
                             f.height(), tris.vertices());
    src.bandwidth.validate(where, "bandwidth", c::kNprGaborMinBandwidth, c::kNprGaborMaxBandwidth,
                           "0.01 <= bandwidth <= 10 (1/pixel)", f.width(), f.height(),
                           tris.vertices());
    src.impulses.validate(where, "impulses", std::numeric_limits<double>::min(),
                          c::kGaborMaxImpulses, "0 < impulses <= 256", f.width(), f.height(),
                          tris.vertices());
  }
  template <class Out>
  static void check_out(const frame& f, const Out& out) {
    if (out.width != f.width() || out.height != f.height() || !out.data)
      detail::throw_out_of_range("hush::npr_gabor::render", "out size",
                                 std::to_string(out.width) + "x" + std::to_string(out.height),
                                 "the frame's size (non-null)");
  }

  // Triangle t's screen positions s, depths z, twice its signed screen area `cross` (y down)
  // and its orientation `facing`; false when it emits nothing whatever its winding (a vertex
  // at depth 0 or with a non-finite value).
  static bool orientation(const triangle_list& tris, std::size_t t, dvec2 (&s)[3], double (&z)[3],
                          double& cross, double& facing) {
    // A vertex behind the camera (depth < 0) has its screen position clip xy / w with w < 0,
    // so (z s, z) is its clip (xy, w) through the viewport, affine in object space.
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t k = tris.indices[3 * t + static_cast<std::size_t>(i)];
      s[i] = {static_cast<double>(tris.screen[k].x), static_cast<double>(tris.screen[k].y)};
      z[i] = static_cast<double>(tris.depth[k]);
      // Depth 0 has no screen position ((z s, z) = 0 loses clip xy): emits nothing.
      if (!(z[i] != 0.0) || !std::isfinite(z[i]) || !std::isfinite(s[i].x) ||
          !std::isfinite(s[i].y))
        return false;
    }
    // Twice the signed area, y down (counter-clockwise on the displayed image: negative). In
    // homogeneous coordinates the orientation is det(z_i (s_i, 1)) = z0 z1 z2 cross: with a
    // vertex behind the camera (negative z) the projected triangle is turned over.
    const double e1x = s[1].x - s[0].x, e1y = s[1].y - s[0].y;
    const double e2x = s[2].x - s[0].x, e2y = s[2].y - s[0].y;
    cross = e1x * e2y - e1y * e2x;
    facing = z[0] * z[1] * z[2] < 0.0 ? -cross : cross;
    return true;
  }
  // Whether orientation `facing` is params::front_face's (NaN: not).
  bool is_front(double facing) const {
    return p_.front_face == npr_gabor_front_face::counter_clockwise ? facing < 0.0 : facing > 0.0;
  }

  // Stage 1 for triangle t: appends its points' records (npr_gabor/tree.hpp's
  // sequence, walked depth first, culled per subtree, then sorted by J);
  // counts the nodes examined in *nodes if given.
  void triangle_splats(const frame& f, const triangle_list& tris, std::size_t t,
                       std::vector<npr_gabor_splat>& splats, const point_parameters& pp,
                       std::uint64_t* nodes) const {
    dvec2 s[3];
    double z[3], cross = 0, facing = 0;
    if (!orientation(tris, t, s, z, cross, facing)) return;
    if (p_.cull_back_faces && !is_front(facing)) return;
    if (!(cross != 0.0) || !std::isfinite(cross)) return;
    const double far = std::max({z[0], z[1], z[2]}), near = std::min({z[0], z[1], z[2]});
    if (!(far > 0.0)) return;  // entirely behind the camera
    // Crossing (or nearly touching) the near plane: the nodes are clipped at w_near.
    const bool crossing = near < detail::constants::kNprGaborNearFraction * far;
    const double w_near = crossing ? detail::constants::kNprGaborNearFraction * far : 0.0;
    // The share t of the count per node in the squared weights (constants.hpp): 1 with
    // params::local_density or crossing, else ramping up with the depth ratio far / near.
    namespace c = detail::constants;
    double blend = 1.0;
    if (!p_.local_density && !crossing)  // most triangles: ratio <= 4, no logarithm
      blend =
          far > c::kNprGaborPerNodeRatioLow * near
              ? std::clamp(std::log(far / (near * c::kNprGaborPerNodeRatioLow)) /
                               std::log(c::kNprGaborPerNodeRatioHigh / c::kNprGaborPerNodeRatioLow),
                           0.0, 1.0)
              : 0.0;
    const std::uint32_t object = tris.object_of(t), id = tris.triangle_id[t];
    const std::uint32_t* vertices = &tris.indices[3 * t];
    const double cull = pp.off_image_radius(object, vertices);
    const double w = static_cast<double>(f.width()), h = static_cast<double>(f.height());
    // The screen position of barycentrics b (of the root triangle): perspective-correct
    // (for b in front of the camera).
    const auto project = [&](const double* b) {
      const double hw = b[0] * z[0] + b[1] * z[1] + b[2] * z[2];
      return dvec2{(b[0] * z[0] * s[0].x + b[1] * z[1] * s[1].x + b[2] * z[2] * s[2].x) / hw,
                   (b[0] * z[0] * s[0].y + b[1] * z[1] * s[1].y + b[2] * z[2] * s[2].y) / hw};
    };
    // The part of a node (corners in root barycentrics) at depth >= w_near, projected into
    // `out`: 0 corners (behind), 3 (the node in front, or one corner in front) or 4. Exact:
    // depth and clip xy are affine in the barycentrics, so that part is the convex polygon
    // of the corners in front and the edges' crossings of w_near, and (all its depths >=
    // w_near > 0) it projects onto the polygon of their projections. `whole`: every corner
    // is in front (the node is not crossing).
    const auto clip_near = [&](const double(&corner)[3][3], dvec2(&out)[4], bool& whole) {
      double d[3];
      for (unsigned i = 0; i < 3; ++i)
        d[i] = corner[i][0] * z[0] + corner[i][1] * z[1] + corner[i][2] * z[2] - w_near;
      int m = 0;
      whole = d[0] >= 0.0 && d[1] >= 0.0 && d[2] >= 0.0;
      for (unsigned i = 0; i < 3; ++i) {
        const unsigned j = (i + 1) % 3;
        if (d[i] >= 0.0) out[m++] = project(corner[i]);
        if ((d[i] < 0.0) != (d[j] < 0.0)) {
          const double u = d[i] / (d[i] - d[j]);
          double b[3];
          for (unsigned k = 0; k < 3; ++k) b[k] = corner[i][k] + u * (corner[j][k] - corner[i][k]);
          out[m++] = project(b);
        }
      }
      return m;
    };
    detail::npr_tree_node root;
    dvec2 clipped[4];
    int clipped_corners = 3;
    if (crossing) {
      bool whole = false;
      clipped_corners = clip_near(root.corner, clipped, whole);
      if (clipped_corners == 0 || !box_meets_image(clipped, clipped_corners, cull, w, h)) return;
    } else if (!box_meets_image(s, cull, w, h)) {
      return;
    }
    // The object-space centroid (b = 1/3 each) and its pixel, sum z_i s_i / sum z_i (none
    // where it is not in front of the camera: the source's constant).
    const double zs = z[0] + z[1] + z[2], third = 1.0 / 3.0;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double lambda =
        pp.density({object,
                    zs > 0.0 ? (z[0] * s[0].x + z[1] * s[1].x + z[2] * s[2].x) / zs : nan,
                    zs > 0.0 ? (z[0] * s[0].y + z[1] * s[1].y + z[2] * s[2].y) / zs : nan,
                    vertices,
                    {third, third, third}},
                   w, h);
    // N = lambda A; crossing the near plane, A is unbounded: n is the clipped part's count
    // (the local walk's bound on every descendant's count).
    const double n =
        lambda * (crossing ? polygon_area(clipped, clipped_corners) : 0.5 * std::fabs(cross));
    // The triangle's plane: 1/z affine in screen space, 1/z = q0 + qx x + qy y
    // (screen barycentrics of (x, y) weight the 1/z_i).
    const double inv = 1.0 / cross;
    const double e1x = s[1].x - s[0].x, e1y = s[1].y - s[0].y;
    const double e2x = s[2].x - s[0].x, e2y = s[2].y - s[0].y;
    const double d1 = 1.0 / z[1] - 1.0 / z[0], d2 = 1.0 / z[2] - 1.0 / z[0];
    const double qx = (d1 * e2y - d2 * e1y) * inv, qy = (d2 * e1x - d1 * e2x) * inv;
    const double q0 = 1.0 / z[0] - qx * s[0].x - qy * s[0].y;
    // Emits the point J at pt, of squared-weight factor `weight` and density `lam`, if its
    // pixel range is not empty.
    const auto emit = [&](const point& pt, std::uint64_t j, double weight, double lam) {
      const dvec2 at = project(pt.b);
      const point_parameters::kernel k =
          pp.at({object, at.x, at.y, vertices, {pt.b[0], pt.b[1], pt.b[2]}}, pt.angle, lam);
      const double r = k.radius;
      // Pixel centres x + 1/2 within r of the point, clamped to the image.
      const double x0 = std::max(std::ceil(at.x - r - 0.5), 0.0);
      const double x1 = std::min(std::floor(at.x + r - 0.5), w - 1.0);
      const double y0 = std::max(std::ceil(at.y - r - 0.5), 0.0);
      const double y1 = std::min(std::floor(at.y + r - 0.5), h - 1.0);
      if (x0 > x1 || y0 > y1) return;
      npr_gabor_splat rec;
      rec.x = at.x;
      rec.y = at.y;
      rec.fx = k.F.x;
      rec.fy = k.F.y;
      rec.bandwidth = k.bandwidth;
      rec.radius = r;
      rec.weight = weight * pt.amplitude * k.scale;
      rec.q0 = q0;
      rec.qx = qx;
      rec.qy = qy;
      rec.object = object;
      rec.triangle = id;
      rec.x0 = static_cast<std::int32_t>(x0);
      rec.x1 = static_cast<std::int32_t>(x1);
      rec.y0 = static_cast<std::int32_t>(y0);
      rec.y1 = static_cast<std::int32_t>(y1);
      rec.index = j;
      splats.push_back(rec);
    };
    // Whether a node's screen triangle (its corners projected: exact under
    // perspective, every point of its subtree lies in it) grown by `cull` meets
    // the image (bounding box: conservative; the points' own pixel-range test
    // decides, with half a pixel to spare for the rounding of a position).
    const auto meets_image = [&](const detail::npr_tree_node& nd) {
      const dvec2 c[3] = {project(nd.corner[0]), project(nd.corner[1]), project(nd.corner[2])};
      return box_meets_image(c, cull, w, h);
    };
    root.seed = triangle_key(object, id);
    const std::size_t first_record = splats.size();
    // J order, whatever the traversal (CPU and GPU stage 1 agree on it).
    const auto sort_records = [&] {
      std::sort(
          splats.begin() + static_cast<std::ptrdiff_t>(first_record), splats.end(),
          [](const npr_gabor_splat& x, const npr_gabor_splat& y) { return x.index < y.index; });
    };
    npr_gabor_lod lod = npr_gabor_lod::of(crossing ? 0.0 : n);
    if (p_.thinning && n < 1.0 && lod.count == 1)
      lod.first_weight = std::sqrt(npr_gabor_lod::thinned_square(n, thinning_uniform(object, id)));
    // Strong perspective, or crossing the near plane (N = lambda A unbounded): the count per
    // node, whatever params::local_density says (docs/npr-gabor.md "Triangles crossing the near
    // plane").
    if (blend > 0.0) {
      local_walk(root, n, lambda, pp, object, id, vertices, w, h, cull, project, emit, nodes,
                 crossing ? &clip_near : nullptr, blend, lod);
      sort_records();
      return;
    }
    if (!(lod.first_weight > 0.0)) return;  // thinned away
    if (lod.count == 0) return;
    if (nodes) ++*nodes;
    if (lod.count == 1) {  // the common small triangle: its root alone, no walk
      emit(node_point(root, detail::npr_tree_words_of(root.seed)), 0, lod.first_weight, lambda);
      return;
    }
    // Depth first with an explicit stack: a node is visited only if its index
    // is below the count (then its own point is emitted), a child pushed only
    // if it meets the image. Indices below 2^41 (kNprGaborMaxPoints) mean depth
    // <= 21 ((4^k - 1) / 3 <= J), and the stack holds at most 3 siblings per
    // level above the node popped plus its 4 children: 3 * 21 + 4 < 72.
    detail::npr_tree_node stack[kStackNodes];
    std::size_t top = 0;
    stack[top++] = root;
    while (top > 0) {
      const detail::npr_tree_node nd = stack[--top];
      const detail::npr_tree_words words = detail::npr_tree_words_of(nd.seed);
      emit(node_point(nd, words), nd.index, lod.weight(nd.index), lambda);
      for (unsigned slot = 0; slot < 4; ++slot) {
        // index + stride (1 + slot) grows with slot: the first one past the count ends.
        if (nd.index + nd.stride * (1u + slot) >= lod.count) break;
        const detail::npr_tree_node child = detail::npr_tree_child(nd, words, slot);
        if (nodes) ++*nodes;
        if (meets_image(child)) stack[top++] = child;
      }
    }
    sort_records();
  }

  // Whether the bounding box of screen triangle c grown by `cull` meets the w x h image: the
  // triangle test, and the subtree test of both walks (a node's projected corners: exact under
  // perspective, every point of its subtree lies in their triangle; a box is conservative, and
  // the points' own pixel-range test decides).
  static bool box_meets_image(const dvec2 (&c)[3], double cull, double w, double h) {
    return !(std::max({c[0].x, c[1].x, c[2].x}) + cull < 0.0 ||
             std::min({c[0].x, c[1].x, c[2].x}) - cull > w ||
             std::max({c[0].y, c[1].y, c[2].y}) + cull < 0.0 ||
             std::min({c[0].y, c[1].y, c[2].y}) - cull > h);
  }
  // The same for a convex polygon of m (1 ... 4) corners (a node clipped at the near plane).
  static bool box_meets_image(const dvec2 (&c)[4], int m, double cull, double w, double h) {
    double x0 = c[0].x, x1 = c[0].x, y0 = c[0].y, y1 = c[0].y;
    for (int i = 1; i < m; ++i) {
      x0 = std::min(x0, c[i].x);
      x1 = std::max(x1, c[i].x);
      y0 = std::min(y0, c[i].y);
      y1 = std::max(y1, c[i].y);
    }
    return !(x1 + cull < 0.0 || x0 - cull > w || y1 + cull < 0.0 || y0 - cull > h);
  }
  // The area of a convex polygon of m corners (shoelace).
  static double polygon_area(const dvec2 (&c)[4], int m) {
    double a = 0.0;
    for (int i = 0; i < m; ++i) {
      const dvec2& p = c[i];
      const dvec2& q = c[(i + 1) % m];
      a += p.x * q.y - q.x * p.y;
    }
    return 0.5 * std::fabs(a);
  }

  // The paper's walk reaches depth 21 at most (its indices are below 2 kNprGaborMaxPoints =
  // 2^41 and depth k starts at J = (4^k - 1) / 3); the local-density walk stops there too,
  // and its stack then holds at most 3 siblings per level above the node popped plus its 4
  // children: 3 * 21 + 4 < kStackNodes.
  static constexpr int kMaxDepth = 21;
  static constexpr std::size_t kStackNodes = 72;
  static_assert(3 * kMaxDepth + 4 < static_cast<int>(kStackNodes), "walk stack too small");
  static_assert((std::uint64_t{1} << (2 * kMaxDepth)) / 3 <
                    static_cast<std::uint64_t>(2.0 * detail::constants::kNprGaborMaxPoints),
                "kMaxDepth is the paper walk's deepest level");

  // Stage 1 of one triangle under params::local_density (docs/npr-gabor.md "Local
  // density"): depth first from the root, each node P with n_P = lambda_P A_P (A_P the
  // area of its projected corners: the projective image of a triangle is the triangle of
  // its projected corners; lambda_P the density at its object-space centroid) emits its own
  // point with weight sqrt(local_square(n_P)) where that is > 0 (n_P in (1/4, 4); the root:
  // n < 4, thinned as the paper's N < 1 point when params::thinning; the deepest level,
  // kMaxDepth: n > 1/4, carrying the levels below it, reached only for n_root above ~4^21).
  // A child is visited only if its parent's n_P > 1/4 (a child's projected area is at most
  // its parent's, so with one density every descendant then has n <= 1/4, h = 0: the cut is
  // exact; with per-pixel or per-vertex densities, a child whose density exceeds its
  // parent's by 4x could be missed) and it meets the image. The root's n and density are
  // the triangle's (n, lambda).
  // A triangle crossing the near plane (clip_near given: a node's part at depth >= w_near,
  // projected, see triangle_splats) has three kinds of nodes: in front (every corner at
  // w >= w_near: as above, its projected triangle exact), behind (every corner at w <=
  // w_near and one below: dropped with its subtree) and crossing (corners on both sides: its
  // projection is unbounded, so its count n is infinite and its own point has weight 0, the
  // hat's value there; its n above is its clipped part's, which bounds every descendant's
  // count, since their parts in front lie in it, so the cut at n <= 1/4 stays exact, and it
  // is culled by that part's projection). The root's n is then its clipped part's too.
  template <class Project, class Emit, class ClipNear>
  void local_walk(const detail::npr_tree_node& root, double n_root, double lambda_root,
                  const point_parameters& pp, std::uint32_t object, std::uint32_t id,
                  const std::uint32_t* vertices, double w, double h, double cull,
                  const Project& project, const Emit& emit, std::uint64_t* nodes,
                  const ClipNear* clip_near, double blend, const npr_gabor_lod& lod) const {
    constexpr std::uint64_t finest_stride = std::uint64_t{1} << (2 * kMaxDepth);
    struct entry {
      detail::npr_tree_node node;
      double n, lambda;
      bool crossing;
    };
    entry stack[kStackNodes];
    std::size_t top = 0;
    stack[top++] = {root, n_root, lambda_root, clip_near != nullptr};
    if (nodes) ++*nodes;
    while (top > 0) {
      const entry e = stack[--top];
      const detail::npr_tree_node& nd = e.node;
      const bool coarsest = nd.stride == 1, finest = nd.stride == finest_stride;
      double f = e.crossing ? 0.0 : npr_gabor_lod::local_square(e.n, coarsest, finest);
      if (coarsest && p_.thinning && e.n < 1.0 && !e.crossing)
        f = npr_gabor_lod::thinned_square(e.n, thinning_uniform(object, id));
      // Blended with the per-triangle LOD's squared weight (its nodes: index below its count).
      const bool paper = blend < 1.0;
      if (paper) {
        const double wp = nd.index < lod.count ? lod.weight(nd.index) : 0.0;
        f = blend * f + (1.0 - blend) * wp * wp;
      }
      const bool descend = !finest && ((e.n > 0.25) || (paper && nd.index + nd.stride < lod.count));
      if (!(f > 0.0) && !descend) continue;  // the root of n <= 0 only
      const detail::npr_tree_words words = detail::npr_tree_words_of(nd.seed);
      if (f > 0.0) emit(node_point(nd, words), nd.index, std::sqrt(f), e.lambda);
      if (!descend) continue;
      for (unsigned slot = 0; slot < 4; ++slot) {
        const detail::npr_tree_node child = detail::npr_tree_child(nd, words, slot);
        if (nodes) ++*nodes;
        // Its corners projected once: its area, and its bounding box grown by `cull` against
        // the image (as the paper's walk's meets_image). Near the near plane: its part in front.
        dvec2 c[4];
        int m = 3;
        bool whole = true;
        if (e.crossing) {
          m = (*clip_near)(child.corner, c, whole);
          if (m == 0) continue;  // behind: nothing of its subtree is in front
        } else {
          for (unsigned i = 0; i < 3; ++i) c[i] = project(child.corner[i]);
        }
        const bool crossing = !whole;
        double lam = lambda_root;
        if (!pp.constant_density()) {
          double b[3];
          for (unsigned k = 0; k < 3; ++k)
            b[k] = (child.corner[0][k] + child.corner[1][k] + child.corner[2][k]) / 3.0;
          const dvec2 at =
              crossing ? c[0] : project(b);  // a crossing node's centroid may be behind
          lam = pp.density({object, at.x, at.y, vertices, {b[0], b[1], b[2]}}, w, h);
        }
        const double n = lam * (m == 3 ? 0.5 * std::fabs((c[1].x - c[0].x) * (c[2].y - c[0].y) -
                                                         (c[1].y - c[0].y) * (c[2].x - c[0].x))
                                       : polygon_area(c, m));
        // h = 0 here and below (one density): nothing to emit, unless the LOD's index is.
        if (!(n > 0.25) && !(paper && child.index < lod.count)) continue;
        if (!box_meets_image(c, m, cull, w, h)) continue;
        stack[top++] = {child, n, lam, crossing};
      }
    }
  }

  params p_;
  gabor_kernel<2> kernel_;
  double lambda_ = 0, scale_ = 0;
};

}  // namespace hush

#endif  // HUSH_NPR_GABOR_HPP
