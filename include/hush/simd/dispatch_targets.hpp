// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::simd::compiled_targets() and chosen_target() of the dynamic route
// (HUSH_SIMD_DYNAMIC), defined once: src/simd/targets.cpp in the CMake target
// hush::simd, or hush/simd/dispatch_impl.hpp.
#ifndef HUSH_SIMD_DISPATCH_TARGETS_HPP
#define HUSH_SIMD_DISPATCH_TARGETS_HPP

#if !defined(HUSH_SIMD_DYNAMIC)
#error "hush/simd/dispatch_targets.hpp needs HUSH_SIMD_DYNAMIC defined for the whole program"
#endif

#include <cstdint>
#include <string>
#include <vector>

#include "hush/config.hpp"  // before Highway: HWY_WANT_AVX3_DL

#include <hwy/highway.h>
#include <hwy/targets.h>

#include "hush/simd/dispatch.hpp"

// NOLINTBEGIN(misc-definitions-in-headers): the body of one translation unit
namespace hush {
namespace simd {

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
}  // namespace hush
// NOLINTEND(misc-definitions-in-headers)

#endif  // HUSH_SIMD_DISPATCH_TARGETS_HPP
