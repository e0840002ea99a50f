// hush.NprGabor: NPR Gabor noise (Benard et al.; include/hush/npr_gabor.hpp) from Python: a
// frame rendered from G-buffer arrays and the frame's triangle list.
#include "frame.hpp"
#include "hush/glsl/npr_gabor.hpp"

namespace hush_python {

void add_npr_gabor_python(py::module_& m) {
  using noise = hush::npr_gabor;
  auto c = bind_noise<noise>(
      m, "NprGabor",
      "NPR Gabor noise (hush::npr_gabor): Gabor kernels attached to the triangles a renderer drew, "
      "splatted in screen space.",
      docs::npr_gabor, [](py::kwargs kw) {
        keywords k("hush.npr_gabor", kw);
        noise::params prm;
        k.get("frequency", prm.frequency);
        k.get("bandwidth", prm.bandwidth);
        k.get("truncation", prm.truncation);
        k.get("impulses", prm.impulses);
        k.get("orientation", prm.orientation);
        k.get("isotropic", prm.isotropic);
        k.get("seed", prm.seed);
        k.get("object_test", prm.object_test);
        k.get("triangle_test", prm.triangle_test);
        k.get("depth_test", prm.depth_test);
        k.get("soft_depth", prm.soft_depth);
        k.get("depth_tolerance", prm.depth_tolerance);
        k.get("cull_back_faces", prm.cull_back_faces);
        k.get_enum("front_face", prm.front_face,
                   {{"counter_clockwise", hush::npr_gabor_front_face::counter_clockwise},
                    {"clockwise", hush::npr_gabor_front_face::clockwise}});
        k.get("thinning", prm.thinning);
        k.get("local_density", prm.local_density);
        k.finish();
        return noise(prm);
      });
  c.def(
      "render",
      [](const held<noise>& self, const py::object& depth, const py::object& indices,
         const py::object& screen, const py::object& vertex_depth, const py::object& triangle_id,
         const py::object& object_id, const py::object& frame_object_id,
         const py::object& frame_triangle_id, const std::string& backend_name) {
        const noise& n = self.noise;
        const backend b = parse_backend(backend_name, 1);
        frame_arrays fa(depth, py::none(), py::none(), frame_object_id, frame_triangle_id);
        const auto idx =
            py::array_t<std::uint32_t, py::array::c_style | py::array::forcecast>::ensure(indices);
        if (!idx || idx.ndim() != 2 || idx.shape(1) != 3)
          throw py::value_error("indices: valid: shape (T, 3), vertex indices");
        const float_array scr = as_rows(screen, "screen", 2);
        const auto vd =
            py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(vertex_depth);
        if (!vd || vd.ndim() != 1) throw py::value_error("vertex_depth: valid: shape (V,)");
        const auto tid =
            py::array_t<std::uint32_t, py::array::c_style | py::array::forcecast>::ensure(
                triangle_id);
        if (!tid || tid.ndim() != 1) throw py::value_error("triangle_id: valid: shape (T,)");
        py::array_t<std::uint32_t, py::array::c_style> oid;
        if (!object_id.is_none()) {
          oid = py::array_t<std::uint32_t, py::array::c_style | py::array::forcecast>::ensure(
              object_id);
          if (!oid || oid.ndim() != 1) throw py::value_error("object_id: valid: shape (T,)");
        }
        hush::triangle_list tris;
        tris.indices = {idx.data(), static_cast<std::size_t>(idx.size())};
        tris.screen = {reinterpret_cast<const hush::vec2*>(scr.data()),
                       static_cast<std::size_t>(scr.shape(0))};
        tris.depth = {vd.data(), static_cast<std::size_t>(vd.size())};
        tris.triangle_id = {tid.data(), static_cast<std::size_t>(tid.size())};
        if (oid) tris.object_id = {oid.data(), static_cast<std::size_t>(oid.size())};
        const std::size_t w = fa.frame.width(), h = fa.frame.height();
        float_array out(
            std::vector<py::ssize_t>{static_cast<py::ssize_t>(h), static_cast<py::ssize_t>(w)});
        const hush::image_view<float> view(out.mutable_data(), w, h);
        {
          py::gil_scoped_release release;
          if (b.glsl)
            run_on_glsl_device([&](hush::glsl::device& d) {
              n.render(hush::exec::glsl<hush::glsl::device>{d}, fa.frame, tris, view);
            });
          else if (b.simd)
            n.render(hush::exec::simd, fa.frame, tris, view);
          else
            n.render(hush::exec::scalar, fa.frame, tris, view);
        }
        return out;
      },
      py::arg("depth"), py::arg("indices"), py::arg("screen"), py::arg("vertex_depth"),
      py::arg("triangle_id"), py::arg("object_id") = py::none(),
      py::arg("frame_object_id") = py::none(), py::arg("frame_triangle_id") = py::none(),
      py::arg("backend") = "simd",
      kept(std::string(
               "One frame: depth (H, W); the triangles drawn: indices (T, 3), screen (V, 2) "
               "pixel positions (x right, y down), vertex_depth (V,), triangle_id (T,), "
               "object_id (T,) or None; the frame's id views (H, W) where the params' tests need "
               "them. Returns (H, W) float32. backend: 'simd' (default), 'scalar' or 'glsl'."
               "\n\nC++ contract (hush::npr_gabor::render):\n") +
           docs::npr_gabor_render));
}

}  // namespace hush_python
