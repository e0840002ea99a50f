// libFuzzer target: every noise's params validation, then evaluation of what it accepted.
// The first byte picks the noise (the registry's list, HUSH_NOISE_LIST); the rest fills its
// params with values at and beyond every edge of their domains. Properties: construction
// either succeeds or throws hush::invalid_argument (nothing else, no crash, no hang, no
// sanitizer report); an accepted noise evaluates as documented (fuzz_util.hpp check_value).
#include <cstddef>
#include <cstdint>

#include "fuzz_util.hpp"
#include "hush_tools/noise_list.hpp"

namespace hush_fuzz {
#define HUSH_FUZZ_DECLARE(noise) void fuzz_##noise(FuzzedDataProvider& in);
HUSH_NOISE_LIST(HUSH_FUZZ_DECLARE)
#undef HUSH_FUZZ_DECLARE
}  // namespace hush_fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using fuzz_fn = void (*)(FuzzedDataProvider&);
  static constexpr fuzz_fn kNoises[] = {
#define HUSH_FUZZ_ENTRY(noise) hush_fuzz::fuzz_##noise,
      HUSH_NOISE_LIST(HUSH_FUZZ_ENTRY)
#undef HUSH_FUZZ_ENTRY
  };
  FuzzedDataProvider in(data, size);
  const auto which = in.ConsumeIntegralInRange<std::size_t>(0, std::size(kNoises) - 1);
  try {
    kNoises[which](in);
  } catch (const hush::invalid_argument&) {
    // The documented answer to parameters outside their domain.
  }
  return 0;
}
