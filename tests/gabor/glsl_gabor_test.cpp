// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Gabor noise on the GLSL backend (hush/glsl/gabor_glsl.hpp) against the
// CPU, through hush::evaluate: points, grids and samples with footprints, 2D
// and 3D, every kind, values and gradients, hard cases.
//
// Tolerances (hush/glsl/gabor_glsl.hpp): the CPU float result and the GLSL
// result are each within gabor.hpp's float budget of the double reference,
// budget = scale 2^-21 (1 + 2 pi Phi) (N' + 1) (each op's rounding bounded
// by 2^-24 relative, which a fused op also meets), so they differ by at most
// twice it; gradients by that times (1 + the kernel's slope bound per cell,
// (2A + 2 pi Phi + 3 / (1 - s0)) / r). Filtered samples add the float filter
// (Jacobi in float instead of double): Q and M within ~2^-21 relative, which
// moves each kernel's phase by 2 pi Phi 2^-21 and its attenuation exponent
// Phi^2 pi^2 / A 2^-21: the budget times (1 + 2 pi Phi + pi^2 Phi^2 / A).
// Any differing Poisson count or impulse mark would move a value by up to a
// whole kernel (~scale), far beyond these tolerances.
// Points and grids each take the CPU's float form (gabor<D>::eval): points the
// point form, grids the separable form. Both forms are within the budget of
// the double reference (gabor_test), and GLSL repeats either operation by
// operation, so the tolerances are the same for both; that GLSL takes the
// right form is checked apart: its values lie nearer the CPU's same form than
// the other one (the two differ by rounding only, docs/gabor.md "Float accuracy").
// That check takes anisotropic noise, whose frequency vector is a uniform, the
// same float on any GPU; the other kinds' frequencies come from sin/cos
// polynomials, sqrt and sums of products, which a GPU may fuse or round
// otherwise (GLSL 4.30 sec. 4.7.1), moving every kernel's phase by a few
// 2 pi Phi 2^-24: as much as the two forms differ (on llvmpipe, 3D hybrid
// points lie 5.2e-4 from the CPU's point form summed over 3000 points, 6.3e-4
// from its separable form; the other kinds 0 and 3.3e-4 ... 3.9e-4).
//
// NPR Gabor noise's splatting on GLSL (hush/glsl/npr_gabor.hpp; the cases named "npr"):
// point sprites against the double and float CPU renders of the npr test scenes, with the
// tolerance derived at npr_bound below.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "glsl/glsl_test_util.hpp"
#include "hush/glsl/npr_gabor/renderer.hpp"
#include "npr_gabor/npr_gabor_scenes.hpp"

namespace {

using hush_glsl_test::headless;

constexpr double kPi = hush::detail::constants::kPi;

template <int D>
typename hush::gabor<D>::params params_of(hush::gabor_kind kind) {
  typename hush::gabor<D>::params p;
  p.seed = 21;
  p.kind = kind;
  p.frequency = 1.3;
  p.orientation = 0.6;
  p.elevation = 0.3;
  if (kind == hush::gabor_kind::hybrid) {
    p.orientation_spread = 1.5;
    p.frequency_spread = 0.8;
  }
  return p;
}

template <int D>
double phi_max(const hush::gabor<D>& g) {
  return g.marks().phi0() + g.marks().dphi();
}
template <int D>
double value_tolerance(const hush::gabor<D>& g) {
  return 2 * g.scale() * std::ldexp(1.0, -21) * (1 + 2 * kPi * phi_max(g)) *
         (g.parameters().impulses + 1);
}
template <int D>
double gradient_tolerance(const hush::gabor<D>& g) {
  const double a = g.kernel().envelope_exponent();
  const double slope =
      (2 * a + 2 * kPi * phi_max(g) + 3 / (1 - hush::detail::constants::kGaborTaperStart)) *
      g.inverse_cell();
  return value_tolerance(g) * (1 + slope);
}
template <int D>
double filter_factor(const hush::gabor<D>& g) {
  const double phi = phi_max(g), a = g.kernel().envelope_exponent();
  return 1 + 2 * kPi * phi + kPi * kPi * phi * phi / a;
}

// Anisotropic noise: every impulse's float frequency is the uniform, the same on any GPU
// (file comment: the check of the form).
template <int D>
bool exact_marks(const hush::gabor<D>& g) {
  return g.parameters().kind == hush::gabor_kind::anisotropic;
}

struct diff {
  double value = 0, grad = 0;
  std::size_t nan_mismatch = 0;
};

template <int D>
diff compare(const std::vector<float>& v, const std::vector<hush::vec<float, D>>& g,
             const std::vector<float>& w, const std::vector<hush::vec<float, D>>& h) {
  diff r;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (std::isnan(v[i]) || std::isnan(w[i])) {
      r.nan_mismatch += std::isnan(v[i]) != std::isnan(w[i]);
      continue;
    }
    r.value = std::max(r.value, std::fabs(double(v[i]) - w[i]));
    for (int a = 0; a < D; ++a) r.grad = std::max(r.grad, std::fabs(double(g[i][a]) - h[i][a]));
  }
  return r;
}

// A random 3D footprint of width 10^lo ... 10^hi noise units (two random derivatives).
hush::footprint<3> random_footprint(hush::rng& r, double lo, double hi) {
  const double s = std::pow(10.0, r.uniform<double>(lo, hi));
  hush::vec<double, 3> dx, dy;
  for (int a = 0; a < 3; ++a) {
    dx[a] = s * r.uniform<double>(-1, 1);
    dy[a] = s * r.uniform<double>(-1, 1);
  }
  return hush::footprint<3>::from_derivatives(dx, dy);
}

// Sum over non-NaN samples of |glsl - a| and of |glsl - b|.
std::pair<double, double> distances(const std::vector<float>& glsl, const std::vector<float>& a,
                                    const std::vector<float>& b) {
  double da = 0, db = 0;
  for (std::size_t i = 0; i < glsl.size(); ++i) {
    if (std::isnan(glsl[i])) continue;
    da += std::fabs(double(glsl[i]) - a[i]);
    db += std::fabs(double(glsl[i]) - b[i]);
  }
  return {da, db};
}

template <int D>
void check_points(const hush::gabor<D>& noise) {
  auto pts = hush_glsl_test::random_points<D>(3000, 5);
  pts[7][0] = std::numeric_limits<float>::quiet_NaN();
  pts[11][D - 1] = std::numeric_limits<float>::infinity();
  const std::size_t n = pts.size();
  std::vector<float> cv(n), gv(n), gv_only(n);
  std::vector<hush::vec<float, D>> cg(n), gg(n);
  hush::evaluate(noise, hush::exec::scalar, hush::span<const hush::vec<float, D>>(pts),
                 hush::span<float>(cv), hush::span<hush::vec<float, D>>(cg));
  hush::evaluate(noise, hush::exec::glsl{headless().device},
                 hush::span<const hush::vec<float, D>>(pts), hush::span<float>(gv),
                 hush::span<hush::vec<float, D>>(gg));
  hush::evaluate(noise, hush::exec::glsl{headless().device},
                 hush::span<const hush::vec<float, D>>(pts), hush::span<float>(gv_only));
  // The double reference and the CPU's separable (grid) form at the same points.
  std::vector<float> sep(n);
  double ref_value = 0, ref_grad = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const hush::vec<double, D> p = hush::vec_cast<double>(pts[i]);
    sep[i] = noise.template grid_sample<float>(p).value;
    const auto ref = noise.template value_and_gradient<double>(p);
    if (std::isnan(ref.value)) continue;
    ref_value = std::max(ref_value, std::fabs(gv[i] - ref.value));
    for (int a = 0; a < D; ++a)
      ref_grad = std::max(ref_grad, std::fabs(gg[i][a] - ref.gradient[a]));
  }
  const diff d = compare<D>(cv, cg, gv, gg);
  const diff d_only = compare<D>(cv, cg, gv_only, gg);
  const auto [to_point, to_separable] = distances(gv, cv, sep);
  MESSAGE("points " << D << "D kind " << int(noise.parameters().kind) << ": max |value diff| "
                    << d.value << " (tolerance " << value_tolerance(noise) << "), gradient "
                    << d.grad << " (" << gradient_tolerance(noise) << "); against the double "
                    << ref_value << " (" << value_tolerance(noise) / 2 << "), gradient " << ref_grad
                    << " (" << gradient_tolerance(noise) / 2 << "); sum |GLSL - CPU point form| "
                    << to_point << ", separable form " << to_separable);
  CHECK(std::isnan(gv[7]));
  CHECK(std::isnan(gv[11]));
  CHECK(d.nan_mismatch == 0);
  CHECK(d.value <= value_tolerance(noise));
  CHECK(d.grad <= gradient_tolerance(noise));
  CHECK(d_only.value <= value_tolerance(noise));
  // value_tolerance is twice the budget (CPU float against GLSL): one against the double.
  CHECK(ref_value <= value_tolerance(noise) / 2);
  CHECK(ref_grad <= gradient_tolerance(noise) / 2);
  // The point form: nearer the CPU's point form than its separable form.
  if (exact_marks(noise)) CHECK(to_point < to_separable);
}

template <int D>
void check_grid(const hush::gabor<D>& noise, const hush::grid<D>& gr) {
  const std::size_t n = gr.count();
  std::vector<float> cv(n), gv(n);
  std::vector<hush::vec<float, D>> cg(n), gg(n);
  hush::evaluate_grid(noise, hush::exec::scalar, gr, hush::span<float>(cv),
                      hush::span<hush::vec<float, D>>(cg));
  hush::evaluate_grid(noise, hush::exec::glsl{headless().device}, gr, hush::span<float>(gv),
                      hush::span<hush::vec<float, D>>(gg));
  // The CPU's point form at the grid's positions (C order, i fastest).
  std::vector<float> pt(n);
  gr.for_each_in_slab(0, gr.size[D - 1], [&](std::size_t idx, const hush::vec<double, D>& p) {
    pt[idx] = noise.template value<float>(p);
  });
  const diff d = compare<D>(cv, cg, gv, gg);
  const auto [to_separable, to_point] = distances(gv, cv, pt);
  MESSAGE("grid " << D << "D: max |value diff| " << d.value << ", gradient " << d.grad
                  << "; sum |GLSL - CPU separable form| " << to_separable << ", point form "
                  << to_point);
  CHECK(d.nan_mismatch == 0);
  CHECK(d.value <= value_tolerance(noise));
  CHECK(d.grad <= gradient_tolerance(noise));
  // The separable form: nearer the CPU's grid than its point form.
  if (exact_marks(noise)) CHECK(to_separable < to_point);
}

}  // namespace

TEST_CASE("gabor glsl: points equal the CPU within the float tolerance, every kind, 2D and 3D") {
  for (const auto kind :
       {hush::gabor_kind::isotropic, hush::gabor_kind::anisotropic, hush::gabor_kind::hybrid}) {
    check_points(hush::gabor<2>(params_of<2>(kind)));
    check_points(hush::gabor<3>(params_of<3>(kind)));
  }
}

TEST_CASE("gabor glsl: grids (CPU-split cells) equal the CPU, near and far") {
  hush::grid<2> g2;
  g2.origin = {-3.25, 1e5};
  g2.step = {0.043, -0.051};
  g2.size = {97, 61};
  check_grid(hush::gabor<2>(params_of<2>(hush::gabor_kind::hybrid)), g2);
  check_grid(hush::gabor<2>(params_of<2>(hush::gabor_kind::anisotropic)), g2);
  hush::grid<3> g3;
  g3.origin = {0.5, -2e6, 7.0};
  g3.step = {0.11, 0.07, -0.13};
  g3.size = {23, 17, 11};
  check_grid(hush::gabor<3>(params_of<3>(hush::gabor_kind::isotropic)), g3);
  check_grid(hush::gabor<3>(params_of<3>(hush::gabor_kind::anisotropic)), g3);
}

