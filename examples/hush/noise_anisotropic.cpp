// hush — the `hush` program: anisotropic noise (hush/anisotropic.hpp), its `hush sample` and
// `hush render` entries.
//
// `hush sample anisotropic`: 2D texture-space noise on the grid, through evaluate_grid without
// per-sample inputs and through hush::samples (float positions) with a footprint or a map.
//
// `hush render anisotropic --gbuffer DIR --out DIR [options]`: the noise over a G-buffer
// sequence: per covered pixel the noise at its uv, filtered by the footprint of its
// screen-to-uv Jacobian, and with --scene NAME compensated by its triangle's surface map from
// the scene's meshes (examples/anisotropic/scene_render.hpp). One channel per frame,
// background 0 (--backend glsl: whole frames on the GPU, hush/glsl/anisotropic/frame.hpp). The
// options are `hush sample anisotropic`'s, less --footprint and --map (the
// G-buffer and the scene give them per pixel).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "glsl_device.hpp"
#include "hush/anisotropic.hpp"
#include "hush/exec.hpp"
#include "noise_entries.hpp"
#include "noises.hpp"
#include "scene_noises.hpp"

#if HUSH_CLI_HAVE_GLSL
#include "hush/glsl/anisotropic/frame.hpp"
#endif
#if HUSH_CLI_HAVE_ANISO_SCENE
#include "scene.hpp"
#include "scene_render.hpp"
#endif

namespace hush_cli {
namespace {

// What `hush sample anisotropic` takes beside the noise's parameters: the
// footprint given to every sample (none: point samples; pixel: the grid
// step's width; or a width in noise units) and one surface map for every
// sample (none: the identity).
struct anisotropic_options {
  hush::anisotropic::params params;
  bool pixel_footprint = false;
  std::optional<double> footprint_width;
  std::optional<hush::surface_map> map;
};

class anisotropic_field final : public noise_field {
 public:
  explicit anisotropic_field(const anisotropic_options& o) : options_(o), noise_(o.params) {}
  bool is_signed() const override { return options_.params.kind == hush::fractal_kind::fbm; }
  std::pair<double, double> png_range() const override {
    return is_signed() ? unit_variance_range() : noise_field::png_range();
  }
  std::string unsupported_reason(backend b) const override {
    if (b == backend::glsl) {
      if (!HUSH_CLI_HAVE_GLSL)
        return "the GLSL backend is not in this build (neither OSMesa nor EGL found)";
      const auto& p = options_.params;
      if (p.filtering == hush::weight_rule::least_squares ||
          p.compensation == hush::weight_rule::least_squares)
        return "least-squares weights run on the CPU only (--filtering and --compensation "
               "centre or three_point on the GPU)";
    }
    if (b == backend::simd && !HUSH_CONFIG_SIMD)
      return "the SIMD backend is not in this build (Highway, libhwy-dev, was not found)";
    return "";
  }
  void sample_rows(const sample_grid& grid, std::size_t j0, std::size_t rows, std::size_t k,
                   float* out, backend b) const override {
    const bool extras = options_.pixel_footprint || options_.footprint_width || options_.map;
    if (!extras) {
      const hush::grid<2> block = row_block<2>(grid, j0, rows, k);
      run(
          [&](const auto& ex) {
            hush::evaluate_grid(noise_, ex, block, hush::span<float>(out, block.count()));
          },
          b);
      return;
    }
    // Per-sample inputs go through hush::samples (float positions).
    const std::size_t n = grid.size[0] * rows;
    std::vector<hush::vec2> pos(n);
    for (std::size_t j = 0; j < rows; ++j)
      for (std::size_t i = 0; i < grid.size[0]; ++i) {
        const hush::dvec3 p = grid.position({i, j0 + j, k});
        pos[j * grid.size[0] + i] = {static_cast<float>(p.x), static_cast<float>(p.y)};
      }
    hush::samples<2> s;
    s.positions = pos;
    std::vector<hush::footprint<2>> fps;
    if (options_.pixel_footprint || options_.footprint_width) {
      const double w =
          options_.pixel_footprint ? std::fabs(grid.step[0]) : *options_.footprint_width;
      fps.assign(n, hush::footprint<2>::isotropic(w));
      s.footprints = fps;
    }
    std::vector<hush::surface_map> maps;
    if (options_.map) {
      maps.assign(n, *options_.map);
      s.surface_maps = maps;
    }
    run([&](const auto& ex) { hush::evaluate(noise_, ex, s, hush::span<float>(out, n)); }, b);
  }

