// hush — the `hush` program: the noises it samples, one table entry each (see noises.hpp).
#include "noises.hpp"

#include <climits>
#include <utility>

#include "anisotropic_noise.hpp"
#include "glsl_device.hpp"

namespace hush_cli {
namespace {

// Whether the GLSL backend has a program for Noise.
template <class Noise>
constexpr bool has_glsl_program() {
#if HUSH_CLI_HAVE_GLSL
  return hush::glsl::has_program_v<Noise>;
#else
  return false;
#endif
}

// Any hush noise of dimension D that hush::evaluate_grid takes.
template <class Noise, int D>
class field final : public noise_field {
 public:
  field(Noise noise, bool is_signed) : noise_(std::move(noise)), signed_(is_signed) {}
  bool is_signed() const override { return signed_; }
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
    // The block as a grid of its own: its origin is the exact double position
    // of sample (0, j0, k), so every sample keeps the position it has in `grid`.
    hush::grid<D> block;
    const hush::dvec3 o = grid.position({0, j0, k});
    for (int a = 0; a < D; ++a) {
      block.origin[a] = o[a];
      block.step[a] = grid.step[a];
    }
    block.size[0] = grid.size[0];
    block.size[1] = rows;
    if constexpr (D == 3) block.size[2] = 1;
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
};

template <int D>
std::unique_ptr<noise_field> make_perlin_d(std::uint32_t seed, const perlin_options& o) {
  std::array<int, D> period{};
  for (int a = 0; a < D; ++a) period[a] = o.period[a];
  if (!o.fractal) {
    typename hush::perlin<D>::params prm;
    prm.seed = seed;
    prm.period = period;
    return std::make_unique<field<hush::perlin<D>, D>>(hush::perlin<D>(prm), true);
  }
  using fractal = hush::fractal<hush::perlin<D>>;
  typename fractal::params prm;
  prm.seed = seed;
  prm.kind = o.kind;
  prm.octaves = o.octaves;
  prm.lacunarity = o.lacunarity;
  prm.gain = o.gain;
  const bool fbm = o.kind == hush::fractal_kind::fbm;
  prm.norm =
      o.norm.value_or(fbm ? hush::normalization::unit_variance : hush::normalization::unit_range);
  prm.period = period;
  return std::make_unique<field<fractal, D>>(fractal(prm), fbm);
}

// `hush sample perlin`: the options are parsed here; their ranges are the library's.
std::unique_ptr<noise_field> make_perlin_from_options(const noise_setup& setup,
                                                      const option_values& given) {
  perlin_options o;
  if (const std::string* v = find_value(given, "--period")) {
    const std::vector<long long> p =
        parse_integer_list("--period", *v, static_cast<std::size_t>(setup.dim), 0, INT_MAX);
    for (int a = 0; a < setup.dim; ++a) o.period[a] = static_cast<int>(p[a]);
  }
  if (const std::string* v = find_value(given, "--octaves"))
    o.octaves = static_cast<int>(
        parse_integer("--octaves", *v, 1, hush::fractal<hush::perlin<2>>::kMaxOctaves));
  if (const std::string* v = find_value(given, "--lacunarity"))
    o.lacunarity = parse_finite("--lacunarity", *v);
  if (const std::string* v = find_value(given, "--gain")) o.gain = parse_finite("--gain", *v);
  if (const std::string* v = find_value(given, "--fractal"))
    o.kind = parse_choice<hush::fractal_kind>(
        "--fractal", *v,
        {{"fbm", hush::fractal_kind::fbm}, {"turbulence", hush::fractal_kind::turbulence}});
  if (const std::string* v = find_value(given, "--norm"))
    o.norm =
        parse_choice<hush::normalization>("--norm", *v,
                                          {{"unit_variance", hush::normalization::unit_variance},
                                           {"unit_range", hush::normalization::unit_range},
                                           {"none", hush::normalization::none}});
  // Any fractal option asks for the octave sum, even with one octave (turbulence and the
  // normalisations change a single octave too); with none of them this is plain Perlin.
  o.fractal = o.octaves > 1;
  for (const char* f : {"--lacunarity", "--gain", "--fractal", "--norm"})
    o.fractal = o.fractal || find_value(given, f) != nullptr;
  // NOLINTNEXTLINE(clang-analyzer-cplusplus.NewDeleteLeaks): analyzer false positive on unique_ptr
  return make_perlin(setup, o);
}

// ---- `hush sample gabor` (hush::gabor<D>, Lagae et al. 2009).

// Surface noise (Lagae 2009 sec. 4.3, `hush sample gabor --dim 3 --normal x,y,z`): every grid
// sample is evaluated with the same normal, i.e. on the plane through it with that normal
// (kernels in the tangent plane: the 2D spectrum on the plane, no slicing).
class gabor_surface_field final : public noise_field {
 public:
  gabor_surface_field(const hush::gabor<3>& noise, const hush::vec3& normal)
      : noise_(noise), normal_(normal) {}
  bool is_signed() const override { return true; }
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
  return std::make_unique<field<hush::gabor<D>, D>>(hush::gabor<D>(prm), true);
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

const char* backend_name(backend b) {
  switch (b) {
    case backend::scalar:
      return "scalar";
    case backend::simd:
      return "simd";
    case backend::glsl:
      return "glsl";
  }
  return "?";
}

std::vector<float> sample_all(const noise_field& field, const sample_grid& grid, backend b) {
  std::vector<float> values(grid.count());
  const std::size_t plane = grid.size[0] * grid.size[1];
  for (std::size_t k = 0; k < grid.size[2]; ++k)
    field.sample_rows(grid, 0, grid.size[1], k, values.data() + k * plane, b);
  return values;
}

std::unique_ptr<noise_field> make_perlin(const noise_setup& setup, const perlin_options& options) {
  return setup.dim == 2 ? make_perlin_d<2>(setup.seed, options)
                        : make_perlin_d<3>(setup.seed, options);
}

const std::vector<noise_entry>& noise_table() {
  static const std::vector<noise_entry> table = {
      {"perlin",
       "improved Perlin noise (Perlin 2002); with fractal options an fBm or turbulence sum",
       {{"--period", "px,py[,pz]",
         "period per axis in lattice cells, one integer >= 0 per dimension; 0 = not periodic "
         "(default 0)",
         "period"},
        {"--octaves", "N",
         "octaves, 1 ... 32 (default 1 = plain Perlin; more sums octaves with hush::fractal)",
         "octaves"},
        {"--lacunarity", "L",
         "frequency ratio between octaves, 1 < L <= 16, an integer with --period (default 2)",
         "lacunarity"},
        {"--gain", "G", "amplitude ratio between octaves, > 0 (default 0.5)", "gain"},
        {"--fractal", "fbm|turbulence", "sum signed octaves or their absolute values (default fbm)",
         nullptr},
        {"--norm", "unit_variance|unit_range|none",
         "scaling of the sum (default unit_variance for fbm, unit_range for turbulence); "
         "any of these fractal options selects the octave sum",
         "norm"}},
       make_perlin_from_options},
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
         "band weights, 1 ... 32 finite numbers not all 0 (instead of "
         "--bands)",
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
       make_wavelet_from_options},
      {"anisotropic",
       "anisotropic noise (Goldberg, Zwicker & Durand 2008): oriented subband tiles, filtered "
       "per footprint, compensated per surface map",
       anisotropic_option_specs(), make_anisotropic_from_options},
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
         "mean number of kernels overlapping a point N', 0 < N <= 256 (default 16)", "impulses"},
        {"--truncation", "t",
         "kernel envelope at its truncation radius, 1e-9 ... 0.5 (default 0.05)", "truncation"},
        {"--normal", "x,y,z",
         "3D: surface noise, every sample on the plane through it with this normal (finite, "
         "any non-zero length) (default: solid noise)",
         nullptr}},
       make_gabor_from_options},
  };
  return table;
}

