// hush.gabor: sparse Gabor convolution noise (Lagae et al.; include/hush/gabor.hpp) from Python.
#include "bindings.hpp"

namespace hush_python {
namespace {

template <int D>
void add_gabor_d(py::module_& m, const char* name) {
  using noise = hush::gabor<D>;
  auto c = bind_noise<noise>(m, name, "Gabor noise (hush::gabor<D>): spectral control, filterable.",
                             docs::gabor, [](py::kwargs kw) {
                               keywords k("hush.gabor", kw);
                               typename noise::params prm;
                               k.get("seed", prm.seed);
                               k.get_enum("kind", prm.kind,
                                          {{"isotropic", hush::gabor_kind::isotropic},
                                           {"anisotropic", hush::gabor_kind::anisotropic},
                                           {"hybrid", hush::gabor_kind::hybrid}});
                               k.get("frequency", prm.frequency);
                               k.get("bandwidth", prm.bandwidth);
                               k.get("orientation", prm.orientation);
                               k.get("elevation", prm.elevation);
                               k.get("orientation_spread", prm.orientation_spread);
                               k.get("frequency_spread", prm.frequency_spread);
                               k.get("impulses", prm.impulses);
                               k.get("truncation", prm.truncation);
                               k.finish();
                               return noise(prm);
                             });
  add_point_methods<noise>(c);
  add_sample_methods<noise>(c);
}

}  // namespace

void add_gabor_python(py::module_& m) {
  add_gabor_d<2>(m, "Gabor2");
  add_gabor_d<3>(m, "Gabor3");
}

}  // namespace hush_python
