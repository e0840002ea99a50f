// hush.wavelet: wavelet noise (Cook & DeRose; include/hush/wavelet.hpp) from Python.
#include "bindings.hpp"

namespace hush_python {
namespace {

template <int D>
void add_wavelet_d(py::module_& m, const char* name) {
  using noise = hush::wavelet<D>;
  auto c = bind_noise<noise>(
      m, name, "Wavelet noise (hush::wavelet<D>): band-limited, unit variance, filterable.",
      docs::wavelet, [](py::kwargs kw) {
        keywords k("hush.wavelet", kw);
        typename noise::params prm;
        k.get("seed", prm.seed);
        k.get("tile_size", prm.tile_size);
        k.get("first_band", prm.first_band);
        k.get("weights", prm.weights);
        std::vector<std::vector<double>> offsets;
        k.get("offsets", offsets);
        for (const auto& o : offsets) {
          if (o.size() != static_cast<std::size_t>(D))
            throw py::value_error("hush.wavelet: offsets: each offset has " + std::to_string(D) +
                                  " numbers");
          hush::vec<double, D> v;
          for (int a = 0; a < D; ++a) v[a] = o[static_cast<std::size_t>(a)];
          prm.offsets.push_back(v);
        }
        k.get("even_odd_fix", prm.even_odd_fix);
        k.get_enum("distribution", prm.distribution,
                   {{"gaussian", hush::wavelet_distribution::gaussian},
                    {"uniform", hush::wavelet_distribution::uniform},
                    {"table", hush::wavelet_distribution::table}});
        k.get("gaussian_scale", prm.gaussian_scale);
        k.get("table", prm.table);
        k.get_enum("projection", prm.projection,
                   {{"exact", hush::wavelet_projection::exact},
                    {"approximate", hush::wavelet_projection::approximate}});
        k.get("widen", prm.widen);
        k.get("relative_weights", prm.relative_weights);
        k.get("relative_bands", prm.relative_bands);
        k.get("variant_overlap", prm.variant_overlap);
        k.finish();
        return noise(prm);
      });
  c.def_property_readonly(
      "bound", [](const held<noise>& h) { return h.noise.bound(); }, docs::wavelet_bound);
  add_point_methods<noise>(c);
  add_sample_methods<noise>(c);
}

}  // namespace

void add_wavelet_python(py::module_& m) {
  add_wavelet_d<2>(m, "Wavelet2");
  add_wavelet_d<3>(m, "Wavelet3");
}

}  // namespace hush_python
