// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The body of one dynamic-dispatch translation unit (HUSH_SIMD_DYNAMIC): it
// compiles the kernels of HUSH_SIMD_UNIT_INL once per SIMD target Highway
// builds for (Highway's HWY_TARGET_INCLUDE + foreach_target.h pattern) and
// defines, from the X-macro list HUSH_SIMD_UNIT_ENTRIES (hush/simd/dispatch.hpp),
// Highway's export table and the hush::simd::<name> function of every entry,
// which runs the best target the CPU supports. A unit first includes the
// public headers its kernels need, then names its kernels and list:
//
//   #include "hush/perlin.hpp"
//   #define HUSH_SIMD_UNIT_INL "hush/perlin/simd-inl.h"
//   #define HUSH_SIMD_UNIT_ENTRIES HUSH_SIMD_ENTRIES_PERLIN
//   #include "hush/simd/dispatch_unit.hpp"
//
// src/simd/<noise>.cpp are these units (one per noise, so a 2-core build
// compiles them side by side and an edit of one noise recompiles one unit);
// hush/simd/dispatch_impl.hpp is one unit holding every noise.
//
// No include guard on purpose: foreach_target.h re-includes this file once
// per target; the HWY_ONCE part at the end is compiled once.
#if !defined(HUSH_SIMD_DYNAMIC)
#error "hush/simd/dispatch_unit.hpp needs HUSH_SIMD_DYNAMIC defined for the whole program"
#endif
#if !defined(HUSH_SIMD_UNIT_INL) || !defined(HUSH_SIMD_UNIT_ENTRIES)
#error \
    "define HUSH_SIMD_UNIT_INL and HUSH_SIMD_UNIT_ENTRIES before including hush/simd/dispatch_unit.hpp"
#endif

#include "hush/config.hpp"  // before Highway: HWY_WANT_AVX3_DL

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "hush/simd/dispatch_unit.hpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include HUSH_SIMD_UNIT_INL

#if HWY_ONCE
#ifndef HUSH_SIMD_DISPATCH_UNIT_ONCE
#define HUSH_SIMD_DISPATCH_UNIT_ONCE

#include "hush/simd/dispatch.hpp"

#define HUSH_SIMD_EXPORT_ONE(name, params, args) HWY_EXPORT(name);
// Defined here exactly once (this header is the body of one translation
// unit), so deliberately not inline: inline would leave them undefined for
// every other translation unit that calls them.
#define HUSH_SIMD_DYNAMIC_ONE(name, params, args) \
  void name params { HWY_DYNAMIC_DISPATCH(name) args; }

// NOLINTBEGIN(misc-definitions-in-headers)
namespace hush {
HUSH_SIMD_UNIT_ENTRIES(HUSH_SIMD_EXPORT_ONE)
namespace simd {
HUSH_SIMD_UNIT_ENTRIES(HUSH_SIMD_DYNAMIC_ONE)
}  // namespace simd
}  // namespace hush
// NOLINTEND(misc-definitions-in-headers)

#undef HUSH_SIMD_EXPORT_ONE
#undef HUSH_SIMD_DYNAMIC_ONE

#endif  // HUSH_SIMD_DISPATCH_UNIT_ONCE
#endif  // HWY_ONCE
