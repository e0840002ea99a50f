// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// NPR Gabor noise's SIMD entry point (kernel: hush/npr_gabor/simd-inl.h):
// stage 2, the job's records added into out (frame-sized, zeroed by the
// caller), per pixel in record order; bit for bit
// detail::npr_gabor_splat_scalar<float> under HUSH_STRICT_FP.
// hush/npr_gabor.hpp calls it on exec::simd.
#ifndef HUSH_NPR_GABOR_SIMD_KERNEL_HPP
#define HUSH_NPR_GABOR_SIMD_KERNEL_HPP

#include "hush/config.hpp"
#include "hush/core/views.hpp"
#include "hush/npr_gabor/splat.hpp"
#include "hush/gabor.hpp"  // the Gabor kernels the splat shares
#include "hush/simd/dispatch.hpp"

#if HUSH_CONFIG_SIMD_STATIC
#include "hush/npr_gabor/simd-inl.h"
#endif

#define HUSH_SIMD_ENTRIES_NPR_GABOR(X)                                                       \
  X(npr_gabor_splat, (const detail::npr_gabor_splat_job& job, const image_view<float>& out), \
    (job, out))

HUSH_SIMD_DECLARE(HUSH_SIMD_ENTRIES_NPR_GABOR)

#endif  // HUSH_NPR_GABOR_SIMD_KERNEL_HPP
