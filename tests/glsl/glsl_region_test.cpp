// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Blocks of a grid (hush::grid::block) on the GLSL device: a block evaluated
// on its own gives, bit for bit, the values and gradients the whole grid's
// call gives the same samples, for every noise with a GLSL grid program. The
// device splits each axis position on the CPU (grid::coordinate), so a block's
// cells and fractions are the whole grid's; the grid is far from the origin
// (1e5 + 0.1, not a multiple of the step 1/3, negative along y) and the blocks
// start at odd indices along every axis.
#include <doctest/doctest.h>

#include <array>
#include <cstddef>
#include <cstring>
#include <vector>

#include "glsl_test_util.hpp"
#include "hush/exec.hpp"
#include "hush/glsl/device.hpp"
#include "hush/glsl/export.hpp"
#include "hush/hush.hpp"

namespace {

using hush_glsl_test::headless;

template <int D>
hush::grid<D> far_grid() {
  hush::grid<D> g;
  for (int a = 0; a < D; ++a) {
    g.origin[a] = 1e5 + 0.1 + 17.0 * a;
    g.step[a] = a == 1 ? -1.0 / 3.0 : 1.0 / 3.0;
    g.size[a] = D == 2 ? 23 - 6 * a : 11 - 2 * a;
  }
  return g;
}

// The whole grid, and blocks cut at 0, 3, an odd middle index and the end along every
// axis, on the device: values and gradients bit for bit.
template <class Noise>
void check_blocks(const Noise& noise) {
  constexpr int D = Noise::dimension;
  hush::glsl::device& dev = headless().device;
  const hush::grid<D> whole = far_grid<D>();
  std::vector<float> want(whole.count());
  std::vector<hush::vec<float, D>> want_g(whole.count());
  hush::evaluate_grid(noise, hush::exec::glsl{dev}, whole, want, want_g);
  std::array<std::vector<std::size_t>, 3> cuts;
  for (int a = 0; a < 3; ++a)
    cuts[a] = a < D ? std::vector<std::size_t>{0, 3, whole.size[a] / 2 | 1, whole.size[a]}
                    : std::vector<std::size_t>{0, 1};
  std::size_t mismatches = 0;
  for (std::size_t bz = 0; bz + 1 < cuts[2].size(); ++bz)
    for (std::size_t by = 0; by + 1 < cuts[1].size(); ++by)
      for (std::size_t bx = 0; bx + 1 < cuts[0].size(); ++bx) {
        const std::size_t lo[3] = {cuts[0][bx], cuts[1][by], cuts[2][bz]};
        const std::size_t hi[3] = {cuts[0][bx + 1], cuts[1][by + 1], cuts[2][bz + 1]};
        std::array<std::size_t, D> first{}, size{};
        for (int a = 0; a < D; ++a) {
          first[a] = lo[a];
          size[a] = hi[a] - lo[a];
        }
        const hush::grid<D> b = whole.block(first, size);
        std::vector<float> got(b.count());
        std::vector<hush::vec<float, D>> got_g(b.count());
        hush::evaluate_grid(noise, hush::exec::glsl{dev}, b, got, got_g);
        std::size_t idx = 0;
        for (std::size_t k = lo[2]; k < hi[2]; ++k)
          for (std::size_t j = lo[1]; j < hi[1]; ++j)
            for (std::size_t i = lo[0]; i < hi[0]; ++i, ++idx) {
              const std::size_t w = (k * whole.size[1] + j) * whole.size[0] + i;
              if (std::memcmp(&got[idx], &want[w], sizeof(float)) != 0 ||
                  std::memcmp(&got_g[idx], &want_g[w], sizeof(got_g[0])) != 0)
                ++mismatches;
            }
      }
  CHECK(mismatches == 0);
}

}  // namespace

TEST_CASE("glsl grid::block: blocks equal the whole grid's samples bit for bit") {
  check_blocks(hush::perlin<2>{61});
  check_blocks(hush::perlin<3>{62});
  hush::fractal<hush::perlin<3>>::params f;
  f.seed = 63;
  f.octaves = 3;
  check_blocks(hush::fractal<hush::perlin<3>>{f});
  hush::wavelet<2>::params w;
  w.seed = 64;
  w.tile_size = 32;
  w.weights = {1.0, 0.5};
  check_blocks(hush::wavelet<2>{w});
  hush::gabor<3>::params g;
  g.seed = 65;
  g.impulses = 4;
  check_blocks(hush::gabor<3>{g});
  hush::anisotropic::params a;
  a.seed = 66;
  a.tile_size = 64;
  a.octaves = 2;
  check_blocks(hush::anisotropic{a});
}
