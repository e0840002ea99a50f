// hush::frame (core/frame.hpp): the uv and uv_jacobian views (anisotropic noise's per-pixel
// inputs) are reported by present() and checked by validate() like the other views.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "hush/core/error.hpp"
#include "hush/core/frame.hpp"

namespace {

std::string message_of(const hush::frame& f, hush::frame_view required) {
  try {
    f.validate("frame_test", required, 64);
  } catch (const hush::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("frame: uv and uv_jacobian views are present, required and size-checked by name") {
  std::vector<float> depth(8 * 4, 1.0f);
  std::vector<hush::vec2> uv(8 * 4);
  std::vector<hush::vec4> jac(8 * 4);
  hush::frame f;
  f.depth = {depth.data(), 8, 4};
  CHECK_FALSE(hush::has_view(f.present(), hush::frame_view::uv));
  CHECK(message_of(f, hush::frame_view::uv).find("frame.uv is required") != std::string::npos);
  CHECK(message_of(f, hush::frame_view::uv_jacobian).find("frame.uv_jacobian is required") !=
        std::string::npos);
  f.uv = {uv.data(), 8, 4};
  f.uv_jacobian = {jac.data(), 8, 4};
  CHECK(hush::has_view(f.present(), hush::frame_view::uv));
  CHECK(hush::has_view(f.present(), hush::frame_view::uv_jacobian));
  CHECK(message_of(f, hush::frame_view::uv | hush::frame_view::uv_jacobian).empty());
  f.uv = {uv.data(), 4, 8};  // same pixel count, wrong shape
  CHECK(message_of(f, hush::frame_view::none).find("frame.uv size") != std::string::npos);
  f.uv = {uv.data(), 8, 4};
  f.uv_jacobian.stride = 2;  // below the width (the constructor refuses it; set afterwards)
  CHECK(message_of(f, hush::frame_view::none).find("frame.uv_jacobian.stride") !=
        std::string::npos);
}
