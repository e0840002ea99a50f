// Tests for hush/core/vec.hpp and hush/core/views.hpp: construction, indexing,
// glm interop both ways, and the views' indexing contracts.
#include <doctest/doctest.h>

#include <array>
#include <vector>

#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"

TEST_CASE("vec: components and indexing name the same storage") {
  hush::vec3 v{1.0f, 2.0f, 3.0f};
  CHECK(v[0] == 1.0f);
  CHECK(v[2] == 3.0f);
  v[1] = 5.0f;
  CHECK(v.y == 5.0f);
  hush::dvec4 w{1, 2, 3, 4};
  CHECK(w[3] == 4.0);
  static_assert(hush::vec2{1, 2}[1] == 2, "constexpr indexing");
  auto [x, y, z] = v;
  CHECK(x + y + z == 9.0f);
}

TEST_CASE("vec: vec_cast converts element types component-wise") {
  const hush::dvec3 d = hush::vec_cast<double>(hush::vec3{0.5f, -1.25f, 3.0f});
  CHECK(d == hush::dvec3{0.5, -1.25, 3.0});
}

#if HUSH_CONFIG_GLM
TEST_CASE("vec: converts implicitly from and to glm::vec") {
  auto takes_hush = [](const hush::vec3& v) { return v.x + v.y + v.z; };
  CHECK(takes_hush(glm::vec3(1.0f, 2.0f, 4.0f)) == 7.0f);
  const glm::dvec2 g = hush::dvec2{3.0, 4.0};
  CHECK(g.x == 3.0);
  CHECK(g.y == 4.0);
  const hush::vec4 h = glm::vec4(1, 2, 3, 4);
  CHECK(h.w == 4.0f);
}
#endif

TEST_CASE("span: views vectors, arrays and C arrays without copying") {
  std::vector<float> v{1, 2, 3};
  hush::span<float> s = v;
  CHECK(s.size() == 3);
  CHECK(s.data() == v.data());
  s[1] = 7;
  CHECK(v[1] == 7);
  hush::span<const float> cs = s;
  CHECK(cs[1] == 7);
  std::array<int, 4> a{};
  CHECK(hush::span<int>(a).size() == 4);
  double c[5] = {};
  CHECK(hush::span<double>(c).size() == 5);
  CHECK(s.subspan(1, 2)[0] == 7);
}

TEST_CASE("grid: positions are origin + step * index and counts multiply") {
  hush::grid<3> g{{1.0, 2.0, 3.0}, {0.5, -1.0, 2.0}, {4, 3, 2}};
  CHECK(g.count() == 24);
  CHECK(g.position({3, 2, 1}) == hush::dvec3{2.5, 0.0, 5.0});
  g.validate("test");
  hush::grid<2> bad{{0.0, 0.0}, {0.0, 1.0}, {2, 2}};
  CHECK_THROWS_AS(bad.validate("test"), hush::invalid_argument);
  CHECK_THROWS_WITH(bad.validate("test"), doctest::Contains("grid.step[0]"));
}

TEST_CASE("image_view: row stride separates rows") {
  std::vector<int> px(12);
  hush::image_view<int> img(px.data(), 3, 3, 4);
  img(2, 1) = 9;
  CHECK(px[1 * 4 + 2] == 9);
  CHECK_THROWS_AS(hush::image_view<int>(px.data(), 5, 2, 4), hush::invalid_argument);
}
