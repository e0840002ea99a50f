// Tests for per-sample inputs through hush::evaluate (core/samples.hpp,
// exec.hpp): validation of the spans, the scalar and SIMD routes, and the
// public sample() overloads, with the probe noise whose value tells every
// input apart (probe_noise.hpp).
#include <doctest/doctest.h>

#include <cstddef>
#include <vector>

#include "hush/hush.hpp"
#include "probe_noise.hpp"

namespace {

// n samples with positions, footprints and normals that are small multiples of 1/8.
template <int D>
struct batch {
  std::vector<hush::vec<float, D>> positions;
  std::vector<hush::footprint<D>> footprints;
  std::vector<hush::vec3> normals;
  explicit batch(std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      hush::vec<float, D> p;
      for (int a = 0; a < D; ++a) p[std::size_t(a)] = float(int(i % 17) - 8 + a) / 8.0f;
      positions.push_back(p);
      hush::vec<double, D> dx{}, dy{};
      dx[0] = double(i % 5) / 2.0;
      dy[1] = double(i % 3) / 2.0;
      footprints.push_back(hush::footprint<D>::from_derivatives(dx, dy));
      normals.push_back({float(i % 4) / 8.0f, 0.5f, float(i % 7) / 8.0f});
    }
  }
};

}  // namespace

TEST_CASE("samples: each given input reaches the noise, per element, on scalar and simd") {
  const hush_test::probe_noise<3> noise;
  const batch<3> b(37);
  hush::samples<3> s{b.positions, b.footprints, b.normals};
  std::vector<float> scalar(37), simd(37);
  std::vector<hush::vec3> grad(37);
  hush::evaluate(noise, hush::exec::scalar, s, scalar, grad);
  hush::evaluate(noise, hush::exec::simd, s, simd);  // no kernel: the scalar loop
  for (std::size_t i = 0; i < 37; ++i) {
    const float want = noise.sample(b.positions[i], b.normals[i], b.footprints[i]);
    CHECK(scalar[i] == want);
    CHECK(simd[i] == want);
    CHECK(grad[i] == hush::vec3{1.0f, 0.5f, 0.25f});
  }
  // Footprints only, normals only: the other input is absent (the probe's -8, or S = 0).
  s.normals = {};
  hush::evaluate(noise, hush::exec::scalar, s, scalar);
  CHECK(scalar[5] == noise.sample(b.positions[5], b.footprints[5]));
  s.footprints = {};
  s.normals = b.normals;
  hush::evaluate(noise, hush::exec::scalar, s, scalar);
  CHECK(scalar[5] == noise.sample(b.positions[5], b.normals[5]));
}

TEST_CASE("samples: surface maps reach a 2D noise that takes them, per element") {
  const hush_test::probe_noise<2> noise;
  const batch<2> b(23);
  std::vector<hush::surface_map> maps;
  for (std::size_t i = 0; i < 23; ++i)
    maps.push_back({float(i % 3) / 8.0f, 0.5f, -float(i % 5) / 8.0f, 1.0f});
  hush::samples<2> s{b.positions, b.footprints, {}};
  s.surface_maps = maps;
  std::vector<float> scalar(23), simd(23);
  hush::evaluate(noise, hush::exec::scalar, s, scalar);
  hush::evaluate(noise, hush::exec::simd, s, simd);
  for (std::size_t i = 0; i < 23; ++i) {
    const float want = noise.sample(b.positions[i], b.footprints[i], maps[i]);
    CHECK(scalar[i] == want);
    CHECK(simd[i] == want);
    CHECK(want != noise.sample(b.positions[i], b.footprints[i]));  // the map counts
  }
  // Maps alone, and a wrong length, named.
  s.footprints = {};
  hush::evaluate(noise, hush::exec::scalar, s, scalar);
  CHECK(scalar[4] == noise.sample(b.positions[4], hush::footprint<2>{}, maps[4]));
  s.surface_maps = hush::span<const hush::surface_map>(maps.data(), 22);
  CHECK_THROWS_WITH_AS(hush::evaluate(noise, hush::exec::scalar, s, scalar),
                       doctest::Contains("samples.surface_maps.size() = 22"),
                       hush::invalid_argument);
  // A noise that takes no map refuses them by name.
  const hush::perlin<2> perlin{3};
  s.surface_maps = maps;
  CHECK_THROWS_WITH_AS(hush::evaluate(perlin, hush::exec::scalar, s, scalar),
                       doctest::Contains("samples.surface_maps given"), hush::invalid_argument);
}

