// hush — the `hush` program: `hush sample gabor` (hush::gabor<D>, Lagae et al. 2009), its
// noise_table entry.
//
// Solid noise goes through hush::evaluate_grid; surface noise (--dim 3 --normal) through
// hush::evaluate over hush::samples with the same normal for every sample.
#include <memory>
#include <optional>
#include <string>

#include "hush/detail/constants.hpp"
#include "hush/gabor.hpp"
#include "noise_entries.hpp"
#include "noises.hpp"

namespace hush_cli {
namespace {

// Surface noise (Lagae 2009 sec. 4.3, `hush sample gabor --dim 3 --normal x,y,z`): every grid
// sample is evaluated with the same normal, i.e. on the plane through it with that normal
// (kernels in the tangent plane: the 2D spectrum on the plane, no slicing).
class gabor_surface_field final : public noise_field {
 public:
  gabor_surface_field(const hush::gabor<3>& noise, const hush::vec3& normal)
      : noise_(noise), normal_(normal) {}
  bool is_signed() const override { return true; }
  std::pair<double, double> png_range() const override { return unit_variance_range(); }
  std::string unsupported_reason(backend b) const override { return backend_missing(b); }
  void sample_rows(const sample_grid& grid, std::size_t j0, std::size_t rows, std::size_t k,
                   float* out, backend b) const override {
    sample_rows_as_samples(noise_, grid, j0, rows, k, out, b, std::nullopt, normal_);
  }

 private:
  hush::gabor<3> noise_;
  hush::vec3 normal_;
};

template <int D>
std::unique_ptr<noise_field> make_gabor_d(const typename hush::gabor<D>::params& prm) {
  return std::make_unique<grid_field<hush::gabor<D>, D>>(hush::gabor<D>(prm), true, true);
}

// Degrees on the command line, radians in the library: an angle option in
// [lo, hi] degrees, refused here with the range in degrees.
double parse_degrees(const char* option, const std::string& token, double lo, double hi) {
  const double deg = parse_finite(option, token);
  if (deg < lo || deg > hi)
    throw usage_error(std::string(option) + " '" + token +
                      "' is invalid; valid: " + std::to_string(static_cast<int>(lo)) + " ... " +
                      std::to_string(static_cast<int>(hi)) + " degrees");
  return deg * hush::detail::constants::kPi / 180.0;
}

std::unique_ptr<noise_field> make_gabor_from_options(const noise_setup& setup,
                                                     const option_values& given) {
  hush::gabor<2>::params prm;  // the 3D params are the same struct's fields
  prm.seed = setup.seed;
  if (const std::string* v = find_value(given, "--kind"))
    prm.kind = parse_choice<hush::gabor_kind>("--kind", *v,
                                              {{"isotropic", hush::gabor_kind::isotropic},
                                               {"anisotropic", hush::gabor_kind::anisotropic},
                                               {"hybrid", hush::gabor_kind::hybrid}});
  if (const std::string* v = find_value(given, "--frequency"))
    prm.frequency = parse_finite("--frequency", *v);
  if (const std::string* v = find_value(given, "--bandwidth"))
    prm.bandwidth = parse_finite("--bandwidth", *v);
  if (const std::string* v = find_value(given, "--orientation"))
    prm.orientation = parse_degrees("--orientation", *v, -360.0, 360.0);
  if (const std::string* v = find_value(given, "--elevation"))
    prm.elevation = parse_degrees("--elevation", *v, -90.0, 90.0);
  if (const std::string* v = find_value(given, "--orientation-spread"))
    prm.orientation_spread = parse_degrees("--orientation-spread", *v, 0.0, 360.0);
  if (const std::string* v = find_value(given, "--frequency-spread"))
    prm.frequency_spread = parse_finite("--frequency-spread", *v);
  if (const std::string* v = find_value(given, "--impulses"))
    prm.impulses = parse_finite("--impulses", *v);
  if (const std::string* v = find_value(given, "--truncation"))
    prm.truncation = parse_finite("--truncation", *v);
  const std::optional<hush::vec3> normal = parse_normal(setup, given);
  if (setup.dim == 2) return make_gabor_d<2>(prm);
  hush::gabor<3>::params p3;
  p3.seed = prm.seed;
  p3.kind = prm.kind;
  p3.frequency = prm.frequency;
  p3.bandwidth = prm.bandwidth;
  p3.orientation = prm.orientation;
  p3.elevation = prm.elevation;
  p3.orientation_spread = prm.orientation_spread;
  p3.frequency_spread = prm.frequency_spread;
  p3.impulses = prm.impulses;
  p3.truncation = prm.truncation;
  if (normal) return std::make_unique<gabor_surface_field>(hush::gabor<3>(p3), *normal);
  return make_gabor_d<3>(p3);
}

}  // namespace

void add_gabor_entries(program_entries& entries) {
  entries.sample.push_back(
      {"gabor",
       "Gabor noise (Lagae et al. 2009): sparse convolution of Gabor kernels, unit variance, "
       "exact power spectrum",
       {{"--kind", "isotropic|anisotropic|hybrid",
         "random orientations, the fixed --orientation, or orientations and frequencies drawn "
         "from ranges (default isotropic)",
         nullptr},
        {"--frequency", "F", "principal frequency F0, cycles per unit, 0 ... 1e6 (default 1)",
         "frequency"},
        {"--bandwidth", "a", "kernel bandwidth a, 1/units, 1e-6 ... 1e6 (default 0.8)",
         "bandwidth"},
        {"--orientation", "deg",
         "orientation omega0 (anisotropic, hybrid): azimuth in degrees, -360 ... 360 (default 0)",
         nullptr},
        {"--elevation", "deg", "3D: omega0's elevation in degrees, -90 ... 90 (default 0)",
         nullptr},
        {"--orientation-spread", "deg",
         "hybrid: width of the orientation range in degrees, 0 ... 360 (default 0)", nullptr},
        {"--frequency-spread", "dF", "hybrid: width of the frequency range, 0 ... 2 F (default 0)",
         "frequency_spread"},
        {"--impulses", "N",
         "mean number of kernels overlapping a point N', 1e-6 <= N <= 256 (default 16)", "impulses"},
        {"--truncation", "t",
         "kernel envelope at its truncation radius, 1e-9 ... 0.5 (default 0.05)", "truncation"},
        {"--normal", "x,y,z",
         "3D: surface noise, every sample on the plane through it with this normal (finite, "
         "any non-zero length) (default: solid noise)",
         nullptr}},
       make_gabor_from_options});
}

}  // namespace hush_cli
