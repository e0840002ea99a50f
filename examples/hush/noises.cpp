// hush — the `hush` program: what the noises it samples share (see noises.hpp).
#include "noises.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace hush_cli {

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
  const double m = std::max({std::fabs(n[0]), std::fabs(n[1]), std::fabs(n[2])});
  if (m == 0) throw_bad_value("--normal", *v, "three finite numbers, not all zero");
  // Only the direction matters: scaled by the largest component in double first, so that
  // 1e-50,0,0 and 1e39,1e39,0 keep their direction in float (no underflow to 0, no inf).
  return hush::vec3{static_cast<float>(n[0] / m), static_cast<float>(n[1] / m),
                    static_cast<float>(n[2] / m)};
}

std::string backend_missing(backend b) {
  if (b == backend::glsl && !HUSH_CLI_HAVE_GLSL)
    return "the GLSL backend is not in this build (neither OSMesa nor EGL found)";
  if (b == backend::simd && !HUSH_CONFIG_SIMD)
    return "the SIMD backend is not in this build (Highway, libhwy-dev, was not found)";
  return "";
}

}  // namespace hush_cli
