// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The batch driver the SIMD point kernels share (simd/perlin-inl.h,
// simd/wavelet-inl.h): fn(first, pts, value, grad) over n points of D floats, one
// vector of lanes at a time from point `first`; the last partial vector goes
// through zero-padded buffers, so no lane reads or writes out of bounds (its
// lanes past n read zeros, their results are dropped). grad may be null (values
// only; fn then gets null). Compiled once per SIMD target (the "-inl.h"
// convention: toggle guard below); reached through hush/simd/dispatch.hpp.
#if defined(HUSH_SIMD_BATCH_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_SIMD_BATCH_INL_H_
#undef HUSH_SIMD_BATCH_INL_H_
#else
#define HUSH_SIMD_BATCH_INL_H_
#endif

#include <cstddef>
#include <cstring>

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace simd_batch {
namespace hn = hwy::HWY_NAMESPACE;

// Largest float lane count of any target (SVE's 2048 bits), for buffers and
// table padding sized once for every target; every kernel uses this one.
constexpr std::size_t kMaxLanes = 64;

template <int D, class Fn>
HWY_INLINE void for_each_vector(std::size_t n, const float* pts, float* value, float* grad,
                                const Fn& fn) {
  constexpr std::size_t kMax = kMaxLanes;
  const std::size_t lanes = hn::Lanes(hn::ScalableTag<float>());
  std::size_t i = 0;
  for (; i + lanes <= n; i += lanes) fn(i, pts + i * D, value + i, grad ? grad + i * D : nullptr);
  if (i == n) return;
  const std::size_t rest = n - i;
  HWY_ALIGN float in[kMax * D] = {}, out[kMax] = {}, g[kMax * D] = {};
  std::memcpy(in, pts + i * D, rest * D * sizeof(float));
  fn(i, in, out, grad ? g : nullptr);
  std::memcpy(value + i, out, rest * sizeof(float));
  if (grad) std::memcpy(grad + i * D, g, rest * D * sizeof(float));
}

}  // namespace simd_batch
}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_SIMD_BATCH_INL_H_ toggle