// The mark a program reads to tell a grid from points (compute_source.hpp): every
// grid runner, plain (Perlin) or banded (Gabor), defines HUSH_GRID; no other runner does.
TEST_CASE("gabor glsl: only grid runners #define HUSH_GRID, plain and banded programs alike") {
  using hush::glsl::batch_layout;
  const std::string mark = "#define HUSH_GRID";
  for (const auto layout : {batch_layout::points, batch_layout::grid, batch_layout::samples})
    for (const bool gradient : {false, true}) {
      const bool grid = layout == batch_layout::grid;
      CHECK((hush::glsl::compute_source<hush::perlin<2>>(layout, gradient).find(mark) !=
             std::string::npos) == grid);
      CHECK((hush::glsl::compute_source<hush::gabor<3>>(layout, gradient).find(mark) !=
             std::string::npos) == grid);
    }
}

TEST_CASE("gabor glsl: filtered samples equal the CPU, degenerate footprints stay finite") {
  const hush::gabor<2> noise(params_of<2>(hush::gabor_kind::anisotropic));
  const std::size_t n = 1200;
  std::vector<hush::vec2> pos(n);
  std::vector<hush::footprint<2>> fps(n);
  hush::rng r(77);
  for (std::size_t i = 0; i < n; ++i) {
    pos[i] = {r.uniform<float>(-30.0f, 30.0f), r.uniform<float>(-30.0f, 30.0f)};
    const double s = std::pow(10.0, r.uniform<double>(-3.0, 1.0));  // 0.001 ... 10 noise units
    const hush::vec<double, 2> dx{s * r.uniform<double>(-1, 1), s * r.uniform<double>(-1, 1)};
    const hush::vec<double, 2> dy{s * r.uniform<double>(-1, 1), s * r.uniform<double>(-1, 1)};
    fps[i] = hush::footprint<2>::from_derivatives(dx, dy);
  }
  // HARD_CASES row 12 at the front: zero, rank 1, det 1e-30 and 1e30 (scaled), NaN.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  fps[0] = hush::footprint<2>::from_derivatives(hush::vec<double, 2>{0, 0}, {0, 0});
  fps[1] = hush::footprint<2>::from_derivatives(hush::vec<double, 2>{0.3, 0.2}, {0.6, 0.4});
  fps[2] = hush::footprint<2>::from_derivatives(hush::vec<double, 2>{1e-15, 0}, {0, 1e-15});
  fps[3] = hush::footprint<2>::from_derivatives(hush::vec<double, 2>{1e15, 0}, {0, 1e15});
  fps[4] = hush::footprint<2>::from_derivatives(hush::vec<double, 2>{nan, 0}, {0, 1});
  fps[5] = hush::footprint<2>::from_derivatives(hush::vec<double, 2>{1e6, 1e6}, {1e6, 1e6});
  const hush::samples<2> s{pos, fps, {}};
  std::vector<float> cv(n), gv(n);
  std::vector<hush::vec2> cg(n), gg(n);
  hush::evaluate(noise, hush::exec::scalar, s, hush::span<float>(cv), hush::span<hush::vec2>(cg));
  hush::evaluate(noise, hush::exec::glsl{headless().device}, s, hush::span<float>(gv),
                 hush::span<hush::vec2>(gg));
  for (std::size_t i = 0; i < 6; ++i) {
    INFO("hard footprint " << i);
    CHECK(std::isfinite(gv[i]));
    CHECK(std::isfinite(gg[i][0]));
    CHECK(std::isfinite(gg[i][1]));
  }
  const diff d = compare<2>(cv, cg, gv, gg);
  const double vt = value_tolerance(noise) * filter_factor(noise);
  const double gt = gradient_tolerance(noise) * filter_factor(noise);
  MESSAGE("filtered samples: max |value diff| " << d.value << " (tolerance " << vt << "), gradient "
                                                << d.grad << " (" << gt << ")");
  CHECK(d.nan_mismatch == 0);
  CHECK(d.value <= vt);
  CHECK(d.grad <= gt);
}

TEST_CASE("gabor glsl: 3D filtered samples equal the CPU") {
  const hush::gabor<3> noise(params_of<3>(hush::gabor_kind::hybrid));
  const std::size_t n = 400;
  std::vector<hush::vec3> pos(n);
  std::vector<hush::footprint<3>> fps(n);
  hush::rng r(78);
  for (std::size_t i = 0; i < n; ++i) {
    pos[i] = {r.uniform<float>(-9.0f, 9.0f), r.uniform<float>(-9.0f, 9.0f),
              r.uniform<float>(-9.0f, 9.0f)};
    fps[i] = random_footprint(r, -3.0, 0.5);
  }
  std::vector<float> cv(n), gv(n);
  std::vector<hush::vec3> cg(n), gg(n);
  hush::evaluate(noise, hush::exec::scalar, hush::samples<3>{pos, fps, {}}, hush::span<float>(cv),
                 hush::span<hush::vec3>(cg));
  hush::evaluate(noise, hush::exec::glsl{headless().device}, hush::samples<3>{pos, fps, {}},
                 hush::span<float>(gv), hush::span<hush::vec3>(gg));
  const diff d = compare<3>(cv, cg, gv, gg);
  MESSAGE("3D filtered samples: max |value diff| " << d.value << ", gradient " << d.grad);
  CHECK(d.nan_mismatch == 0);
  CHECK(d.value <= value_tolerance(noise) * filter_factor(noise));
  CHECK(d.grad <= gradient_tolerance(noise) * filter_factor(noise));
}

namespace {

// Surface noise (samples with normals) against the double reference
// (gabor<3>::sample_value_and_gradient<double>). The surface sum is the 2D
// sum of the same kernel over the impulses in the slab (N' kernels reach a
// point on average, like the solid noise's), times the slab taper, so the
// float budget is the solid one with surface_scale: scale 2^-21 (1 + 2 pi Phi)
// (N' + 1), times filter_factor for the float filter of the projected
// footprint. The shader also forms the unit normal and the tangent frame in
// float (the CPU in double, rounded once): each within ~2^-21 relative, which
// moves an impulse's offsets (|d| < 2 surface cells = 2.5 kernel cells) by
// 2.5 2^-21 and its kernel by at most that times the kernel's slope bound per
// cell (2A + 2 pi Phi + 3 / (1 - s0)) plus the slab taper's (3 / (1 - s0)
// per h): frame_error below, per kernel, for N' + 1 kernels. GLSL and the
// double reference differ by at most the sum, except for the rare impulse
// whose direction is nearly the normal: its projected frequency is
// normalised by |P omega| (f = Phi / |P omega|), which magnifies the
// projection's rounding by 1 / |P omega| (probability ~x^2 / 2 that it
// exceeds 1 / x), on the CPU's float path as on GLSL; the bench's 262144
// surface samples reach 8e-5 on both (docs/gabor.md), far inside these
// tolerances (5e-3 ... 1.3e-2), which the samples here meet with ~1000x margin. A differing count, mark or
// kept impulse (beyond the tapered edges) would move a value by up to a whole
// kernel (~surface_scale), a wrong frame or normal by O(1).
double frame_error(const hush::gabor<3>& g) {
  namespace c = hush::detail::constants;
  const double a = g.kernel().envelope_exponent();
  const double taper = 3 / (1 - c::kGaborTaperStart);
  const double slope = 2 * a + 2 * kPi * phi_max(g) + taper +
                       taper * c::kGaborSurfaceCell / c::kGaborSurfaceSlab;
  return g.surface_scale() * (g.parameters().impulses + 1) * 2.5 * std::ldexp(1.0, -21) * slope;
}

void check_surface(const hush::gabor<3>& noise) {
  const std::size_t n = 500;
  std::vector<hush::vec3> pos(n), nrm(n);
  std::vector<hush::footprint<3>> fps(n);
  hush::rng r(79);
  for (std::size_t i = 0; i < n; ++i) {
    // Every fifth sample far out (1e5 ... 2e6 units); others near.
    const float extent = i % 5 == 4 ? 2e6f : 9.0f;
    for (int a = 0; a < 3; ++a) pos[i][a] = r.uniform<float>(-extent, extent);
    for (int a = 0; a < 3; ++a) nrm[i][a] = r.uniform<float>(-1.0f, 1.0f);
    // Half point samples (unfiltered surface noise), half footprints of 0.001 ... 3 units.
    fps[i] = i % 2 ? random_footprint(r, -3.0, 0.5) : hush::footprint<3>{};
  }
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  // Hard normals and footprints at the front: zero (the solid noise), NaN and
  // Inf (NaN), tiny and huge lengths, the basis's branch points (n.z = +-1, -0),
  // a NaN position; footprints zero, rank 1, NaN and huge (HARD_CASES row 12).
  const hush::vec3 hard[] = {{0, 0, 0},           {nan, 0, 1},          {0, inf, 0},
                             {1e-30f, -2e-30f, 3e-30f}, {1e30f, 3e30f, -2e30f}, {0, 0, -1},
                             {0, 0, 1},           {0.6f, 0.8f, -0.0f},  {0, 1, 0},
                             {0.3f, -0.4f, 0.5f}, {-1, 2, 0.5f},        {0.2f, 0.1f, -3}};
  for (std::size_t i = 0; i < std::size(hard); ++i) nrm[i] = hard[i];
  pos[8] = {nan, 1, 2};
  const double dnan = std::numeric_limits<double>::quiet_NaN();
  fps[9] = hush::footprint<3>::from_derivatives(hush::vec<double, 3>{0.3, 0.2, 0.1}, {0.6, 0.4, 0.2});
  fps[10] = hush::footprint<3>::from_derivatives(hush::vec<double, 3>{dnan, 0, 0}, {0, 1, 0});
  fps[11] = hush::footprint<3>::from_derivatives(hush::vec<double, 3>{1e15, 0, 0}, {0, 1e15, 0});
  const hush::samples<3> s{pos, fps, nrm};
  std::vector<float> gv(n), gv_only(n), cv(n);
  std::vector<hush::vec3> gg(n);
  hush::evaluate(noise, hush::exec::glsl{headless().device}, s, hush::span<float>(gv),
                 hush::span<hush::vec3>(gg));
  hush::evaluate(noise, hush::exec::glsl{headless().device}, s, hush::span<float>(gv_only));
  hush::evaluate(noise, hush::exec::scalar, s, hush::span<float>(cv));
  const double scale = std::max(noise.scale(), noise.surface_scale());
  const double cell = std::max(noise.inverse_cell(), noise.inverse_surface_cell());
  const double a = noise.kernel().envelope_exponent();
  // value_tolerance is twice the budget (CPU float against GLSL): one here.
  const double vt =
      value_tolerance(noise) / 2 * scale / noise.scale() * filter_factor(noise) + frame_error(noise);
  const double gt =
      vt * (1 + (2 * a + 2 * kPi * phi_max(noise) +
                 3 / (1 - hush::detail::constants::kGaborTaperStart)) *
                    cell);
  double worst = 0, worst_grad = 0, worst_cpu = 0;
  std::size_t nan_mismatch = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto ref = noise.sample_value_and_gradient<double>(s.at(i));
    INFO("sample " << i);
    if (std::isnan(ref.value)) {
      nan_mismatch += !std::isnan(gv[i]) || !std::isnan(gv_only[i]);
      continue;
    }
    nan_mismatch += !std::isfinite(gv[i]) || gv[i] != gv_only[i];
    worst = std::max(worst, std::fabs(gv[i] - ref.value));
    worst_cpu = std::max(worst_cpu, std::fabs(double(gv[i]) - cv[i]));
    for (int k = 0; k < 3; ++k)
      worst_grad = std::max(worst_grad, std::fabs(gg[i][k] - ref.gradient[k]));
  }
  MESSAGE("surface " << int(noise.parameters().kind) << ": max |GLSL - double| " << worst
                     << " (tolerance " << vt << "), gradient " << worst_grad << " (" << gt
                     << "); max |GLSL - CPU float| " << worst_cpu);
  CHECK(std::isnan(gv[1]));
  CHECK(std::isnan(gv[2]));
  CHECK(std::isnan(gv[8]));
  CHECK(nan_mismatch == 0);
  CHECK(worst <= vt);
  CHECK(worst_grad <= gt);
}

}  // namespace

