// hush — the `hush` program: `hush sample perlin` (hush/perlin.hpp), its noise_table entry; the
// octave options it lists after --period are fractal sums' (noise_fractal.cpp).
#include "noise_perlin.hpp"

#include <array>
#include <climits>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "noise_entries.hpp"

namespace hush_cli {
namespace {

template <int D>
std::unique_ptr<noise_field> make_plain_perlin(std::uint32_t seed, const perlin_options& o) {
  typename hush::perlin<D>::params prm;
  prm.seed = seed;
  for (int a = 0; a < D; ++a) prm.period[a] = o.period[a];
  return std::make_unique<grid_field<hush::perlin<D>, D>>(hush::perlin<D>(prm), true);
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
  parse_fractal_options(given, o);
  // NOLINTNEXTLINE(clang-analyzer-cplusplus.NewDeleteLeaks): analyzer false positive on unique_ptr
  return make_perlin(setup, o);
}

}  // namespace

std::unique_ptr<noise_field> make_perlin(const noise_setup& setup, const perlin_options& options) {
  if (options.fractal) return make_fractal_perlin(setup, options);
  return setup.dim == 2 ? make_plain_perlin<2>(setup.seed, options)
                        : make_plain_perlin<3>(setup.seed, options);
}

void add_perlin_entries(program_entries& entries) {
  std::vector<option_spec> options = {
      {"--period", "px,py[,pz]",
       "period per axis in lattice cells, one integer >= 0 per dimension; 0 = not periodic "
       "(default 0)",
       "period"}};
  const std::vector<option_spec> fractal = fractal_option_specs();
  options.insert(options.end(), fractal.begin(), fractal.end());
  entries.sample.push_back(
      {"perlin",
       "improved Perlin noise (Perlin 2002); with fractal options an fBm or turbulence sum",
       std::move(options), make_perlin_from_options});
}

}  // namespace hush_cli
