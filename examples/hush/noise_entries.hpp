// hush — the `hush` program: every noise's entries, one file per noise.
//
// Each noise of the registry (HUSH_NOISES, the top-level CMakeLists.txt) defines, in
// examples/hush/noise_<noise>.cpp, add_<noise>_entries: it appends its `hush sample` entry
// (noises.hpp) and/or its `hush render` entry (scene_noises.hpp), or none. noise_table() and
// render_table() (noise_entries.cpp) are assembled from HUSH_NOISE_LIST, the registry's
// X-macro, so adding a noise to the program edits no shared file of the program.
#ifndef HUSH_CLI_NOISE_ENTRIES_HPP
#define HUSH_CLI_NOISE_ENTRIES_HPP

#include <vector>

#include "hush_tools/noise_list.hpp"
#include "noises.hpp"
#include "scene_noises.hpp"

namespace hush_cli {

struct program_entries {
  std::vector<noise_entry> sample;   // `hush sample NOISE`
  std::vector<render_entry> render;  // `hush render NOISE`
};

#define HUSH_CLI_DECLARE_ENTRIES(noise) void add_##noise##_entries(program_entries& entries);
HUSH_NOISE_LIST(HUSH_CLI_DECLARE_ENTRIES)
#undef HUSH_CLI_DECLARE_ENTRIES

}  // namespace hush_cli

#endif  // HUSH_CLI_NOISE_ENTRIES_HPP
