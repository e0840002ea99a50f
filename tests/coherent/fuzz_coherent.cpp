// Coherent noise's part of the params fuzz target (tests/fuzz/fuzz_params.cpp): validation,
// then two frames of a stream over a tiny G-buffer whose depths and velocities are fuzzed too
// (NaN, infinities, huge motion). Property beyond validation: the output never holds NaN or an
// infinity (the history never holds NaN, HARD_CASES row 13).
#include "fuzz/fuzz_util.hpp"

namespace hush_fuzz {

void fuzz_coherent(FuzzedDataProvider& in) {
  hush::coherent_params prm;
  prm.seed = in.ConsumeIntegral<std::uint32_t>();
  prm.alpha = any_double(in);
  prm.epsilon = any_double(in);
  prm.epsilon_absolute = any_double(in);
  prm.filter = any_enum<hush::coherent_filter>(in, 2);
  prm.input = any_enum<hush::coherent_input>(in, 2);
  prm.bandpass_pixels = any_double(in);
  prm.smoothing = any_double(in);
  prm.channels = any_int(in, -1, 5);
  hush::coherent_stream stream(prm);
  constexpr std::size_t w = 4, h = 3;
  std::vector<float> depth(w * h);
  std::vector<hush::vec3> velocity(w * h);
  const auto channels = static_cast<std::size_t>(prm.channels);
  std::vector<float> out(w * h * channels);
  std::vector<hush::image_view<float>> views;
  for (std::size_t c = 0; c < channels; ++c) views.push_back({out.data() + c * w * h, w, h});
  for (int f = 0; f < 2; ++f) {
    for (std::size_t i = 0; i < w * h; ++i) {
      depth[i] = static_cast<float>(in.ConsumeBool() ? any_double(in) : 1.0 + 0.01 * double(i));
      velocity[i] = hush::vec3{static_cast<float>(any_double(in)), static_cast<float>(any_double(in)),
                               static_cast<float>(any_double(in))};
    }
    hush::frame fr;
    fr.depth = {depth.data(), w, h};
    fr.velocity = {velocity.data(), w, h};
    stream.advance(hush::exec::scalar, fr,
                   hush::span<const hush::image_view<float>>(views.data(), views.size()));
    for (float v : out)
      if (!std::isfinite(v)) fail("coherent noise output a non-finite value", double(v));
  }
}

}  // namespace hush_fuzz
