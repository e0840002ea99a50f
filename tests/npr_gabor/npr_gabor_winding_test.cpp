// npr_gabor::params::front_face and render's count of back faces (hush/npr_gabor.hpp
// "skipped triangles"): the winding that faces the camera, as seen on the displayed image.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "hush/hush.hpp"
#include "npr_gabor_scenes.hpp"

namespace {

using npr_test::grid_scene;

struct rendered {
  std::vector<float> image;
  hush::npr_gabor_render_stats stats;
};

template <class Exec>
rendered render(const Exec& ex, const hush::npr_gabor::params& p, const grid_scene& sc) {
  rendered r;
  r.image.assign(sc.width * sc.height, 0.0f);
  r.stats = hush::npr_gabor{p}.render(ex, sc.frame(), sc.triangles(),
                                      hush::image_view<float>(r.image.data(), sc.width, sc.height));
  return r;
}

bool all_zero(const std::vector<float>& v) {
  return std::all_of(v.begin(), v.end(), [](float x) { return x == 0.0f; });
}

}  // namespace

TEST_CASE("npr_gabor front_face: the wrong winding culls every triangle, counted, image 0") {
  // grid_scene's triangles are (i, j), (i, j + 1), (i + 1, j) in y-down pixels: down, then up
  // to the right, counter-clockwise as displayed (e1.x e2.y - e1.y e2.x < 0).
  const grid_scene ccw(48, 40, -4, -4, 7, 8, 7);
  grid_scene cw = ccw;  // every triangle's winding reversed
  for (std::size_t t = 0; t + 2 < cw.indices.size(); t += 3)
    std::swap(cw.indices[t + 1], cw.indices[t + 2]);
  const std::size_t triangles = ccw.indices.size() / 3;
  hush::npr_gabor::params p;
  p.bandwidth = 0.2;
  auto check = [&](const auto& ex) {
    // Default (counter-clockwise front): the scene renders, nothing culled.
    rendered r = render(ex, p, ccw);
    CHECK(r.stats.triangles == triangles);
    CHECK(r.stats.back_faces_culled == 0);
    CHECK_FALSE(all_zero(r.image));
    // The other winding with the default: every triangle a back face, the image 0.
    r = render(ex, p, cw);
    CHECK(r.stats.back_faces_culled == triangles);
    CHECK(all_zero(r.image));
    // front_face = clockwise: the reversed scene renders and the original is culled.
    hush::npr_gabor::params q = p;
    q.front_face = hush::npr_gabor_front_face::clockwise;
    r = render(ex, q, cw);
    CHECK(r.stats.back_faces_culled == 0);
    CHECK_FALSE(all_zero(r.image));
    r = render(ex, q, ccw);
    CHECK(r.stats.back_faces_culled == triangles);
    CHECK(all_zero(r.image));
    // Two-sided: nothing culled, whatever the winding.
    q.cull_back_faces = false;
    r = render(ex, q, ccw);
    CHECK(r.stats.back_faces_culled == 0);
    CHECK_FALSE(all_zero(r.image));
  };
  SUBCASE("scalar") { check(hush::exec::scalar); }
  SUBCASE("simd") { check(hush::exec::simd); }
}
