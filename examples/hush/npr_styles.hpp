// hush — the `hush` program: `hush render npr-gabor --style ...`, the styles of Benard,
// Lagae et al. 2010 (sec. 4, Figs. 2-3) drawn from NPR Gabor noise layers and the G-buffer
// with the library's style layer (include/hush/style.hpp).
//
// Per frame: the tone comes from shading (N.L of the G-buffer's world-space normals and a
// world-space light direction, plus ambient); the orientation field is the screen direction
// of the projected normal (hush::style::projected_normal_field: grad(1/depth)); where the
// surface faces the camera (relative slope below kFaceOn per pixel) it is NaN and the noise
// takes the constant --orientation. With npr_field::curvature the orientation is the principal
// direction of largest curvature (hush::style::curvature_field from the G-buffer's normals:
// across a cylinder's axis), the projected normal where the surface is flat (the normal turns
// by less than kFlat radians per pixel) or umbilic (anisotropy below kUmbilic). Layers, each an hush::npr_gabor:
//  - hatching: one anisotropic layer along the field; binary threshold of the tone.
//  - stippling: one isotropic layer; the same threshold.
//  - crosshatch: two anisotropic layers (field and field + pi/2, seeds s and s + 1);
//    hush::style::crosshatch.
//  - graphite: the hatching layer and an isotropic layer at 3 F0 (capped at 0.5) and 3 a
//    (capped at 10), seed s + 2; hush::style::graphite.
//  - watercolor: one isotropic layer overlaid on the object's colour times the tone.
#ifndef HUSH_CLI_NPR_STYLES_HPP
#define HUSH_CLI_NPR_STYLES_HPP

#include <cstdint>
#include <functional>
#include <vector>

#include "hush/core/frame.hpp"
#include "hush/core/triangles.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/npr_gabor.hpp"
#include "npr_fields.hpp"

namespace hush_cli {

enum class npr_style { none, hatching, stippling, crosshatch, graphite, watercolor };
// The orientation field: --orientation everywhere, the projected normal, or the principal
// curvature (hush::style::curvature_field, the projected normal where flat or umbilic).
enum class npr_field { constant, normal, curvature };

struct npr_style_options {
  npr_style style = npr_style::none;
  double softness = 0.6;             // smooth-step width, noise sigmas (hush::style::binary)
  double grain = 0.7;                // graphite's fine layer
  double gain = 0.35;                // watercolour overlay gain
  double ambient = 0.15;             // tone where N.L <= 0
  hush::dvec3 light{0.4, 0.7, 0.6};  // towards the light, world space
  npr_field field = npr_field::normal;  // where the anisotropic layers' orientation comes from
};

class npr_stylizer {
 public:
  // `base`: the noise's parameters (frequency, bandwidth, N', seed, visibility); throws
  // hush::invalid_argument for bad style values (naming "width", "grain", "gain").
  npr_stylizer(const hush::npr_gabor::params& base, const npr_style_options& o);
  // Frame views the layers read (the G-buffer's normals come separately).
  hush::frame_view needs() const;
  // Draws one frame as 8-bit RGB (rows top to bottom) into `rgb` (resized); `simd`: the
  // layers are splatted by exec::simd (npr_gabor::render), else by exec::scalar.
  void draw(bool simd, const hush::frame& f, const hush::triangle_list& tris,
            hush::image_view<const hush::vec3> normals, std::vector<std::uint8_t>& rgb);
  // The same with each layer rendered by `render` (e.g. on exec::glsl). `fields` (updated
  // for this frame by the caller; none when null) drive F0, a and N' of every layer; graphite's
  // fine layer takes 3 F0 and 3 a of them, capped like its constants.
  using layer_render =
      std::function<void(const hush::npr_gabor&, const hush::frame&, const hush::triangle_list&,
                         const hush::image_view<float>&, const hush::npr_gabor::sources&)>;
  void draw(const layer_render& render, const hush::frame& f, const hush::triangle_list& tris,
            hush::image_view<const hush::vec3> normals, std::vector<std::uint8_t>& rgb,
            npr_fields* fields = nullptr);

 private:
  npr_style_options o_;
  std::vector<hush::npr_gabor> layers_;
  std::vector<std::vector<float>> images_;
  std::vector<float> field_, field_turned_, tone_;
};

}  // namespace hush_cli

#endif  // HUSH_CLI_NPR_STYLES_HPP