TEST_CASE("gabor glsl: surface noise (normals) equals the double reference, every kind") {
  for (const auto kind :
       {hush::gabor_kind::isotropic, hush::gabor_kind::anisotropic, hush::gabor_kind::hybrid})
    check_surface(hush::gabor<3>(params_of<3>(kind)));
}

// ---- NPR Gabor noise: GLSL splatting (hush/glsl/npr_gabor.hpp).
namespace {

// Two objects: a slanted plane (object 1; 1/z = 0.5 + 0.002 x + 0.001 y, affine in screen
// space as on any plane) covering the frame, and in front of it a flat patch (object 2, depth
// 0.8, triangle ids from 100000) of 5 x 4 cells: depth discontinuities, object boundaries and
// triangle edges. Built from two npr_test::grid_scenes, merged into the first.
npr_test::grid_scene npr_two_objects(std::size_t w, std::size_t h) {
  auto inv_z = [](double x, double y) { return 0.5 + 0.002 * x + 0.001 * y; };
  npr_test::grid_scene sc = npr_test::covering(w, h, 14.0, 20.0);
  const npr_test::grid_scene front(w, h, 31.0, 42.0, 11.0, 5, 4, 0.8f);
  for (std::size_t v = 0; v < sc.screen.size(); ++v)
    sc.vdepth[v] = static_cast<float>(1.0 / inv_z(sc.screen[v].x, sc.screen[v].y));
  const auto base = static_cast<std::uint32_t>(sc.screen.size());
  sc.screen.insert(sc.screen.end(), front.screen.begin(), front.screen.end());
  sc.vdepth.insert(sc.vdepth.end(), front.vdepth.begin(), front.vdepth.end());
  for (std::uint32_t i : front.indices) sc.indices.push_back(i + base);
  for (std::uint32_t t : front.tri_id) {
    sc.tri_id.push_back(t + 100000u);
    sc.obj_id.push_back(2u);
  }
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const std::size_t p = y * w + x;
      sc.depth[p] = static_cast<float>(1.0 / inv_z(double(x) + 0.5, double(y) + 0.5));
      if (front.object[p] != 0u) {
        sc.depth[p] = front.depth[p];
        sc.object[p] = 2u;
        sc.triangle[p] = front.triangle[p] + 100000u;
      }
    }
  return sc;
}

// The GLSL tolerance of hush/glsl/npr_gabor.hpp against the double reference, per pixel p:
// S(p) (2 K + 2^-24 n(p)) with S(p) the sum of |weight| and n(p) the count of the kernels
// whose disc holds p's centre. K per unit weight: the kernel's float budget 2^-21 (1 + 2 pi
// F0 r) (gabor_kernel.hpp), plus the offsets: d = (c + k) / r is formed from a float c
// (|c| <= r + 1), so |delta d| <= 3 2^-24 (r + 1) / r + 2^-24 (the CPU's own rounding of d)
// <= 2^-21 on each axis, times the kernel's slope in d, 2 A + 2 pi F0 r + 2 taper_k (envelope,
// harmonic, taper), for both axes; soft depth adds the fade's rounding: rel is formed in float
// (a few 2^-24 relative), divided by the tolerance: 4 2^-24 / tol. 2 K: GPUs whose float ops
// err by 2 ulp. The visibility decisions must be the CPU's except at ties: a fragment whose
// double relative depth difference is within 2^-18 of the tolerance (or twice it, soft) may
// flip; those pixels are counted and left out.
// GPU stage 1 (hush/glsl/npr_gabor.hpp) computes in float what CPU stage 1 computes in double
// from the same float inputs. Per record of triangle (s_i, z_i) with edges e1, e2 from vertex
// 0, L = max |e|, kappa = (|e1x e2y| + |e1y e2x|) / |cross| >= 1 (the
// cross product's cancellation), each op's error at most 2 ulp (GLSL asks 2.5 for division,
// inversesqrt-based sqrt ~ 5: counted below), u = 2^-24:
//  - N: the edges, the cross product and lambda N: |dN| / N <= 2 u (3 kappa + 4) =: nu.
//  - weights: 1 (exact); sqrt(N) (N < 1): relative nu / 2; alpha = sqrt(N / M - 1): N / M - 1 is
//    exact from N, so |d alpha| <= sqrt(|d(N / M)|) <= sqrt(2 nu) (sqrt is 1/2-Hoelder), which
//    also bounds a second half that float drops or keeps (N within nu of a power of two); the
//    thinned weight sqrt(g): |dg| <= 2 u (3 kappa + 8), |d sqrt g| <= sqrt(|dg|). Then the
//    products with the amplitude (exact) and the weight factor: 6 u relative.
//  - position: the point is its node's (J's node, at depth K: (4^K - 1) / 3 <= J), placed
//    from the node's screen corners and depths, which the walk carries down as perspective-
//    correct midpoints of the parent's, (z_a s_a + z_b s_b) / (z_a + z_b) and (z_a + z_b) / 2.
//    A midpoint at level m rounds at the size of its coordinates, A_m = max |corner - o| of
//    the level-m ancestor (o: vertex 0 clamped into the frame, the corners' origin): 4 ops, 4 u A_m per ulp; the depths carry m u relative error, which moves
//    the midpoint by <= m u E_m / 2 per depth (E_m the ancestor's extent, |s_a - s_b| <= E_m);
//    parents' errors pass on with convex weights (no growth). Corners: sum over m = 1 ... K of
//    2 u (4 A_m + m E_m). The own point d = sum l_i z_i (s_i - s_0) / sum l_i z_i from corner 0:
//    l from sqrt(u) (6 u), the differences round at A_K, the rest at E_K: 2 u (6 A_K +
//    (K + 4) E_K); the first pixel's offset ((x0 + 1/2 - o) - s_0) - d: 2 u (E_K + r + 1)
//    more (and A_K), and both sides round c: 2 u (r + 1). For a triangle in the frame A_m is at
//    most its extent L; for a huge one A_m shrinks with the ancestors near the frame, so the sum
//    is about 8 u (frame size + twice the root's extent) there, not K times it. Boxes equal unless the
//    position is that close to a pixel-centre decision.
//  - plane: 1/z_i (5 u each), slopes q = (d1 e2 - d2 e1) / cross: |dq| <= 2 u (12 L /
//    (z_min |cross|) + |q| (3 kappa + 6)); its value at the first pixel centre 1/z0 + q . (p0 -
//    s0): 2 u 8 / z_min + |dq| (L + r + 1); at any pixel of the box |dq| (2 r + 1) more.
//  - frequency: exact (the table's doubles, rounded once) except isotropic, where (F r)
//    (cos, sin) come from the library's float sincos: 2^-20 F r.
// A record's kernel at a pixel then moves by at most |w| (slope (dc / r) 2 + 2 pi d(F r)) + dw
// (slope = 2 A + 2 pi F r + 2 taper_k per unit of d, both axes), and the depth test may decide
// differently within z_pixel |d plane| of its threshold.
// What GPU stage 1 may change in one CPU record (npr_record_tolerance): extra absolute
// error of its kernel at any pixel, and the half-width of the depth test's tie window.
struct npr_slack {
  double error = 0, tie = 0;
};

