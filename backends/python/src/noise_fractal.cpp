// hush.fractal: fBm and turbulence over Perlin noise (include/hush/fractal.hpp) from Python.
#include "bindings.hpp"

namespace hush_python {
namespace {

template <int D>
void add_fractal_d(py::module_& m, const char* name) {
  using noise = hush::fractal<hush::perlin<D>>;
  auto c = bind_noise<noise>(
      m, name, "fBm or turbulence over Perlin noise (hush::fractal<hush::perlin<D>>).",
      docs::fractal, [](py::kwargs kw) {
        keywords k("hush.fractal", kw);
        typename noise::params prm;
        k.get("seed", prm.seed);
        k.get_enum(
            "kind", prm.kind,
            {{"fbm", hush::fractal_kind::fbm}, {"turbulence", hush::fractal_kind::turbulence}});
        k.get("octaves", prm.octaves);
        k.get("frequency", prm.frequency);
        k.get("lacunarity", prm.lacunarity);
        k.get("gain", prm.gain);
        k.get("weights", prm.weights);
        k.get_enum("normalization", prm.norm,
                   {{"unit_variance", hush::normalization::unit_variance},
                    {"unit_range", hush::normalization::unit_range},
                    {"none", hush::normalization::none}});
        k.get_axes("period", prm.period);
        k.finish();
        return noise(prm);
      });
  add_point_methods<noise>(c);
}

}  // namespace

void add_fractal_python(py::module_& m) {
  add_fractal_d<2>(m, "Fractal2");
  add_fractal_d<3>(m, "Fractal3");
}

}  // namespace hush_python
