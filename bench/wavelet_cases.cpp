// hush — the speed-vs-error benchmark: wavelet noise's rows (include/hush/wavelet.hpp).
//
// On the scalar, SIMD and GLSL backends, seed 7, default tiles (128^2, 64^3): a single band on
// grids and points (value, value + gradient); 2 and 4 bands (weights 1, 1/2, ...) on grids and
// points (the cost grows linearly in bands); 3D projected onto surfaces with random unit
// normals (exact and the paper's approximation); on SIMD, the memory bounds of the 3D points.
// The quality note is the band leakage (detail/band_limit.hpp) beside improved Perlin noise's:
// the fraction of band 0's power below half its peak radial frequency, from a kLeakSize^2 grid
// sample at kLeakStep units (64 units: half the 2D tile, a whole 3D tile).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "cases.hpp"
#include "hush/detail/band_limit.hpp"
#include "hush/perlin.hpp"
#include "hush/wavelet.hpp"
#include "rows.hpp"

namespace hush_bench {
namespace {

constexpr int kWaveletBands[] = {2, 4};
constexpr std::size_t kLeakSize = 256;
constexpr double kLeakStep = 0.25;
constexpr double kLeakSliceZ = 0.375;  // the 3D slice plane z = this (off the lattice)
constexpr float kWaveletL1Box = 4;     // the L1-bound row's points: [0, 4)^3
constexpr int kWaveletL2Tile = 32;     // the L2-bound row's tile: 32^3 (140 KiB)

template <int D>
hush::wavelet<D> make_wavelet(int bands) {
  typename hush::wavelet<D>::params prm;
  prm.seed = kNoiseSeed;
  prm.weights.clear();
  for (int b = 0; b < bands; ++b) prm.weights.push_back(std::ldexp(1.0, -b));
  return hush::wavelet<D>(prm);
}

// Band leakage of `eval(x, y)` on the leak grid (see above).
template <class Eval>
double band_leakage(Eval eval) {
  std::vector<double> v(kLeakSize * kLeakSize);
  for (std::size_t j = 0; j < kLeakSize; ++j)
    for (std::size_t i = 0; i < kLeakSize; ++i)
      v[j * kLeakSize + i] = eval(static_cast<double>(i) * kLeakStep + kGridOrigin[0],
                                  static_cast<double>(j) * kLeakStep + kGridOrigin[1]);
  return hush::detail::band_limit_fraction(v, kLeakSize, kLeakStep).fraction;
}

// The quality note of a wavelet row (computed once per kind, on first use): its band
// leakage beside improved Perlin noise's, measured the same way.
std::string wavelet_leakage_note(int kind) {  // 0: 2D, 1: 3D slice, 2: 3D projected
  static const std::array<std::string, 3> notes = [] {
    const hush::perlin<2> perlin(kNoiseSeed);
    const double p = band_leakage([&](double x, double y) { return perlin(dvec<2>{x, y}); });
    const hush::wavelet<2> w2 = make_wavelet<2>(1);
    const hush::wavelet<3> w3 = make_wavelet<3>(1);
    const hush::footprint<3> none{};
    const double leak[3] = {
        band_leakage([&](double x, double y) { return w2(dvec<2>{x, y}); }),
        band_leakage([&](double x, double y) { return w3(dvec<3>{x, y, kLeakSliceZ}); }),
        band_leakage([&](double x, double y) {
          return w3.sample(dvec<3>{x, y, kLeakSliceZ}, dvec<3>{0, 0, 1}, none);
        })};
    std::array<std::string, 3> out;
    for (int k = 0; k < 3; ++k) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "band leakage %.2g (perlin 2D %.2g)", leak[k], p);
      out[static_cast<std::size_t>(k)] = buf;
    }
    return out;
  }();
  return notes[static_cast<std::size_t>(kind)];
}

// Adds the leakage note to cases[first ...]: measured while preparing (not at start-up).
void add_leakage_quality(std::vector<bench_case>& cases, std::size_t first, int kind) {
  for (std::size_t i = first; i < cases.size(); ++i) {
    cases[i].prepare = [prepare = cases[i].prepare, kind] {
      prepared_case p = prepare();
      p.quality = wavelet_leakage_note(kind);
      return p;
    };
  }
}

// Projected samples: random points with random unit normals (or all along z: the
// separable case), no footprint.
template <class Exec>
prepared_case prepare_wavelet_projected(const hush::wavelet<3>& noise, const Exec& ex,
                                        std::size_t n, bool along_z) {
  struct sample_buffers {
    std::vector<fvec<3>> points, normals;
    std::vector<float> out;
  };
  auto b = std::make_shared<sample_buffers>();
  b->points = make_points<3>(n);
  hush::rng r(kPointSeed + 2);
  for (std::size_t i = 0; i < n; ++i) {
    fvec<3> u;
    float len = 0;
    do {  // uniform on the sphere: rejection from the cube
      for (int a = 0; a < 3; ++a) u[a] = r.uniform(-1.0f, 1.0f);
      len = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
    } while (len > 1 || len < 1e-4f);
    b->normals.push_back(along_z ? fvec<3>{0, 0, 1} : u);
  }
  b->out.resize(n);
  prepared_case p;
  p.samples = n;
  p.run = [noise, ex, b] {
    const hush::samples<3> s{b->points, {}, b->normals};
    hush::evaluate(noise, ex, s, hush::span<float>(b->out));
    keep(b->out);
  };
  p.run();
  for (std::size_t i = 0; i < n; ++i) {
    hush::sample_input<3> in;
    in.position = hush::vec_cast<double>(b->points[i]);
    in.normal = hush::vec_cast<double>(b->normals[i]);
    in.has_normal = true;
    p.value_error.add(b->out[i], noise.template sample_value<double>(in));
  }
  return p;
}