struct npr_record_tolerance {
  double offset = 0, weight = 0, frequency = 0, plane0 = 0, slope = 0;
};
// Triangle tri's screen positions and depths, in double.
void npr_vertices_of(const hush::triangle_list& t, std::size_t tri, double (&sx)[3],
                     double (&sy)[3], double (&z)[3]) {
  for (std::size_t i = 0; i < 3; ++i) {
    const std::uint32_t v = t.indices[3 * tri + i];
    sx[i] = t.screen[v].x;
    sy[i] = t.screen[v].y;
    z[i] = t.depth[v];
  }
}
// J's node (npr_gabor/tree.hpp) in triangle tri, reached from the root: its depth, its corners
// projected in double (the CPU's), and the float corners' error terms of the position bound
// below: corners = sum over m = 1 ... K of (4 A_m + m E_m), A_K and E_K.
struct npr_node_path {
  std::size_t depth = 0;
  double corners = 0, a_k = 0, e_k = 0;
  double cx[3] = {}, cy[3] = {};
  // Crossing the near plane (homogeneous corners h = (z (s - o), z), midpoints (h_a + h_b) / 2):
  // sum_x = 2 X_0 + sum over m = 1 ... K of X_m (X_m = max |h.xy| of the level-m ancestor's
  // corners: the root's z (s - o) rounds twice, each midpoint once), sum_w = sum of W_m (max
  // h.w), x_k, w_k the node's own, w_min its smallest depth.
  bool homog = false;
  double sum_x = 0, sum_w = 0, x_k = 0, w_k = 0, w_min = 0;
};
// Whether stage 1 walks triangle tri per node without local density (npr_gabor::walks_per_node
// for one triangle: far > 4 near), and whether it crosses the near plane (near < far / 1024).
bool npr_per_node(const hush::triangle_list& t, std::size_t tri, bool* crossing = nullptr) {
  double sx[3], sy[3], z[3];
  npr_vertices_of(t, tri, sx, sy, z);
  const double far = std::max({z[0], z[1], z[2]}), near = std::min({z[0], z[1], z[2]});
  namespace c = hush::detail::constants;
  if (crossing) *crossing = far > 0 && near < c::kNprGaborNearFraction * far;
  return far > 0 && far > c::kNprGaborPerNodeRatioLow * near;
}
npr_node_path npr_path_of(const hush::npr_gabor& noise, const hush::frame& f,
                          const hush::triangle_list& t, std::size_t tri, std::uint64_t index) {
  double sx[3], sy[3], z[3];
  npr_vertices_of(t, tri, sx, sy, z);
  hush::detail::npr_tree_node nd;
  nd.seed = hush::hash32(hush::hash32(hush::seed_key(noise.parameters().seed), t.object_of(tri)),
                         t.triangle_id[tri]);
  std::vector<std::uint64_t> path;
  for (std::uint64_t j = index; j > 0; j = (j - 1) / 4) path.push_back((j - 1) % 4);
  npr_node_path o;
  o.depth = path.size();
  npr_per_node(t, tri, &o.homog);
  // The corners' origin: vertex 0 clamped into the frame (hush_npr_origin).
  const double ox = std::clamp(sx[0], 0.0, double(f.width())),
               oy = std::clamp(sy[0], 0.0, double(f.height()));
  for (std::size_t m = 0;; ++m) {
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (int i = 0; i < 3; ++i) {
      const double* c = nd.corner[i];
      const double cw = c[0] * z[0] + c[1] * z[1] + c[2] * z[2];
      const double p[2] = {(c[0] * z[0] * sx[0] + c[1] * z[1] * sx[1] + c[2] * z[2] * sx[2]) / cw,
                           (c[0] * z[0] * sy[0] + c[1] * z[1] * sy[1] + c[2] * z[2] * sy[2]) / cw};
      o.cx[i] = p[0];
      o.cy[i] = p[1];
      for (int k = 0; k < 2; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    }
    o.a_k = std::max({std::fabs(lo[0] - ox), std::fabs(lo[1] - oy), std::fabs(hi[0] - ox),
                      std::fabs(hi[1] - oy)});
    if (o.homog) {
      double xm = 0, wm = 0, wl = 1e300;
      for (int i = 0; i < 3; ++i) {
        const double* c = nd.corner[i];
        double hx = 0, hy = 0, hw = 0;
        for (int k = 0; k < 3; ++k) {
          hx += c[k] * z[k] * (sx[k] - ox);
          hy += c[k] * z[k] * (sy[k] - oy);
          hw += c[k] * z[k];
        }
        xm = std::max({xm, std::fabs(hx), std::fabs(hy)});
        wm = std::max(wm, std::fabs(hw));
        wl = std::min(wl, hw);
      }
      o.sum_x += m == 0 ? 2 * xm : xm;
      o.sum_w += wm;
      o.x_k = xm;
      o.w_k = wm;
      o.w_min = wl;
    }
    o.e_k = std::max(hi[0] - lo[0], hi[1] - lo[1]);
    if (m > 0) o.corners += 4 * o.a_k + double(m) * o.e_k;
    if (m == path.size()) break;
    nd = hush::detail::npr_tree_child(nd, hush::detail::npr_tree_words_of(nd.seed),
                                      unsigned(path[m]));  // the root's slot is (J - 1) mod 4
  }
  return o;
}
// Under params::local_density: J's node's count n as the CPU walk computes it (the root: the
// triangle's lambda A; below: lambda times the area of its corners projected in double) and
// the relative error nu of the GPU's float count. The root's is the triangle's N's (below).
// Below the root: the area of the float corners, each within delta = 2 u corners (the
// position bound's corner sum) of the CPU's: |dA| <= delta (|e1| + |e2|) + 2 delta^2; then
// the edges, the cross product and the products with 1/2 and the float lambda, as N's:
// 2 u (3 kappa_P + 4), kappa_P the node's cancellation (its edges e1, e2 from corner 0).
struct npr_local_node {
  double n = 0, nu = 0;
};
npr_local_node npr_local_node_of(const hush::npr_gabor& noise, const hush::frame& f,
                                 const hush::triangle_list& t, std::size_t tri, std::uint64_t j,
                                 const hush::npr_gabor::sources& src) {
  const double u = std::ldexp(1.0, -24);
  const npr_node_path p = npr_path_of(noise, f, t, tri, j);
  const double e1x = p.cx[1] - p.cx[0], e1y = p.cy[1] - p.cy[0], e2x = p.cx[2] - p.cx[0],
               e2y = p.cy[2] - p.cy[0];
  const double cross = std::fabs(e1x * e2y - e1y * e2x);
  const double kappa = (std::fabs(e1x * e2y) + std::fabs(e1y * e2x)) / std::max(cross, 1e-300);
  const double lambda = noise.kernel_of_object(t.object_of(tri), src).density;
  npr_local_node o;
  o.n = lambda * 0.5 * cross;
  // Homogeneous corners: a projected corner c = h.xy / h.w is off by (dX + |c| dW) / W + u |c|,
  // dX = u sum_x, dW = u sum_w (2 ulp per op: twice that).
  const double delta = p.homog ? 2 * u * ((p.sum_x + p.a_k * p.sum_w) / p.w_min + p.a_k)
                               : 2 * u * p.corners;
  o.nu = 2 * u * (3 * kappa + 4) +
         (delta * (std::hypot(e1x, e1y) + std::hypot(e2x, e2y)) + 2 * delta * delta) /
             std::max(0.5 * cross, 1e-300);
  return o;
}
npr_record_tolerance npr_tolerance_of(const hush::npr_gabor& noise, const hush::frame& f,
                                      const hush::triangle_list& t, std::size_t tri,
                                      const hush::npr_gabor_splat& s,
                                      const hush::npr_gabor::sources& src) {
  const double u = std::ldexp(1.0, -24);
  double sx[3], sy[3], z[3];
  npr_vertices_of(t, tri, sx, sy, z);
  const double e1x = sx[1] - sx[0], e1y = sy[1] - sy[0], e2x = sx[2] - sx[0], e2y = sy[2] - sy[0];
  const double cross = e1x * e2y - e1y * e2x;
  const double kappa = (std::fabs(e1x * e2y) + std::fabs(e1y * e2x)) / std::fabs(cross);
  const double l = std::max({std::hypot(e1x, e1y), std::hypot(e2x, e2y)});
  const double zmin = std::min({z[0], z[1], z[2]});
  const double nu = 2 * u * (3 * kappa + 4), r = s.radius;
  npr_record_tolerance o;
  const npr_node_path path = npr_path_of(noise, f, t, tri, s.index);
  const double corners = path.corners, a_k = path.a_k, e_k = path.e_k;
  const double k_depth = double(path.depth);
  // w = lod weight v scale: the LOD weight's error for this record's point J, times
  // |v scale| = |w| / lod weight. |alpha_f - alpha_d| = |de| / (alpha_f + alpha_d)
  // <= min(sqrt |de|, |de| / alpha_d), the same for sqrt(g) when thinned.
  const hush::npr_gabor::object_kernel ok = noise.kernel_of_object(t.object_of(tri), src);
  const double n = ok.density * 0.5 * std::fabs(cross);
  hush::npr_gabor_lod lod = hush::npr_gabor_lod::of(n);
  const std::uint64_t j = s.index;
  bool crossing = false;
  const bool per_node = npr_per_node(t, tri, &crossing);
  const bool local = noise.parameters().local_density;
  REQUIRE((local || per_node || j < lod.count));
  const double dg = 2 * u * (3 * kappa + 8);
  double dlod = 0;  // |v| < 1
  namespace c = hush::detail::constants;
  const double zmax = std::max({z[0], z[1], z[2]});
  if (!local && per_node && !crossing) {
    // Blended (depth ratio 4 - 8, or 1 from 8 on): f = b f_local + (1 - b) w_p^2, b =
    // log2(far / (4 near)): the division (2.5 ulp) through log2's slope <= 1 / ln 2 on (1, 2) and
    // log2's 2^-21 absolute: |db| <= 2^-20. f_local's error as under local density (the root's
    // n its triangle's N, nu), w_p^2's: 1 exact, alpha^2 = N / M - 1 within 2 nu N / M <= 4 nu,
    // sqrt(N)^2 = N within nu N, thinned g within dg; the blend's own ops 4 u f.
    const double ratio = zmax / std::min({z[0], z[1], z[2]});
    const double b = std::clamp(std::log2(ratio / c::kNprGaborPerNodeRatioLow) /
                                    std::log2(c::kNprGaborPerNodeRatioHigh /
                                              c::kNprGaborPerNodeRatioLow),
                                0.0, 1.0);
    const npr_local_node nd = j == 0 ? npr_local_node{n, nu} : npr_local_node_of(noise, f, t, tri, j, src);
    const bool finest = path.depth == std::size_t(hush::npr_gabor::max_depth());
    const double fl = hush::npr_gabor_lod::local_square(nd.n, j == 0, finest);
    const double dfl = (1 + 1 / std::log(4.0)) * nd.nu * nd.n + nd.n * std::ldexp(1.0, -21);
    const double wp = j < lod.count ? lod.weight(j) : 0.0;
    const double dwp = j >= lod.count ? 0.0
                       : n < 1        ? (noise.parameters().thinning ? dg : nu * n)
                       : j < lod.first ? 0.0
                                       : 4 * nu;
    const double fd = b < 1 ? b * fl + (1 - b) * wp * wp : fl;
    const double df = (b < 1 ? b * dfl + (1 - b) * dwp + std::ldexp(1.0, -20) * std::fabs(fl - wp * wp)
                             : dfl) + 4 * u * fd + (j == 0 && n < 1 && noise.parameters().thinning ? dg : 0.0);
    dlod = std::min(std::sqrt(df), df / std::max(std::sqrt(fd), 1e-300));
  } else if ((local || crossing) && (j > 0 || n >= 1 || crossing)) {
    // sqrt(f), f = n h(n): |df/dn| = |h -+ 1 / ln 4| <= 1 + 1 / ln 4 on (1/4, 4), times the
    // count's error nu n; the hat's float log2 (absolute error < 2^-21 on [1/2, 2], 3 ulp
    // beyond: < 2^-21 over (1/4, 4) for half of it) adds n 2^-21; then as alpha above.
    const npr_local_node nd = npr_local_node_of(noise, f, t, tri, j, src);
    const double df = (1 + 1 / std::log(4.0)) * nd.nu * nd.n + nd.n * std::ldexp(1.0, -21);
    const double wd = std::sqrt(hush::npr_gabor_lod::local_square(
        nd.n, j == 0, path.depth == std::size_t(hush::npr_gabor::max_depth())));
    dlod = std::min(std::sqrt(df), df / std::max(wd, 1e-300));
  } else if (n < 1 && noise.parameters().thinning) {
    dlod = std::sqrt(dg);
  } else if (n < 1) {
    dlod = lod.first_weight * nu / 2;
  } else if (j >= lod.first) {
    dlod = std::min(std::sqrt(2 * nu), 2 * nu / std::max(lod.second_weight, 1e-300));
  }
  o.weight = std::fabs(s.weight) * 6 * u + std::fabs(ok.scale) * dlod;
  o.offset = 2 * u * (corners + 6 * a_k + (k_depth + 4) * e_k + e_k + r + 1) + 2 * u * (r + 1);
  if (path.homog) {
    // The point P = sum b_i h_i.xy / sum b_i h_i.w (b from sqrt: 6 u; the sums 5 u of their
    // magnitudes): (dX + |P| dW) / W_min + u |P| with dX = u (sum_x + 11 X_K), dW = u (sum_w +
    // 11 W_K); then the first pixel's offset (x0 + 1/2 - o) - P: u (|P| + r + 1), 2 ulp per op.
    const double ox = std::clamp(sx[0], 0.0, double(f.width())),
                 oy = std::clamp(sy[0], 0.0, double(f.height()));
    const double pm = std::max(std::fabs(s.x - ox), std::fabs(s.y - oy));
    o.offset = 2 * u *
                   ((path.sum_x + 11 * path.x_k + pm * (path.sum_w + 11 * path.w_k)) / path.w_min +
                    2 * pm + r + 1) +
               2 * u * (r + 1);
  }
  o.frequency =
      noise.parameters().isotropic ? std::ldexp(1.0, -20) * std::hypot(s.fx, s.fy) * r : 0;
  // A vertex behind the camera: 1/z_i's absolute error u / |z_i|, so |z| min; the plane anchored
  // at the deepest vertex k (hush_npr_lod's plane.w), the first pixel within |x - s_k| + r + 1.
  const double zabs = std::min({std::fabs(z[0]), std::fabs(z[1]), std::fabs(z[2])});
  o.slope =
      2 * u *
      (12 * l / (zabs * std::fabs(cross)) + (std::fabs(s.qx) + std::fabs(s.qy)) * (3 * kappa + 6));
  o.plane0 = 2 * u * 8 / zmin + o.slope * (l + r + 1);
  if (crossing) {
    const int k = zmax == z[0] ? 0 : zmax == z[1] ? 1 : 2;
    o.plane0 = 2 * u * 8 / zmax +
               o.slope * (std::max(std::fabs(s.x - sx[k]), std::fabs(s.y - sy[k])) + r + 1);
  }
  return o;
}
// The triangle index of each (object, triangle id) of the list (unique in the test scenes).
std::vector<std::size_t> npr_triangle_of(const hush::triangle_list& t,
                                         const std::vector<hush::npr_gabor_splat>& splats) {
  std::vector<std::pair<std::uint64_t, std::size_t>> keys;
  for (std::size_t i = 0; i < t.triangles(); ++i)
    keys.push_back({(std::uint64_t(t.object_of(i)) << 32) | t.triangle_id[i], i});
  std::sort(keys.begin(), keys.end());
  std::vector<std::size_t> out;
  for (const hush::npr_gabor_splat& s : splats) {
    const std::uint64_t k = (std::uint64_t(s.object) << 32) | s.triangle;
    out.push_back(
        std::lower_bound(keys.begin(), keys.end(), std::make_pair(k, std::size_t(0)))->second);
  }
  return out;
}
std::vector<npr_slack> npr_slacks(const hush::npr_gabor& noise, const hush::frame& f,
                                  const hush::triangle_list& t,
                                  const std::vector<hush::npr_gabor_splat>& splats,
                                  const hush::npr_gabor::sources& src) {
  namespace c = hush::detail::constants;
  const double a = noise.kernel().envelope_exponent(), taper_k = 1.0 / (1.0 - c::kGaborTaperStart);
  const std::vector<std::size_t> tri = npr_triangle_of(t, splats);
  std::vector<npr_slack> out;
  for (std::size_t i = 0; i < splats.size(); ++i) {
    const hush::npr_gabor_splat& s = splats[i];
    const npr_record_tolerance tol = npr_tolerance_of(noise, f, t, tri[i], s, src);
    const double fr = std::hypot(s.fx, s.fy) * s.radius;
    const double slope = 2 * a + c::kTwoPi * fr + 2 * taper_k;
    const double plane = tol.plane0 + tol.slope * (2 * s.radius + 1);
    // The pixel depth is at most 1 / (the plane's smallest 1/z on the box) (1 + tolerance).
    const double pz = 2.0 / std::max(1e-30, std::fabs(s.q0 + s.qx * s.x + s.qy * s.y) -
                                                (std::fabs(s.qx) + std::fabs(s.qy)) * s.radius);
    out.push_back(
        {std::fabs(s.weight) * (slope * 2 * tol.offset / s.radius + c::kTwoPi * tol.frequency) +
             tol.weight,
         pz * plane});
  }
  return out;
}

// GPU stage 1's records (read back) against CPU stage 1's, both sorted by (triangle, J) (the
// GPU lists them level by level, the CPU triangle by triangle in J order): per triangle the
// same points (J) except where float N and double N straddle a power of two (or 1, or a
// thinning threshold: `switched`, each checked to be that close); the same records (ids, J,
// boxes, 1/r exact), and offsets, weights, frequencies and planes within npr_tolerance_of.
struct npr_records_compare {
  std::size_t cpu = 0, gpu = 0, empty = 0, switched = 0, near_switch = 0, levels = 0;
  std::size_t box_ties = 0;  // box edges moved at a pixel-centre tie
  std::uint64_t cpu_nodes = 0, gpu_nodes = 0;  // nodes the CPU examined, the GPU's lists held
  double worst = 0;  // largest |GPU - CPU| / tolerance over the compared fields
  double worst_offset = 0;  // the same for the first pixel's offset alone (the position)
  bool same_records = true;
  // params::local_density: records on one side only (CPU, GPU), each a boundary node (its
  // count within its float error of a cut, 1/4 or 4: npr_local_boundary), listed.
  std::size_t cpu_only = 0, gpu_only = 0;
  std::string boundary_list;
};
// Whether J's node is a boundary node under params::local_density: its double count n within
// the GPU count's float error nu n of a cut of the hat (1/4, 4), where f = n h(n) is 0 on one
// side (and where n > 1/4 decides the descent); its record may then exist on one backend only,
// with weight sqrt(f) <= sqrt((1 + 1 / ln 4) nu n) (f's slope at the cuts), which the image
// comparison's per-record slack covers.
bool npr_local_boundary(const hush::npr_gabor& noise, const hush::frame& f,
                        const hush::triangle_list& t, std::size_t tri, std::uint64_t j,
                        const hush::npr_gabor::sources& src, std::string& list, bool cpu_side) {
  const npr_local_node nd = npr_local_node_of(noise, f, t, tri, j, src);
  bool near = std::fabs(nd.n - 0.25) <= nd.nu * nd.n || std::fabs(nd.n - 4.0) <= nd.nu * nd.n;
  bool crossing = false;
  if (!noise.parameters().local_density && npr_per_node(t, tri, &crossing)) {
    // Blended with the paper's LOD: also a point whose index J is at the count's float switch
    // (N within nu of a power of two, the triangle's M or 2M); crossing the near plane: a node
    // with a corner within its depth's float error u sum_w (2 ulp per op) of w_near (whole on
    // one side, crossing, weight 0, on the other).
    double sx[3], sy[3], z[3];
    npr_vertices_of(t, tri, sx, sy, z);
    const double e1x = sx[1] - sx[0], e1y = sy[1] - sy[0], e2x = sx[2] - sx[0],
                 e2y = sy[2] - sy[0];
    const double cross = std::fabs(e1x * e2y - e1y * e2x);
    const double kappa = (std::fabs(e1x * e2y) + std::fabs(e1y * e2x)) / cross;
    const double n = noise.kernel_of_object(t.object_of(tri), src).density * 0.5 * cross;
    const double nu = 2 * std::ldexp(1.0, -24) * (3 * kappa + 4);
    const double mm = std::exp2(std::round(std::log2(n)));
    near = near || std::fabs(n / mm - 1) <= nu;
    if (crossing) {
      const npr_node_path p = npr_path_of(noise, f, t, tri, j);
      const double w_near =
          hush::detail::constants::kNprGaborNearFraction * std::max({z[0], z[1], z[2]});
      near = near || std::fabs(p.w_min - w_near) <= 2 * std::ldexp(1.0, -24) * (p.sum_w + w_near);
    }
  }
  char text[160];
  std::snprintf(text, sizeof text, " (triangle %zu, J %llu, n - cut %.3g, nu n %.3g, %s only)",
                tri, static_cast<unsigned long long>(j),
                std::fabs(nd.n - 0.25) < 1 ? nd.n - 0.25 : nd.n - 4.0, nd.nu * nd.n,
                cpu_side ? "CPU" : "GPU");
  list += text;
  return near;
}
npr_records_compare npr_records_against_cpu(const hush::npr_gabor& noise, const hush::frame& f,
                                            const hush::triangle_list& t,
                                            const hush::npr_gabor::sources& src = {}) {
  std::vector<hush::npr_gabor_splat> splats;
  npr_records_compare r;
  noise.make_splats(f, t, splats, src, &r.cpu_nodes);
  std::vector<std::uint32_t> words, ids;
  auto& state = hush::glsl::npr_gabor_state(headless().device);
  const bool on_gpu = state.records(noise, f, t, src, words, ids, r.empty);  // not in REQUIRE:
  REQUIRE(on_gpu);  // bench/experiments/npr_gabor_gpu_error.cpp compiles it away
  r.gpu_nodes = state.stage1_nodes();
  r.levels = state.stage1_levels();
  r.cpu = splats.size();
  r.gpu = ids.size() / 4;
  const std::vector<std::size_t> tri = npr_triangle_of(t, splats);
  // (triangle, J, record) for both sides, sorted.
  using key = std::pair<std::pair<std::size_t, std::uint64_t>, std::size_t>;
  std::vector<key> c, g;
  for (std::size_t i = 0; i < splats.size(); ++i) c.push_back({{tri[i], splats[i].index}, i});
  std::vector<hush::npr_gabor_splat> gpu_ids(r.gpu);  // object and triangle id, to find the triangle
  for (std::size_t k = 0; k < r.gpu; ++k) {
    gpu_ids[k].object = ids[4 * k];
    gpu_ids[k].triangle = ids[4 * k + 1];
  }
  const std::vector<std::size_t> gtri = npr_triangle_of(t, gpu_ids);
  for (std::size_t k = 0; k < r.gpu; ++k)
    g.push_back({{gtri[k], ids[4 * k + 2] | (std::uint64_t(ids[4 * k + 3]) << 32)}, k});
  std::sort(c.begin(), c.end());
  std::sort(g.begin(), g.end());
  std::size_t i = 0, k = 0;
  while (i < c.size() || k < g.size()) {
    // The next triangle on either side and its records on both.
    const std::size_t tr = std::min(i < c.size() ? c[i].first.first : SIZE_MAX,
                                    k < g.size() ? g[k].first.first : SIZE_MAX);
    std::size_t i1 = i, k1 = k;
    while (i1 < c.size() && c[i1].first.first == tr) ++i1;
    while (k1 < g.size() && g[k1].first.first == tr) ++k1;
    bool same_points = i1 - i == k1 - k;
    for (std::size_t m = 0; same_points && m < i1 - i; ++m)
      same_points = c[i + m].first.second == g[k + m].first.second;
    // CPU record sp against GPU record gk.
    const auto compare = [&](const hush::npr_gabor_splat& sp, std::size_t gk) {
        hush::glsl::npr_gabor_gpu_record q, e = hush::glsl::npr_gabor_gpu_record::of(sp);
        std::memcpy(&q, &words[16 * gk], sizeof q);
        const npr_record_tolerance tol = npr_tolerance_of(noise, f, t, tr, sp, src);
        // Boxes equal, except an edge the position's float error may move: the CPU's
        // x -+ r - 1/2 (y) within the offset tolerance of an integer (`box_ties`); the first
        // pixel's offset and plane then move with the first pixel.
        const double edge[4] = {sp.x - sp.radius - 0.5, sp.y - sp.radius - 0.5,
                                sp.x + sp.radius - 0.5, sp.y + sp.radius - 0.5};
        for (int b = 0; b < 4; ++b) {
          if (q.box[b] == e.box[b]) continue;
          if (std::abs(q.box[b] - e.box[b]) == 1 &&
              std::fabs(edge[b] - std::round(edge[b])) <= tol.offset)
            ++r.box_ties;
          else
            r.same_records = false;
        }
        if (q.kern[2] != e.kern[2] || ids[4 * gk] != sp.object || ids[4 * gk + 1] != sp.triangle)
          r.same_records = false;
        const int dx0 = q.box[0] - e.box[0], dy0 = q.box[1] - e.box[1];
        e.kern[0] += float(dx0);
        e.kern[1] += float(dy0);
        e.plane[0] = float(sp.q0 + sp.qx * (q.box[0] + 0.5) + sp.qy * (q.box[1] + 0.5));
        const double d[6] = {
            std::fabs(double(q.kern[0]) - e.kern[0]) / tol.offset,
            std::fabs(double(q.kern[1]) - e.kern[1]) / tol.offset,
            std::fabs(double(q.kern[3]) - e.kern[3]) / tol.weight,
            std::hypot(double(q.freq[0]) - e.freq[0], double(q.freq[1]) - e.freq[1]) /
                std::max(tol.frequency, 1e-300),
            std::fabs(double(q.plane[0]) - e.plane[0]) / tol.plane0,
            std::hypot(double(q.plane[1]) - e.plane[1], double(q.plane[2]) - e.plane[2]) /
                tol.slope};
        for (double x : d) r.worst = std::max(r.worst, x);
        r.worst_offset = std::max({r.worst_offset, d[0], d[1]});
    };
    if (noise.parameters().local_density || npr_per_node(t, tr)) {
      // Merge by J: equal records compared, a one-sided one must be a boundary node.
      for (std::size_t a = i, b = k; a < i1 || b < k1;) {
        const std::uint64_t ja = a < i1 ? c[a].first.second : UINT64_MAX,
                            jb = b < k1 ? g[b].first.second : UINT64_MAX;
        if (ja == jb) {
          compare(splats[c[a++].second], g[b++].second);
          continue;
        }
        const bool cpu_side = ja < jb;
        ++(cpu_side ? r.cpu_only : r.gpu_only);
        if (!npr_local_boundary(noise, f, t, tr, cpu_side ? ja : jb, src, r.boundary_list,
                                cpu_side))
          r.same_records = false;
        ++(cpu_side ? a : b);
      }
    } else if (!same_points) {
      ++r.switched;
    } else {
      for (std::size_t m = 0; m < i1 - i; ++m) compare(splats[c[i + m].second], g[k + m].second);
    }
    i = i1;
    k = k1;
  }
  // Triangles near a switch: |N / 2^k - 1| <= nu for some k, or N near 1 (double N here).
  for (std::size_t m = 0; m < t.triangles(); ++m) {
    double sx[3], sy[3];
    for (std::size_t v = 0; v < 3; ++v) {
      sx[v] = t.screen[t.indices[3 * m + v]].x;
      sy[v] = t.screen[t.indices[3 * m + v]].y;
    }
    const double e1x = sx[1] - sx[0], e1y = sy[1] - sy[0], e2x = sx[2] - sx[0], e2y = sy[2] - sy[0];
    const double cross = e1x * e2y - e1y * e2x;
    if (cross == 0) continue;
    const double kappa = (std::fabs(e1x * e2y) + std::fabs(e1y * e2x)) / std::fabs(cross);
    const double n = noise.kernel_of_object(t.object_of(m), src).density * 0.5 * std::fabs(cross);
    const double mm = std::exp2(std::round(std::log2(n)));
    r.near_switch += std::fabs(n / mm - 1) <= 2 * std::ldexp(1.0, -24) * (3 * kappa + 4);
  }
  return r;
}

struct npr_compare {
  double max_abs = 0, rms = 0, max_vs_float = 0, worst_ratio = 0;
  std::size_t ties = 0, reached = 0;
  // Object-passing fragments the depth test cuts (binary or beyond 2 tolerances) and those in
  // the soft test's fade band: the decisions the comparison exercises.
  std::size_t cut = 0, faded = 0;
  // Per pixel: the GLSL image, the double reference, the bound's two parts (the splatting's
  // float evaluation S (2 K + 2^-24 n); GPU stage 1's records' slack) and the tie pixels left
  // out (bench/experiments/npr_gabor_gpu_error.cpp traces where an error comes from).
  std::vector<float> gpu;
  std::vector<double> ref, splat_bound, stage1_bound;
  std::vector<char> tie;
};

// The image of `gpu_stage1` (exec::glsl render: both stages on the GPU) or of CPU stage 1's
// records splatted on the GPU, against the double reference, within the bound above plus each
// record's slack (GPU stage 1).
npr_compare npr_against_cpu(const hush::npr_gabor& noise, const hush::frame& f,
                            const hush::triangle_list& t, bool gpu_stage1 = true,
                            const hush::npr_gabor::sources& src = {}) {
  namespace c = hush::detail::constants;
  const std::size_t w = f.width(), h = f.height();
  std::vector<float> gpu(w * h, -7.0f), cpu(w * h);
  std::vector<double> ref(w * h);
  std::vector<hush::npr_gabor_splat> splats;
  noise.make_splats(f, t, splats, src);
  auto& state = hush::glsl::npr_gabor_state(headless().device);
  const std::size_t gpu_frames = state.gpu_stage1_frames();
  if (gpu_stage1) {
    noise.render(hush::exec::glsl{headless().device}, f, t,
                 hush::image_view<float>(gpu.data(), w, h), src);
    CHECK(state.gpu_stage1_frames() == gpu_frames + 1);  // not the CPU fallback
  } else {
    noise.splat(hush::exec::glsl{headless().device}, f, splats.data(), splats.size(),
                hush::image_view<float>(gpu.data(), w, h));
  }
  noise.render(hush::exec::scalar, f, t, hush::image_view<float>(cpu.data(), w, h), src);
  noise.render(hush::exec::scalar, f, t, hush::image_view<double>(ref.data(), w, h), src);
  std::vector<npr_slack> slack(splats.size());
  if (gpu_stage1) slack = npr_slacks(noise, f, t, splats, src);
  std::vector<double> extra(w * h, 0.0);
  bool any_per_node = false;
  for (std::size_t m = 0; m < t.triangles(); ++m) any_per_node = any_per_node || npr_per_node(t, m);
  if (gpu_stage1 && (noise.parameters().local_density || any_per_node)) {
    // Boundary nodes (npr_local_boundary): a record on one side only adds at most its |weight|
    // at each pixel of its box to the difference (|kernel| <= |weight|). The records test
    // checks that every one-sided record is a boundary node.
    std::vector<std::uint32_t> words, ids;
    std::size_t empty = 0;
    const bool on_gpu = state.records(noise, f, t, src, words, ids, empty);
    REQUIRE(on_gpu);
    const auto key = [](std::uint32_t object, std::uint32_t id, std::uint64_t j) {
      return std::make_pair((std::uint64_t(object) << 32) | id, j);
    };
    std::vector<std::pair<std::uint64_t, std::uint64_t>> cpu_keys, gpu_keys;
    for (const hush::npr_gabor_splat& sp : splats)
      cpu_keys.push_back(key(sp.object, sp.triangle, sp.index));
    for (std::size_t k = 0; k < ids.size() / 4; ++k)
      gpu_keys.push_back(
          key(ids[4 * k], ids[4 * k + 1], ids[4 * k + 2] | (std::uint64_t(ids[4 * k + 3]) << 32)));
    std::vector<std::pair<std::uint64_t, std::uint64_t>> cs = cpu_keys, gs = gpu_keys;
    std::sort(cs.begin(), cs.end());
    std::sort(gs.begin(), gs.end());
    for (std::size_t i = 0; i < splats.size(); ++i)
      if (!std::binary_search(gs.begin(), gs.end(), cpu_keys[i]))
        slack[i].error += std::fabs(splats[i].weight);
    for (std::size_t k = 0; k < gpu_keys.size(); ++k) {
      if (std::binary_search(cs.begin(), cs.end(), gpu_keys[k])) continue;
      hush::glsl::npr_gabor_gpu_record q;
      std::memcpy(&q, &words[16 * k], sizeof q);
      for (std::int32_t y = q.box[1]; y <= q.box[3]; ++y)
        for (std::int32_t x = q.box[0]; x <= q.box[2]; ++x)
          extra[std::size_t(y) * w + std::size_t(x)] += std::fabs(double(q.kern[3]));
    }
  }
  const auto& p = noise.parameters();
  const double a = noise.kernel().envelope_exponent(), taper_k = 1.0 / (1.0 - c::kGaborTaperStart);
  std::vector<double> sum_w(w * h, 0.0), count(w * h, 0.0);
  std::vector<char> tie(w * h, 0);
  double k_max = 0;
  std::size_t cut = 0, faded = 0;
  for (std::size_t i = 0; i < splats.size(); ++i) {
    const hush::npr_gabor_splat& s = splats[i];
    const double fr = std::hypot(s.fx, s.fy) * s.radius;
    double k = std::ldexp(1.0, -21) * (1 + c::kTwoPi * fr) +
               2 * std::ldexp(1.0, -21) * (2 * a + c::kTwoPi * fr + 2 * taper_k);
    if (p.soft_depth) k += 4 * std::ldexp(1.0, -24) / p.depth_tolerance;
    k_max = std::max(k_max, k);
    for (std::int32_t y = s.y0; y <= s.y1; ++y)
      for (std::int32_t x = s.x0; x <= s.x1; ++x) {
        const double dx = x + 0.5 - s.x, dy = y + 0.5 - s.y;
        if (dx * dx + dy * dy >= s.radius * s.radius * 1.0000001) continue;
        const std::size_t q = std::size_t(y) * w + std::size_t(x);
        sum_w[q] += std::fabs(s.weight);
        count[q] += 1;
        extra[q] += slack[i].error;
        if (!p.depth_test) continue;
        const double rel = std::fabs(double(f.depth(std::size_t(x), std::size_t(y))) *
                                         (s.q0 + s.qx * (x + 0.5) + s.qy * (y + 0.5)) -
                                     1.0);
        const bool same_object =
            !p.object_test || f.object_id(std::size_t(x), std::size_t(y)) == s.object;
        const double limit = p.soft_depth ? 2 * p.depth_tolerance : p.depth_tolerance;
        cut += same_object && rel > limit;
        faded += same_object && p.soft_depth && rel > p.depth_tolerance && rel <= limit;
        const double eps = std::max(std::ldexp(1.0, -18), slack[i].tie);
        if (std::fabs(rel - p.depth_tolerance) <= eps ||
            (p.soft_depth && std::fabs(rel - 2 * p.depth_tolerance) <= eps))
          tie[q] = 1;
      }
  }
  npr_compare r;
  r.cut = cut;
  r.faded = faded;
  r.splat_bound.assign(w * h, 0.0);
  double sq = 0;
  for (std::size_t q = 0; q < w * h; ++q) {
    if (tie[q]) {
      ++r.ties;
      continue;
    }
    r.reached += count[q] > 0;
    const double e = std::fabs(double(gpu[q]) - ref[q]);
    r.splat_bound[q] = sum_w[q] * (2 * k_max + std::ldexp(1.0, -24) * count[q]);
    const double bound = r.splat_bound[q] + extra[q];
    r.max_abs = std::max(r.max_abs, e);
    sq += e * e;
    r.max_vs_float = std::max(r.max_vs_float, std::fabs(double(gpu[q]) - cpu[q]));
    // Unreached pixels must be exactly 0 (bound 0).
    r.worst_ratio = std::max(r.worst_ratio, bound > 0 ? e / bound : (e > 0 ? 1e30 : 0.0));
  }
  r.rms = std::sqrt(sq / double(w * h));
  r.gpu = std::move(gpu);
  r.ref = std::move(ref);
  r.stage1_bound = std::move(extra);
  r.tie = std::move(tie);
  return r;
}

hush::npr_gabor::params npr_params() {
  hush::npr_gabor::params p;
  p.orientation = 0.5;
  p.seed = 11;
  return p;
}

}  // namespace

