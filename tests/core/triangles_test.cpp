// hush::triangle_list (include/hush/core/triangles.hpp): validation names the array and the
// valid range, and reads no vertex value.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "hush/core/triangles.hpp"

namespace {

struct two_triangles {
  std::vector<std::uint32_t> indices{0, 1, 2, 2, 1, 3};
  std::vector<hush::vec2> screen{{0, 0}, {0, 4}, {4, 0}, {4, 4}};
  std::vector<float> depth{1, 1, 1, 1};
  std::vector<std::uint32_t> ids{7, 8}, objects{1, 1};
  hush::triangle_list list() const {
    hush::triangle_list t;
    t.indices = indices;
    t.screen = screen;
    t.depth = depth;
    t.triangle_id = ids;
    t.object_id = objects;
    return t;
  }
};

}  // namespace

TEST_CASE("triangle_list: a well-formed list validates, object ids are optional") {
  two_triangles s;
  CHECK(s.list().triangles() == 2);
  CHECK(s.list().vertices() == 4);
  CHECK_NOTHROW(s.list().validate("test", 2));
  hush::triangle_list t = s.list();
  t.object_id = {};
  CHECK_NOTHROW(t.validate("test", 2));
  CHECK(t.object_of(1) == 0u);
  CHECK(s.list().object_of(1) == 1u);
  // Vertex values are not validated: NaN positions are the noise's business.
  s.screen[0] = {std::nanf(""), 0};
  CHECK_NOTHROW(s.list().validate("test", 2));
}

TEST_CASE("triangle_list: malformed lists throw naming the array and the valid range") {
  two_triangles s;
  auto fails = [](const hush::triangle_list& t, const char* name) {
    CHECK_THROWS_WITH_AS(t.validate("where", 2), doctest::Contains(name), hush::invalid_argument);
  };
  hush::triangle_list t = s.list();
  t.indices = hush::span<const std::uint32_t>(s.indices.data(), 5);
  fails(t, "multiple of 3");
  CHECK_THROWS_WITH_AS(s.list().validate("where", 1), doctest::Contains("at most 3 x 1"),
                       hush::invalid_argument);
  t = s.list();
  t.depth = hush::span<const float>(s.depth.data(), 3);
  fails(t, "triangles.depth size");
  t = s.list();
  t.triangle_id = hush::span<const std::uint32_t>(s.ids.data(), 1);
  fails(t, "triangles.triangle_id size");
  t = s.list();
  t.object_id = hush::span<const std::uint32_t>(s.objects.data(), 1);
  fails(t, "triangles.object_id size");
  s.indices[5] = 4;
  fails(s.list(), "triangles.indices[5] = 4");
}
