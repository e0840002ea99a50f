// Gabor noise's part of the params fuzz target (tests/fuzz/fuzz_params.cpp).
#include "fuzz/fuzz_util.hpp"

namespace hush_fuzz {

template <int D>
void fuzz_gabor_d(FuzzedDataProvider& in) {
  typename hush::gabor<D>::params prm;
  prm.seed = in.ConsumeIntegral<std::uint32_t>();
  prm.kind = any_enum<hush::gabor_kind>(in, 3);
  prm.frequency = any_double(in);
  prm.bandwidth = any_double(in);
  prm.orientation = any_double(in);
  prm.elevation = any_double(in);
  prm.orientation_spread = any_double(in);
  prm.frequency_spread = any_double(in);
  prm.impulses = any_double(in);
  prm.truncation = any_double(in);
  const hush::gabor<D> n(prm);
  // The documented domain: |p| / r finite (the cell coordinate).
  probe_points(n, in, std::numeric_limits<double>::max() / n.inverse_cell());
  // A filtered sample with an arbitrary footprint width.
  const hush::vec<double, D> p = any_position<D>(in);
  const double w = any_double(in);
  if (std::isfinite(w) && w > 0) check_value(n.sample(p, hush::footprint<D>::isotropic(w)), all_finite<D>(p));
}

void fuzz_gabor(FuzzedDataProvider& in) {
  if (in.ConsumeBool())
    fuzz_gabor_d<2>(in);
  else
    fuzz_gabor_d<3>(in);
}

}  // namespace hush_fuzz
