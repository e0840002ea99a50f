// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Where wavelet noise's 3D random points and projected samples spend their work
// (the costs behind docs/wavelet.md's "Limits" and measured figures):
//  1. 3D points on the SIMD backend, thread CPU time (best of 7) per sample, 2^18 points:
//     the bench's spread points, the same binned by (z, y) cell (with the binning and
//     scatter-back costs), 32^3 and 16^3 tiles, and points confined to [0, 4]^3
//     (the tile's accesses L1-resident), beside Perlin 3D;
//  2. the paper's approximate projection (random unit normals): the coefficients its
//     slab visits per sample, with non-zero weight, and the steps of the SIMD kernel's
//     union of 16 lanes' ranges per vector (detail::wavelet_general_approx's ranges);
//  3. the exact projection: knots, Gauss-Legendre nodes and coefficient reads per sample.
// Not built by default (no CI cost):
//   cmake --build build/release --target hush_wavelet_probe -j1
//   build/release/bench/hush_wavelet_probe
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <limits>
#include <vector>

#include "hush/hush.hpp"
#include <hwy/targets.h>

namespace {

double cpu_ns() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e9 + static_cast<double>(t.tv_nsec);
}
template <class F>
double best_ns(F f, std::size_t n) {
  double b = std::numeric_limits<double>::infinity();
  for (int r = 0; r < 7; ++r) {
    const double t0 = cpu_ns();
    f();
    b = std::min(b, cpu_ns() - t0);
  }
  return b / static_cast<double>(n);
}

using pts3 = std::vector<hush::vec<float, 3>>;

