// Wavelet noise's part of the params fuzz target (tests/fuzz/fuzz_params.cpp). Tile sizes stay
// small unless invalid, so one input builds its tile in milliseconds.
#include "fuzz/fuzz_util.hpp"

namespace hush_fuzz {

template <int D>
void fuzz_wavelet_d(FuzzedDataProvider& in) {
  typename hush::wavelet<D>::params prm;
  prm.seed = in.ConsumeIntegral<std::uint32_t>();
  constexpr int kSizes[] = {-16, 0, 15, 16, 17, 18, 32, 5000};
  prm.tile_size = kSizes[in.ConsumeIntegralInRange<std::size_t>(0, std::size(kSizes) - 1)];
  prm.first_band = any_int(in, -40, 40);
  const int nw = in.ConsumeIntegralInRange<int>(0, 34);
  prm.weights.clear();
  for (int i = 0; i < nw; ++i) prm.weights.push_back(any_double(in));
  if (in.ConsumeIntegralInRange<int>(0, 3) == 0) {
    const int no = in.ConsumeIntegralInRange<int>(0, nw + 1);
    for (int i = 0; i < no; ++i) {
      hush::vec<double, D> o;
      for (int a = 0; a < D; ++a) o[a] = any_double(in);
      prm.offsets.push_back(o);
    }
  }
  prm.even_odd_fix = in.ConsumeBool();
  prm.distribution = any_enum<hush::wavelet_distribution>(in, 3);
  prm.gaussian_scale = any_double(in);
  if (prm.distribution == hush::wavelet_distribution::table) {
    const int nt = in.ConsumeIntegralInRange<int>(0, 12);
    for (int i = 0; i < nt; ++i) prm.table.push_back(any_double(in));
  }
  prm.projection = any_enum<hush::wavelet_projection>(in, 2);
  prm.widen = in.ConsumeBool();
  prm.relative_weights = in.ConsumeBool();
  prm.relative_bands = any_int(in, -2, 40);
  prm.variant_overlap = any_int(in, -2, 8);
  const hush::wavelet<D> n(prm);
  probe_points(n, in);
}

void fuzz_wavelet(FuzzedDataProvider& in) {
  if (in.ConsumeBool())
    fuzz_wavelet_d<2>(in);
  else
    fuzz_wavelet_d<3>(in);
}

}  // namespace hush_fuzz
