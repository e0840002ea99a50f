// Anisotropic noise on a test scene's G-buffer (examples/anisotropic/scene_render.hpp):
// per-pixel footprints from the uv Jacobian, per-triangle surface maps from the meshes;
// finite everywhere, 0 on the background, scalar and SIMD agree.
#include <doctest/doctest.h>

#include <cmath>

#include "raster_cpu.hpp"
#include "scene_render.hpp"

TEST_CASE("anisotropic scene render: walkthrough frame, compensated, every backend agrees") {
  const hush_tools::scene::scene s = hush_tools::scene::make_scene("walkthrough");
  const hush_tools::scene::gbuffer g = hush_tools::scene::render_cpu(s, 3, 96, 54);
  const auto maps = hush_tools::aniso::scene_surface_maps(s);
  REQUIRE(maps.size() == s.objects.size());
  hush::anisotropic::params p;
  p.scales = 6;
  p.base_scale = 2;
  p.octaves = 2;
  p.frequency = 4;
  p.tile_size = 64;
  const hush::anisotropic noise(p);
  const std::vector<float> scalar =
      hush_tools::aniso::render_gbuffer(noise, g, maps, hush::exec::scalar);
  const std::vector<float> simd =
      hush_tools::aniso::render_gbuffer(noise, g, maps, hush::exec::simd);
  std::size_t covered = 0, nonzero = 0;
  for (std::size_t q = 0; q < g.pixels(); ++q) {
    REQUIRE(std::isfinite(scalar[q]));
    CHECK(std::fabs(double(simd[q]) - scalar[q]) <=
          2 * noise.float_budget() * noise.bound_with_maps() / noise.bound());
    if (!g.covered(q)) {
      CHECK(scalar[q] == 0.0f);
      continue;
    }
    ++covered;
    nonzero += scalar[q] != 0.0f;
  }
  CHECK(covered > g.pixels() / 2);
  // Zero where every subband is filtered away (the ground plane near the horizon).
  CHECK(nonzero > covered * 3 / 4);
}
