// The SIMD kernels compiled with this suite's flags (HUSH_STRICT_FP,
// -ffp-contract=off), not taken from hush::simd, so the bit-identity claim is
// tested on code built the way it is made.
#include "hush/simd/dispatch_impl.hpp"
