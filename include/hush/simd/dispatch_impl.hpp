// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Dynamic dispatch of the SIMD backend: include this in exactly ONE .cpp of
// a program built with HUSH_SIMD_DYNAMIC, and link Highway (libhwy). It
// compiles every kernel once per SIMD target Highway builds for (Highway's
// HWY_TARGET_INCLUDE + foreach_target.h pattern) and defines the entry
// points of hush/simd/dispatch.hpp, which pick the best target the CPU
// supports on first use. The CMake target hush::simd is exactly this.
//
// No include guard on purpose: foreach_target.h re-includes this file once
// per target; the HWY_ONCE part at the end is compiled once.
#if !defined(HUSH_SIMD_DYNAMIC)
#error "hush/simd/dispatch_impl.hpp needs HUSH_SIMD_DYNAMIC defined for the whole program"
#endif

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "hush/simd/dispatch_impl.hpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "hush/simd/anisotropic-inl.h"
#include "hush/simd/coherent-inl.h"
#include "hush/simd/gabor-inl.h"
#include "hush/simd/npr_gabor-inl.h"
#include "hush/simd/perlin-inl.h"
#include "hush/simd/wavelet-inl.h"

#if HWY_ONCE
#ifndef HUSH_SIMD_DISPATCH_IMPL_ONCE
#define HUSH_SIMD_DISPATCH_IMPL_ONCE

#include <string>
#include <vector>

#include <hwy/targets.h>

#include "hush/simd/dispatch.hpp"

