// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Blocks of a grid (hush::grid::block, core/views.hpp): a block evaluated on
// its own gives, bit for bit, the values and gradients the whole grid's call
// gives the same samples, for every noise with grids, on the scalar, SIMD and
// parallel policies. The blocks start at odd indices along every axis; the
// grids sit far from the origin (1e5 + 0.1 and 3e9 + 0.1, not multiples of
// the step 1/3), have a negative step on one axis, or fine steps whose cells
// hold many columns. A block re-based as a grid of its own (origin + step * first) gives
// other values on these grids, which the last cases show, so the comparisons
// see the position rounding. Built with hush::simd (dynamic dispatch,
// contraction allowed: a block runs the whole grid's arithmetic, so identical
// results do not need strict FP).
#include <doctest/doctest.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "hush/hush.hpp"

namespace {

// Cut points of one axis of n samples: 0, odd interior indices, n.
std::vector<std::size_t> cuts(std::size_t n) {
  std::vector<std::size_t> c{0};
  for (std::size_t k : {std::size_t(3), n / 2 | 1})
    if (k > c.back() && k < n) c.push_back(k);
  c.push_back(n);
  return c;
}


// Which axes a check splits (bits: 1 = x, 2 = y, 4 = z).
constexpr int kAllAxes = 7;

// Every block of the grid cut at cuts() along the axes in `split` (the others
// whole), evaluated on its own with `policy`, against the whole grid's samples.
template <class Noise, class Policy>
void check_blocks(const Noise& noise, Policy policy, const hush::grid<Noise::dimension>& whole,
                  bool gradients, int split = kAllAxes) {
  constexpr int D = Noise::dimension;
  INFO("policy " << std::string(Policy::name) << ", gradients " << gradients);
  const std::size_t n = whole.count();
  std::vector<float> want(n);
  std::vector<hush::vec<float, D>> want_g(n);
  if (gradients)
    hush::evaluate_grid(noise, policy, whole, want, want_g);
  else
    hush::evaluate_grid(noise, policy, whole, want);
  std::array<std::vector<std::size_t>, 3> c;
  for (int a = 0; a < 3; ++a) {
    const std::size_t size = a < D ? whole.size[a] : 1;
    c[a] = a < D && (split >> a & 1) ? cuts(size) : std::vector<std::size_t>{0, size};
  }
  std::size_t mismatches = 0, blocks = 0;
  for (std::size_t bz = 0; bz + 1 < c[2].size(); ++bz)
    for (std::size_t by = 0; by + 1 < c[1].size(); ++by)
      for (std::size_t bx = 0; bx + 1 < c[0].size(); ++bx) {
        std::array<std::size_t, D> first{}, size{};
        const std::size_t lo[3] = {c[0][bx], c[1][by], c[2][bz]};
        const std::size_t hi[3] = {c[0][bx + 1], c[1][by + 1], c[2][bz + 1]};
        for (int a = 0; a < D; ++a) {
          first[a] = lo[a];
          size[a] = hi[a] - lo[a];
        }
        const hush::grid<D> b = whole.block(first, size);
        std::vector<float> got(b.count(), -7.0f);
        std::vector<hush::vec<float, D>> got_g(b.count());
        if (gradients)
          hush::evaluate_grid(noise, policy, b, got, got_g);
        else
          hush::evaluate_grid(noise, policy, b, got);
        ++blocks;
        std::size_t idx = 0;
        for (std::size_t k = lo[2]; k < hi[2]; ++k)
          for (std::size_t j = lo[1]; j < hi[1]; ++j)
            for (std::size_t i = lo[0]; i < hi[0]; ++i, ++idx) {
              const std::size_t w = (k * whole.size[1] + j) * whole.size[0] + i;
              bool same = std::memcmp(&got[idx], &want[w], sizeof(float)) == 0;
              if (gradients)
                same = same && std::memcmp(&got_g[idx], &want_g[w], sizeof(got_g[0])) == 0;
              if (!same && mismatches++ == 0)
                FAIL_CHECK("block at (" << lo[0] << ", " << lo[1] << ", " << lo[2]
                                        << "): sample (" << i << ", " << j << ", " << k
                                        << ") is " << got[idx] << ", the whole grid's "
                                        << want[w]);
            }
      }
  CHECK(blocks >= (D == 2 ? 4u : 8u) / (split == kAllAxes ? 1u : 2u));
  CHECK(mismatches == 0);
}

// Grids far from the origin with steps that round: origin 1e5 + 0.1 (not a
// multiple of the step), step 1/3, negative along y.
template <int D>
hush::grid<D> far_grid(std::size_t nx, std::size_t ny, std::size_t nz = 1, double at = 1e5) {
  hush::grid<D> g;
  for (int a = 0; a < D; ++a) {
    g.origin[a] = at + 0.1 + 17.0 * a;
    g.step[a] = a == 1 ? -1.0 / 3.0 : 1.0 / 3.0;
  }
  g.size[0] = nx;
  g.size[1] = ny;
  if constexpr (D == 3) g.size[2] = nz;
  return g;
}
// A fine grid: many columns per lattice cell (the noises' shared-cell grid paths).
template <int D>
hush::grid<D> fine_grid(std::size_t nx, std::size_t ny, std::size_t nz = 1) {
  hush::grid<D> g = far_grid<D>(nx, ny, nz);
  for (int a = 0; a < D; ++a) {
    g.origin[a] = -3.3e3 + 0.7 * a;
    g.step[a] = (a == 2 ? -1.0 : 1.0) / (29 + 2 * a);
  }
  return g;
}

template <class Noise>
void check_policies(const Noise& noise, const hush::grid<Noise::dimension>& g, bool gradients,
                    int split = kAllAxes) {
  check_blocks(noise, hush::exec::scalar, g, gradients, split);
  check_blocks(noise, hush::exec::simd, g, gradients, split);
  check_blocks(noise, hush::exec::parallel(hush::exec::simd, 3), g, gradients, split);
}

// Grids so far out (3e9) that a double's rounding is as coarse as a float
// fraction's: positions rounded another way split into other fractions.
template <int D>
hush::grid<D> farther_grid(std::size_t nx, std::size_t ny, std::size_t nz = 1) {
  return far_grid<D>(nx, ny, nz, 3e9);
}

// Values and gradients on a far and a fine grid. Gradients of 3D Perlin and
// fBm grids are split along y and z only (core/views.hpp grid::block: their
// affine-in-x form is chosen from the block's x extent).
template <class Noise>
void check_noise(const Noise& noise, int gradient_split = kAllAxes) {
  constexpr int D = Noise::dimension;
  const auto far = D == 2 ? far_grid<D>(37, 23) : far_grid<D>(15, 11, 9);
  const auto fine = D == 2 ? fine_grid<D>(61, 19) : fine_grid<D>(45, 9, 7);
  const auto farther = D == 2 ? farther_grid<D>(29, 13) : farther_grid<D>(11, 9, 7);
  for (bool gradients : {false, true}) {
    const int split = gradients ? gradient_split : kAllAxes;
    check_policies(noise, far, gradients, split);
    check_policies(noise, fine, gradients, split);
    check_policies(noise, farther, gradients, split);
  }
}
constexpr int kYZ = 6;

// The block re-based as a grid of its own: origin + step * first, first 0.
template <int D>
hush::grid<D> rebased(const hush::grid<D>& b) {
  hush::grid<D> r = b;
  for (int a = 0; a < D; ++a) {
    r.origin[a] = b.origin[a] + b.step[a] * static_cast<double>(b.first[a]);
    r.first[a] = 0;
  }
  return r;
}

// How many samples of block `b` of `whole` differ, bit for bit, between
// evaluating b and evaluating its re-based copy.
template <class Noise>
std::size_t rebased_differences(const Noise& noise, const hush::grid<Noise::dimension>& b) {
  std::vector<float> got(b.count()), moved(b.count());
  hush::evaluate_grid(noise, hush::exec::simd, b, got);
  hush::evaluate_grid(noise, hush::exec::simd, rebased(b), moved);
  std::size_t n = 0;
  for (std::size_t i = 0; i < got.size(); ++i)
    n += std::memcmp(&got[i], &moved[i], sizeof(float)) != 0;
  return n;
}

}  // namespace

