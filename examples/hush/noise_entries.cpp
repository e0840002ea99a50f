// hush — the `hush` program: noise_table() and render_table(), assembled from every registered
// noise's entries (see noise_entries.hpp).
#include "noise_entries.hpp"

#include <string_view>
#include <vector>

namespace hush_cli {
namespace {

// The order usage text and "valid:" messages list the entries in, by name. An entry not named
// here follows these, in registry order, so a new noise needs no place in them.
constexpr std::string_view kSampleOrder[] = {"perlin", "wavelet", "anisotropic", "gabor"};
constexpr std::string_view kRenderOrder[] = {"coherent", "npr-gabor", "anisotropic"};

const program_entries& all_entries() {
  static const program_entries entries = [] {
    program_entries e;
#define HUSH_CLI_ADD_ENTRIES(noise) add_##noise##_entries(e);
    HUSH_NOISE_LIST(HUSH_CLI_ADD_ENTRIES)
#undef HUSH_CLI_ADD_ENTRIES
    const auto name = [](const auto& entry) { return entry.name; };
    hush_tools::put_in_order(e.sample, kSampleOrder, name);
    hush_tools::put_in_order(e.render, kRenderOrder, name);
    return e;
  }();
  return entries;
}

}  // namespace

const std::vector<noise_entry>& noise_table() { return all_entries().sample; }

const std::vector<render_entry>& render_table() { return all_entries().render; }

}  // namespace hush_cli
