// hush — the speed-vs-error benchmark's cases (see cases.hpp).
#include "cases.hpp"

#include "gabor_quality.hpp"

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "hush/core/rng.hpp"
#include "hush/detail/band_limit.hpp"
#include "hush/exec.hpp"
#include "hush/fractal.hpp"
#include "hush/gabor.hpp"
#include "hush/perlin.hpp"
#include "hush/wavelet.hpp"

#if HUSH_CONFIG_SIMD && !HUSH_CONFIG_SIMD_STATIC
#include <hwy/targets.h>
#endif
#if HUSH_BENCH_HAVE_GLSL
#include "hush/glsl/device.hpp"
#include "hush/glsl/headless.hpp"
#endif

#if HUSH_BENCH_HAVE_GLM
#include <glm/gtc/noise.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#endif
#if HUSH_BENCH_HAVE_LIBNOISE
#include <noise.h>
#endif

namespace hush_bench {
namespace {

// ---- The workloads. Every constant of the benchmark is here, once.

constexpr std::uint32_t kNoiseSeed = 7;
constexpr int kBenchThreads = 2;            // exec::parallel rows: this machine's cores
constexpr std::uint32_t kPointSeed = 2024;  // of the random point sets (hush::rng)
constexpr int kFbmOctaves = 4;              // lacunarity 2, gain 0.5: fractal's defaults
// Grid spacing 1/37 lattice units: not a power of two, so sample positions fall at ever
// different fractions and every cell is exercised; the origin is off the lattice too.
constexpr double kGridStep = 1.0 / 37;
constexpr std::array<double, 3> kGridOrigin = {0.3125, -2.71875, 5.0625};
// Random points fill [-kPointRange, kPointRange)^D.
constexpr float kPointRange = 128;
// The full and quick sizes (sizes's defaults are the full ones).
constexpr std::size_t kQuickGrid2 = 64, kQuickGrid3 = 16, kQuickPoints = 4096;
constexpr std::size_t kQuickFrameWidth = 192, kQuickFrameHeight = 108;

template <int D>
using fvec = hush::vec<float, D>;
template <int D>
using dvec = hush::vec<double, D>;

template <int D>
hush::grid<D> make_grid(const sizes& s) {
  hush::grid<D> g;
  for (int a = 0; a < D; ++a) {
    g.origin[a] = kGridOrigin[a];
    g.step[a] = kGridStep;
    g.size[a] = D == 2 ? s.grid2 : s.grid3;
  }
  return g;
}

template <int D>
std::string grid_name(const hush::grid<D>& g) {
  std::string name = "grid ";
  for (int a = 0; a < D; ++a) name += (a ? "x" : "") + std::to_string(g.size[a]);
  return name;
}

template <int D>
std::vector<fvec<D>> make_points(std::size_t n, float lo = -kPointRange, float hi = kPointRange) {
  hush::rng r(kPointSeed, static_cast<std::uint32_t>(D));
  std::vector<fvec<D>> pts(n);
  for (fvec<D>& p : pts)
    for (int a = 0; a < D; ++a) p[a] = r.uniform(lo, hi);
  return pts;
}

// Calls f(index, position) for every sample of g, in the output's C order (i fastest).
template <int D, class F>
void for_each_sample(const hush::grid<D>& g, F f) {
  const std::size_t nz = D == 3 ? g.size[D - 1] : 1;
  std::size_t idx = 0;
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < g.size[1]; ++j)
      for (std::size_t i = 0; i < g.size[0]; ++i, ++idx) {
        std::array<std::size_t, D> ijk{};
        ijk[0] = i;
        ijk[1] = j;
        if constexpr (D == 3) ijk[D - 1] = k;
        f(idx, g.position(ijk));
      }
}

// The buffers a case evaluates into; shared by the case's run() closures.
template <int D>
struct buffers {
  std::vector<fvec<D>> points;
  std::vector<float> out;
  std::vector<fvec<D>> grad;
};

// Keeps the results observable, so the compiler cannot drop the evaluation.
template <class T>
void keep(std::vector<T>& v) {
  benchmark::DoNotOptimize(v.data());
  benchmark::ClobberMemory();
}

// Error of the evaluated (out, grad) against noise's double reference at `pos(idx)`.
template <class Noise, int D>
void measure(const Noise& noise, std::size_t idx, const dvec<D>& pos, const buffers<D>& b,
             prepared_case& p) {
  if (b.grad.empty()) {
    p.value_error.add(b.out[idx], noise.template value<double>(pos));
    return;
  }
  const auto ref = noise.template value_and_gradient<double>(pos);
  p.value_error.add(b.out[idx], ref.value);
  for (int a = 0; a < D; ++a) p.gradient_error.add(b.grad[idx][a], ref.gradient[a]);
}

// ---- hush's rows.

template <class Noise, class Exec>
prepared_case prepare_hush_grid(const Noise& noise, const Exec& ex,
                                const hush::grid<Noise::dimension>& g, bool gradient) {
  constexpr int D = Noise::dimension;
  auto b = std::make_shared<buffers<D>>();
  b->out.resize(g.count());
  if (gradient) b->grad.resize(g.count());
  prepared_case p;
  p.samples = g.count();
  p.run = [noise, ex, g, b] {
    if (b->grad.empty())
      hush::evaluate_grid(noise, ex, g, hush::span<float>(b->out));
    else
      hush::evaluate_grid(noise, ex, g, hush::span<float>(b->out), hush::span<fvec<D>>(b->grad));
    keep(b->out);
  };
  p.run();
  for_each_sample(g, [&](std::size_t idx, const dvec<D>& pos) { measure(noise, idx, pos, *b, p); });
  return p;
}

template <class Noise, class Exec>
prepared_case prepare_hush_points(const Noise& noise, const Exec& ex, std::size_t n,
                                  bool gradient, float lo = -kPointRange, float hi = kPointRange) {
  constexpr int D = Noise::dimension;
  auto b = std::make_shared<buffers<D>>();
  b->points = make_points<D>(n, lo, hi);
  b->out.resize(n);
  if (gradient) b->grad.resize(n);
  prepared_case p;
  p.samples = n;
  p.run = [noise, ex, b] {
    const hush::span<const fvec<D>> pts(b->points.data(), b->points.size());
    if (b->grad.empty())
      hush::evaluate(noise, ex, pts, hush::span<float>(b->out));
    else
      hush::evaluate(noise, ex, pts, hush::span<float>(b->out), hush::span<fvec<D>>(b->grad));
    keep(b->out);
  };
  p.run();
  for (std::size_t i = 0; i < n; ++i)
    measure(noise, i, hush::vec_cast<double>(b->points[i]), *b, p);
  return p;
}

// Rows of one noise on one backend: {grid, points} x {value, value + gradient}.
template <class Noise, class Exec>
void add_noise_rows(std::vector<bench_case>& cases, const sizes& s, const std::string& name,
                    const Noise& noise, const Exec& ex) {
  constexpr int D = Noise::dimension;
  const hush::grid<D> g = make_grid<D>(s);
  for (const bool gradient : {false, true}) {
    bench_case c;
    c.noise = name;
    c.backend = Exec::name;
    c.wall_clock = std::string(Exec::name) == "glsl";
    c.gradient = gradient;
    c.workload = grid_name(g);
    c.prepare = [noise, ex, g, gradient] { return prepare_hush_grid(noise, ex, g, gradient); };
    cases.push_back(c);
    const std::size_t n = s.points;
    c.workload = "points " + std::to_string(n);
    c.prepare = [noise, ex, n, gradient] { return prepare_hush_points(noise, ex, n, gradient); };
    cases.push_back(c);
  }
}

template <int D>
hush::fractal<hush::perlin<D>> make_fbm() {
  typename hush::fractal<hush::perlin<D>>::params prm;
  prm.seed = kNoiseSeed;
  prm.octaves = kFbmOctaves;
  return hush::fractal<hush::perlin<D>>(prm);
}

// ---- Gabor noise (hush/gabor.hpp, issue 10): isotropic, F0 = 1, a = 0.8 (the
// defaults; kernel radius 1.22 units, so the grid's 1/37 step puts ~45 samples
// across a cell), unit variance, N' kernels per point.
constexpr double kGaborImpulses[] = {16, 32, 64};  // N': the first on every backend
// The filtered rows' footprints: a receding-plane-like range of pixel sizes,
// isotropic widths 10^u noise units, u uniform in [kGaborFootprintLog10Lo, Hi]. The
// anisotropic row's pixels are that wide across and 1 ... kGaborFootprintElongationHi
// times longer (uniform) along a uniform direction, as on a receding plane: the filter's
// general form (an eigen-decomposition per footprint, a full 2 x 2 quadratic form).
constexpr double kGaborFootprintLog10Lo = -3, kGaborFootprintLog10Hi = 0;
constexpr double kGaborFootprintElongationHi = 8;
enum class gabor_footprints { isotropic, anisotropic };

template <int D>
hush::gabor<D> make_gabor(double impulses) {
  typename hush::gabor<D>::params prm;
  prm.seed = kNoiseSeed;
  prm.impulses = impulses;
  return hush::gabor<D>(prm);
}

// Filtered evaluation (samples with footprints of the kind `shape`) against the double
// reference; with `normals` (3D), surface noise: each sample also has a random unit normal.
template <int D, class Exec>
prepared_case prepare_gabor_samples(const hush::gabor<D>& noise, const Exec& ex, std::size_t n,
                                    bool normals = false,
                                    gabor_footprints shape = gabor_footprints::isotropic) {
  struct sample_buffers {
    std::vector<fvec<D>> points;
    std::vector<hush::footprint<D>> fps;
    std::vector<fvec<3>> normals;
    std::vector<float> out;
  };
  auto b = std::make_shared<sample_buffers>();
  b->points = make_points<D>(n);
  hush::rng r(kPointSeed + 1);
  for (std::size_t i = 0; i < n; ++i) {
    const double w =
        std::pow(10.0, r.uniform<double>(kGaborFootprintLog10Lo, kGaborFootprintLog10Hi));
    if constexpr (D == 2) {
      if (shape == gabor_footprints::anisotropic) {
        const double t = r.uniform<double>(0, hush::detail::constants::kTwoPi);
        const double e = r.uniform<double>(1, kGaborFootprintElongationHi);
        b->fps.push_back(hush::footprint<2>::from_derivatives(
            hush::vec<double, 2>{w * std::cos(t), w * std::sin(t)},
            hush::vec<double, 2>{-w * e * std::sin(t), w * e * std::cos(t)}));
        continue;
      }
    }
    b->fps.push_back(hush::footprint<D>::isotropic(w));
  }
  // Uniform on the sphere: z uniform in [-1, 1], azimuth uniform.
  for (std::size_t i = 0; normals && i < n; ++i) {
    const double z = r.uniform<double>(-1, 1), phi = r.uniform<double>(0, hush::detail::constants::kTwoPi);
    const double rho = std::sqrt(1 - z * z);
    b->normals.push_back({float(rho * std::cos(phi)), float(rho * std::sin(phi)), float(z)});
  }
  b->out.resize(n);
  prepared_case p;
  p.samples = n;
  p.run = [noise, ex, b] {
    const hush::samples<D> s{b->points, b->fps, b->normals};
    hush::evaluate(noise, ex, s, hush::span<float>(b->out));
    keep(b->out);
  };
  p.run();
  for (std::size_t i = 0; i < n; ++i) {
    hush::sample_input<D> in;
    in.position = hush::vec_cast<double>(b->points[i]);
    in.fp = b->fps[i];
    if (normals) {
      in.normal = hush::vec_cast<double>(b->normals[i]);
      in.has_normal = true;
    }
    p.value_error.add(b->out[i], noise.template sample_value<double>(in));
  }
  return p;
}

// The spectrum error (gabor_quality.hpp) as the quality note of cases [from, end) of
// Gabor noise `noise` on `ex`: measured once, when the first of them is prepared.
template <int D, class Exec>
void add_spectrum_note(std::vector<bench_case>& cases, std::size_t from,
                       const hush::gabor<D>& noise, const Exec& ex) {
  auto note = std::make_shared<std::string>();
  for (std::size_t i = from; i < cases.size(); ++i) {
    cases[i].prepare = [inner = cases[i].prepare, note, noise, ex] {
      prepared_case p = inner();
      if (note->empty()) *note = gabor_spectrum_note(noise, ex);
      p.quality = *note;
      return p;
    };
  }
}

// Gabor rows on `ex`: N' = 16 grid and points (value, value + gradient); N' = 32,
// 64 values (cost linear in N'); filtered vs unfiltered points at N' = 16 (2D with
// isotropic and anisotropic footprints, 3D); 3D surface noise (samples with normals and the
// filtered rows' footprints). The unfiltered rows, 2D and 3D, carry the spectrum error.
template <class Exec>
void add_gabor_rows(std::vector<bench_case>& cases, const sizes& s, const Exec& ex) {
  const std::size_t first_2d = cases.size();
  add_noise_rows(cases, s, "gabor 2D", make_gabor<2>(kGaborImpulses[0]), ex);
  add_spectrum_note(cases, first_2d, make_gabor<2>(kGaborImpulses[0]), ex);
  const std::size_t first_3d = cases.size();
  add_noise_rows(cases, s, "gabor 3D", make_gabor<3>(kGaborImpulses[0]), ex);
  add_spectrum_note(cases, first_3d, make_gabor<3>(kGaborImpulses[0]), ex);
  const hush::grid<2> g = make_grid<2>(s);
  for (std::size_t k = 1; k < std::size(kGaborImpulses); ++k) {
    const hush::gabor<2> noise = make_gabor<2>(kGaborImpulses[k]);
    const std::size_t first = cases.size();
    bench_case c;
    c.noise = "gabor 2D n" + std::to_string(static_cast<int>(kGaborImpulses[k]));
    c.backend = Exec::name;
    c.wall_clock = std::string(Exec::name) == "glsl";
    c.workload = grid_name(g);
    c.prepare = [noise, ex, g] { return prepare_hush_grid(noise, ex, g, false); };
    cases.push_back(c);
    const std::size_t n = s.points;
    c.workload = "points " + std::to_string(n);
    c.prepare = [noise, ex, n] { return prepare_hush_points(noise, ex, n, false); };
    cases.push_back(c);
    add_spectrum_note(cases, first, noise, ex);
  }
  bench_case c;
  c.noise = "gabor 2D filtered";
  c.backend = Exec::name;
  c.wall_clock = std::string(Exec::name) == "glsl";
  c.workload = "samples " + std::to_string(s.points);
  c.note = "footprints: isotropic, 0.001 ... 1 units";
  c.prepare = [ex, n = s.points] {
    return prepare_gabor_samples(make_gabor<2>(kGaborImpulses[0]), ex, n);
  };
  cases.push_back(c);
  c.noise = "gabor 2D filtered anisotropic";
  c.note = "footprints: 0.001 ... 1 units across, 1 ... 8 times longer along a random direction";
  c.prepare = [ex, n = s.points] {
    return prepare_gabor_samples(make_gabor<2>(kGaborImpulses[0]), ex, n, false,
                                 gabor_footprints::anisotropic);
  };
  cases.push_back(c);
  c.noise = "gabor 3D filtered";
  c.note = "footprints: isotropic, 0.001 ... 1 units";
  c.prepare = [ex, n = s.points] {
    return prepare_gabor_samples(make_gabor<3>(kGaborImpulses[0]), ex, n);
  };
  cases.push_back(c);
  c.noise = "gabor 3D surface";
  c.note = "random unit normals; footprints: isotropic, 0.001 ... 1 units";
  c.prepare = [ex, n = s.points] {
    return prepare_gabor_samples(make_gabor<3>(kGaborImpulses[0]), ex, n, true);
  };
  cases.push_back(c);
}

// ---- Wavelet noise (hush/wavelet.hpp, issue 8): seed 7, default tiles (128^2, 64^3).
// Single band on grids and points (value, value + gradient); 2 and 4 bands (weights
// 1, 1/2, ...) on grids and points (the cost grows linearly in bands); 3D projected
// onto surfaces with random unit normals (exact and the paper's approximation). The
// quality note is the band leakage (detail/band_limit.hpp): the fraction of band 0's
// power below half its peak radial frequency, from a kLeakSize^2 grid sample at
// kLeakStep units (64 units: half the 2D tile, a whole 3D tile).
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

// A backend is a row generator: every noise x workload x output on `ex`.
template <class Exec>
void add_backend_rows(std::vector<bench_case>& cases, const sizes& s, const Exec& ex) {
  add_noise_rows(cases, s, "perlin 2D", hush::perlin<2>(kNoiseSeed), ex);
  add_noise_rows(cases, s, "perlin 3D", hush::perlin<3>(kNoiseSeed), ex);
  add_noise_rows(cases, s, "fbm 2D", make_fbm<2>(), ex);
  add_noise_rows(cases, s, "fbm 3D", make_fbm<3>(), ex);
  add_gabor_rows(cases, s, ex);
  add_wavelet_rows(cases, s, ex);
}

// ---- Peer rows: the same positions through another library, value only (neither offers
// gradients). Grid rows form each position in double as hush's grid path does.

// A peer case from its per-position evaluation `eval(dvec<D>) -> float or double`; the loop
// reads double positions, as hush's grid path forms them (a float peer converts each).
template <int D, class Eval>
prepared_case prepare_peer(std::vector<dvec<D>> positions, Eval eval) {
  auto pos = std::make_shared<std::vector<dvec<D>>>(std::move(positions));
  auto out = std::make_shared<std::vector<float>>(pos->size());
  prepared_case p;
  p.samples = pos->size();
  p.run = [pos, out, eval] {
    float* o = out->data();
    for (std::size_t i = 0; i < pos->size(); ++i) o[i] = static_cast<float>(eval((*pos)[i]));
    keep(*out);
  };
  p.run();
  return p;
}

template <int D>
std::vector<dvec<D>> grid_positions(const hush::grid<D>& g) {
  std::vector<dvec<D>> pos(g.count());
  for_each_sample(g, [&](std::size_t idx, const dvec<D>& q) { pos[idx] = q; });
  return pos;
}

template <int D>
std::vector<dvec<D>> point_positions(std::size_t n) {
  std::vector<dvec<D>> pos;
  for (const fvec<D>& q : make_points<D>(n)) pos.push_back(hush::vec_cast<double>(q));
  return pos;
}

// Adds a peer's {grid, points} rows for one noise; `make_eval` returns the evaluator and
// `add_error(positions, stats)` measures its float error (nullptr: double only).
template <int D, class MakeEval>
void add_peer_rows(std::vector<bench_case>& cases, const sizes& s, bench_case row,
                   MakeEval make_eval,
                   void (*add_error)(const std::vector<dvec<D>>&, error_stats&)) {
  const hush::grid<D> g = make_grid<D>(s);
  const std::size_t n = s.points;
  auto prepare = [make_eval, add_error](std::vector<dvec<D>> pos) {
    prepared_case p = prepare_peer<D>(pos, make_eval());
    if (add_error) add_error(pos, p.value_error);
    return p;
  };
  row.peer = true;
  row.workload = grid_name(g);
  row.prepare = [prepare, g] { return prepare(grid_positions(g)); };
  cases.push_back(row);
  row.workload = "points " + std::to_string(n);
  row.prepare = [prepare, n] { return prepare(point_positions<D>(n)); };
  cases.push_back(row);
}

#if HUSH_BENCH_HAVE_GLM
// glm::perlin takes float vectors; its error is float against glm's own double evaluation at
// the same float-rounded positions (like for like: what float arithmetic costs glm).
template <int D>
using glm_vec = glm::vec<D, float, glm::defaultp>;
template <int D>
using glm_dvec = glm::vec<D, double, glm::defaultp>;

template <int D>
glm_vec<D> to_glm_float(const dvec<D>& p) {
  glm_vec<D> v;
  for (int a = 0; a < D; ++a) v[a] = static_cast<float>(p[a]);
  return v;
}

template <int D>
void glm_error(const std::vector<dvec<D>>& positions, error_stats& e) {
  for (const dvec<D>& p : positions) {
    const glm_vec<D> f = to_glm_float(p);
    e.add(glm::perlin(f), glm::perlin(glm_dvec<D>(f)));
  }
}

template <int D>
void add_glm_rows(std::vector<bench_case>& cases, const sizes& s) {
  bench_case row;
  row.noise = D == 2 ? "perlin 2D" : "perlin 3D";
  row.backend = "glm::perlin";
  row.reference = error_reference::glm_double;
  add_peer_rows<D>(
      cases, s, row, [] { return [](const dvec<D>& p) { return glm::perlin(to_glm_float(p)); }; },
      &glm_error<D>);
}
#endif

#if HUSH_BENCH_HAVE_LIBNOISE
// libnoise's Perlin module is 3D and double only; 2D rows evaluate the plane z = 0.
// QUALITY_BEST is the quintic fade of improved Perlin noise, as hush uses.
template <int D>
void add_libnoise_rows(std::vector<bench_case>& cases, const sizes& s, int octaves) {
  bench_case row;
  row.noise = std::string(octaves == 1 ? "perlin " : "fbm ") + (D == 2 ? "2D" : "3D");
  row.backend = "libnoise";
  row.reference = error_reference::none;
  row.note = "QUALITY_BEST, " + std::to_string(octaves) + " octave" + (octaves > 1 ? "s" : "") +
             (D == 2 ? ", 3D module at z = 0" : "");
  add_peer_rows<D>(
      cases, s, row,
      [octaves] {
        auto module = std::make_shared<noise::module::Perlin>();
        module->SetSeed(static_cast<int>(kNoiseSeed));
        module->SetOctaveCount(octaves);
        module->SetNoiseQuality(noise::QUALITY_BEST);
        return [module](const dvec<D>& p) {
          return module->GetValue(p[0], p[1], D == 3 ? p[D - 1] : 0.0);
        };
      },
      nullptr);
}
#endif

// Perlin and 2D Gabor noise on the SIMD backend over kBenchThreads threads
// (hush::exec::parallel on a hush::thread_pool, as a program with many batches would run
// it: no thread start per call): the scaling on this machine's cores. Wall-clock time,
// since the work runs on other threads too.
void add_parallel_rows(std::vector<bench_case>& cases, const sizes& s) {
  static hush::thread_pool pool(kBenchThreads);  // outlives every case that captures it
  const auto ex = hush::exec::parallel(hush::exec::simd, pool);
  const std::size_t first = cases.size();
  add_noise_rows(cases, s, "perlin 2D", hush::perlin<2>(kNoiseSeed), ex);
  add_noise_rows(cases, s, "perlin 3D", hush::perlin<3>(kNoiseSeed), ex);
  const std::size_t gabor_first = cases.size();
  add_noise_rows(cases, s, "gabor 2D", make_gabor<2>(kGaborImpulses[0]), ex);
  add_spectrum_note(cases, gabor_first, make_gabor<2>(kGaborImpulses[0]), ex);
  for (std::size_t i = first; i < cases.size(); ++i) {
    cases[i].backend = "simd, " + std::to_string(kBenchThreads) + " threads";
    cases[i].wall_clock = true;
  }
}

}  // namespace

