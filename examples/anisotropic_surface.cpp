#include <cstdio>
#include <hush/hush.hpp>
#include <vector>

int main() {
  hush::anisotropic::params p;  // K = 4 orientations, 3 scales, 3 octaves of fbm
  p.seed = 7;
  p.frequency = 4.0;  // octave 0: 4 cycles per texture unit
  const hush::anisotropic noise{p};
  // Per sample: the uv, the pixel's screen-to-uv Jacobian (dFdx(uv), dFdy(uv)) and the
  // texture-to-surface map T of the triangle it lies on (from its 3D positions and uvs).
  const hush::surface_map t = hush::surface_map::from_triangle(
      {0, 0, 0}, {2, 0, 0}, {0, 1, 0},  // a 2 x 1 triangle in 3D ...
      {0, 0}, {1, 0}, {0, 1});          // ... mapped onto a unit uv square: u is squeezed
  std::vector<hush::vec2> uv = {{0.25f, 0.25f}, {0.5f, 0.1f}, {0.1f, 0.6f}};
  std::vector<hush::footprint<2>> fp = {
      hush::footprint<2>{},  // a point sample: nothing filtered
      hush::footprint<2>::from_derivatives(hush::dvec2{0.01, 0.0}, hush::dvec2{0.0, 0.002}),
      hush::footprint<2>::from_derivatives(hush::dvec2{0.2, 0.05}, hush::dvec2{0.0, 0.3})};
  std::vector<hush::surface_map> maps(uv.size(), t);
  hush::samples<2> s;
  s.positions = uv;
  s.footprints = fp;
  s.surface_maps = maps;
  std::vector<float> out(uv.size());
  hush::evaluate(noise, hush::exec::scalar, s, hush::span<float>(out));
  for (std::size_t i = 0; i < out.size(); ++i)
    std::printf("n(%.2f, %.2f) = %+.4f (double reference %+.4f)\n", uv[i].x, uv[i].y, out[i],
                noise.sample(hush::vec_cast<double>(uv[i]), fp[i], t));
}