 private:
  template <class F>
  void run(F f, backend b) const {
    if (b == backend::simd) return f(hush::exec::simd);
#if HUSH_CLI_HAVE_GLSL
    if (b == backend::glsl) return f(hush::exec::glsl{glsl_device()});
#endif
    f(hush::exec::scalar);
  }

  anisotropic_options options_;
  hush::anisotropic noise_;
};

hush::weight_rule parse_rule(const char* option, const std::string& v) {
  return parse_choice<hush::weight_rule>(option, v,
                                         {{"centre", hush::weight_rule::centre},
                                          {"three_point", hush::weight_rule::three_point},
                                          {"least_squares", hush::weight_rule::least_squares}});
}

// The noise's options (`hush render anisotropic` takes them less --footprint and --map).
std::vector<option_spec> anisotropic_option_specs() {
  return {
      {"--orientations", "K", "orientations of the subband tiles, 2 ... 8 (default 4)",
       "orientations"},
      {"--scales", "S", "subband scales, 1 ... 12 (default 3)", "scales"},
      {"--base-scale", "b",
       "the scale of octave 0, 0 ... S-1; scales below it compensate stretching maps (default 0)",
       "base_scale"},
      {"--octaves", "O", "octaves, 1 ... S - b (default S - b)", "octaves"},
      {"--gain", "G", "amplitude ratio between octaves, in (0, 1e6] (default 0.5)", "gain"},
      {"--frequency", "F",
       "centre frequency of octave 0 in cycles per unit, in (0, 1e12] (default 1)", "frequency"},
      {"--fractal", "fbm|turbulence", "sum octaves or their absolute values (default fbm)",
       nullptr},
      {"--tile-size", "N", "subband tile size, a power of two 16 ... 2048 (default 256)",
       "tile_size"},
      {"--filtering", "centre|three_point|least_squares",
       "subband weights of the pixel filter (default centre, the paper's heuristic)", nullptr},
      {"--compensation", "centre|three_point|least_squares",
       "subband weights of the surface map (default centre)", nullptr},
      {"--footprint", "none|pixel|W",
       "every sample's footprint: none (point samples, default), pixel (the grid step) or an "
       "isotropic width W > 0 in noise units",
       nullptr},
      {"--map", "a,b,c,d",
       "one surface map T = [a b; c d] (texture <- surface) for every sample (default: none, the "
       "identity)",
       nullptr},
  };
}

// Parses them; throws usage_error (library refusals go through make_noise).
anisotropic_options parse_anisotropic(const noise_setup& setup, const option_values& given) {
  if (setup.dim != 2)
    throw usage_error("--dim " + std::to_string(setup.dim) +
                      ": anisotropic noise is 2D texture-space noise; valid: --dim 2");
  anisotropic_options o;
  auto& p = o.params;
  p.seed = setup.seed;
  // Integers are range-checked by the library (make_noise names the option);
  // here only their form.
  auto integer = [&](const char* name, int& field) {
    if (const std::string* v = find_value(given, name))
      field = static_cast<int>(parse_integer(name, *v, -1000000, 1000000));
  };
  integer("--orientations", p.orientations);
  integer("--scales", p.scales);
  integer("--base-scale", p.base_scale);
  p.octaves = p.scales - p.base_scale;
  integer("--octaves", p.octaves);
  integer("--tile-size", p.tile_size);
  if (const std::string* v = find_value(given, "--gain")) p.gain = parse_finite("--gain", *v);
  if (const std::string* v = find_value(given, "--frequency"))
    p.frequency = parse_finite("--frequency", *v);
  if (const std::string* v = find_value(given, "--fractal"))
    p.kind = parse_choice<hush::fractal_kind>(
        "--fractal", *v,
        {{"fbm", hush::fractal_kind::fbm}, {"turbulence", hush::fractal_kind::turbulence}});
  if (const std::string* v = find_value(given, "--filtering"))
    p.filtering = parse_rule("--filtering", *v);
  if (const std::string* v = find_value(given, "--compensation"))
    p.compensation = parse_rule("--compensation", *v);
  if (const std::string* v = find_value(given, "--footprint")) {
    if (*v == "pixel") {
      o.pixel_footprint = true;
    } else if (*v != "none") {
      const char* valid = "none, pixel or a finite width > 0";
      double w = 0;
      if (!to_finite(*v, w) || !(w > 0)) throw_bad_value("--footprint", *v, valid);
      o.footprint_width = w;
    }
  }
  if (const std::string* v = find_value(given, "--map")) {
    const std::vector<double> m = parse_finite_list("--map", *v, 4);
    o.map = hush::surface_map::from_matrix(m[0], m[1], m[2], m[3]);
  }
  return o;
}

std::unique_ptr<noise_field> make_anisotropic_from_options(const noise_setup& setup,
                                                           const option_values& given) {
  return std::make_unique<anisotropic_field>(parse_anisotropic(setup, given));
}

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
#if HUSH_CLI_HAVE_GLSL
    if (b == backend::glsl) return run_resident(frames, sink);
#endif
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

#if HUSH_CLI_HAVE_GLSL
  // The GPU: each frame through hush::glsl::anisotropic_frame (uv, Jacobian and, compensated,
  // each pixel's triangle map as textures; one draw per frame, the image read back), the
  // weights formed in the shader rather than per sample on the CPU.
  void run_resident(gbuffer_sequence& frames, render_sink& sink) {
    hush::glsl::anisotropic_frame gpu(glsl_device().gl().loader, noise_);
    const std::size_t n = frames.size();
    const auto w = static_cast<std::size_t>(frames.width());
    const auto h = static_cast<std::size_t>(frames.height());
    const hush::frame_view needs = hush::frame_view::uv | hush::frame_view::uv_jacobian |
                                   hush::frame_view::object_id | hush::frame_view::triangle_id;
    std::vector<hush::surface_map> pixel_maps;
    for (std::size_t i = 0; i < n; ++i) {
      const hush::frame f = frames.frame(i, needs);
      pixel_maps.clear();
      if (compensate_) {
        // As collect_samples: the pixel's triangle's map, the identity for unknown ids.
        pixel_maps.assign(w * h, hush::surface_map::identity());
        for (std::size_t y = 0; y < h; ++y)
          for (std::size_t x = 0; x < w; ++x) {
            const std::uint32_t object = f.object_id(x, y), tri = f.triangle_id(x, y);
            if (object != 0 && object - 1 < maps_.size() && tri < maps_[object - 1].size())
              pixel_maps[y * w + x] = maps_[object - 1][tri];
          }
      }
      const std::vector<float> out = gpu.render_image(f, pixel_maps);
      sink.write(i, {hush::image_view<const float>(out.data(), w, h)});
      sink.progress("anisotropic", i + 1, n);
    }
  }
#endif

  hush::anisotropic noise_;
  std::vector<std::vector<hush::surface_map>> maps_;
  bool compensate_;
};
#endif

std::unique_ptr<scene_noise> make_anisotropic_render(const render_setup& setup,
                                                     const option_values& given,
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

void add_anisotropic_entries(program_entries& entries) {
  entries.sample.push_back(
      {"anisotropic",
       "anisotropic noise (Goldberg, Zwicker & Durand 2008): oriented subband tiles, filtered "
       "per footprint, compensated per surface map",
       anisotropic_option_specs(), make_anisotropic_from_options});
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
  entries.render.push_back(
      {"anisotropic",
       "anisotropic noise (Goldberg, Zwicker & Durand 2008) at each pixel's uv, filtered "
       "by its screen-to-uv Jacobian; with --scene, compensated per triangle; needs uv, "
       "uv_jacobian, object_id and triangle_id",
       options,
       {},
       make_anisotropic_render});
}

}  // namespace hush_cli
