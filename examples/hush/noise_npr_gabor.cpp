// hush — the `hush` program: `hush render npr-gabor` (hush/npr_gabor.hpp), its render_table
// entry: NPR Gabor noise over a G-buffer sequence, as noise frames or, with --style, drawn
// (npr_styles.hpp), with per-pixel or per-vertex parameter fields (npr_fields.hpp).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "glsl_device.hpp"
#include "hush/detail/constants.hpp"
#include "hush/exec.hpp"
#include "hush/npr_gabor.hpp"
#include "noise_entries.hpp"
#include "npr_fields.hpp"
#include "npr_styles.hpp"
#include "scene_noises.hpp"

#if HUSH_CLI_HAVE_GLSL
#include "hush/glsl/npr_gabor/renderer.hpp"
#endif

namespace hush_cli {
namespace {

// NPR Gabor noise: kernels splatted at points on the triangles.
// With --style, each frame is drawn (npr_styles.hpp) and written as OUT/NNNN.png.
class npr_gabor_noise final : public scene_noise {
 public:
  npr_gabor_noise(const hush::npr_gabor::params& prm, const npr_style_options& style,
                  const npr_field_options& fields)
      : noise_(prm), style_(style), stylizer_(prm, style), fields_(fields) {}
  int channels() const override { return style_.style == npr_style::none ? 1 : 3; }
  std::string unsupported_reason(backend b) const override { return backend_missing(b); }
  void render(gbuffer_sequence& frames, render_sink& sink, backend b) override {
    if (b == backend::simd) {
      run(hush::exec::simd, frames, sink);
    } else if (b == backend::glsl) {
#if HUSH_CLI_HAVE_GLSL
      // Stage 1 on the CPU, the splatting as point sprites (hush/glsl/npr_gabor.hpp).
      run(hush::exec::glsl<hush::glsl::device>{glsl_device()}, frames, sink);
#endif
    } else {
      run(hush::exec::scalar, frames, sink);
    }
  }

 private:
  template <class Exec>
  void run(const Exec& ex, gbuffer_sequence& frames, render_sink& sink) {
    const std::size_t n = frames.size();
    const std::size_t w = static_cast<std::size_t>(frames.width());
    const std::size_t h = static_cast<std::size_t>(frames.height());
    if (style_.style != npr_style::none) {
      std::vector<std::uint8_t> rgb;
      for (std::size_t i = 0; i < n; ++i) {
        const hush::frame f = frames.frame(i, stylizer_.needs());
        const hush::triangle_list t = frames.triangles(i);
        update_fields(frames, i, f, t);
        stylizer_.draw(
            [&ex](const hush::npr_gabor& layer, const hush::frame& fr,
                  const hush::triangle_list& tl, const hush::image_view<float>& image,
                  const hush::npr_gabor::sources& src) { layer.render(ex, fr, tl, image, src); },
            f, t, frames.normals(i), rgb, fields_.any() ? &fields_ : nullptr);
        sink.write_png(i, rgb, w, h);
        sink.progress("drawing", i + 1, n);
      }
      return;
    }
    std::vector<float> plane(w * h);
    for (std::size_t i = 0; i < n; ++i) {
      const hush::frame f = frames.frame(i, noise_.needs());
      const hush::triangle_list t = frames.triangles(i);
      update_fields(frames, i, f, t);
      noise_.render(ex, f, t, hush::image_view<float>(plane.data(), w, h),
                    fields_.any() ? fields_.sources() : hush::npr_gabor::sources{});
      sink.write(i, {hush::image_view<const float>(plane.data(), w, h)});
      sink.progress("splatting", i + 1, n);
    }
  }

  // Frame i's --frequency-field ... fields (npr_fields.hpp), when any is given.
  void update_fields(gbuffer_sequence& frames, std::size_t i, const hush::frame& f,
                     const hush::triangle_list& t) {
    if (!fields_.any()) return;
    // The frame's views stay valid: normals() and field() reload nothing for frame i.
    fields_.update(f, t, frames.normals(i),
                   [&frames, i](const std::string& name) { return frames.field(i, name); });
  }