TEST_CASE("npr: GLSL point sprites equal the CPU render within the derived tolerance") {
  const std::size_t w = 128, h = 128;
  const npr_test::grid_scene sc = npr_two_objects(w, h);
  const hush::frame f = sc.frame();
  const hush::triangle_list t = sc.triangles();
  struct config {
    const char* name;
    hush::npr_gabor::params p;
  };
  std::vector<config> configs;
  configs.push_back({"defaults (object + depth tests)", npr_params()});
  hush::npr_gabor::params q = npr_params();
  q.object_test = false;  // the depth test alone cuts the kernels at the patch's edges
  configs.push_back({"depth test only", q});
  // Kernels of the plane reaching the patch see relative depth differences of 0.39 - 0.52
  // (1 - 0.8 / z_plane), the patch's on the plane 0.66 - 1.08: a tolerance of 0.45 cuts some
  // of the first and not others; a soft test with tolerance 0.25 fades them (band 0.25 - 0.5).
  q.depth_tolerance = 0.45;
  configs.push_back({"depth test only, tolerance 0.45", q});
  q.soft_depth = true;
  q.depth_tolerance = 0.25;
  configs.push_back({"soft depth test, tolerance 0.25", q});
  q = npr_params();
  q.triangle_test = true;
  q.isotropic = true;
  configs.push_back({"triangle test, isotropic", q});
  q = npr_params();
  q.bandwidth = 0.02;  // r = 49 px: quads larger than a third of the frame, still one each
  q.impulses = 4;
  q.depth_test = false;
  configs.push_back({"large kernels, object test only", q});
  for (const config& cf : configs)
    for (const bool gpu_stage1 : {false, true}) {
      const std::string name =
          std::string(cf.name) + (gpu_stage1 ? ", GPU stage 1" : ", CPU stage 1");
      CAPTURE(name);
      const npr_compare r = npr_against_cpu(hush::npr_gabor{cf.p}, f, t, gpu_stage1);
      MESSAGE(name << ": GLSL vs double max " << r.max_abs << " RMS " << r.rms
                   << ", vs CPU float max " << r.max_vs_float << ", worst error / bound "
                   << r.worst_ratio << ", tie pixels " << r.ties << ", reached " << r.reached
                   << ", fragments cut by depth " << r.cut << ", faded " << r.faded);
      CHECK(r.worst_ratio <= 1.0);
      CHECK(r.reached > w * h / 2);  // the comparison covers the frame
      CHECK(r.ties < w * h / 100);
      if (cf.p.depth_test && !cf.p.object_test) CHECK(r.cut > 0);  // with it, the ids decide here
      if (cf.p.soft_depth) CHECK(r.faded > 0);
    }
}

