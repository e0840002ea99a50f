// hush — the speed-vs-error benchmark: anisotropic noise's rows (include/hush/anisotropic.hpp).
//
// The workload: one frame of a receding plane (1920 x 1080; every pixel sees the
// plane, out to the horizon's grazing angles), K = 4 and 8 orientations, 3 scales, the
// centre heuristic's filtering weights per pixel from the screen-to-texture Jacobian. Error
// columns: the float path against the double reference at the same inputs. The quality
// metric, in the note: RMS against each pixel's supersampled Gaussian reference
// (examples/anisotropic, every 97th pixel), and the unfiltered noise's for comparison.
// And the least-squares preprocessing: compensation weights for distinct triangle maps.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "cases.hpp"
#include "figures.hpp"
#include "hush/exec.hpp"
#include "hush/hush.hpp"
#include "rows.hpp"

#if HUSH_BENCH_HAVE_GLSL
#include "hush/glsl/device.hpp"
#endif

namespace hush_bench {

namespace {

constexpr std::uint32_t kSeed = 7;
constexpr double kFrequency = 2.0;  // octave 0, cycles per world unit of the plane
constexpr std::size_t kQualityStride = 97;

hush::anisotropic make_noise(int k, hush::weight_rule compensation = hush::weight_rule::centre) {
  hush::anisotropic::params p;
  p.seed = kSeed;
  p.orientations = k;
  p.scales = 3;
  p.octaves = 3;
  p.frequency = kFrequency;
  p.compensation = compensation;
  return hush::anisotropic(p);
}

struct frame_buffers {
  hush_tools::aniso::receding_plane plane;
  std::vector<float> out;
};

// The quality note: RMS of the filtered and the unfiltered float noise against the
// supersampled reference over every kQualityStride-th pixel.
std::string quality_note(const hush::anisotropic& noise, const frame_buffers& b) {
  std::vector<std::size_t> pixels;
  for (std::size_t q = 0; q < b.out.size(); q += kQualityStride) pixels.push_back(q);
  const std::vector<double> ref = hush_tools::aniso::supersampled(noise, b.plane, pixels);
  double e = 0, eu = 0;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const std::size_t q = pixels[i];
    const double v = noise.sample(b.plane.positions[q], b.plane.footprints[q]);
    e += (v - ref[i]) * (v - ref[i]);
    const double u = noise(b.plane.positions[q]);
    eu += (u - ref[i]) * (u - ref[i]);
  }
  char text[160];
  std::snprintf(text, sizeof text,
                "receding plane, %zu x %zu; RMS vs supersampled Gaussian %.4f (unfiltered %.4f)",
                b.plane.width, b.plane.height, std::sqrt(e / double(pixels.size())),
                std::sqrt(eu / double(pixels.size())));
  return text;
}

template <class Exec>
void add_frame_rows(std::vector<bench_case>& cases, const sizes& s, const Exec& ex,
                    const std::shared_ptr<const frame_buffers>& shared) {
  for (int k : {4, 8}) {
    bench_case c;
    c.noise = "anisotropic K=" + std::to_string(k);
    c.backend = Exec::name;
    c.wall_clock = std::string(Exec::name) == "glsl";
    c.workload = "frame " + std::to_string(s.frame_width) + "x" + std::to_string(s.frame_height);
    const hush::anisotropic noise = make_noise(k);
    c.note = quality_note(noise, *shared) + "; 3 scales, centre heuristic per pixel";
    c.prepare = [noise, ex, shared] {
      auto b = std::make_shared<frame_buffers>(*shared);
      prepared_case p;
      p.samples = b->out.size();
      p.run = [noise, ex, b] {
        hush::samples<2> smp;
        smp.positions = b->plane.positions;
        smp.footprints = b->plane.footprints;
        hush::evaluate(noise, ex, smp, hush::span<float>(b->out));
        benchmark::DoNotOptimize(b->out.data());
        benchmark::ClobberMemory();
      };
      p.run();
      for (std::size_t q = 0; q < b->out.size(); ++q)
        p.value_error.add(b->out[q], noise.sample(hush::vec_cast<double>(b->plane.positions[q]),
                                                  b->plane.footprints[q]));
      return p;
    };
    cases.push_back(c);
  }
}

}  // namespace

// Its rows are all in the frames pass: the frame rows on every backend (their SIMD rows pinned
// to AVX2 with the others), then the least-squares weights.
void add_anisotropic_cases(std::vector<bench_case>& cases, const sizes& s, bench_pass pass) {
  if (pass != bench_pass::frames) return;
  auto shared = std::make_shared<frame_buffers>();
  shared->plane = hush_tools::aniso::make_receding_plane(s.frame_width, s.frame_height);
  shared->out.assign(s.frame_width * s.frame_height, 0.0f);
  add_frame_rows(cases, s, hush::exec::scalar, shared);
  add_frame_rows(cases, s, hush::exec::simd, shared);
#if HUSH_BENCH_HAVE_GLSL
  add_frame_rows(cases, s, hush::exec::glsl<hush::glsl::device>{bench_glsl_device()}, shared);
#endif
  // Least-squares compensation weights: 2 octaves, 5 scales, K = 4 (the paper's fig. 6
  // set-up), one fit per octave and distinct triangle map (maps never repeat, so the
  // noise's per-map cache never hits).
  bench_case c;
  c.noise = "anisotropic K=4";
  c.backend = "scalar";
  c.workload = "triangles " + std::to_string(s.triangles);
  c.reference = error_reference::weights;
  c.note = "least-squares compensation weights per triangle (2 octaves, 5 scales)";
  const std::size_t n = s.triangles;
  c.prepare = [n] {
    hush::anisotropic::params p;
    p.seed = kSeed;
    p.scales = 5;
    p.base_scale = 1;
    p.octaves = 2;
    p.compensation = hush::weight_rule::least_squares;
    auto noise = std::make_shared<hush::anisotropic>(p);
    auto counter = std::make_shared<std::uint32_t>(0);
    prepared_case r;
    r.samples = n;
    r.run = [noise, counter, n] {
      float w[hush::detail::constants::kAnisoMaxScales * hush::anisotropic::kMaxChannels];
      for (std::size_t t = 0; t < n; ++t) {
        hush::rng g(kSeed, (*counter)++);
        hush::sample_input<2> in;
        in.has_map = true;
        in.map = hush::surface_map::from_matrix(g.uniform(0.5, 2.0), g.uniform(-0.5, 0.5),
                                                g.uniform(-0.5, 0.5), g.uniform(0.5, 2.0));
        noise->weights<float>(in, w);
        benchmark::DoNotOptimize(w);
      }
    };
    return r;
  };
  cases.push_back(c);
}

}  // namespace hush_bench
