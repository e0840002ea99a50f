// hush — the public include paths of 0.1.x that now forward to a noise's folder
// (hush/wavelet_tile.hpp, hush/gabor_kernel.hpp, ...): each still compiles on its
// own and declares what it declared. This unit includes them and nothing else of
// hush, so a forward that lost its target fails to build.
#include <doctest/doctest.h>

#include <type_traits>

#include "hush/gabor_kernel.hpp"
#include "hush/steerable.hpp"
#include "hush/style.hpp"
#include "hush/subband_fit.hpp"
#include "hush/wavelet_tile.hpp"

TEST_CASE("include paths: the forwarding headers of 0.1.x declare their types") {
  CHECK(std::is_class<hush::wavelet_tile<2>>::value);
  CHECK(std::is_class<hush::wavelet_tile<3>>::value);
  CHECK(std::is_class<hush::gabor_kernel<2>>::value);
  CHECK(std::is_class<hush::steerable_bank>::value);
  CHECK(std::is_class<hush::subband_fit>::value);
  CHECK(std::is_class<hush::style::binary>::value);
}