std::string noise_names() {
  std::string names;
  for (const noise_entry& e : noise_table())
    names += (names.empty() ? "" : ", ") + std::string(e.name);
  return names;
}

const noise_entry& find_noise(const std::string& name) {
  for (const noise_entry& e : noise_table())
    if (name == e.name) return e;
  throw usage_error("unknown noise '" + name + "'; valid: " + noise_names());
}

std::unique_ptr<noise_field> make_noise(const noise_entry& entry, const noise_setup& setup,
                                        const option_values& given) {
  try {
    return entry.make(setup, given);
  } catch (const hush::invalid_argument& e) {
    // Library messages read "hush::<type>: <param>[...] = <value> ...; valid: <range>".
    const std::string message = e.what();
    for (const option_spec& o : entry.options) {
      if (!o.library_param) continue;
      const std::string key = std::string(": ") + o.library_param;
      const std::size_t at = message.find(key), after = at + key.size();
      if (at == std::string::npos || after >= message.size() ||
          (message[after] != ' ' && message[after] != '['))
        continue;
      const std::string* value = find_value(given, o.name);
      throw usage_error(std::string(o.name) + (value ? " '" + *value + "'" : " (default)") +
                        " is invalid: " + message);
    }
    throw usage_error(message);
  }
}

std::optional<hush::vec3> parse_normal(const noise_setup& setup, const option_values& given) {
  const std::string* v = find_value(given, "--normal");
  if (!v) return std::nullopt;
  if (setup.dim != 3) throw usage_error("--normal needs --dim 3 (samples on a surface in 3D)");
  const std::vector<double> n = parse_finite_list("--normal", *v, 3);
  if (n[0] == 0 && n[1] == 0 && n[2] == 0)
    throw_bad_value("--normal", *v, "three finite numbers, not all zero");
  return hush::vec3{static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2])};
}

std::string backend_missing(backend b) {
  if (b == backend::glsl && !HUSH_CLI_HAVE_GLSL)
    return "the GLSL backend is not in this build (neither OSMesa nor EGL found)";
  if (b == backend::simd && !HUSH_CONFIG_SIMD)
    return "the SIMD backend is not in this build (Highway, libhwy-dev, was not found)";
  return "";
}

}  // namespace hush_cli
