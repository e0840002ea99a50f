// Anisotropic noise's part of the params fuzz target (tests/fuzz/fuzz_params.cpp). Tile sizes
// stay small unless invalid, so one input builds its subband tiles in milliseconds.
#include "fuzz/fuzz_util.hpp"

namespace hush_fuzz {

void fuzz_anisotropic(FuzzedDataProvider& in) {
  hush::anisotropic::params prm;
  prm.seed = in.ConsumeIntegral<std::uint32_t>();
  prm.orientations = any_int(in, 0, 10);
  prm.scales = any_int(in, 0, 14);
  prm.base_scale = any_int(in, -1, 14);
  prm.octaves = any_int(in, 0, 14);
  prm.gain = any_double(in);
  prm.kind = any_enum<hush::fractal_kind>(in, 2);
  prm.frequency = any_double(in);
  constexpr int kSizes[] = {-16, 0, 8, 16, 24, 32, 4096};
  prm.tile_size = kSizes[in.ConsumeIntegralInRange<std::size_t>(0, std::size(kSizes) - 1)];
  prm.filtering = any_enum<hush::weight_rule>(in, 3);
  prm.compensation = any_enum<hush::weight_rule>(in, 3);
  const hush::anisotropic n(prm);
  probe_points(n, in);
  // A filtered sample: an arbitrary footprint from screen derivatives.
  const hush::vec<double, 2> p = any_position<2>(in);
  const hush::vec<double, 2> dx = any_position<2>(in), dy = any_position<2>(in);
  if (all_finite<2>(dx) && all_finite<2>(dy))
    check_value(n.sample(p, hush::footprint<2>::from_derivatives(dx, dy)), all_finite<2>(p));
}

}  // namespace hush_fuzz
