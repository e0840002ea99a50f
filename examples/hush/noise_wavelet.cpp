// hush — the `hush` program: `hush sample wavelet` (hush/wavelet.hpp), its noise_table entry.
//
// Without --footprint and --normal the grid goes through hush::evaluate_grid; with either,
// every sample is evaluated through hush::evaluate over hush::samples (the same isotropic
// footprint and normal for every sample), on the chosen backend, its position reduced
// modulo the noise's period in double first (exact: as many distinct values at origin
// 1e9 as at 0; the scalar backend takes the double positions themselves).
#include <cmath>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "glsl_device.hpp"
#include "noise_entries.hpp"
#include "noises.hpp"

namespace hush_cli {
namespace {

struct wavelet_sample_options {
  double footprint = -1;  // < 0: none given
  std::optional<hush::vec3> normal;
};

template <int D>
class wavelet_field final : public noise_field {
 public:
  wavelet_field(hush::wavelet<D> noise, wavelet_sample_options o)
      : noise_(std::move(noise)), o_(o) {}
  bool is_signed() const override { return true; }
  std::pair<double, double> png_range() const override {
    // Gaussian: unit variance; uniform: (-1, 1).
    return noise_.parameters().distribution == hush::wavelet_distribution::gaussian
               ? unit_variance_range()
               : noise_field::png_range();
  }
  std::string unsupported_reason(backend b) const override { return backend_missing(b); }
  void sample_rows(const sample_grid& grid, std::size_t j0, std::size_t rows, std::size_t k,
                   float* out, backend b) const override {
    const hush::span<float> dst(out, grid.size[0] * rows);
    if (o_.footprint < 0 && !o_.normal) {
      const hush::grid<D> block = row_block<D>(grid, j0, rows, k);
      with_exec(b, [&](const auto& ex) { hush::evaluate_grid(noise_, ex, block, dst); });
      return;
    }
    std::optional<hush::footprint<D>> fp;
    if (o_.footprint >= 0) fp = hush::footprint<D>::isotropic(o_.footprint);
    // Every band repeats with tile_size / 2^first_band unless tile variants are on.
    const auto& prm = noise_.parameters();
    const double period =
        prm.variant_overlap > 0 ? 0.0 : std::ldexp(double(prm.tile_size), -prm.first_band);
    sample_rows_as_samples(noise_, grid, j0, rows, k, out, b, fp, o_.normal, period);
  }

 private:
  hush::wavelet<D> noise_;
  wavelet_sample_options o_;
};

template <int D>
std::unique_ptr<noise_field> make_wavelet_d(const noise_setup& setup, const option_values& given,
                                            const wavelet_sample_options& so) {
  typename hush::wavelet<D>::params prm;
  prm.seed = setup.seed;
  if (const std::string* v = find_value(given, "--tile-size"))
    prm.tile_size = static_cast<int>(parse_integer("--tile-size", *v, 0, 1 << 20));
  if (const std::string* v = find_value(given, "--first-band"))
    prm.first_band = static_cast<int>(parse_integer("--first-band", *v, -1000, 1000));
  const std::string* bands = find_value(given, "--bands");
  const std::string* weights = find_value(given, "--weights");
  if (bands && weights) throw usage_error("--bands and --weights: give one of them, not both");
  if (bands) {
    const auto n =
        static_cast<std::size_t>(parse_integer("--bands", *bands, 1, hush::wavelet<D>::kMaxBands));
    prm.weights.clear();
    for (std::size_t i = 0; i < n; ++i)
      prm.weights.push_back(std::ldexp(1.0, -static_cast<int>(i)));
  }
  if (weights) {
    const std::vector<std::string> parts = split(*weights, ',');
    if (parts.size() > static_cast<std::size_t>(hush::wavelet<D>::kMaxBands))
      throw_bad_value("--weights", *weights, "1 ... 32 comma-separated finite numbers");
    prm.weights.clear();
    for (const std::string& p : parts) prm.weights.push_back(parse_finite("--weights", p));
  }
  if (const std::string* v = find_value(given, "--distribution"))
    prm.distribution = parse_choice<hush::wavelet_distribution>(
        "--distribution", *v,
        {{"gaussian", hush::wavelet_distribution::gaussian},
         {"uniform", hush::wavelet_distribution::uniform}});
  if (const std::string* v = find_value(given, "--projection"))
    prm.projection = parse_choice<hush::wavelet_projection>(
        "--projection", *v,
        {{"exact", hush::wavelet_projection::exact},
         {"approximate", hush::wavelet_projection::approximate}});
  if (const std::string* v = find_value(given, "--widen"))
    prm.widen = parse_choice<bool>("--widen", *v, {{"on", true}, {"off", false}});
  if (const std::string* v = find_value(given, "--variants"))
    prm.variant_overlap = static_cast<int>(parse_integer("--variants", *v, 0, 1 << 20));
  return std::make_unique<wavelet_field<D>>(hush::wavelet<D>(prm), so);
}

std::unique_ptr<noise_field> make_wavelet_from_options(const noise_setup& setup,
                                                       const option_values& given) {
  wavelet_sample_options so;
  if (const std::string* v = find_value(given, "--footprint")) {
    so.footprint = parse_finite("--footprint", *v, "a finite width >= 0 in noise units");
    if (so.footprint < 0) throw_bad_value("--footprint", *v, "a finite width >= 0 in noise units");
  }
  so.normal = parse_normal(setup, given);
  if (setup.dim == 2) return make_wavelet_d<2>(setup, given, so);
  return make_wavelet_d<3>(setup, given, so);
}

}  // namespace

void add_wavelet_entries(program_entries& entries) {
  entries.sample.push_back(
      {"wavelet",
       "wavelet noise (Cook & DeRose 2005): band-limited, multiband, anti-aliased from a footprint",
       {{"--tile-size", "N",
         "coefficients per tile side, even, 16 ... 2048 (2D) / 128 (3D) "
         "(default 128 in 2D, 64 in 3D)",
         "tile_size"},
        {"--first-band", "B", "frequency of the first band is 2^B, -32 ... 32 (default 0)",
         "first_band"},
        {"--bands", "N", "N bands with weights 1, 1/2, 1/4, ..., 1 ... 32 (default 1)", nullptr},
        {"--weights", "w0,w1,...",
         "band weights, 1 ... 32 finite numbers, |w| <= 1e30, the largest >= 1e-30 (instead "
         "of --bands)",
         "weights"},
        {"--footprint", "W",
         "every sample's pixel: an isotropic footprint W noise units wide, "
         "W >= 0; bands finer than it are faded out (default: none)",
         nullptr},
        {"--normal", "x,y,z",
         "with --dim 3: project onto the surface with this normal, "
         "not all zero (default: none, plain 3D noise)",
         nullptr},
        {"--projection", "exact|approximate", "projection kernel along the normal (default exact)",
         nullptr},
        {"--widen", "on|off", "basis widening for one sample per pixel (default off)", "widen"},
        {"--distribution", "gaussian|uniform", "output distribution (default gaussian)", nullptr},
        {"--variants", "K",
         "0: the tile repeats; 1 ... tile_size/4: hashed tile variants "
         "blended over K coefficients (default 0)",
         "variant_overlap"}},
       make_wavelet_from_options});
}

}  // namespace hush_cli
