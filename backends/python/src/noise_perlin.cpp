// hush.perlin: Perlin noise (include/hush/perlin.hpp) from Python.
#include "bindings.hpp"

namespace hush_python {
namespace {

template <int D>
void add_perlin_d(py::module_& m, const char* name) {
  using noise = hush::perlin<D>;
  auto c = bind_noise<noise>(m, name, "Perlin gradient noise (hush::perlin<D>): values in [-1, 1].",
                             docs::perlin, [](py::kwargs kw) {
                               keywords k("hush.perlin", kw);
                               typename noise::params prm;
                               k.get("seed", prm.seed);
                               k.get_axes("period", prm.period);
                               k.finish();
                               return noise(prm);
                             });
  add_point_methods<noise>(c);
}

}  // namespace

void add_perlin_python(py::module_& m) {
  add_perlin_d<2>(m, "Perlin2");
  add_perlin_d<3>(m, "Perlin3");
}

}  // namespace hush_python
