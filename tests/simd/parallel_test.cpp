// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::exec::parallel (exec.hpp): a batch split over threads gives exactly
// the inner policy's results on the whole batch, bit for bit, for points,
// per-sample batches and grids (slabs along the slowest axis), values and
// gradients, on the scalar and SIMD policies (Perlin, fractal and Gabor noise,
// whose SIMD grid kernels take slabs; every noise with each per-sample input
// it takes, so a part never reads another part's footprints, normals or
// surface maps); bad thread counts are rejected
// with a message naming the parameter; the same through hush::thread_pool,
// whose run() calls every part exactly once, serialises concurrent callers
// and runs nested calls inline. Built with hush::simd (dynamic
// dispatch, contraction allowed: identical results do not need strict FP).
#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "hush/hush.hpp"
#include "probe_noise.hpp"

namespace {

// The thread counts tried: one, two, an odd count, more threads than parts
// of the batch (limited by exec::parallel_t::kParallelGrain), and 0 (one per
// hardware thread).
const int kThreads[] = {1, 2, 3, 7, 0};

// Pools of the same sizes (0 aside), kept for the whole test program: the
// batches run on the same workers over and over, as a caller's would.
hush::thread_pool& test_pool(int i) {
  static hush::thread_pool pools[] = {hush::thread_pool(1), hush::thread_pool(2),
                                      hush::thread_pool(3), hush::thread_pool(7)};
  return pools[i];
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}
template <int D>
bool same_bits(const std::vector<hush::vec<float, D>>& a,
               const std::vector<hush::vec<float, D>>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

template <int D>
std::vector<hush::vec<float, D>> random_points(std::size_t n, std::uint32_t seed) {
  hush::rng r(seed, D);
  std::vector<hush::vec<float, D>> pts(n);
  for (auto& q : pts)
    for (int a = 0; a < D; ++a) q[a] = r.uniform(-300.0f, 300.0f);
  return pts;
}

const int kAllPools[] = {0, 1, 2, 3};

// Every thread count (and pool: indices of test_pool) against the inner
// policy alone, values and gradients.
template <class Noise, class Inner, class Run>
void check_parallel(const Noise& noise, Inner inner, std::size_t n, const Run& run,
                    hush::span<const int> threads = kThreads,
                    hush::span<const int> pools = kAllPools) {
  constexpr int D = Noise::dimension;
  std::vector<float> want(n), got(n);
  std::vector<hush::vec<float, D>> want_g(n), got_g(n);
  run(noise, inner, want, want_g);
  for (int t : threads) {
    INFO("threads " << t << ", policy " << std::string(Inner::name));
    std::fill(got.begin(), got.end(), -7.0f);
    run(noise, hush::exec::parallel(inner, t), got, got_g);
    CHECK(same_bits(got, want));
    CHECK(same_bits<D>(got_g, want_g));
  }
  for (int i : pools) {
    INFO("pool of " << test_pool(i).size() << ", policy " << std::string(Inner::name));
    std::fill(got.begin(), got.end(), -7.0f);
    run(noise, hush::exec::parallel(inner, test_pool(i)), got, got_g);
    CHECK(same_bits(got, want));
    CHECK(same_bits<D>(got_g, want_g));
  }
}

template <class Noise>
void check_all(const Noise& noise, const hush::grid<Noise::dimension>& g) {
  constexpr int D = Noise::dimension;
  const auto pts = random_points<D>(20000 + 13, 5);  // several parts and a ragged tail
  auto points = [&](const Noise& n, auto policy, std::vector<float>& out, auto& grad) {
    hush::evaluate(n, policy, pts, out, grad);
  };
  auto grids = [&](const Noise& n, auto policy, std::vector<float>& out, auto& grad) {
    hush::evaluate_grid(n, policy, g, out, grad);
  };
  auto values_only = [&](const Noise& n, auto policy, std::vector<float>& out, auto&) {
    hush::evaluate_grid(n, policy, g, out);
  };
  for (auto run_inner : {0, 1}) {
    if (run_inner == 0) {
      check_parallel(noise, hush::exec::simd, pts.size(), points);
      check_parallel(noise, hush::exec::simd, g.count(), grids);
      check_parallel(noise, hush::exec::simd, g.count(), values_only);
    } else {
      check_parallel(noise, hush::exec::scalar, pts.size(), points);
      check_parallel(noise, hush::exec::scalar, g.count(), grids);
    }
  }
}

// Per-sample batches: enough samples that 7 threads get 7 parts
// (kParallelGrain each) plus a ragged tail, and inputs that differ at every
// sample, so a part reading another part's footprint, normal or map changes
// its result.
constexpr std::size_t kSampleCount =
    7 * hush::exec::parallel_t<hush::exec::scalar_t>::kParallelGrain + 13;

template <int D>
struct sample_batch {
  std::vector<hush::vec<float, D>> positions = random_points<D>(kSampleCount, 40 + D);
  std::vector<hush::footprint<D>> footprints;
  std::vector<hush::vec3> normals;
  std::vector<hush::surface_map> maps;

  sample_batch() {
    hush::rng r(41, D);
    for (std::size_t i = 0; i < kSampleCount; ++i) {
      const double width = std::pow(10.0, r.uniform<double>(-3.0, 0.3));
      hush::vec<double, D> dx, dy;
      for (int a = 0; a < D; ++a) {
        dx[a] = width * r.uniform<double>(-1, 1);
        dy[a] = width * r.uniform<double>(-1, 1);
      }
      footprints.push_back(hush::footprint<D>::from_derivatives(dx, dy));
      normals.push_back({r.uniform(-1.0f, 1.0f), r.uniform(-1.0f, 1.0f), r.uniform(-1.0f, 1.0f)});
      maps.push_back(
          hush::surface_map::from_matrix(r.uniform<double>(-3, 3), r.uniform<double>(-3, 3),
                                         r.uniform<double>(-3, 3), r.uniform<double>(-3, 3)));
    }
  }
};

// The splits of a per-sample batch: one part, two, an odd count, seven (one
// per kParallelGrain), and seven on a pool.
const int kSampleThreads[] = {1, 2, 3, 7};
const int kSamplePool[] = {3};

// Which spans of a batch are given (bits).
constexpr int kPositionsOnly = 0, kFootprints = 1, kNormals = 2, kMaps = 4;

// The noise on the batch with the given inputs, values alone and with
// gradients, split over every thread count and pool of both inner policies.
template <class Noise>
void check_sample_split(const Noise& noise, const sample_batch<Noise::dimension>& b, int inputs) {
  constexpr int D = Noise::dimension;
  INFO("footprints " << bool(inputs & kFootprints) << ", normals " << bool(inputs & kNormals)
                     << ", surface maps " << bool(inputs & kMaps));
  hush::samples<D> s;
  s.positions = b.positions;
  if (inputs & kFootprints) s.footprints = b.footprints;
  if (inputs & kNormals) s.normals = b.normals;
  if (inputs & kMaps) s.surface_maps = b.maps;
  auto values = [&](const Noise& n, auto policy, std::vector<float>& out, auto&) {
    hush::evaluate(n, policy, s, out);
  };
  auto with_gradients = [&](const Noise& n, auto policy, std::vector<float>& out, auto& grad) {
    hush::evaluate(n, policy, s, out, grad);
  };
  check_parallel(noise, hush::exec::scalar, s.size(), values, kSampleThreads, kSamplePool);
  check_parallel(noise, hush::exec::scalar, s.size(), with_gradients, kSampleThreads, kSamplePool);
  check_parallel(noise, hush::exec::simd, s.size(), values, kSampleThreads, kSamplePool);
  check_parallel(noise, hush::exec::simd, s.size(), with_gradients, kSampleThreads, kSamplePool);
}

// A noise that filters in 2D and 3D and takes normals in 3D (wavelet, gabor):
// every input combination it accepts.
template <template <int> class Noise>
void check_footprints_and_normals(const typename Noise<2>::params& p2,
                                  const typename Noise<3>::params& p3) {
  check_sample_split(Noise<2>{p2}, sample_batch<2>(), kFootprints);
  const Noise<3> noise{p3};
  const sample_batch<3> b;
  for (int inputs : {kFootprints, kNormals, kFootprints | kNormals})
    check_sample_split(noise, b, inputs);
}

template <int D>
hush::grid<D> test_grid(std::size_t nx, std::size_t slow) {
  hush::grid<D> g;
  for (int a = 0; a < D; ++a) {
    g.origin[a] = -3.3 + 1.7 * a;
    g.step[a] = 1.0 / (29 + 2 * a);  // positions with rounding in every row
    g.size[a] = nx;
  }
  g.size[D - 1] = slow;
  return g;
}

}  // namespace

TEST_CASE("exec::parallel: perlin batches equal the single-thread call bit for bit") {
  check_all(hush::perlin<2>{21}, test_grid<2>(300, 61));
  check_all(hush::perlin<3>{22}, test_grid<3>(40, 23));
  hush::perlin<3>::params prm;
  prm.seed = 23;
  prm.period = {5, 0, 3};
  check_all(hush::perlin<3>{prm}, test_grid<3>(33, 17));
}

TEST_CASE("exec::parallel: fractal batches equal the single-thread call bit for bit") {
  hush::fractal<hush::perlin<2>>::params p2;
  p2.seed = 24;
  p2.octaves = 3;
  check_all(hush::fractal<hush::perlin<2>>{p2}, test_grid<2>(200, 45));
  hush::fractal<hush::perlin<3>>::params p3;
  p3.seed = 25;
  p3.octaves = 3;
  p3.kind = hush::fractal_kind::turbulence;
  p3.norm = hush::normalization::unit_range;
  check_all(hush::fractal<hush::perlin<3>>{p3}, test_grid<3>(24, 19));
}

TEST_CASE("exec::parallel: a noise without SIMD kernels, and per-sample batches") {
  const hush_test::probe_noise<3> noise;
  const std::size_t n = 9000;
  std::vector<hush::vec3> pos(n), normals(n);
  std::vector<hush::footprint<3>> fps(n);
  for (std::size_t i = 0; i < n; ++i) {
    pos[i] = {float(i % 11) / 8, float(i % 7) / 8, float(i % 5) / 8};
    normals[i] = {float(i % 3) / 8, 0.5f, 0.25f};
    fps[i] = hush::footprint<3>::isotropic(float(i % 4) / 8);
  }
  const hush::samples<3> s{pos, fps, normals};
  std::vector<float> want(n), got(n);
  hush::evaluate(noise, hush::exec::scalar, s, want);
  for (int t : kThreads) {
    INFO("threads " << t);
    hush::evaluate(noise, hush::exec::parallel(hush::exec::simd, t), s, got);
    CHECK(same_bits(got, want));
  }
  check_parallel(noise, hush::exec::simd, 4096 * 3,
                 [&](const auto& nz, auto policy, auto& out, auto& grad) {
                   hush::evaluate_grid(nz, policy, test_grid<3>(32, 12), out, grad);
                 });
}

TEST_CASE("exec::parallel: thread counts outside 0 ... 1024 are rejected, naming the parameter") {
  for (int t : {-1, 1025, -1000000}) {
    INFO("threads " << t);
    try {
      (void)hush::exec::parallel(hush::exec::simd, t);
      FAIL("no exception");
    } catch (const hush::invalid_argument& e) {
      const std::string msg = e.what();
      CHECK(msg.find("hush::exec::parallel") != std::string::npos);
      CHECK(msg.find("threads") != std::string::npos);
      CHECK(msg.find("1024") != std::string::npos);
    }
  }
  CHECK(hush::exec::parallel(hush::exec::scalar, 0).threads >= 1);
  CHECK(hush::exec::parallel(hush::exec::scalar, 5).threads == 5);
}

TEST_CASE("exec::parallel: gabor batches and grid slabs equal the single-thread call bit for bit") {
  // Fine grids take the SIMD block path, the coarse one its points path, in every slab.
  hush::gabor<2>::params p2;
  p2.seed = 26;
  check_all(hush::gabor<2>{p2}, test_grid<2>(300, 61));
  hush::grid<2> coarse = test_grid<2>(200, 90);
  coarse.step = {0.61, -0.43};
  check_all(hush::gabor<2>{p2}, coarse);
  hush::gabor<3>::params p3;
  p3.seed = 27;
  p3.kind = hush::gabor_kind::hybrid;
  p3.orientation_spread = 1.0;
  p3.frequency_spread = 0.5;
  check_all(hush::gabor<3>{p3}, test_grid<3>(24, 19));
}

TEST_CASE("thread_pool: run() calls every part exactly once, batch after batch") {
  for (int i = 0; i < 4; ++i) {
    hush::thread_pool& pool = test_pool(i);
    INFO("pool of " << pool.size());
    CHECK(pool.size() == unsigned(i == 0 ? 1 : i == 1 ? 2 : i == 2 ? 3 : 7));
    // Part counts below, at and above the pool's size, 500 batches each: a
    // worker that missed a batch or ran a part twice changes a count.
    for (std::size_t parts : {std::size_t(1), std::size_t(2), std::size_t(pool.size()),
                              std::size_t(pool.size() + 5)}) {
      std::vector<std::atomic<int>> calls(parts);
      for (int batch = 0; batch < 500; ++batch)
        pool.run(parts, [&](std::size_t p) { calls[p].fetch_add(1); });
      for (std::size_t p = 0; p < parts; ++p) CHECK(calls[p].load() == 500);
    }
  }
}

TEST_CASE("thread_pool: concurrent callers are serialised and nested calls run inline") {
  hush::thread_pool& pool = test_pool(3);
  std::atomic<int> in_batch{0}, overlap{0}, total{0};
  auto caller = [&] {
    for (int batch = 0; batch < 200; ++batch)
      pool.run(4, [&](std::size_t p) {
        if (p == 0 && in_batch.fetch_add(1) != 0) overlap.fetch_add(1);
        // A nested call from inside a part: must not wait for the pool it runs on.
        pool.run(3, [&](std::size_t) { total.fetch_add(1); });
        if (p == 0) in_batch.fetch_sub(1);
      });
  };
  std::thread a(caller), b(caller);
  a.join();
  b.join();
  CHECK(overlap.load() == 0);
  CHECK(total.load() == 2 * 200 * 4 * 3);
}

TEST_CASE("thread_pool: thread counts outside 0 ... 1024 are rejected, naming the parameter") {
  for (int t : {-1, 1025}) {
    INFO("threads " << t);
    try {
      hush::thread_pool pool(t);
      FAIL("no exception");
    } catch (const hush::invalid_argument& e) {
      const std::string msg = e.what();
      CHECK(msg.find("hush::thread_pool") != std::string::npos);
      CHECK(msg.find("threads") != std::string::npos);
      CHECK(msg.find("1024") != std::string::npos);
    }
  }
  CHECK(hush::thread_pool(0).size() >= 1);
  CHECK(hush::exec::parallel(hush::exec::simd, test_pool(2)).threads == 3);
}

TEST_CASE(
    "exec::parallel: positions-only sample batches equal the single-thread call bit for bit") {
  const sample_batch<2> b2;
  const sample_batch<3> b3;
  check_sample_split(hush::perlin<2>{31}, b2, kPositionsOnly);
  check_sample_split(hush::perlin<3>{32}, b3, kPositionsOnly);
  hush::fractal<hush::perlin<2>>::params p2;
  p2.seed = 33;
  p2.octaves = 3;
  check_sample_split(hush::fractal<hush::perlin<2>>{p2}, b2, kPositionsOnly);
  hush::fractal<hush::perlin<3>>::params p3;
  p3.seed = 34;
  p3.octaves = 3;
  check_sample_split(hush::fractal<hush::perlin<3>>{p3}, b3, kPositionsOnly);
}

TEST_CASE("exec::parallel: wavelet samples keep each footprint and normal with its position") {
  hush::wavelet<2>::params p2;
  p2.seed = 35;
  p2.tile_size = 32;
  hush::wavelet<3>::params p3;
  p3.seed = 36;
  p3.tile_size = 32;
  p3.projection = hush::wavelet_projection::approximate;  // half the exact one's scalar time
  check_footprints_and_normals<hush::wavelet>(p2, p3);
}

TEST_CASE("exec::parallel: gabor samples keep each footprint and normal with its position") {
  hush::gabor<2>::params p2;
  p2.seed = 37;
  p2.impulses = 4;  // few kernels per sample: the split is under test, not the noise
  hush::gabor<3>::params p3;
  p3.seed = 38;
  p3.impulses = 4;
  check_footprints_and_normals<hush::gabor>(p2, p3);
}

TEST_CASE(
    "exec::parallel: anisotropic samples keep each footprint and surface map with its position") {
  hush::anisotropic::params p;
  p.seed = 39;
  p.tile_size = 64;
  p.octaves = 2;
  const hush::anisotropic a{p};
  const sample_batch<2> b;
  for (int inputs : {kFootprints, kMaps, kFootprints | kMaps}) check_sample_split(a, b, inputs);
}