sizes full_sizes() { return sizes{}; }
sizes quick_sizes() {
  sizes s{kQuickGrid2, kQuickGrid3, kQuickPoints, kQuickFrameWidth, kQuickFrameHeight};
  s.triangles = 16;
  s.npr_width = kQuickFrameWidth;
  s.npr_height = kQuickFrameHeight;
  s.npr_triangles = {5000};
  return s;
}

void error_stats::add(double measured, double reference) {
  const double e = measured - reference;
  max_abs = std::fmax(max_abs, std::fabs(e));
  sum_sq += e * e;
  ++count;
}

double error_stats::rms() const {
  return count ? std::sqrt(sum_sq / static_cast<double>(count)) : 0.0;
}

const char* describe(error_reference r) {
  switch (r) {
    case error_reference::hush_double:
      return "hush double";
    case error_reference::glm_double:
      return "glm double";
    case error_reference::none:
      return "n.a. (double only)";
    case error_reference::weights:
      return "n.a. (preprocessing)";
  }
  return "?";
}

std::string bench_case::id() const {
  std::string n = noise + "/" + backend + "/" + workload.substr(0, workload.find(' ')) + "/" +
                  (gradient ? "value+gradient" : "value");
  std::string id;
  for (const char ch : n)
    if (ch != ' ') id += ch == ':' ? '_' : ch;
  return id;
}

