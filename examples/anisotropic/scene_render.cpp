// hush — anisotropic noise on the test scenes' G-buffers (see scene_render.hpp).
#include "scene_render.hpp"

namespace hush_tools::aniso {

std::vector<std::vector<hush::surface_map>> scene_surface_maps(const hush_tools::scene::scene& s) {
  std::vector<std::vector<hush::surface_map>> out;
  for (const hush_tools::scene::object& o : s.objects) {
    const hush_tools::scene::mesh& m = *o.shape;
    std::vector<hush::surface_map> maps;
    for (std::size_t t = 0; t < m.triangles(); ++t) {
      hush::dvec3 p[3];
      hush::dvec2 uv[3];
      for (int c = 0; c < 3; ++c) {
        const std::uint32_t v = m.indices[3 * t + static_cast<std::size_t>(c)];
        p[c] = {m.positions[v].x, m.positions[v].y, m.positions[v].z};
        uv[c] = {m.uvs[v].x, m.uvs[v].y};
      }
      maps.push_back(hush::surface_map::from_triangle(p[0], p[1], p[2], uv[0], uv[1], uv[2]));
    }
    out.push_back(std::move(maps));
  }
  return out;
}

hush::samples<2> gbuffer_samples::samples(bool compensate) const {
  hush::samples<2> s;
  s.positions = uv;
  s.footprints = footprints;
  if (compensate) s.surface_maps = maps;
  return s;
}

gbuffer_samples collect_samples(const hush::frame& f,
                                const std::vector<std::vector<hush::surface_map>>& maps) {
  f.validate("hush_tools::aniso::collect_samples",
             hush::frame_view::uv | hush::frame_view::uv_jacobian | hush::frame_view::object_id |
                 hush::frame_view::triangle_id,
             std::size_t(1) << 16);
  gbuffer_samples b;
  for (std::size_t y = 0; y < f.height(); ++y)
    for (std::size_t x = 0; x < f.width(); ++x) {
      const std::uint32_t object = f.object_id(x, y), tri = f.triangle_id(x, y);
      if (object == 0) continue;  // background
      // A G-buffer from another scene (ids beyond this one's meshes): no map, the identity.
      const bool known = object - 1 < maps.size() && tri < maps[object - 1].size();
      b.uv.push_back(f.uv(x, y));
      const hush::vec4 j = f.uv_jacobian(x, y);  // du/dx, du/dy, dv/dx, dv/dy
      b.footprints.push_back(
          hush::footprint<2>::from_derivatives(hush::dvec2{j.x, j.z}, hush::dvec2{j.y, j.w}));
      b.maps.push_back(known ? maps[object - 1][tri] : hush::surface_map::identity());
      b.pixel.push_back(y * f.width() + x);
    }
  return b;
}

}  // namespace hush_tools::aniso
