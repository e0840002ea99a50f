// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Coherent noise's SIMD entry point (kernel: hush/coherent/simd-inl.h): one
// recursive-filter pass over a frame, the same result as
// detail::coherent_pass_scalar, bit for bit under HUSH_STRICT_FP.
// hush/coherent.hpp calls it on exec::simd.
#ifndef HUSH_COHERENT_SIMD_KERNEL_HPP
#define HUSH_COHERENT_SIMD_KERNEL_HPP

#include "hush/config.hpp"
#include "hush/coherent/kernel.hpp"
#include "hush/simd/dispatch.hpp"

#if HUSH_CONFIG_SIMD_STATIC
#include "hush/coherent/simd-inl.h"
#endif

#define HUSH_SIMD_ENTRIES_COHERENT(X) \
  X(coherent_pass, (const detail::coherent_pass_job<float>& job), (job))

HUSH_SIMD_DECLARE(HUSH_SIMD_ENTRIES_COHERENT)

#endif  // HUSH_COHERENT_SIMD_KERNEL_HPP
