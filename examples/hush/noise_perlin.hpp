// hush — the `hush` program: improved Perlin noise (hush/perlin.hpp), plain (noise_perlin.cpp)
// or summed over octaves by hush::fractal (hush/fractal.hpp, noise_fractal.cpp). Fractal sums
// have no `hush sample` entry of their own: they are the perlin entry's octave options.
#ifndef HUSH_CLI_NOISE_PERLIN_HPP
#define HUSH_CLI_NOISE_PERLIN_HPP

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "args.hpp"
#include "hush/fractal.hpp"
#include "hush/perlin.hpp"
#include "noises.hpp"

namespace hush_cli {

struct perlin_options {
  std::array<int, 3> period{};  // per axis, the first `dim` are used; 0 = not periodic
  // Sum octaves with hush::fractal; otherwise plain hush::perlin (the fields below unused).
  bool fractal = false;
  hush::fractal_kind kind = hush::fractal_kind::fbm;
  int octaves = 1;
  double lacunarity = hush::fractal<hush::perlin<2>>::params{}.lacunarity;
  double gain = hush::fractal<hush::perlin<2>>::params{}.gain;
  // Default: unit_variance for fBm, unit_range for turbulence (which has no unit_variance).
  std::optional<hush::normalization> norm;
};

// Plain Perlin noise, or with options.fractal its octave sum (make_fractal_perlin). Throws
// hush::invalid_argument for parameters the library refuses.
std::unique_ptr<noise_field> make_perlin(const noise_setup& setup, const perlin_options& options);

// ---- The octave sum (noise_fractal.cpp).

// --octaves, --lacunarity, --gain, --fractal, --norm: the perlin entry's options after its own.
std::vector<option_spec> fractal_option_specs();
// Reads them into `o`; any of them given, or more than one octave, sets o.fractal (turbulence
// and the normalisations change a single octave too). Throws usage_error.
void parse_fractal_options(const option_values& given, perlin_options& o);
// hush::fractal<hush::perlin<D>> of o's period and fractal fields, D = setup.dim. Throws
// hush::invalid_argument for parameters the library refuses.
std::unique_ptr<noise_field> make_fractal_perlin(const noise_setup& setup, const perlin_options& o);

}  // namespace hush_cli

#endif  // HUSH_CLI_NOISE_PERLIN_HPP
