// Fractal sums' part of the params fuzz target (tests/fuzz/fuzz_params.cpp).
#include "fuzz/fuzz_util.hpp"

namespace hush_fuzz {

template <int D>
void fuzz_fractal_d(FuzzedDataProvider& in) {
  typename hush::fractal<hush::perlin<D>>::params prm;
  prm.seed = in.ConsumeIntegral<std::uint32_t>();
  prm.kind = any_enum<hush::fractal_kind>(in, 2);
  prm.octaves = any_int(in, -2, 40);
  prm.frequency = any_double(in);
  prm.lacunarity = any_double(in);
  prm.gain = any_double(in);
  const int nw = in.ConsumeIntegralInRange<int>(0, 3) == 0 ? in.ConsumeIntegralInRange<int>(0, 34) : 0;
  for (int i = 0; i < nw; ++i) prm.weights.push_back(any_double(in));
  prm.norm = any_enum<hush::normalization>(in, 3);
  for (int a = 0; a < D; ++a) prm.period[a] = any_int(in, -4, 1 << 16);
  const hush::fractal<hush::perlin<D>> n(prm);
  probe_points(n, in);
}

void fuzz_fractal(FuzzedDataProvider& in) {
  if (in.ConsumeBool())
    fuzz_fractal_d<2>(in);
  else
    fuzz_fractal_d<3>(in);
}

}  // namespace hush_fuzz