namespace hush {

HWY_EXPORT(perlin2_points);
HWY_EXPORT(perlin3_points);
HWY_EXPORT(perlin2_grid);
HWY_EXPORT(perlin3_grid);
HWY_EXPORT(fractal2_points);
HWY_EXPORT(fractal3_points);
HWY_EXPORT(fractal2_grid);
HWY_EXPORT(fractal3_grid);
HWY_EXPORT(wavelet2_points);
HWY_EXPORT(wavelet3_points);
HWY_EXPORT(wavelet2_grid);
HWY_EXPORT(wavelet3_grid);
HWY_EXPORT(wavelet2_samples);
HWY_EXPORT(wavelet3_samples);
HWY_EXPORT(coherent_pass);
HWY_EXPORT(anisotropic_samples);
HWY_EXPORT(anisotropic_grid);
HWY_EXPORT(gabor2_points);
HWY_EXPORT(gabor3_points);
HWY_EXPORT(gabor2_grid);
HWY_EXPORT(gabor3_grid);
HWY_EXPORT(gabor2_filtered);
HWY_EXPORT(gabor3_filtered);
HWY_EXPORT(npr_gabor_splat);
HWY_EXPORT(gabor3_surface);

// The dispatch functions declared in dispatch.hpp, defined here exactly once:
// this header is the body of one translation unit (src/simd_dispatch.cpp or
// the user's one .cpp), so they are deliberately not inline (inline would
// leave them undefined for every other translation unit that calls them).
// NOLINTBEGIN(misc-definitions-in-headers)
namespace simd {

void perlin2_points(std::uint32_t key, const std::uint32_t* period, const float* xy, std::size_t n,
                    float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(perlin2_points)(key, period, xy, n, value, grad);
}
void perlin3_points(std::uint32_t key, const std::uint32_t* period, const float* xyz, std::size_t n,
                    float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(perlin3_points)(key, period, xyz, n, value, grad);
}
void perlin2_grid(std::uint32_t key, const std::uint32_t* period, const grid<2>& g,
                  std::size_t first, std::size_t count, float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(perlin2_grid)(key, period, g, first, count, value, grad);
}
void perlin3_grid(std::uint32_t key, const std::uint32_t* period, const grid<3>& g,
                  std::size_t first, std::size_t count, float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(perlin3_grid)(key, period, g, first, count, value, grad);
}

void fractal2_points(const fractal<perlin<2>>& fr, const float* xy, std::size_t n, float* value,
                     float* grad) {
  HWY_DYNAMIC_DISPATCH(fractal2_points)(fr, xy, n, value, grad);
}
void fractal3_points(const fractal<perlin<3>>& fr, const float* xyz, std::size_t n, float* value,
                     float* grad) {
  HWY_DYNAMIC_DISPATCH(fractal3_points)(fr, xyz, n, value, grad);
}
void fractal2_grid(const fractal<perlin<2>>& fr, const grid<2>& g, std::size_t first,
                   std::size_t count, float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(fractal2_grid)(fr, g, first, count, value, grad);
}
void fractal3_grid(const fractal<perlin<3>>& fr, const grid<3>& g, std::size_t first,
                   std::size_t count, float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(fractal3_grid)(fr, g, first, count, value, grad);
}

void coherent_pass(const detail::coherent_pass_job<float>& job) {
  HWY_DYNAMIC_DISPATCH(coherent_pass)(job);
}

void wavelet2_points(const wavelet<2>& w, const float* xy, std::size_t n, float* value,
                     float* grad) {
  HWY_DYNAMIC_DISPATCH(wavelet2_points)(w, xy, n, value, grad);
}
void wavelet3_points(const wavelet<3>& w, const float* xyz, std::size_t n, float* value,
                     float* grad) {
  HWY_DYNAMIC_DISPATCH(wavelet3_points)(w, xyz, n, value, grad);
}
void wavelet2_grid(const wavelet<2>& w, const grid<2>& g, float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(wavelet2_grid)(w, g, value, grad);
}
void wavelet3_grid(const wavelet<3>& w, const grid<3>& g, float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(wavelet3_grid)(w, g, value, grad);
}
void wavelet2_samples(const wavelet<2>& w, const samples<2>& s, float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(wavelet2_samples)(w, s, value, grad);
}
void wavelet3_samples(const wavelet<3>& w, const samples<3>& s, float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(wavelet3_samples)(w, s, value, grad);
}
void anisotropic_samples(const anisotropic& a, const float* xy, const float* fp, const float* map,
                         std::size_t n, float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(anisotropic_samples)(a, xy, fp, map, n, value, grad);
}
void anisotropic_grid(const anisotropic& a, const grid<2>& g, float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(anisotropic_grid)(a, g, value, grad);
}
void gabor2_points(const gabor<2>& g, const float* xy, std::size_t n, float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(gabor2_points)(g, xy, n, value, grad);
}
void gabor3_points(const gabor<3>& g, const float* xyz, std::size_t n, float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(gabor3_points)(g, xyz, n, value, grad);
}

void gabor2_grid(const gabor<2>& g, const grid<2>& gr, std::size_t first, std::size_t count,
                 float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(gabor2_grid)(g, gr, first, count, value, grad);
}
void gabor3_grid(const gabor<3>& g, const grid<3>& gr, std::size_t first, std::size_t count,
                 float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(gabor3_grid)(g, gr, first, count, value, grad);
}
void gabor2_filtered(const gabor<2>& g, const float* xy, const footprint<2>* fps, std::size_t n,
                     float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(gabor2_filtered)(g, xy, fps, n, value, grad);
}
void gabor3_filtered(const gabor<3>& g, const float* xyz, const footprint<3>* fps, std::size_t n,
                     float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(gabor3_filtered)(g, xyz, fps, n, value, grad);
}
void gabor3_surface(const gabor<3>& g, const float* xyz, const float* normals,
                    const footprint<3>* fps, std::size_t n, float* value, float* grad) {
  HWY_DYNAMIC_DISPATCH(gabor3_surface)(g, xyz, normals, fps, n, value, grad);
}

void npr_gabor_splat(const detail::npr_gabor_splat_job& job, const image_view<float>& out) {
  HWY_DYNAMIC_DISPATCH(npr_gabor_splat)(job, out);
}

std::vector<std::string> compiled_targets() {
  std::vector<std::string> names;
  // Lower bits are better targets in Highway's encoding.
  for (std::int64_t t = HWY_TARGETS; t != 0; t &= t - 1) names.push_back(hwy::TargetName(t & -t));
  return names;
}

std::string chosen_target() {
  const std::int64_t usable = hwy::SupportedTargets() & HWY_TARGETS;
  return usable ? hwy::TargetName(usable & -usable) : "none";
}

}  // namespace simd
// NOLINTEND(misc-definitions-in-headers)
}  // namespace hush

#endif  // HUSH_SIMD_DISPATCH_IMPL_ONCE
#endif  // HWY_ONCE
