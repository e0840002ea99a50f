// hush.CoherentStream: coherent noise for NPR (Kass & Pesare; include/hush/coherent.hpp) from
// Python: a stream that advances frame by frame over G-buffer arrays.
#include <utility>

#include "frame.hpp"
#include "hush/glsl/coherent.hpp"

namespace hush_python {

// A stream advanced on backend="glsl" keeps its history in GL buffers of the process's device,
// whose context is current on the GL thread alone (glsl.hpp): from then on its every step (a CPU
// step first downloads the history) and its end (the buffers' deletion) run on that thread.
template <>
struct held<hush::coherent_stream> {
  hush::coherent_stream noise;
  py::dict params;
  bool on_gl = false;

  held(hush::coherent_stream n, py::dict p) : noise(std::move(n)), params(std::move(p)) {}
  held(const held&) = delete;
  held& operator=(const held&) = delete;
  held(held&&) = default;
  held& operator=(held&&) = delete;
  ~held() {
    if (!on_gl) return;
    try {
      // The moved-from stream left here holds no device state.
      run_on_glsl_device([this](hush::glsl::device&) { hush::coherent_stream gone(std::move(noise)); });
    } catch (...) {  // NOLINT(bugprone-empty-catch): a forked child cannot reach the parent's device
    }
  }
};

void add_coherent_python(py::module_& m) {
  using stream = hush::coherent_stream;
  auto c = bind_noise<stream>(m, "CoherentStream",
                              "Coherent noise (hush::coherent_stream): the history of a frame "
                              "sequence, owned by the caller; advance() once per frame. A copy or "
                              "a pickle holds the parameters, not the history: it starts fresh.",
                              docs::coherent, [](py::kwargs kw) {
                                keywords k("hush.coherent", kw);
                                hush::coherent_params prm;
                                k.get("seed", prm.seed);
                                k.get("alpha", prm.alpha);
                                k.get("epsilon", prm.epsilon);
                                k.get("epsilon_absolute", prm.epsilon_absolute);
                                k.get_enum("filter", prm.filter,
                                           {{"paper", hush::coherent_filter::paper},
                                            {"stationary", hush::coherent_filter::stationary}});
                                k.get_enum("input", prm.input,
                                           {{"white", hush::coherent_input::white},
                                            {"bandpass", hush::coherent_input::bandpass}});
                                k.get("bandpass_pixels", prm.bandpass_pixels);
                                k.get("smoothing", prm.smoothing);
                                k.get("channels", prm.channels);
                                k.finish();
                                return stream(prm);
                              });
  c.def(
      "advance",
      [](held<stream>& self, const py::object& depth, const py::object& velocity,
         const py::object& object_id, const std::string& backend_name) {
        const backend b = parse_backend(backend_name, 1);
        frame_arrays fa(depth, velocity, py::none(), object_id, py::none());
        const std::size_t w = fa.frame.width(), h = fa.frame.height();
        hush::coherent_stream& s = self.noise;
        const auto channels = static_cast<std::size_t>(s.parameters().channels);
        float_array out(std::vector<py::ssize_t>{static_cast<py::ssize_t>(channels),
                                                 static_cast<py::ssize_t>(h),
                                                 static_cast<py::ssize_t>(w)});
        std::vector<hush::image_view<float>> views;
        for (std::size_t ch = 0; ch < channels; ++ch)
          views.push_back({out.mutable_data() + ch * w * h, w, h});
        {
          py::gil_scoped_release release;
          const hush::span<const hush::image_view<float>> v(views.data(), views.size());
          auto step = [&](hush::glsl::device* d) {
            if (d)
              s.advance(hush::exec::glsl<hush::glsl::device>{*d}, fa.frame, v);
            else if (b.simd)
              s.advance(hush::exec::simd, fa.frame, v);
            else
              s.advance(hush::exec::scalar, fa.frame, v);
          };
          if (b.glsl || self.on_gl) {
            self.on_gl = true;
            run_on_glsl_device([&](hush::glsl::device& d) { step(b.glsl ? &d : nullptr); });
          } else {
            step(nullptr);
          }
        }
        return out;
      },
      py::arg("depth"), py::arg("velocity"), py::arg("object_id") = py::none(),
      py::arg("backend") = "simd",
      kept(std::string(
               "The next frame: depth (H, W) linear view depth, velocity (H, W, 3) motion from "
               "the previous frame in pixels (dx, dy) and depth (dz), object_id (H, W) uint32 or "
               "None. Returns (channels, H, W) float32, unit variance. backend: 'simd' "
               "(default), 'scalar' or 'glsl' (the history stays on the GL device between "
               "glsl frames; a frame on another backend first brings it back).\n\nC++ contract (hush::coherent_stream::advance):\n") +
           docs::coherent_advance));
  c.def(
      "reset", [](held<stream>& h, std::uint32_t next_frame) { h.noise.reset(next_frame); },
      py::arg("next_frame") = 0u, docs::coherent_reset);
}

}  // namespace hush_python
