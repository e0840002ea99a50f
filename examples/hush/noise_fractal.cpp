// hush — the `hush` program: fractal sums of improved Perlin noise (hush/fractal.hpp), the
// octave options of `hush sample perlin` (see noise_perlin.hpp). No entry of its own.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "noise_entries.hpp"
#include "noise_perlin.hpp"

namespace hush_cli {
namespace {

template <int D>
std::unique_ptr<noise_field> make_fractal_perlin_d(std::uint32_t seed, const perlin_options& o) {
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
  for (int a = 0; a < D; ++a) prm.period[a] = o.period[a];
  return std::make_unique<grid_field<fractal, D>>(
      fractal(prm), fbm, fbm && prm.norm == hush::normalization::unit_variance);
}

}  // namespace

std::vector<option_spec> fractal_option_specs() {
  return {{"--octaves", "N",
           "octaves, 1 ... 32 (default 1 = plain Perlin; more sums octaves with hush::fractal)",
           "octaves"},
          {"--lacunarity", "L",
           "frequency ratio between octaves, 1 < L <= 16, an integer with --period (default 2)",
           "lacunarity"},
          {"--gain", "G", "amplitude ratio between octaves, > 0 (default 0.5)", "gain"},
          {"--fractal", "fbm|turbulence",
           "sum signed octaves or their absolute values (default fbm)", nullptr},
          {"--norm", "unit_variance|unit_range|none",
           "scaling of the sum (default unit_variance for fbm, unit_range for turbulence); "
           "any of these fractal options selects the octave sum",
           "norm"}};
}

void parse_fractal_options(const option_values& given, perlin_options& o) {
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
}

std::unique_ptr<noise_field> make_fractal_perlin(const noise_setup& setup,
                                                 const perlin_options& o) {
  return setup.dim == 2 ? make_fractal_perlin_d<2>(setup.seed, o)
                        : make_fractal_perlin_d<3>(setup.seed, o);
}

// Fractal sums are `hush sample perlin --octaves N ...`: the perlin entry lists their options
// (fractal_option_specs) and builds them (make_perlin), so this module adds no entry.
void add_fractal_entries(program_entries& /*entries*/) {}

}  // namespace hush_cli
