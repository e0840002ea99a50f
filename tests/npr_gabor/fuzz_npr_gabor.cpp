// NPR Gabor noise's part of the params fuzz target (tests/fuzz/fuzz_params.cpp).
#include "fuzz/fuzz_util.hpp"

namespace hush_fuzz {

void fuzz_npr_gabor(FuzzedDataProvider& in) {
  hush::npr_gabor::params prm;
  prm.frequency = any_double(in);
  prm.bandwidth = any_double(in);
  prm.truncation = any_double(in);
  prm.impulses = any_double(in);
  prm.orientation = any_double(in);
  prm.isotropic = in.ConsumeBool();
  prm.seed = in.ConsumeIntegral<std::uint32_t>();
  prm.object_test = in.ConsumeBool();
  prm.triangle_test = in.ConsumeBool();
  prm.depth_test = in.ConsumeBool();
  prm.soft_depth = in.ConsumeBool();
  prm.depth_tolerance = any_double(in);
  prm.cull_back_faces = in.ConsumeBool();
  prm.thinning = in.ConsumeBool();
  prm.local_density = in.ConsumeBool();
  const hush::npr_gabor n(prm);
  (void)n;
}

}  // namespace hush_fuzz