  hush::npr_gabor noise_;
  npr_style_options style_;
  npr_stylizer stylizer_;
  npr_fields fields_;
};

std::unique_ptr<scene_noise> make_npr_gabor(const render_setup& setup, const option_values& given,
                                            const std::vector<std::string>& flags) {
  hush::npr_gabor::params p;
  p.seed = setup.seed;
  // Ranges are the library's (hush::npr_gabor checks them and make_scene_noise names the
  // option); here only "is it a number".
  auto number = [&](const char* name, double& field) {
    if (const std::string* v = find_value(given, name))
      field = parse_finite(name, *v, "a finite number");
  };
  number("--frequency", p.frequency);
  number("--bandwidth", p.bandwidth);
  number("--truncation", p.truncation);
  number("--impulses", p.impulses);
  number("--orientation", p.orientation);
  number("--depth-tolerance", p.depth_tolerance);
  for (const std::string& f : flags) {
    if (f == "--isotropic") p.isotropic = true;
    if (f == "--no-object-test") p.object_test = false;
    if (f == "--triangle-test") p.triangle_test = true;
    if (f == "--no-depth-test") p.depth_test = false;
    if (f == "--soft-depth") p.soft_depth = true;
    if (f == "--two-sided") p.cull_back_faces = false;
    if (f == "--thin") p.thinning = true;
    if (f == "--local-density") p.local_density = true;
  }
  npr_style_options s;
  if (const std::string* v = find_value(given, "--style"))
    s.style = parse_choice<npr_style>("--style", *v,
                                      {{"hatching", npr_style::hatching},
                                       {"stippling", npr_style::stippling},
                                       {"crosshatch", npr_style::crosshatch},
                                       {"graphite", npr_style::graphite},
                                       {"watercolor", npr_style::watercolor}});
  const bool styled = s.style != npr_style::none;
  namespace c = hush::detail::constants;
  npr_field_options fo;
  auto field = [&](const char* name, npr_param_field& out, double lo, double hi,
                   const char* valid) {
    if (const std::string* v = find_value(given, name))
      out = parse_npr_field(name, *v, lo, hi, valid);
  };
  field("--frequency-field", fo.frequency, 0, c::kNprGaborMaxFrequency, "0 ... 0.5");
  field("--bandwidth-field", fo.bandwidth, c::kNprGaborMinBandwidth, c::kNprGaborMaxBandwidth,
        "0.01 ... 10");
  field("--impulses-field", fo.impulses, 0, c::kGaborMaxImpulses, "0 ... 256");
  const bool shaded = styled || fo.uses(npr_param_field::kind::shading);
  for (const char* o : {"--softness", "--grain", "--gain", "--orientation-field"})
    if (!styled && find_value(given, o)) throw usage_error(std::string(o) + " needs --style");
  for (const char* o : {"--ambient", "--light"})
    if (!shaded && find_value(given, o))
      throw usage_error(std::string(o) + " needs --style or a shading:LO,HI field");
  if (const std::string* v = find_value(given, "--field-depth-range")) {
    if (!fo.uses(npr_param_field::kind::depth))
      throw usage_error("--field-depth-range needs a depth:LO,HI field");
    const std::vector<double> z = parse_finite_list("--field-depth-range", *v, 2);
    if (!(z[0] >= 0 && z[1] > z[0]))
      throw_bad_value("--field-depth-range", *v, "z0,z1 with 0 <= z0 < z1");
    fo.depth_range_given = true;
    fo.z0 = z[0];
    fo.z1 = z[1];
  }
  number("--softness", s.softness);
  number("--grain", s.grain);
  number("--gain", s.gain);
  s.ambient = parse_range(given, "--ambient", 0, 1, false, "a number in 0 ... 1", s.ambient);
  if (const std::string* v = find_value(given, "--light")) {
    const std::vector<double> l = parse_finite_list("--light", *v, 3);
    if (l[0] == 0 && l[1] == 0 && l[2] == 0) throw_bad_value("--light", *v, "a non-zero x,y,z");
    s.light = {l[0], l[1], l[2]};
  }
  if (const std::string* v = find_value(given, "--orientation-field"))
    s.field = parse_choice<npr_field>("--orientation-field", *v,
                                      {{"normal", npr_field::normal},
                                       {"curvature", npr_field::curvature},
                                       {"constant", npr_field::constant}});
  fo.ambient = s.ambient;
  fo.light = s.light;
  return std::make_unique<npr_gabor_noise>(p, s, fo);
}

}  // namespace

void add_npr_gabor_entries(program_entries& entries) {
  entries.render.push_back(
      {"npr-gabor",
       "NPR Gabor noise (Benard, Lagae et al. 2010): Gabor kernels in screen space at points "
       "attached to the triangles (2D look, follows the motion); needs depth, object ids "
       "(triangle ids with --triangle-test) and the tri_*.npy files of hush scene render",
       {
           {"--frequency", "f", "F0 in cycles per pixel, 0 ... 0.5 (default 0.125)", "frequency"},
           {"--bandwidth", "a",
            "kernel bandwidth in 1/pixel, 0.01 ... 10 (default 0.08: radius 12 pixels)",
            "bandwidth"},
           {"--impulses", "n", "N', kernels overlapping a pixel on average, (0, 256] (default 16)",
            "impulses"},
           {"--orientation", "rad",
            "omega0 in radians from +x towards +y (down) (default 0; ignored with --isotropic)",
            "orientation"},
           {"--truncation", "t", "kernel truncation, 1e-9 ... 0.5 (default 0.05)", "truncation"},
           {"--depth-tolerance", "d",
            "depth test tolerance, relative to depth, 0 ... 1 (default 0.02)", "depth_tolerance"},
           {"--style", "hatching|stippling|crosshatch|graphite|watercolor",
            "draw the frames in a style (hush/style.hpp) and write OUT/NNNN.png instead of .npy"},
           {"--softness", "w",
            "style: smooth-step width in noise sigmas, 0 (hard) ... 8 (default 0.6)", "width"},
           {"--grain", "g", "graphite: weight of the fine layer, 0 ... 8 (default 0.7)", "grain"},
           {"--gain", "g", "watercolor: overlay gain of the noise, 0 ... 4 (default 0.35)", "gain"},
           {"--ambient", "k",
            "style or shading field: tone where N.L <= 0, 0 ... 1 (default 0.15)"},
           {"--light", "x,y,z",
            "style or shading field: direction towards the light, world space (default "
            "0.4,0.7,0.6)"},
           {"--orientation-field", "normal|curvature|constant",
            "style: orientation along the projected normal (default), the principal curvature "
            "(the normal where flat) or --orientation"},
           {"--frequency-field", "shading:LO,HI|depth:LO,HI|file:NAME",
            "F0 per pixel: LO (tone 0, or depth z0) ... HI (tone 1, or depth z1), in 0 ... 0.5; "
            "or DIR/frame_NNNN/NAME.npy, float32 (H, W) per pixel or (V,) per vertex"},
           {"--bandwidth-field", "shading:LO,HI|depth:LO,HI|file:NAME",
            "a per pixel or per vertex, like --frequency-field; LO, HI in 0.01 ... 10"},
           {"--impulses-field", "shading:LO,HI|depth:LO,HI|file:NAME",
            "N' per pixel or per vertex (one density per triangle, read at its centroid), like "
            "--frequency-field; LO, HI in 0 ... 256"},
           {"--field-depth-range", "z0,z1",
            "depth:LO,HI fields: the depths of LO and HI, 0 <= z0 < z1 (default: the covered "
            "depth range of frame 0, fixed for the sequence)"},
       },
       {
           {"--isotropic", "", "a random orientation per point (stippling) instead of omega0"},
           {"--no-object-test", "", "splat across object boundaries"},
           {"--triangle-test", "", "cut every kernel to its own triangle"},
           {"--no-depth-test", "", "splat across depth discontinuities"},
           {"--soft-depth", "", "fade kernels between 1 and 2 depth tolerances instead of a cut"},
           {"--two-sided", "", "back-facing triangles emit points too"},
           {"--thin", "",
            "thin the points of triangles with N < 1 (same variance and spectrum, fewer "
            "points: faster on dense meshes)"},
           {"--local-density", "",
            "a point count per node of each triangle's point tree (variance constant across "
            "foreshortened triangles)"},
       },
       make_npr_gabor});
}

}  // namespace hush_cli
