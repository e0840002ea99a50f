// hush — the `hush` program: `hush render anisotropic`, anisotropic noise on scene G-buffers
// (see render_anisotropic.hpp).
#include "render_anisotropic.hpp"

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "anisotropic_noise.hpp"
#include "glsl_device.hpp"
#include "hush/anisotropic.hpp"
#include "hush/exec.hpp"

#if HUSH_CLI_HAVE_ANISO_SCENE
#include "scene.hpp"
#include "scene_render.hpp"
#endif

namespace hush_cli {
namespace {

#if HUSH_CLI_HAVE_ANISO_SCENE
class anisotropic_scene_noise final : public scene_noise {
 public:
  // maps: per object and triangle (empty: no compensation).
  anisotropic_scene_noise(const hush::anisotropic::params& p,
                          std::vector<std::vector<hush::surface_map>> maps, bool compensate)
      : noise_(p), maps_(std::move(maps)), compensate_(compensate) {}
  int channels() const override { return 1; }
  std::string unsupported_reason(backend b) const override {
    if (b == backend::glsl && HUSH_CLI_HAVE_GLSL) {
      const auto& p = noise_.parameters();
      if (p.filtering == hush::weight_rule::least_squares ||
          (compensate_ && p.compensation == hush::weight_rule::least_squares))
        return "least-squares weights run on the CPU only (--filtering and --compensation "
               "centre or three_point on the GPU)";
    }
    return backend_missing(b);
  }
  void render(gbuffer_sequence& frames, render_sink& sink, backend b) override {
    with_exec(b, [&](const auto& ex) { run(ex, frames, sink); });
  }

 private:
  template <class Exec>
  void run(const Exec& ex, gbuffer_sequence& frames, render_sink& sink) {
    const std::size_t n = frames.size();
    const auto w = static_cast<std::size_t>(frames.width());
    const auto h = static_cast<std::size_t>(frames.height());
    const hush::frame_view needs = hush::frame_view::uv | hush::frame_view::uv_jacobian |
                                   hush::frame_view::object_id | hush::frame_view::triangle_id;
    for (std::size_t i = 0; i < n; ++i) {
      const hush::frame f = frames.frame(i, needs);
      const std::vector<float> out =
          hush_tools::aniso::render_frame(noise_, f, maps_, ex, compensate_);
      sink.write(i, {hush::image_view<const float>(out.data(), w, h)});
      sink.progress("anisotropic", i + 1, n);
    }
  }

  hush::anisotropic noise_;
  std::vector<std::vector<hush::surface_map>> maps_;
  bool compensate_;
};
#endif

std::unique_ptr<scene_noise> make_render(const render_setup& setup, const option_values& given,
                                         const std::vector<std::string>&) {
  noise_setup ns;
  ns.dim = 2;
  ns.seed = setup.seed;
  option_values noise_options;
  for (const auto& [name, value] : given)
    if (name != "--scene") noise_options[name] = value;
  const anisotropic_options o = parse_anisotropic(ns, noise_options);
#if HUSH_CLI_HAVE_ANISO_SCENE
  std::vector<std::vector<hush::surface_map>> maps;
  const std::string* scene = find_value(given, "--scene");
  if (scene) {
    try {
      maps = hush_tools::aniso::scene_surface_maps(hush_tools::scene::make_scene(*scene));
    } catch (const hush::invalid_argument& e) {
      throw usage_error("--scene '" + *scene + "' is invalid: " + e.what());
    }
  }
  return std::make_unique<anisotropic_scene_noise>(o.params, std::move(maps), scene != nullptr);
#else
  (void)o;
  throw usage_error("hush render anisotropic is not in this build (needs the scene library)");
#endif
}

}  // namespace

render_entry anisotropic_render_entry() {
  std::vector<option_spec> options;
  for (const option_spec& s : anisotropic_option_specs()) {
    const std::string name = s.name;
    if (name == "--footprint" || name == "--map") continue;  // from the G-buffer and the scene
    options.push_back(s);
  }
  options.push_back({"--scene", "NAME",
                     "the scene the G-buffers show (hush scene list): each triangle's surface "
                     "map from its mesh compensates the UV distortion, frequencies in object "
                     "units; without it, plain texture-space noise (frequencies in uv units)"});
  return {"anisotropic",
          "anisotropic noise (Goldberg, Zwicker & Durand 2008) at each pixel's uv, filtered "
          "by its screen-to-uv Jacobian; with --scene, compensated per triangle; needs uv, "
          "uv_jacobian, object_id and triangle_id",
          options,
          {},
          make_render};
}

}  // namespace hush_cli