#if HUSH_CONFIG_SIMD && !HUSH_CONFIG_SIMD_STATIC
// The SIMD rows again with dispatch pinned to one target (e.g. AVX2 on an AVX-512 machine),
// named "simd AVX2": the targets are stated per machine, and a program may run on either.
void add_pinned_simd_rows(std::vector<bench_case>& cases, std::int64_t target) {
  std::vector<bench_case> pinned;
  for (const bench_case& c : cases) {
    if (c.backend != hush::exec::simd_t::name && c.backend.rfind("memory-bound pass", 0) != 0)
      continue;
    bench_case p = c;
    p.backend = std::string(c.backend) + " " + hwy::TargetName(target);
    p.prepare = [prepare = c.prepare, target] {
      hwy::SetSupportedTargetsForTest(target);
      prepared_case r = prepare();
      hwy::SetSupportedTargetsForTest(0);
      r.run = [run = r.run, target] {
        hwy::SetSupportedTargetsForTest(target);
        run();
        hwy::SetSupportedTargetsForTest(0);
      };
      return r;
    };
    pinned.push_back(std::move(p));
  }
  cases.insert(cases.end(), pinned.begin(), pinned.end());
}
#endif

#if HUSH_BENCH_HAVE_GLSL
// Coherent noise's GLSL row (coherent_cases.cpp).
void add_coherent_glsl_rows(std::vector<bench_case>& cases, const sizes& s,
                            hush::glsl::device& device);

