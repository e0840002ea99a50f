// Perlin noise's part of the params fuzz target (tests/fuzz/fuzz_params.cpp).
#include "fuzz/fuzz_util.hpp"

namespace hush_fuzz {

template <int D>
void fuzz_perlin_d(FuzzedDataProvider& in) {
  typename hush::perlin<D>::params prm;
  prm.seed = in.ConsumeIntegral<std::uint32_t>();
  for (int a = 0; a < D; ++a) prm.period[a] = any_int(in, -4, 1 << 20);
  const hush::perlin<D> n(prm);
  probe_points(n, in);
}

void fuzz_perlin(FuzzedDataProvider& in) {
  if (in.ConsumeBool())
    fuzz_perlin_d<2>(in);
  else
    fuzz_perlin_d<3>(in);
}

}  // namespace hush_fuzz
