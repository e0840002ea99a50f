// hush — the `hush` program: what the noises it samples share.
//
// A noise_entry names a noise, lists its own options and builds a noise_field from them.
// `hush sample NOISE` looks NOISE up in noise_table(), and usage text and option errors are
// generated from the entries. Each noise's entry is in its own file, noise_<noise>.cpp
// (noise_entries.hpp), so adding a noise to the program is that file: its entry plus the
// function that builds it, often a grid_field below.
#ifndef HUSH_CLI_NOISES_HPP
#define HUSH_CLI_NOISES_HPP

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "args.hpp"
#include "glsl_device.hpp"
#include "hush/hush.hpp"

namespace hush_cli {

// The samples a command asks for: sample (i, j, k) sits at grid.position({i, j, k}),
// i.e. origin + step * (first + (i, j, k)) in double (first: where a --region block
// starts in the whole grid). 2D noises read x and y (size[2] is then 1).
using sample_grid = hush::grid<3>;

// Rows j0 ... j0 + rows - 1 of z-plane k of `grid` as a D-dimensional block of the
// whole grid (hush::grid::block): every sample keeps its whole-grid position bit for bit.
template <int D>
hush::grid<D> row_block(const sample_grid& grid, std::size_t j0, std::size_t rows,
                        std::size_t k) {
  const sample_grid b = grid.block({0, j0, k}, {grid.size[0], rows, 1});
  hush::grid<D> g;
  for (int a = 0; a < D; ++a) {
    g.origin[a] = b.origin[a];
    g.step[a] = b.step[a];
    g.first[a] = b.first[a];
    g.size[a] = b.size[a];
  }
  return g;
}

// Where a noise is evaluated: hush::exec::scalar, hush::exec::simd or hush::exec::glsl.
enum class backend { scalar, simd, glsl };
const char* backend_name(backend b);
// Why backend b is not in this build ("" when it is): the reason every noise shares.
std::string backend_missing(backend b);

// Calls run(exec) with the hush::exec policy of backend b (glsl: the process's device;
// nothing where this build has no GLSL: unsupported_reason has refused it before).
template <class Run>
void with_exec(backend b, Run&& run) {
  switch (b) {
    case backend::scalar:
      run(hush::exec::scalar);
      break;
    case backend::simd:
      run(hush::exec::simd);
      break;
    case backend::glsl:
#if HUSH_CLI_HAVE_GLSL
      run(hush::exec::glsl<hush::glsl::device>{glsl_device()});
#endif
      break;
  }
}

// A configured noise, sampled a block of grid rows at a time.
class noise_field {
 public:
  virtual ~noise_field() = default;
  // True for values symmetric about 0; false for values >= 0 (turbulence).
  virtual bool is_signed() const = 0;
  // The values a PNG shows from black to white unless --range says otherwise: [-1, 1] for
  // signed noise bounded by 1, [0, 1] for turbulence; noises of unit variance override it
  // with unit_variance_range.
  virtual std::pair<double, double> png_range() const {
    return {is_signed() ? -1.0 : 0.0, 1.0};
  }
  // Empty when this noise runs on backend `b` in this build, else why not (one phrase).
  virtual std::string unsupported_reason(backend b) const = 0;
  // Rows j0 ... j0 + rows - 1 of z-plane k into out (rows * grid.size[0] floats, C order):
  // out = noise.value<float>(grid.position({i, j, k})) up to the backend's stated
  // agreement (hush/exec.hpp), through hush::evaluate_grid on backend `b`.
  virtual void sample_rows(const sample_grid& grid, std::size_t j0, std::size_t rows, std::size_t k,
                           float* out, backend b) const = 0;
};

// The PNG range of signed unit-variance noise: +-3 (three standard deviations), which clips
// 0.27 % of a unit Gaussian (2 (1 - Phi(3))), leaving room for heavier tails under the 1 %
// that tests/cli checks on wavelet, Gabor and fBm images.
constexpr double kUnitVarianceRange = 3.0;
inline std::pair<double, double> unit_variance_range() {
  return {-kUnitVarianceRange, kUnitVarianceRange};
}

// Every sample of `grid`, in C order (i fastest, then j, then k).
std::vector<float> sample_all(const noise_field& field, const sample_grid& grid,
                              backend b = backend::scalar);

// What every noise is built from: the common options of `hush sample`.
struct noise_setup {
  int dim = 2;
  std::uint32_t seed = 0;
};

struct noise_entry {
  const char* name;     // as typed after `hush sample`
  const char* summary;  // one line for the usage text
  std::vector<option_spec> options;
  // Builds the noise. Throws usage_error for a value it cannot parse, and lets the
  // library's hush::invalid_argument through (make_noise reports it against the option).
  std::unique_ptr<noise_field> (*make)(const noise_setup& setup, const option_values& given);
};

// Every noise's `hush sample` entry, as usage lists them (noise_entries.cpp).
const std::vector<noise_entry>& noise_table();
// "perlin, ..." for messages.
std::string noise_names();
// The entry called `name`; throws usage_error listing the valid names.
const noise_entry& find_noise(const std::string& name);

// `--normal x,y,z` (3D surface noise: every sample evaluated with this normal, i.e. on the
// plane through it): nullopt when not given. Throws usage_error when it is given without
// --dim 3, is not three finite numbers, or is all zero. Returned scaled so that its largest
// component is +-1 (only the direction matters).
std::optional<hush::vec3> parse_normal(const noise_setup& setup, const option_values& given);

// Rows j0 ... j0 + rows - 1 of z-plane k of `grid` into `out`, with the same footprint (when
// given) and normal (when given, 3D) for every sample, on backend b. Positions stay exact:
// with `period` > 0 (the noise repeats with that period along every axis) each is first
// reduced modulo the period in double, which is exact, so the float positions of
// hush::samples keep every digit that matters at any origin; the scalar backend evaluates
// the double position itself (noise.sample_value<float>, hush::evaluate's own scalar step).
// Without a period, SIMD and GLSL get the positions rounded to float.
template <class Noise>
void sample_rows_as_samples(const Noise& noise, const sample_grid& grid, std::size_t j0,
                            std::size_t rows, std::size_t k, float* out, backend b,
                            const std::optional<hush::footprint<Noise::dimension>>& footprint,
                            const std::optional<hush::vec3>& normal, double period = 0) {
  constexpr int D = Noise::dimension;
  const std::size_t nx = grid.size[0], n = nx * rows;
  std::vector<hush::vec<double, D>> dpos(n);
  for (std::size_t j = 0; j < rows; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      const hush::dvec3 p = grid.position({i, j0 + j, k});
      for (int a = 0; a < D; ++a) {
        double x = p[a];
        // x - period floor(x / period): exact for |x| < 2^40 period (period floor(x / period)
        // is exact, and so is the difference of two doubles this close).
        if (period > 0) x -= period * std::floor(x / period);
        dpos[j * nx + i][a] = x;
      }
    }
  if (b == backend::scalar) {
    for (std::size_t i = 0; i < n; ++i) {
      hush::sample_input<D> in;
      in.position = dpos[i];
      if (footprint) in.fp = *footprint;
      if constexpr (D == 3) {
        if (normal) {
          in.normal = hush::vec_cast<double>(*normal);
          in.has_normal = true;
        }
      }
      out[i] = noise.template sample_value<float>(in);
    }
    return;
  }
  std::vector<hush::vec<float, D>> pos(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < D; ++a) pos[i][a] = static_cast<float>(dpos[i][a]);
  std::vector<hush::footprint<D>> fps;
  if (footprint) fps.assign(n, *footprint);
  std::vector<hush::vec3> nrm;
  if (normal) nrm.assign(n, *normal);
  hush::samples<D> s;
  s.positions = pos;
  s.footprints = fps;
  s.normals = nrm;
  with_exec(b, [&](const auto& ex) { hush::evaluate(noise, ex, s, hush::span<float>(out, n)); });
}

// entry.make(setup, given), with a hush::invalid_argument turned into a usage_error naming
// the option that carries the refused library parameter.
std::unique_ptr<noise_field> make_noise(const noise_entry& entry, const noise_setup& setup,
                                        const option_values& given);

// Whether the GLSL backend has a program for Noise (false where this build has no GLSL).
template <class Noise>
constexpr bool has_glsl_program() {
#if HUSH_CLI_HAVE_GLSL
  return hush::glsl::has_program_v<Noise>;
#else
  return false;
#endif
}

// Any hush noise of dimension D that hush::evaluate_grid takes, sampled through it on every
// backend that has it: values symmetric about 0 when `is_signed`, else >= 0; `unit_variance`:
// shown over unit_variance_range() in PNGs.
template <class Noise, int D>
class grid_field final : public noise_field {
 public:
  grid_field(Noise noise, bool is_signed, bool unit_variance = false)
      : noise_(std::move(noise)), signed_(is_signed), unit_variance_(unit_variance) {}
  bool is_signed() const override { return signed_; }
  std::pair<double, double> png_range() const override {
    return unit_variance_ ? unit_variance_range() : noise_field::png_range();
  }
  std::string unsupported_reason(backend b) const override {
    if (b == backend::glsl) {
      if (!HUSH_CLI_HAVE_GLSL) return "the GLSL backend is not in this build (neither OSMesa nor EGL found)";
      if (!has_glsl_program<Noise>())
        return "the GLSL backend has no program for this noise (hush::glsl::has_program_v)";
    }
    if (b == backend::simd && !HUSH_CONFIG_SIMD)
      return "the SIMD backend is not in this build (Highway, libhwy-dev, was not found)";
    return "";
  }
  void sample_rows(const sample_grid& grid, std::size_t j0, std::size_t rows, std::size_t k,
                   float* out, backend b) const override {
    const hush::grid<D> block = row_block<D>(grid, j0, rows, k);
    const hush::span<float> dst(out, block.count());
    if (b == backend::simd) {
      hush::evaluate_grid(noise_, hush::exec::simd, block, dst);
      return;
    }
#if HUSH_CLI_HAVE_GLSL
    if constexpr (has_glsl_program<Noise>()) {
      if (b == backend::glsl) {
        hush::evaluate_grid(noise_, hush::exec::glsl{glsl_device()}, block, dst);
        return;
      }
    }
#endif
    hush::evaluate_grid(noise_, hush::exec::scalar, block, dst);
  }

 private:
  Noise noise_;
  bool signed_;
  bool unit_variance_;
};

}  // namespace hush_cli

#endif  // HUSH_CLI_NOISES_HPP