// The GLSL rows run on one headless context for the whole process (OSMesa's llvmpipe here;
// HUSH_GL_CONTEXT=egl: the machine's GPU).
// (declared in bench/anisotropic_cases.cpp too)
hush::glsl::device& bench_glsl_device() {
  static hush::glsl::headless_device h;
  return h.device;
}
#endif

std::vector<bench_case> all_cases(const sizes& s) {
  std::vector<bench_case> cases;
  add_backend_rows(cases, s, hush::exec::scalar);
  add_backend_rows(cases, s, hush::exec::simd);
  add_parallel_rows(cases, s);
  add_coherent_rows(cases, s);  // its simd rows are pinned to AVX2 below too
  add_anisotropic_cases(cases, s);  // before the pinned rows: its simd rows get theirs
#if HUSH_BENCH_HAVE_SCENE
  add_npr_gabor_cases(cases, s);  // likewise
#endif
#if HUSH_CONFIG_SIMD && !HUSH_CONFIG_SIMD_STATIC
  // AVX2 pinned when the machine would pick something better: the targets are AVX2's.
  const std::int64_t usable = hwy::SupportedTargets() & HWY_TARGETS;
  if ((usable & HWY_AVX2) && (usable & (HWY_AVX2 - 1))) add_pinned_simd_rows(cases, HWY_AVX2);
#endif
#if HUSH_BENCH_HAVE_GLSL
  {
    const hush::exec::glsl<hush::glsl::device> gpu{bench_glsl_device()};
    add_noise_rows(cases, s, "perlin 2D", hush::perlin<2>(kNoiseSeed), gpu);
    add_noise_rows(cases, s, "perlin 3D", hush::perlin<3>(kNoiseSeed), gpu);
    add_noise_rows(cases, s, "fbm 2D", make_fbm<2>(), gpu);
    add_noise_rows(cases, s, "fbm 3D", make_fbm<3>(), gpu);
    add_gabor_rows(cases, s, gpu);
    add_wavelet_rows(cases, s, gpu);
    add_coherent_glsl_rows(cases, s, bench_glsl_device());
  }
#endif
#if HUSH_BENCH_HAVE_GLM
  add_glm_rows<2>(cases, s);
  add_glm_rows<3>(cases, s);
#endif
#if HUSH_BENCH_HAVE_LIBNOISE
  for (const int octaves : {1, kFbmOctaves}) {
    add_libnoise_rows<2>(cases, s, octaves);
    add_libnoise_rows<3>(cases, s, octaves);
  }
#endif
  // Rows made by copying a case (the backend and pinned-target variants) copied its quality
  // pointer too: give every row its own, so that no row reports a sibling's note.
  for (bench_case& c : cases) c.quality = std::make_shared<std::string>();
  return cases;
}

