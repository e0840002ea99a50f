// hush — the `hush` program: what the scene-driven noises share (see scene_noises.hpp).
#include "scene_noises.hpp"

#include <string>
#include <vector>

namespace hush_cli {

double parse_range(const option_values& given, const char* name, double lo, double hi, bool hi_open,
                   const char* valid, double fallback) {
  const std::string* v = find_value(given, name);
  if (!v) return fallback;
  const double x = parse_finite(name, *v, valid);
  if (!(x >= lo && (hi_open ? x < hi : x <= hi))) throw_bad_value(name, *v, valid);
  return x;
}

std::string render_names() {
  std::string names;
  for (const render_entry& e : render_table())
    names += (names.empty() ? "" : ", ") + std::string(e.name);
  return names;
}

const render_entry& find_render(const std::string& name) {
  for (const render_entry& e : render_table())
    if (name == e.name) return e;
  throw_bad_value("NOISE", name, render_names());
}

std::unique_ptr<scene_noise> make_scene_noise(const render_entry& entry, const render_setup& setup,
                                              const option_values& given,
                                              const std::vector<std::string>& flags) {
  try {
    return entry.make(setup, given, flags);
  } catch (const hush::invalid_argument& e) {
    const std::string message = e.what();
    for (const option_spec& o : entry.options) {
      if (!o.library_param) continue;
      const std::string key = std::string(": ") + o.library_param + " ";
      if (message.find(key) == std::string::npos) continue;
      const std::string* value = find_value(given, o.name);
      throw usage_error(std::string(o.name) + (value ? " '" + *value + "'" : " (default)") +
                        " is invalid: " + message);
    }
    throw usage_error(message);
  }
}

}  // namespace hush_cli