namespace {
void check_records(const std::string& name, const hush::npr_gabor& noise, const hush::frame& f,
                   const hush::triangle_list& t, const hush::npr_gabor::sources& src = {}) {
  CAPTURE(name);
  const npr_records_compare r = npr_records_against_cpu(noise, f, t, src);
  MESSAGE(name << ": records CPU " << r.cpu << ", GPU " << r.gpu << " (and " << r.empty
               << " empty), worst difference / tolerance " << r.worst << " (offsets "
               << r.worst_offset << "), triangles switched "
               << r.switched << " (near a switch " << r.near_switch << "), box edges at ties "
               << r.box_ties << ", nodes CPU examined "
               << r.cpu_nodes << ", GPU lists " << r.gpu_nodes << " in " << r.levels
               << " levels; one-sided (local density): CPU " << r.cpu_only << ", GPU "
               << r.gpu_only << r.boundary_list);
  CHECK(r.same_records);
  CHECK(r.box_ties <= 2 + r.cpu / 100);  // ties are rare: a position within ~1e-4 px of one
  CHECK(r.empty == 0);
  CHECK(r.worst <= 1.0);
  CHECK(r.switched <= r.near_switch);
  // The walk's lists hold the nodes near the frame: at most the CPU's examined nodes (kept
  // and culled children) plus those the cull margin keeps in excess (a small share).
  CHECK(r.gpu_nodes <= r.cpu_nodes + r.cpu_nodes / 4 + 16);
  CHECK(r.levels <= 22);
}

// A w x h frame of object 1 at depth 1 (one grid cell covering it, whose two triangles come
// first, ids 0 and 1) and loose triangles added after it (ids 2, 3, ...): hard cases.
struct npr_loose : npr_test::grid_scene {
  npr_loose(std::size_t w, std::size_t h)
      : grid_scene(w, h, -1.0, -1.0, double(std::max(w, h)) + 2.0, 1, 1) {}
  void add(hush::vec2 a, hush::vec2 b, hush::vec2 c) {
    for (const hush::vec2& v : {a, b, c}) {
      indices.push_back(static_cast<std::uint32_t>(screen.size()));
      screen.push_back(v);
      vdepth.push_back(1.0f);
    }
    tri_id.push_back(static_cast<std::uint32_t>(tri_id.size()));
    obj_id.push_back(1u);
  }
};
}  // namespace