namespace {

// Runs one case under Google Benchmark, which calls it again per repetition and while it
// sizes the iteration count; `prepared` prepares the case on its first call.
void run_case(benchmark::State& state, const bench_case& c, prepared_cases& prepared,
              const loop_observer& after_loop) {
  prepared_case& p = prepared.get(c);
  for (auto _ : state)  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's idiom
    p.run();
  if (after_loop) after_loop(c, static_cast<std::int64_t>(state.iterations()));
  const double samples = static_cast<double>(p.samples);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(p.samples));
  // Samples per iteration as a rate, inverted: CPU seconds per sample (printed "25.8ns").
  state.counters[kSecondsPerSample] = benchmark::Counter(
      samples, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  if (c.reference == error_reference::none || c.reference == error_reference::weights) return;
  state.counters[kMaxAbs] = p.value_error.max_abs;
  state.counters[kRms] = p.value_error.rms();
  if (p.gradient_error.count) {
    state.counters[kGradMaxAbs] = p.gradient_error.max_abs;
    state.counters[kGradRms] = p.gradient_error.rms();
  }
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos && colon + 2 <= line.size()) return line.substr(colon + 2);
    }
  return "unknown";
}

}  // namespace

prepared_case& prepared_cases::get(const bench_case& c) {
  const auto it = held_.find(&c);
  if (it != held_.end()) return it->second;
  // Free the held case before preparing the next, so that two are never held together.
  if (keep_ == keep_prepared::latest) held_.clear();
  prepared_case& p = held_.emplace(&c, c.prepare()).first->second;
  *c.quality = p.quality;
  return p;
}