void points_locality() {
  const std::size_t n = std::size_t(1) << 18;
  hush::rng r(12345, 3);
  pts3 pts(n), box(n), sorted(n);
  for (auto& p : pts)
    for (int a = 0; a < 3; ++a) p[a] = r.uniform(-128.f, 128.f);
  for (auto& p : box)
    for (int a = 0; a < 3; ++a) p[a] = r.uniform(0.f, 4.f);
  std::vector<float> out(n), back(n);
  hush::wavelet<3>::params prm;
  prm.seed = 7;
  const hush::wavelet<3> w64(prm);
  prm.tile_size = 32;
  const hush::wavelet<3> w32(prm);
  prm.tile_size = 16;
  const hush::wavelet<3> w16(prm);
  prm.tile_size = 64;
  prm.projection = hush::wavelet_projection::approximate;
  const hush::wavelet<3> w64a(prm);
  const hush::perlin<3> per(7);
  const std::vector<hush::vec<float, 3>> along_z(n, hush::vec<float, 3>{0, 0, 1});
  const auto run_z = [&](const hush::wavelet<3>& noise, const pts3& p) {
    return best_ns(
        [&] {
          const hush::samples<3> s{p, {}, along_z};
          hush::evaluate(noise, hush::exec::simd, s, hush::span<float>(out));
        },
        n);
  };
  const auto run = [&](const auto& noise, const pts3& p) {
    return best_ns(
        [&] {
          hush::evaluate(noise, hush::exec::simd, hush::span<const hush::vec<float, 3>>(p),
                         hush::span<float>(out));
        },
        n);
  };
  // Counting sort by band 0's (z, y) cell modulo the tile, keeping the permutation.
  std::vector<std::uint32_t> perm(n), key(n);
  const auto bin = [&] {
    std::vector<std::uint32_t> count(64 * 64 + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      const int z = static_cast<int>(std::floor(pts[i][2])) & 63;
      const int y = static_cast<int>(std::floor(pts[i][1])) & 63;
      key[i] = static_cast<std::uint32_t>(z * 64 + y);
      ++count[key[i] + 1];
    }
    for (std::size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t d = count[key[i]]++;
      perm[d] = static_cast<std::uint32_t>(i);
      sorted[d] = pts[i];
    }
  };
  const double t_bin = best_ns(bin, n);
  const double t_back = best_ns(
      [&] {
        for (std::size_t i = 0; i < n; ++i) back[perm[i]] = out[i];
      },
      n);
  // The chosen target, then AVX2 pinned where the machine would pick something better
  // (the bench's "simd AVX2" rows): the two targets' kernels side by side.
  const auto report = [&](const char* target) {
    std::printf("1. 3D points, SIMD (%s), ns/sample (thread CPU time, best of 7), 2^18 points\n",
                target);
    std::printf("   perlin 3D, uniform in [-128, 128]^3       %6.2f\n", run(per, pts));
    std::printf("   wavelet 64^3 tile (%4zu KiB), same points %6.2f\n", w64.tile().bytes() >> 10,
                run(w64, pts));
    std::printf("   wavelet 64^3 tile, binned by (z, y) cell  %6.2f  + binning %.2f + scatter %.2f\n",
                run(w64, sorted), t_bin, t_back);
    std::printf("   wavelet 32^3 tile (%3zu KiB), spread       %6.2f\n", w32.tile().bytes() >> 10,
                run(w32, pts));
    std::printf("   wavelet 16^3 tile (%3zu KiB), spread       %6.2f\n", w16.tile().bytes() >> 10,
                run(w16, pts));
    std::printf("   wavelet 64^3 tile, points in [0, 4]^3     %6.2f\n", run(w64, box));
    // The spread points without their streams through the caches: 1024 at a time from
    // a small buffer refilled from the rng (its refill time subtracted), into a small
    // output: what the 3 MiB of points and 1 MiB of values cost by evicting the tile.
    constexpr std::size_t kChunk = 1024;
    pts3 buf(kChunk);
    std::vector<float> small(kChunk);
    const auto refill = [&](hush::rng& g) {
      for (auto& p : buf)
        for (int a = 0; a < 3; ++a) p[a] = g.uniform(-128.f, 128.f);
    };
    const double t_refill = best_ns(
        [&] {
          hush::rng g(777, 3);
          for (std::size_t i = 0; i < n; i += kChunk) refill(g);
        },
        n);
    const double t_chunks = best_ns(
        [&] {
          hush::rng g(777, 3);
          for (std::size_t i = 0; i < n; i += kChunk) {
            refill(g);
            hush::evaluate(w64, hush::exec::simd, hush::span<const hush::vec<float, 3>>(buf),
                           hush::span<float>(small));
          }
        },
        n);
    std::printf("   wavelet 64^3 tile, spread, no streams     %6.2f  (+ refill %.2f)\n",
                t_chunks - t_refill, t_refill);
    // Projected along z (the separable case): 9 (beta) or 7 (B2) z taps per (x, y),
    // so 27 or 21 row loads per sample against plain points' 9, spread and L1-resident.
    std::printf("   projected along z, exact / approx, spread %6.2f / %6.2f\n",
                run_z(w64, pts), run_z(w64a, pts));
    std::printf("   the same, points in [0, 4]^3             %6.2f / %6.2f\n", run_z(w64, box),
                run_z(w64a, box));
  };
  report(hush::simd::chosen_target().c_str());
#if HUSH_CONFIG_SIMD && !HUSH_CONFIG_SIMD_STATIC && HWY_ARCH_X86
  const std::int64_t usable = hwy::SupportedTargets();
  if ((usable & HWY_AVX2) && (usable & (HWY_AVX2 - 1))) {
    hwy::SetSupportedTargetsForTest(HWY_AVX2);
    report("AVX2 pinned");
    hwy::SetSupportedTargetsForTest(0);
  }
#endif
}

struct counting_access {
  mutable long long reads = 0;
  float at(const int (&)[3]) const {
    ++reads;
    return 1.0f;
  }
};

// A random unit normal (uniform on the sphere) and a position within its cell.
void random_lane(hush::rng& r, float (&y)[3], float (&u)[3]) {
  for (float& v : y) v = r.uniform(0.5f, 1.5f);
  float len = 0;
  do {
    len = 0;
    for (float& v : u) {
      v = r.uniform(-1.f, 1.f);
      len += v * v;
    }
  } while (len > 1 || len < 1e-4f);
  for (float& v : u) v /= std::sqrt(len);
}