TEST_CASE(
    "npr: GPU stage 1 records equal the CPU's, sorted by (triangle, J): ids, J and boxes exact, "
    "values within the derived tolerance") {
  const npr_test::grid_scene sc = npr_two_objects(128, 128);
  check_records("defaults", hush::npr_gabor{npr_params()}, sc.frame(), sc.triangles());
  hush::npr_gabor::params q = npr_params();
  q.isotropic = true;
  q.cull_back_faces = false;
  check_records("isotropic, two-sided", hush::npr_gabor{q}, sc.frame(), sc.triangles());
  // Cells of 3 px: N = 0.15 per triangle (N < 1), thinned; over 2000 triangles, so the scans
  // of level 0 take two blocks of 1024 and the recursion over the blocks' totals.
  const npr_test::grid_scene fine = npr_test::covering(96, 96, 3.0, 16.0);
  q = npr_params();
  q.thinning = true;
  check_records("N < 1, thinning", hush::npr_gabor{q}, fine.frame(), fine.triangles());
  q.thinning = false;
  check_records("N < 1", hush::npr_gabor{q}, fine.frame(), fine.triangles());
  // Per-object F0, omega0, a and N' (object 2 past the bandwidth table: the constant).
  const std::vector<double> freq = {0.1, 0.2, 0.3}, angle = {0.0, 1.0, -0.5}, band = {0.1, 0.05},
                            imp = {4.0, 8.0, 24.0};
  hush::npr_gabor::sources src;
  src.frequency = hush::param_source::per_object(freq);
  src.orientation = hush::param_source::per_object(angle);
  src.bandwidth = hush::param_source::per_object(band);
  src.impulses = hush::param_source::per_object(imp);
  check_records("per-object sources", hush::npr_gabor{npr_params()}, sc.frame(), sc.triangles(),
                src);
  const npr_compare r =
      npr_against_cpu(hush::npr_gabor{npr_params()}, sc.frame(), sc.triangles(), true, src);
  MESSAGE("per-object sources, image: max " << r.max_abs << ", worst error / bound "
                                            << r.worst_ratio);
  CHECK(r.worst_ratio <= 1.0);
}

TEST_CASE(
    "npr: GPU stage 1 hard cases: empty list, zero area, back faces, N < 1, huge triangles, the "
    "M switch") {
  const hush::npr_gabor noise{npr_params()};
  const double lambda = noise.density();
  npr_loose sc(64, 64);
  sc.add({10, 10}, {20, 20}, {30, 30});  // zero area
  sc.add({10, 10}, {40, 10}, {10, 40});  // back-facing (counter-clockwise, y up)
  sc.add({30, 30}, {30, 31}, {31, 30});  // N = lambda / 2 < 1
  // N sweeping across 8 and 64 in steps of ~2^-23 relative: float and double N straddle the
  // power of two for some; each must be one the tolerance allows (the M switch).
  for (const double target : {8.0, 64.0})
    for (int i = -40; i < 40; ++i) {
      const double side = std::sqrt(2 * target * (1 + i * std::ldexp(1.0, -23)) / lambda);
      sc.add({20, 20}, {20, float(20 + side)}, {float(20 + side), 20});
    }
  const hush::frame f = sc.frame();
  check_records("hard cases", noise, f, sc.triangles());
  std::vector<std::uint32_t> words, ids;
  std::size_t empty = 0;
  REQUIRE(hush::glsl::npr_gabor_state(headless().device)
              .records(noise, f, sc.triangles(), {}, words, ids, empty));
  // The covering cell (ids 0, 1), then no zero-area (2) or back-facing (3) triangle's records.
  std::size_t after_cell = 0;
  // Level 0 (the roots' own points) comes first, in triangle order.
  while (after_cell < ids.size() && ids[after_cell + 1] < 2u) after_cell += 4;
  REQUIRE(after_cell < ids.size());
  CHECK(ids[after_cell + 1] == 4u);  // the N < 1 triangle's one point comes next
  const npr_compare img = npr_against_cpu(noise, f, sc.triangles());
  MESSAGE("hard cases, image: max " << img.max_abs << ", worst error / bound " << img.worst_ratio);
  CHECK(img.worst_ratio <= 1.0);
  // Huge triangles mostly off the frame: legs of 2 10^4 px (N = 6.8 10^6) and 10^5 px
  // (N = 1.7 10^8, 2^28 points in the sequence): the walk visits only the nodes near the
  // 32 x 32 frame (a few hundred, in at most 22 levels), their records equal to the CPU's
  // and the image within the bound.
  for (const float leg : {2e4f, 1e5f}) {
    npr_loose huge(32, 32);
    huge.add({-leg / 2, -leg / 2}, {-leg / 2, leg / 2}, {leg / 2, -leg / 2});
    const std::string name = "huge triangle, legs " + std::to_string(int(leg)) + " px";
    check_records(name, noise, huge.frame(), huge.triangles());
    const npr_compare hi = npr_against_cpu(noise, huge.frame(), huge.triangles());
    MESSAGE(name << ", image: max " << hi.max_abs << ", worst error / bound " << hi.worst_ratio);
    CHECK(hi.worst_ratio <= 1.0);
  }
  // The empty list: an all-zero image, stage 1 still on the GPU.
  npr_test::grid_scene none(16, 16, 0.0, 0.0, 1.0, 0, 0);
  auto& state = hush::glsl::npr_gabor_state(headless().device);
  const std::size_t before = state.gpu_stage1_frames();
  std::vector<float> out(std::size_t{16} * 16, -1.0f);
  noise.render(hush::exec::glsl{headless().device}, none.frame(), none.triangles(),
               hush::image_view<float>(out.data(), 16, 16));
  CHECK(state.gpu_stage1_frames() == before + 1);
  CHECK(std::all_of(out.begin(), out.end(), [](float v) { return v == 0.0f; }));
}

TEST_CASE(
    "npr: GPU stage 1 with local density: records equal the CPU's except at boundary nodes "
    "(listed), images within the derived tolerance") {
  // The two-object scene (cells of 14 - 20 px: roots of n ~ 5, two levels below), a dense
  // small kernel (n ~ 10^2 per cell: four levels), per-object sources, thinning on a fine grid
  // (N < 1 roots) and a huge triangle around the frame (n = 2 10^5 near the frame's nodes:
  // nine levels). Records: every (triangle, J) on both sides compared as in the paper's LOD;
  // a record on one side only must be a boundary node, its count n within its float error of
  // 1/4 or 4 (npr_local_boundary); the image bound adds each one-sided record's |weight|.
  hush::npr_gabor::params p = npr_params();
  p.local_density = true;
  const npr_test::grid_scene sc = npr_two_objects(128, 128);
  check_records("local density", hush::npr_gabor{p}, sc.frame(), sc.triangles());
  hush::npr_gabor::params dense = p;
  dense.bandwidth = 0.3;  // r = 3.3 px, lambda = 0.48 / px^2
  dense.isotropic = true;
  const npr_test::grid_scene small = npr_two_objects(64, 64);
  check_records("local density, small dense kernel", hush::npr_gabor{dense}, small.frame(),
                small.triangles());
  // Boundary nodes: roots whose n sweeps across 4 (the root's hat cut: its record exists only
  // below) and across 1 (its four children's n across 1/4), in steps of 2^-24 relative, each
  // at its own sub-pixel offset (so the float coordinates, hence the float counts, round
  // differently): float and double counts straddle a cut for some, whose record is then on one
  // side only.
  const hush::npr_gabor local{p};
  npr_loose cuts(64, 64);
  for (const double target : {1.0, 4.0})
    for (int i = -80; i < 80; ++i) {
      // Twice the area: side^2 - 0.2 * 0.3.
      const double side =
          std::sqrt(2 * target / local.density() * (1 + i * std::ldexp(1.0, -24)) + 0.06);
      const double x = 20.1 + 0.013 * i, y = 21.3 + 0.007 * i;
      cuts.add({float(x), float(y)}, {float(x + 0.2), float(y + side)},
               {float(x + side), float(y + 0.3)});
    }
  const npr_records_compare rc = npr_records_against_cpu(local, cuts.frame(), cuts.triangles());
  check_records("local density, counts sweeping 1 and 4", local, cuts.frame(), cuts.triangles());
  CHECK(rc.cpu_only + rc.gpu_only > 0);  // the sweep reaches the boundary on both sides
  const std::vector<double> freq = {0.1, 0.2, 0.3}, band = {0.1, 0.05}, imp = {4.0, 8.0, 24.0};
  hush::npr_gabor::sources src;
  src.frequency = hush::param_source::per_object(freq);
  src.bandwidth = hush::param_source::per_object(band);
  src.impulses = hush::param_source::per_object(imp);
  check_records("local density, per-object sources", hush::npr_gabor{p}, sc.frame(),
                sc.triangles(), src);
  const npr_test::grid_scene fine = npr_test::covering(96, 96, 3.0, 16.0);
  hush::npr_gabor::params thin = p;
  thin.thinning = true;
  check_records("local density, N < 1, thinning", hush::npr_gabor{thin}, fine.frame(),
                fine.triangles());
  npr_loose huge(32, 32);
  huge.add({-5e3f, -5e3f}, {-5e3f, 5e3f}, {5e3f, -5e3f});
  check_records("local density, huge triangle", hush::npr_gabor{p}, huge.frame(),
                huge.triangles());
  struct image_case {
    const char* name;
    const hush::npr_gabor noise;
    const npr_test::grid_scene& scene;
    const hush::npr_gabor::sources& src;
  };
  const hush::npr_gabor::sources none;
  const image_case images[] = {{"local density", hush::npr_gabor{p}, sc, none},
                               {"small dense kernel", hush::npr_gabor{dense}, small, none},
                               {"counts sweeping 1 and 4", local, cuts, none},
                               {"per-object sources", hush::npr_gabor{p}, sc, src},
                               {"huge triangle", hush::npr_gabor{p}, huge, none}};
  for (const image_case& ic : images) {
    const std::string name = ic.name;
    CAPTURE(name);
    const npr_compare r = npr_against_cpu(ic.noise, ic.scene.frame(), ic.scene.triangles(), true,
                                          ic.src);
    MESSAGE(ic.name << ", image: GLSL vs double max " << r.max_abs << " RMS " << r.rms
                    << ", worst error / bound " << r.worst_ratio << ", tie pixels " << r.ties);
    CHECK(r.worst_ratio <= 1.0);
    CHECK(r.ties < ic.scene.frame().width() * ic.scene.frame().height() / 100);
  }
}