void register_benchmarks(const std::vector<bench_case>& cases, double min_time, int repetitions,
                         prepared_cases& prepared, const loop_observer& after_loop) {
  for (const bench_case& c : cases) {
    // Google Benchmark's registry owns what RegisterBenchmark allocates; the analyzer cannot
    // see that (the registry is in the compiled library).
    // NOLINTNEXTLINE(clang-analyzer-cplusplus.NewDeleteLeaks)
    benchmark::internal::Benchmark* b = benchmark::RegisterBenchmark(
        c.id().c_str(), [&c, &prepared, after_loop](benchmark::State& state) {
          run_case(state, c, prepared, after_loop);
        });
    b->Unit(benchmark::kMillisecond);
    if (c.wall_clock) b->UseRealTime();
    if (repetitions > 0) b->Repetitions(repetitions);
    if (repetitions > 1) b->ReportAggregatesOnly(true);
    if (min_time > 0) b->MinTime(min_time);
  }
}

std::string simd_target() {
#if HUSH_CONFIG_SIMD
  return hush::simd::chosen_target() + " (" + hush::simd::dispatch_mode() + " dispatch)";
#else
  return "none (built without Highway: exec::simd runs the scalar loop)";
#endif
}

machine_info describe_machine() {
  machine_info m;
  m.cpu = cpu_model();
  const benchmark::CPUInfo& info = benchmark::CPUInfo::Get();
  m.cpus = info.num_cpus;
  m.mhz = info.cycles_per_second / 1e6;
  for (const double l : info.load_avg) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", l);
    m.load += (m.load.empty() ? "" : ", ") + std::string(buf);
  }
  if (m.load.empty()) m.load = "unknown";
#if defined(__clang__)
  m.compiler = "Clang " __clang_version__;
#elif defined(__GNUC__)
  m.compiler = "GCC " __VERSION__;
#else
  m.compiler = "unknown";
#endif
  m.build = HUSH_BENCH_BUILD;
#if defined(__AVX2__)
  m.build += ", compiled for AVX2";
#elif defined(__SSE4_2__)
  m.build += ", compiled for SSE4.2";
#else
  m.build += ", baseline x86-64 ISA (no -march)";
#endif
  m.simd_target = simd_target();
  m.peers = "";
#if HUSH_BENCH_HAVE_GLM
  m.peers += "glm " + std::to_string(GLM_VERSION_MAJOR) + "." + std::to_string(GLM_VERSION_MINOR) +
             "." + std::to_string(GLM_VERSION_PATCH) + "." + std::to_string(GLM_VERSION_REVISION);
#endif
#if HUSH_BENCH_HAVE_LIBNOISE
  m.peers += std::string(m.peers.empty() ? "" : ", ") + "libnoise (no version macro)";
#endif
  if (m.peers.empty()) m.peers = "none found at build time";
  return m;
}

}  // namespace hush_bench