// wavelet_general_approx's ranges (s = 1): the column (k_u, k_v)'s slab along w.
struct approx_lane {
  float y[3], u[3];
  int w = 0, au = 0, av = 0, ulo = 0, un = 0, vlo = 0, vn = 0;
  void init() {
    for (int a = 1; a < 3; ++a)
      if (std::fabs(u[a]) > std::fabs(u[w])) w = a;
    au = w == 0 ? 1 : 0;
    av = w == 2 ? 1 : 2;
    const float half = static_cast<float>(hush::detail::kBspline.half_support());
    const float l1 = std::fabs(u[0]) + std::fabs(u[1]) + std::fabs(u[2]);
    const float ru = half * (1 + std::fabs(u[au]) * l1), rv = half * (1 + std::fabs(u[av]) * l1);
    ulo = static_cast<int>(std::ceil(y[au] - ru));
    un = static_cast<int>(std::floor(y[au] + ru)) - ulo;
    vlo = static_cast<int>(std::ceil(y[av] - rv));
    vn = static_cast<int>(std::floor(y[av] + rv)) - vlo;
  }
  // Steps along w of column (ku, kv) minus 1, or -1 where the slab is empty.
  int steps(int ku, int kv) const {
    const float half = static_cast<float>(hush::detail::kBspline.half_support());
    const float stretch = 1.0f / static_cast<float>(hush::detail::constants::kWaveletProjectionStretch);
    float d[3] = {0, 0, 0};
    d[au] = y[au] - static_cast<float>(ku);
    d[av] = y[av] - static_cast<float>(kv);
    const float p = u[au] * d[au] + u[av] * d[av];
    float lo = -std::numeric_limits<float>::infinity(), hi = -lo;
    for (int a = 0; a < 3; ++a) {
      const float A = (a == w ? 0.f : d[a]) - u[a] * p * stretch;
      const float C = (a == w ? 1.f : 0.f) - u[a] * u[w] * stretch;
      if (C == 0) {
        if (!(std::fabs(A) < half)) return -1;
        continue;
      }
      const float e0 = (-half - A) / C, e1 = (half - A) / C;
      lo = std::max(lo, std::min(e0, e1));
      hi = std::min(hi, std::max(e0, e1));
    }
    if (!(lo < hi)) return -1;
    return static_cast<int>(std::ceil(y[w] - lo)) - static_cast<int>(std::floor(y[w] - hi));
  }
};

void projection_counts() {
  constexpr int kLanes = 16, kGroups = 20000;
  hush::rng r(11);
  long long nonzero = 0, scalar_steps = 0, vector_steps = 0, knots = 0, nodes = 0;
  const float s[3] = {1, 1, 1};
  for (int g = 0; g < kGroups; ++g) {
    approx_lane lanes[kLanes];
    int nu = 0, nv = 0;
    for (approx_lane& l : lanes) {
      random_lane(r, l.y, l.u);
      l.init();
      nu = std::max(nu, l.un);
      nv = std::max(nv, l.vn);
      counting_access acc;
      hush::detail::wavelet_general_approx<float, false>(l.y, l.u, s, acc);
      nonzero += acc.reads;
      for (int i = 0; i <= l.un; ++i)
        for (int j = 0; j <= l.vn; ++j) scalar_steps += l.steps(l.ulo + i, l.vlo + j) + 1;
      float k[hush::detail::constants::kWaveletMaxKnots];
      const int nk = hush::detail::wavelet_exact_knots<float>(l.y, l.u, s, k);
      knots += nk;
      for (int i = 0; i + 1 < nk; ++i)
        nodes += k[i + 1] > k[i] ? hush::detail::constants::kGaussLegendreOrder : 0;
    }
    for (int i = 0; i <= nu; ++i)
      for (int j = 0; j <= nv; ++j) {
        int most = -1;
        for (const approx_lane& l : lanes)
          if (i <= l.un && j <= l.vn) most = std::max(most, l.steps(l.ulo + i, l.vlo + j));
        vector_steps += most + 1;
      }
  }
  const double samples = double(kGroups) * kLanes;
  std::printf("2. approximate projection, random unit normals, per sample: %.1f coefficients with\n"
              "   non-zero weight, %.1f visited in the slabs (of the 6^3 = 216 box); SIMD: %.1f\n"
              "   vector steps per vector of %d lanes (the union of their ranges)\n",
              double(nonzero) / samples, double(scalar_steps) / samples,
              double(vector_steps) / kGroups, kLanes);
  std::printf("3. exact projection, per sample: %.1f knots, %.1f nodes, %.0f coefficient reads\n",
              double(knots) / samples, double(nodes) / samples, 27.0 * double(nodes) / samples);
}

}  // namespace

int main() {
  points_locality();
  projection_counts();
}
