// hush — the `hush` program: `hush render anisotropic --gbuffer DIR --out DIR [options]`,
// anisotropic noise (hush/anisotropic.hpp) over a G-buffer sequence: per covered pixel the
// noise at its uv, filtered by the footprint of its screen-to-uv Jacobian, and with --scene
// NAME compensated by its triangle's surface map from the scene's meshes
// (examples/anisotropic/scene_render.hpp). One channel per frame, background 0. The options
// are `hush sample anisotropic`'s, less --footprint and --map (the G-buffer and the scene
// give them per pixel).
#ifndef HUSH_CLI_RENDER_ANISOTROPIC_HPP
#define HUSH_CLI_RENDER_ANISOTROPIC_HPP

#include "scene_noises.hpp"

namespace hush_cli {

render_entry anisotropic_render_entry();

}  // namespace hush_cli

#endif  // HUSH_CLI_RENDER_ANISOTROPIC_HPP