TEST_CASE("npr: per-pixel and per-vertex sources: stage 1 on the CPU; the near plane on the GPU") {
  const std::size_t w = 64, h = 64;
  const npr_test::grid_scene sc = npr_test::covering(w, h, 9.0, 16.0);
  hush::npr_gabor::params p = npr_params();
  const hush::npr_gabor plain{p};
  p.local_density = true;  // with local density too
  const hush::npr_gabor local{p};
  std::vector<float> field(w * h);
  for (std::size_t i = 0; i < field.size(); ++i) field[i] = 0.01f * float(i % w);
  std::vector<float> vertex(sc.screen.size(), 0.12f);
  hush::npr_gabor::sources pixel, vert;
  pixel.orientation = hush::param_source::per_pixel({field.data(), w, h});
  vert.frequency = hush::param_source::per_vertex(vertex);
  auto& state = hush::glsl::npr_gabor_state(headless().device);
  const std::pair<const hush::npr_gabor*, const hush::npr_gabor::sources*> runs[] = {
      {&plain, &pixel}, {&plain, &vert}, {&local, &pixel}};
  for (const auto& [noise_of_run, src] : runs) {
    const hush::npr_gabor& noise = *noise_of_run;
    const std::size_t cpu_before = state.cpu_stage1_frames(),
                      gpu_before = state.gpu_stage1_frames();
    std::vector<float> a(w * h), b(w * h);
    noise.render(hush::exec::glsl{headless().device}, sc.frame(), sc.triangles(),
                 hush::image_view<float>(a.data(), w, h), *src);
    CHECK(state.cpu_stage1_frames() == cpu_before + 1);
    CHECK(state.gpu_stage1_frames() == gpu_before);
    std::vector<hush::npr_gabor_splat> splats;
    noise.make_splats(sc.frame(), sc.triangles(), splats, *src);
    noise.splat(hush::exec::glsl{headless().device}, sc.frame(), splats.data(), splats.size(),
                hush::image_view<float>(b.data(), w, h));
    CHECK(a == b);  // the same records, the same draws
  }
  // Triangles crossing the near plane (a vertex behind the camera): stage 1 on the GPU too
  // (clipped per node; compared in "npr: GPU stage 1 walks near-plane ...").
  const npr_test::grid_scene ground = npr_test::ground_under_camera(-1.0f);
  REQUIRE(hush::npr_gabor::walks_per_node(ground.triangles()));
  const std::size_t cpu_before = state.cpu_stage1_frames(), gpu_before = state.gpu_stage1_frames();
  std::vector<float> a(ground.width * ground.height);
  plain.render(hush::exec::glsl{headless().device}, ground.frame(), ground.triangles(),
               hush::image_view<float>(a.data(), ground.width, ground.height));
  CHECK(state.cpu_stage1_frames() == cpu_before);
  CHECK(state.gpu_stage1_frames() == gpu_before + 1);
}

TEST_CASE("npr: one quad per record never reaches the GL geometry-output limits") {
  const hush::glsl::npr_gabor_limits l = hush::glsl::npr_gabor_gl_limits(headless().device.gl());
  MESSAGE("GL_MAX_GEOMETRY_OUTPUT_VERTICES " << l.max_geometry_output_vertices
                                             << ", GL_MAX_GEOMETRY_TOTAL_OUTPUT_COMPONENTS "
                                             << l.max_geometry_output_components);
  // GL 3.2's minimums are 256 and 1024; one quad needs 4 and 4 x 5.
  CHECK(l.max_geometry_output_vertices >= 256);
  CHECK(l.max_geometry_output_components >= 1024);
  CHECK(l.sprites_fit());
  // The geometry stage declares exactly one quad, whatever the kernel's size.
  const std::string gs = hush::glsl::npr_gabor_geometry_source();
  CHECK(gs.find("max_vertices = HUSH_NPR_SPRITE_VERTICES") != std::string::npos);
  CHECK(gs.find("#define HUSH_NPR_SPRITE_VERTICES 4\n") != std::string::npos);
  CHECK(hush::glsl::npr_gabor_state(headless().device).limits().sprites_fit());
  // A frame wider than the GL's largest target is refused, naming the frame size.
  const std::size_t wide = static_cast<std::size_t>(l.max_frame_side) + 1;
  if (wide <= hush::detail::constants::kNprGaborMaxImageSide) {
    const std::vector<float> depth(wide, 1.0f);
    const std::vector<std::uint32_t> ids(wide, 1u);
    hush::frame f;
    f.depth = {depth.data(), wide, 1};
    f.object_id = {ids.data(), wide, 1};
    std::vector<float> out(wide);
    try {
      hush::npr_gabor{npr_params()}.render(hush::exec::glsl{headless().device}, f,
                                           hush::triangle_list{},
                                           hush::image_view<float>(out.data(), wide, 1));
      FAIL("no exception");
    } catch (const hush::invalid_argument& e) {
      CHECK(std::string(e.what()).find("frame size") != std::string::npos);
    }
  }
}

TEST_CASE("npr: records beyond one storage block are drawn in order, state is restored") {
  // A device whose storage blocks hold 128 records (and 128 nodes of the walk: its 32
  // triangles of N = 4.4 have 32, 128 and 96 nodes on levels 0, 1, 2): the records go in
  // several draws, generated level by level into each batch, and the image is the one-draw
  // image bit for bit (blending in record order either way).
  const std::size_t w = 32, h = 32;
  const npr_test::grid_scene sc = npr_test::covering(w, h, 16.0, 8.0);
  const hush::npr_gabor noise{npr_params()};
  const hush::glsl::detail::gl_api& gl = headless().device.gl();  // the context, current
  hush::glsl::device::options o;
  o.max_buffer_bytes = 128 * hush::glsl::kNprGaborRecordBytes;
  hush::glsl::device small(hush_glsl_test::headless().context.loader(), o);
  std::vector<hush::npr_gabor_splat> splats;
  noise.make_splats(sc.frame(), sc.triangles(), splats);
  REQUIRE(splats.size() > 128);
  hush::glsl::detail::gl_int program_before = -1, program_after = -2;
  gl.GetIntegerv(hush::glsl::detail::kGlCurrentProgram, &program_before);
  std::vector<float> one(w * h), many(w * h);
  noise.render(hush::exec::glsl{headless().device}, sc.frame(), sc.triangles(),
               hush::image_view<float>(one.data(), w, h));
  noise.render(hush::exec::glsl{small}, sc.frame(), sc.triangles(),
               hush::image_view<float>(many.data(), w, h));
  gl.GetIntegerv(hush::glsl::detail::kGlCurrentProgram, &program_after);
  CHECK(program_after == program_before);
  CHECK(hush::glsl::npr_gabor_state(small).draws() >= (splats.size() + 127) / 128);
  CHECK(hush::glsl::npr_gabor_state(small).gpu_stage1_frames() == 1);  // generated in batches too
  CHECK(one == many);
  double energy = 0;
  for (float v : one) energy += double(v) * v;
  CHECK(energy > 0.1 * double(w * h));  // unit variance where covered: not an empty image
}

TEST_CASE(
    "npr: GPU stage 1 walks near-plane and foreshortened triangles per node: records equal the "
    "CPU's except at boundary nodes (listed), images within the derived tolerance") {
  // ground_under_camera: a ground quad from depth 3 to `back` (npr_gabor_scenes.hpp): -1 crosses
  // the near plane (homogeneous corners, clipped at w_near = 3 / 1024), 0.5 a depth ratio of 6
  // (the count per node blended with the paper's LOD at b = log2(6 / 4)), 0.2 one of 15 (the
  // count per node alone). Records: per (triangle, J) as under local density (a one-sided record
  // must be a boundary node: its count at a cut of the hat, N at a power of two, or a corner
  // at w_near, each within its float error); the images against the double reference within
  // npr_against_cpu's bound plus each record's slack (npr_tolerance_of, homogeneous terms).
  hush::npr_gabor::params p = npr_params();
  hush::npr_gabor::params local = p;
  local.local_density = true;
  auto& state = hush::glsl::npr_gabor_state(headless().device);
  for (const float back : {-1.0f, 0.5f, 0.2f}) {
    const npr_test::grid_scene sc = npr_test::ground_under_camera(back);
    const hush::frame f = sc.frame();
    const hush::triangle_list t = sc.triangles();
    REQUIRE(hush::npr_gabor::walks_per_node(t));
    // Without local density (the per-triangle LOD blended in for the ratio of 6) and with it.
    for (const auto& [label, prm] :
         {std::make_pair("paper LOD", p), std::make_pair("local density", local)}) {
      const std::string name = std::string(label) + ", back " + std::to_string(back);
      CAPTURE(name);
      const hush::npr_gabor noise{prm};
      check_records(name, noise, f, t);
      const std::size_t gpu_before = state.gpu_stage1_frames();
      const npr_compare r = npr_against_cpu(noise, f, t);
      CHECK(state.gpu_stage1_frames() == gpu_before + 1);
      MESSAGE(name << ", image: GLSL vs double max " << r.max_abs << " RMS " << r.rms
                   << ", worst error / bound " << r.worst_ratio << ", tie pixels " << r.ties
                   << ", reached " << r.reached);
      CHECK(r.worst_ratio <= 1.0);
      CHECK(r.reached > f.width() * f.height() / 4);
      CHECK(r.ties < f.width() * f.height() / 100);
    }
  }
  // More of each kind, records and images with the paper's LOD: a vertex far behind (-3) and
  // just behind (-0.05), both near vertices in front but below w_near (0.002: crossing with no
  // vertex behind the camera), ratios just above 4 (0.7: t = 0.10) and just below 8 (0.4: t =
  // 0.91).
  const hush::npr_gabor noise{p};
  for (const float back : {-3.0f, -0.05f, 0.002f, 0.7f, 0.4f}) {
    const npr_test::grid_scene sc = npr_test::ground_under_camera(back);
    const std::string name = "paper LOD, back " + std::to_string(back);
    CAPTURE(name);
    REQUIRE(hush::npr_gabor::walks_per_node(sc.triangles()));
    check_records(name, noise, sc.frame(), sc.triangles());
    const npr_compare r = npr_against_cpu(noise, sc.frame(), sc.triangles());
    MESSAGE(name << ", image: max " << r.max_abs << ", worst error / bound " << r.worst_ratio);
    CHECK(r.worst_ratio <= 1.0);
  }
}