TEST_CASE("grid::block: perlin blocks equal the whole grid's samples bit for bit") {
  check_noise(hush::perlin<2>{41});
  check_noise(hush::perlin<3>{42}, kYZ);
  hush::perlin<3>::params prm;
  prm.seed = 43;
  prm.period = {5, 0, 3};
  check_noise(hush::perlin<3>{prm}, kYZ);
}

TEST_CASE("grid::block: fractal blocks equal the whole grid's samples bit for bit") {
  hush::fractal<hush::perlin<2>>::params p2;
  p2.seed = 44;
  p2.octaves = 4;
  check_noise(hush::fractal<hush::perlin<2>>{p2});
  hush::fractal<hush::perlin<3>>::params p3;
  p3.seed = 45;
  p3.octaves = 3;
  p3.kind = hush::fractal_kind::turbulence;
  p3.norm = hush::normalization::unit_range;
  check_noise(hush::fractal<hush::perlin<3>>{p3}, kYZ);
}

TEST_CASE("grid::block: wavelet blocks equal the whole grid's samples bit for bit") {
  hush::wavelet<2>::params p2;
  p2.seed = 46;
  p2.tile_size = 32;
  check_noise(hush::wavelet<2>{p2});
  p2.weights = {1.0, 0.5, 0.25};  // several bands
  p2.first_band = -1;
  check_noise(hush::wavelet<2>{p2});
  hush::wavelet<3>::params p3;
  p3.seed = 47;
  p3.tile_size = 16;
  p3.weights = {1.0, 0.5};
  check_noise(hush::wavelet<3>{p3});
}