TEST_CASE("samples: positions only equal the points overload, for any noise") {
  const hush::perlin<2> perlin{7};
  const batch<2> b(50);
  std::vector<float> via_samples(50), via_points(50);
  hush::evaluate(perlin, hush::exec::simd, hush::samples<2>{b.positions, {}, {}}, via_samples);
  hush::evaluate(perlin, hush::exec::simd, b.positions, via_points);
  CHECK(via_samples == via_points);
  const hush_test::probe_noise<2> probe;
  hush::evaluate(probe, hush::exec::scalar, hush::samples<2>{b.positions, {}, {}}, via_samples);
  for (std::size_t i = 0; i < 50; ++i) CHECK(via_samples[i] == probe(b.positions[i]));
}

TEST_CASE("samples: mismatched spans and inputs the noise does not take are refused by name") {
  const hush_test::probe_noise<3> probe;
  const batch<3> b(10);
  std::vector<float> out(10);
  const std::vector<hush::footprint<3>> short_fp(b.footprints.begin(), b.footprints.begin() + 9);
  CHECK_THROWS_WITH_AS(
      hush::evaluate(probe, hush::exec::scalar, hush::samples<3>{b.positions, short_fp, {}}, out),
      doctest::Contains("samples.footprints.size() = 9"), hush::invalid_argument);
  const std::vector<hush::vec3> long_n(11);
  CHECK_THROWS_WITH_AS(
      hush::evaluate(probe, hush::exec::scalar, hush::samples<3>{b.positions, {}, long_n}, out),
      doctest::Contains("samples.normals.size() = 11"), hush::invalid_argument);
  std::vector<float> short_out(9);
  CHECK_THROWS_WITH_AS(
      hush::evaluate(probe, hush::exec::scalar, hush::samples<3>{b.positions, {}, {}}, short_out),
      doctest::Contains("out"), hush::invalid_argument);
  // Perlin filters nothing and takes no normal.
  const hush::perlin<3> perlin{1};
  CHECK_THROWS_WITH_AS(hush::evaluate(perlin, hush::exec::scalar,
                                      hush::samples<3>{b.positions, b.footprints, {}}, out),
                       doctest::Contains("samples.footprints given"), hush::invalid_argument);
  CHECK_THROWS_WITH_AS(
      hush::evaluate(perlin, hush::exec::simd, hush::samples<3>{b.positions, {}, b.normals}, out),
      doctest::Contains("samples.normals given"), hush::invalid_argument);
  // A 2D noise takes no normal either.
  const hush_test::probe_noise<2> probe2;
  const batch<2> b2(10);
  CHECK_THROWS_WITH_AS(hush::evaluate(probe2, hush::exec::scalar,
                                      hush::samples<2>{b2.positions, {}, b.normals}, out),
                       doctest::Contains("samples.normals given"), hush::invalid_argument);
  // Nothing was written by a refused call, and an empty batch is fine.
  std::vector<float> empty;
  hush::evaluate(probe, hush::exec::scalar, hush::samples<3>{}, empty);
}

TEST_CASE("samples: subrange cuts every given span and refuses a range past the batch") {
  const batch<3> b(10);
  const hush::samples<3> all{b.positions, b.footprints, {}};
  const hush::samples<3> part = all.subrange(3, 4);
  REQUIRE(part.size() == 4);
  CHECK(part.positions.data() == all.positions.data() + 3);
  CHECK(part.footprints.data() == all.footprints.data() + 3);
  CHECK(part.footprints.size() == 4);
  CHECK(part.normals.empty());
  CHECK(all.subrange(10, 0).size() == 0);
  CHECK_THROWS_WITH_AS(all.subrange(7, 4),
                       doctest::Contains("offset = 7, count = 4 is out of range; valid: "
                                         "offset + count <= size() = 10"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(all.subrange(11, 0), doctest::Contains("offset = 11, count = 0"),
                       hush::invalid_argument);
  // An offset near SIZE_MAX cannot wrap the check around.
  CHECK_THROWS_AS(all.subrange(3, static_cast<std::size_t>(-1)), hush::invalid_argument);
  const std::vector<hush::footprint<3>> short_fp(b.footprints.begin(), b.footprints.begin() + 9);
  CHECK_THROWS_WITH_AS((hush::samples<3>{b.positions, short_fp, {}}.subrange(0, 5)),
                       doctest::Contains("footprints.size() = 9 is out of range"),
                       hush::invalid_argument);
}
