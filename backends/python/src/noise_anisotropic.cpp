// hush.Anisotropic: anisotropic noise (Goldberg, Zwicker & Durand; include/hush/anisotropic.hpp)
// from Python.
#include "bindings.hpp"

namespace hush_python {

void add_anisotropic_python(py::module_& m) {
  using noise = hush::anisotropic;
  const std::vector<std::pair<const char*, hush::weight_rule>> rules = {
      {"centre", hush::weight_rule::centre},
      {"three_point", hush::weight_rule::three_point},
      {"least_squares", hush::weight_rule::least_squares}};
  auto c = bind_noise<noise>(m, "Anisotropic",
                             "Anisotropic noise (hush::anisotropic): 2D texture-space noise "
                             "filtered by footprints and compensated for surface maps.",
                             docs::anisotropic, [rules](py::kwargs kw) {
                               keywords k("hush.anisotropic", kw);
                               noise::params prm;
                               k.get("seed", prm.seed);
                               k.get("orientations", prm.orientations);
                               k.get("scales", prm.scales);
                               k.get("base_scale", prm.base_scale);
                               k.get("octaves", prm.octaves);
                               k.get("gain", prm.gain);
                               k.get_enum("kind", prm.kind,
                                          {{"fbm", hush::fractal_kind::fbm},
                                           {"turbulence", hush::fractal_kind::turbulence}});
                               k.get("frequency", prm.frequency);
                               k.get("tile_size", prm.tile_size);
                               k.get_enum("filtering", prm.filtering, rules);
                               k.get_enum("compensation", prm.compensation, rules);
                               k.finish();
                               return noise(prm);
                             });
  add_point_methods<noise>(c);
  add_sample_methods<noise>(c);
}

}  // namespace hush_python
