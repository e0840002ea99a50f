// hush — anisotropic noise on the test scenes' G-buffers (examples/scene): what
// `hush render anisotropic --gbuffer DIR` runs per frame. Example/test infrastructure.
//
// Per covered pixel (hush::frame views: uv, uv_jacobian, object and triangle ids) the noise is
// evaluated at the pixel's uv with the footprint of its screen-to-uv Jacobian
// (gbuffer::uv_jacobian) and the surface map T of its triangle, from the mesh's object-space
// positions and uvs (hush::surface_map::from_triangle): the noise looks uniform on every object
// whatever its UV mapping does, in object units. Background pixels are 0.
#ifndef HUSH_ANISO_SCENE_RENDER_HPP
#define HUSH_ANISO_SCENE_RENDER_HPP

#include <vector>

#include "gbuffer.hpp"
#include "hush/core/frame.hpp"
#include "hush/hush.hpp"
#include "scene.hpp"

namespace hush_tools::aniso {

// T per triangle of every object of `s` (objects[k] has id k + 1), in mesh order.
std::vector<std::vector<hush::surface_map>> scene_surface_maps(const hush_tools::scene::scene& s);

// The batch of one frame: covered pixels' uvs, footprints and maps, and their pixel index.
struct gbuffer_samples {
  std::vector<hush::vec2> uv;
  std::vector<hush::footprint<2>> footprints;
  std::vector<hush::surface_map> maps;
  std::vector<std::size_t> pixel;
  hush::samples<2> samples(bool compensate) const;
};
// Covered pixels (object_id != 0) of a frame with uv, uv_jacobian, object_id and
// triangle_id views (hush::frame; examples/scene's as_frame gives them).
gbuffer_samples collect_samples(const hush::frame& f,
                                const std::vector<std::vector<hush::surface_map>>& maps);
inline gbuffer_samples collect_samples(const hush_tools::scene::gbuffer& g,
                                       const std::vector<std::vector<hush::surface_map>>& maps) {
  return collect_samples(hush_tools::scene::as_frame(g), maps);
}

// The frame's noise (width * height floats, row-major) on backend `ex`; without
// compensation the maps are not given (plain texture-space noise).
template <class Exec>
std::vector<float> render_frame(const hush::anisotropic& noise, const hush::frame& f,
                                const std::vector<std::vector<hush::surface_map>>& maps,
                                const Exec& ex, bool compensate = true) {
  const gbuffer_samples b = collect_samples(f, maps);
  std::vector<float> values(b.uv.size()), out(f.pixels(), 0.0f);
  hush::evaluate(noise, ex, b.samples(compensate), hush::span<float>(values));
  for (std::size_t i = 0; i < values.size(); ++i) out[b.pixel[i]] = values[i];
  return out;
}
template <class Exec>
std::vector<float> render_gbuffer(const hush::anisotropic& noise,
                                  const hush_tools::scene::gbuffer& g,
                                  const std::vector<std::vector<hush::surface_map>>& maps,
                                  const Exec& ex, bool compensate = true) {
  return render_frame(noise, hush_tools::scene::as_frame(g), maps, ex, compensate);
}

}  // namespace hush_tools::aniso

#endif  // HUSH_ANISO_SCENE_RENDER_HPP