TEST_CASE("grid::block: gabor blocks equal the whole grid's samples bit for bit") {
  hush::gabor<2>::params p2;
  p2.seed = 48;
  p2.impulses = 8;
  check_noise(hush::gabor<2>{p2});
  hush::gabor<3>::params p3;
  p3.seed = 49;
  p3.impulses = 4;
  check_noise(hush::gabor<3>{p3});
}

TEST_CASE("grid::block: anisotropic blocks equal the whole grid's samples bit for bit") {
  hush::anisotropic::params p;
  p.seed = 50;
  p.tile_size = 64;
  p.octaves = 2;
  check_noise(hush::anisotropic{p});
}

TEST_CASE("grid::block: a block re-based at origin + step * first rounds its positions otherwise") {
  // What the block comparisons above would see with positions formed the old
  // way: samples of a far grid's block move, in every noise family.
  const hush::grid<2> g2 = farther_grid<2>(37, 23).block({{5, 7}}, {{21, 11}});
  const hush::grid<3> g3 = farther_grid<3>(15, 11, 9).block({{3, 5, 1}}, {{9, 5, 7}});
  CHECK(rebased_differences(hush::perlin<2>{41}, g2) > g2.count() / 8);
  CHECK(rebased_differences(hush::perlin<3>{42}, g3) > g3.count() / 8);
  hush::wavelet<2>::params w;
  w.tile_size = 32;
  CHECK(rebased_differences(hush::wavelet<2>{w}, g2) > g2.count() / 8);
  hush::gabor<2>::params g;
  g.impulses = 8;
  CHECK(rebased_differences(hush::gabor<2>{g}, g2) > g2.count() / 8);
}

TEST_CASE("grid::block: blocks outside the grid are rejected, naming the axis") {
  const hush::grid<3> g = far_grid<3>(15, 11, 9);
  const hush::grid<3> b = g.block({{2, 3, 4}}, {{13, 8, 5}});  // up to the far edges
  CHECK(b.first == std::array<std::size_t, 3>{{2, 3, 4}});
  CHECK(b.size == std::array<std::size_t, 3>{{13, 8, 5}});
  // A block of a block counts from the whole grid's sample 0.
  CHECK(b.block({{1, 1, 1}}, {{2, 2, 2}}).first == std::array<std::size_t, 3>{{3, 4, 5}});
  CHECK(g.block({{15, 0, 0}}, {{0, 11, 9}}).count() == 0);
  auto rejects = [&](std::array<std::size_t, 3> first, std::array<std::size_t, 3> size,
                     const char* name) {
    INFO("expects " << name);
    try {
      (void)g.block(first, size);
      FAIL_CHECK("no exception");
    } catch (const hush::invalid_argument& e) {
      const std::string msg = e.what();
      CHECK(msg.find("hush::grid::block") != std::string::npos);
      CHECK(msg.find(name) != std::string::npos);
    }
  };
  rejects({{0, 0, 0}}, {{16, 1, 1}}, "size[0]");
  rejects({{0, 5, 0}}, {{1, 7, 1}}, "size[1]");
  rejects({{0, 0, 10}}, {{1, 1, 0}}, "first[2]");
  rejects({{0, 0, 1}}, {{1, 1, SIZE_MAX}}, "size[2]");
  // first + size past size_t: validate() names grid.first.
  hush::grid<3> wrapped = b;
  wrapped.first[1] = SIZE_MAX - 2;
  std::vector<float> out(wrapped.count());
  CHECK_THROWS_WITH_AS(hush::evaluate_grid(hush::perlin<3>{1}, hush::exec::scalar, wrapped, out),
                       doctest::Contains("grid.first[1]"), hush::invalid_argument);
}
