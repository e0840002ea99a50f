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
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>
#include <vector>

#include "glsl_test_util.hpp"

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
  const diff d = compare<D>(cv, cg, gv, gg);
  const diff d_only = compare<D>(cv, cg, gv_only, gg);
  MESSAGE("points " << D << "D kind " << int(noise.parameters().kind) << ": max |value diff| "
                    << d.value << " (tolerance " << value_tolerance(noise) << "), gradient "
                    << d.grad << " (" << gradient_tolerance(noise) << ")");
  CHECK(std::isnan(gv[7]));
  CHECK(std::isnan(gv[11]));
  CHECK(d.nan_mismatch == 0);
  CHECK(d.value <= value_tolerance(noise));
  CHECK(d.grad <= gradient_tolerance(noise));
  CHECK(d_only.value <= value_tolerance(noise));
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
  const diff d = compare<D>(cv, cg, gv, gg);
  MESSAGE("grid " << D << "D: max |value diff| " << d.value << ", gradient " << d.grad);
  CHECK(d.nan_mismatch == 0);
  CHECK(d.value <= value_tolerance(noise));
  CHECK(d.grad <= gradient_tolerance(noise));
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
  hush::grid<3> g3;
  g3.origin = {0.5, -2e6, 7.0};
  g3.step = {0.11, 0.07, -0.13};
  g3.size = {23, 17, 11};
  check_grid(hush::gabor<3>(params_of<3>(hush::gabor_kind::isotropic)), g3);
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
