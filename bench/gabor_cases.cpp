// hush — the speed-vs-error benchmark: Gabor noise's rows (include/hush/gabor.hpp).
//
// Isotropic, F0 = 1, a = 0.8 (the defaults; kernel radius 1.22 units, so the grid's 1/37 step
// puts ~45 samples across a cell), unit variance, N' kernels per point. On the scalar, SIMD and
// GLSL backends: N' = 16 on the 2D and 3D grids and random points of rows.hpp (value, value +
// gradient), N' = 32 and 64 values, and filtered samples (2D with isotropic and anisotropic
// footprints, 3D, 3D surface noise); on exec::parallel, the 2D N' = 16 rows. The unfiltered
// rows carry the spectrum error (gabor_quality.hpp) as their quality note.
#include <cmath>
#include <cstddef>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "cases.hpp"
#include "gabor_quality.hpp"
#include "hush/detail/constants.hpp"
#include "hush/gabor.hpp"
#include "rows.hpp"

namespace hush_bench {
namespace {

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

}  // namespace

void add_gabor_cases(std::vector<bench_case>& cases, const sizes& s, bench_pass pass) {
  if (pass == bench_pass::parallel) {
    on_parallel_backend(cases, [&](const auto& ex) {
      const std::size_t first = cases.size();
      add_noise_rows(cases, s, "gabor 2D", make_gabor<2>(kGaborImpulses[0]), ex);
      add_spectrum_note(cases, first, make_gabor<2>(kGaborImpulses[0]), ex);
    });
    return;
  }
  on_backend(pass, [&](const auto& ex) { add_gabor_rows(cases, s, ex); });
}

}  // namespace hush_bench