template <class Exec>
void add_wavelet_rows(std::vector<bench_case>& cases, const sizes& s, const Exec& ex) {
  std::size_t first = cases.size();
  add_noise_rows(cases, s, "wavelet 2D", make_wavelet<2>(1), ex);
  add_leakage_quality(cases, first, 0);
  first = cases.size();
  add_noise_rows(cases, s, "wavelet 3D", make_wavelet<3>(1), ex);
  add_leakage_quality(cases, first, 1);
  bench_case c;
  c.backend = Exec::name;
  c.wall_clock = std::string(Exec::name) == "glsl";
  for (const int bands : kWaveletBands) {
    const auto add = [&](const auto& noise, const std::string& dim) {
      constexpr int D = std::decay_t<decltype(noise)>::dimension;
      const hush::grid<D> g = make_grid<D>(s);
      c.noise = "wavelet " + dim + " b" + std::to_string(bands);
      c.note = std::to_string(bands) + " bands, weights 1, 1/2, ...";
      c.workload = grid_name(g);
      c.prepare = [noise, ex, g] { return prepare_hush_grid(noise, ex, g, false); };
      cases.push_back(c);
      c.workload = "points " + std::to_string(s.points);
      c.prepare = [noise, ex, n = s.points] { return prepare_hush_points(noise, ex, n, false); };
      cases.push_back(c);
    };
    add(make_wavelet<2>(bands), "2D");
    add(make_wavelet<3>(bands), "3D");
  }
  if constexpr (std::is_same_v<Exec, hush::exec::simd_t>) {
    // The memory bounds of "wavelet 3D" points (SIMD only; its AVX2 copy comes with the
    // pinned rows): the same kernel with every tile read L1-resident (points confined to
    // [0, kWaveletL1Box)^3: 6^3 coefficients) and L2-resident (the same spread points on a
    // 32^3 tile, 140 KiB); the spread row's time above these is cache misses on the 64^3
    // tile (1.05 MiB, more than this machine's L2 once the points stream through it).
    c.noise = "wavelet 3D";
    c.note = "memory bound: tile reads L1-resident (points in [0, 4)^3)";
    c.workload = "points-L1 " + std::to_string(s.points);
    c.prepare = [noise = make_wavelet<3>(1), ex, n = s.points] {
      return prepare_hush_points(noise, ex, n, false, 0.0f, kWaveletL1Box);
    };
    cases.push_back(c);
    typename hush::wavelet<3>::params prm;
    prm.seed = kNoiseSeed;
    prm.tile_size = kWaveletL2Tile;
    c.note = "memory bound: 32^3 tile, L2-resident (the spread points)";
    c.workload = "points-L2 " + std::to_string(s.points);
    c.prepare = [noise = hush::wavelet<3>(prm), ex, n = s.points] {
      return prepare_hush_points(noise, ex, n, false);
    };
    cases.push_back(c);
  }
  first = cases.size();
  for (const auto proj : {hush::wavelet_projection::exact, hush::wavelet_projection::approximate}) {
    typename hush::wavelet<3>::params prm;
    prm.seed = kNoiseSeed;
    prm.projection = proj;
    const hush::wavelet<3> noise(prm);
    const bool exact = proj == hush::wavelet_projection::exact;
    c.noise = exact ? "wavelet 3D projected" : "wavelet 3D projected approx";
    c.note = exact ? "random unit normals, exact projection"
                   : "random unit normals, the paper's approximation";
    c.workload = "samples " + std::to_string(s.points);
    c.prepare = [noise, ex, n = s.points] {
      return prepare_wavelet_projected(noise, ex, n, false);
    };
    cases.push_back(c);
    if (!exact) continue;
    c.noise = "wavelet 3D projected z";
    c.note = "normals (0, 0, 1): the separable exact projection (beta along z)";
    c.prepare = [noise, ex, n = s.points] { return prepare_wavelet_projected(noise, ex, n, true); };
    cases.push_back(c);
  }
  add_leakage_quality(cases, first, 2);
}


}  // namespace

void add_wavelet_cases(std::vector<bench_case>& cases, const sizes& s, bench_pass pass) {
  on_backend(pass, [&](const auto& ex) { add_wavelet_rows(cases, s, ex); });
}

}  // namespace hush_bench
