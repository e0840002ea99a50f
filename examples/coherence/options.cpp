// hush — temporal-coherence metrics: option validation (see options.hpp).
#include "coherence/options.hpp"

#include <limits>

#include "hush/core/error.hpp"

namespace hush_tools {
namespace coherence {

void validate(const options& o) {
  const char* where = "hush_tools::coherence::options";
  hush::detail::require_in_range(where, "depth_epsilon", o.depth_epsilon, 0.0, 1.0, "0 ... 1");
  hush::detail::require_in_range(where, "min_pixels", o.min_pixels, std::size_t{2},
                                 std::numeric_limits<std::size_t>::max(), ">= 2");
  hush::detail::require_in_range(where, "popping_threshold", o.popping_threshold, 0.0,
                                 std::numeric_limits<double>::max(), "a finite number >= 0");
  hush::detail::require_in_range(where, "window", o.window, 4, 4096, "4 ... 4096");
  hush::detail::require_in_range(where, "window_stride", o.window_stride, 1, 4096, "1 ... 4096");
  hush::detail::require_in_range(where, "depth_bins", o.depth_bins, 1, 64, "1 ... 64");
  hush::detail::require_in_range(where, "min_windows", o.min_windows, std::size_t{1},
                                 std::numeric_limits<std::size_t>::max(), ">= 1");
}

}  // namespace coherence
}  // namespace hush_tools
