// hush — the `hush` program: anisotropic noise (hush/anisotropic.hpp) in the noise table.
#ifndef HUSH_CLI_ANISOTROPIC_NOISE_HPP
#define HUSH_CLI_ANISOTROPIC_NOISE_HPP

#include <memory>
#include <optional>
#include <vector>

#include "args.hpp"
#include "hush/hush.hpp"
#include "noises.hpp"

namespace hush_cli {

// What `hush sample anisotropic` takes beside the noise's parameters: the
// footprint given to every sample (none: point samples; pixel: the grid
// step's width; or a width in noise units) and one surface map for every
// sample (none: the identity).
struct anisotropic_options {
  hush::anisotropic::params params;
  bool pixel_footprint = false;
  std::optional<double> footprint_width;
  std::optional<hush::surface_map> map;
};

// The noise's options, for its noise_table() entry.
std::vector<option_spec> anisotropic_option_specs();
// Parses them; throws usage_error (library refusals go through make_noise).
anisotropic_options parse_anisotropic(const noise_setup& setup, const option_values& given);
// The field `hush sample` evaluates: evaluate_grid without per-sample inputs,
// hush::samples (float positions) with a footprint or a map.
std::unique_ptr<noise_field> make_anisotropic(const anisotropic_options& options);
// The noise_entry maker.
std::unique_ptr<noise_field> make_anisotropic_from_options(const noise_setup& setup,
                                                           const option_values& given);

}  // namespace hush_cli

#endif  // HUSH_CLI_ANISOTROPIC_NOISE_HPP
