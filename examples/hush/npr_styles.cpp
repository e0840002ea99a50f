// hush — the `hush` program: NPR Gabor noise styles (see npr_styles.hpp).
#include "npr_styles.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "hush/core/param_source.hpp"
#include "hush/npr_gabor/style.hpp"

namespace hush_cli {

namespace {

// Below this relative change of depth per pixel (|grad(1/z)| z) the surface is taken as
// facing the camera: the projected normal's direction is noise there (a tilt of about
// 0.1 rad at a focal length of 1000 pixels).
constexpr double kFaceOn = 1e-4;
constexpr double kHalfPi = 1.57079632679489661923;
// curvature_field's thresholds: a normal turning by less than 1e-3 rad per pixel is flat (a
// radius of curvature above 1000 pixels), and below an anisotropy of 0.2 (principal
// curvatures within a factor 1.22 of each other) the principal direction is not trusted.
constexpr double kFlat = 1e-3, kUmbilic = 0.2;
// Graphite's fine layer: this multiple of F0 and a (capped at their maxima).
constexpr double kFineScale = 3.0;

// Watercolour base colours per object id (pastel pigments; id 0 = background, paper).
constexpr double kPigments[][3] = {{0.95, 0.55, 0.35}, {0.35, 0.6, 0.9},  {0.5, 0.8, 0.45},
                                   {0.9, 0.8, 0.35},   {0.75, 0.5, 0.85}, {0.4, 0.8, 0.8}};

std::uint8_t byte_of(double v) {
  return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(v, 0.0, 1.0)));
}

}  // namespace

npr_stylizer::npr_stylizer(const hush::npr_gabor::params& base, const npr_style_options& o)
    : o_(o) {
  // Validate the style's values once (the constructors throw naming them).
  (void)hush::style::binary(o.softness);
  (void)hush::style::graphite(o.softness, o.grain);
  (void)hush::style::watercolor(o.gain);
  hush::npr_gabor::params p = base;
  switch (o.style) {
    case npr_style::none:
      break;
    case npr_style::hatching:
      layers_.emplace_back(p);
      break;
    case npr_style::stippling:
    case npr_style::watercolor:
      p.isotropic = true;
      layers_.emplace_back(p);
      break;
    case npr_style::crosshatch: {
      layers_.emplace_back(p);
      hush::npr_gabor::params q = p;
      q.orientation += kHalfPi;
      q.seed += 1;
      layers_.emplace_back(q);
      break;
    }
    case npr_style::graphite: {
      layers_.emplace_back(p);
      hush::npr_gabor::params q = p;
      q.isotropic = true;
      q.frequency = std::min(kFineScale * p.frequency, hush::detail::constants::kNprGaborMaxFrequency);
      q.bandwidth = std::min(kFineScale * p.bandwidth, hush::detail::constants::kNprGaborMaxBandwidth);
      q.seed += 2;
      layers_.emplace_back(q);
      break;
    }
  }
  images_.resize(layers_.size());
}

hush::frame_view npr_stylizer::needs() const {
  hush::frame_view v = hush::frame_view::depth | hush::frame_view::object_id;
  for (const hush::npr_gabor& l : layers_) v = v | l.needs();
  return v;
}

void npr_stylizer::draw(bool simd, const hush::frame& f, const hush::triangle_list& tris,
                        hush::image_view<const hush::vec3> normals,
                        std::vector<std::uint8_t>& rgb) {
  draw(
      [simd](const hush::npr_gabor& layer, const hush::frame& fr, const hush::triangle_list& t,
             const hush::image_view<float>& image, const hush::npr_gabor::sources& src) {
        if (simd)
          layer.render(hush::exec::simd, fr, t, image, src);
        else
          layer.render(hush::exec::scalar, fr, t, image, src);
      },
      f, tris, normals, rgb);
}

void npr_stylizer::draw(const layer_render& render, const hush::frame& f,
                        const hush::triangle_list& tris, hush::image_view<const hush::vec3> normals,
                        std::vector<std::uint8_t>& rgb, npr_fields* fields) {
  const std::size_t w = f.width(), h = f.height();
  const bool field = o_.field != npr_field::constant;
  if (field) {
    field_.resize(w * h);
    const hush::image_view<float> out(field_.data(), w, h);
    if (o_.field == npr_field::curvature)
      hush::style::curvature_field(f, normals, out, kFlat, kUmbilic, kFaceOn);
    else
      hush::style::projected_normal_field(f, out, kFaceOn);
    field_turned_.resize(field_.size());
    for (std::size_t i = 0; i < field_.size(); ++i)
      field_turned_[i] = field_[i] + static_cast<float>(kHalfPi);  // NaN stays NaN
  }
  for (std::size_t k = 0; k < layers_.size(); ++k) {
    images_[k].resize(w * h);
    // Graphite's second layer is the fine one (3 F0, 3 a: see the constructor).
    const double scale = o_.style == npr_style::graphite && k == 1 ? kFineScale : 1.0;
    hush::npr_gabor::sources src = fields ? fields->sources(scale, scale) : hush::npr_gabor::sources{};
    if (field && !layers_[k].parameters().isotropic)
      src.orientation =
          hush::param_source::per_pixel({(k == 0 ? field_ : field_turned_).data(), w, h});
    const hush::image_view<float> image(images_[k].data(), w, h);
    render(layers_[k], f, tris, image, src);
  }
  tone_.resize(w * h);
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const hush::vec3 n = normals(x, y);
      tone_[y * w + x] = f.object_id(x, y) == 0 ? 1.0f
                                                : static_cast<float>(hush::style::shading_tone(
                                                      {n.x, n.y, n.z}, o_.light, o_.ambient));
    }
  rgb.assign(w * h * 3, 255);
  const hush::style::binary binary(o_.softness);
  const hush::style::crosshatch cross(o_.softness);
  const hush::style::graphite graphite(o_.softness, o_.grain);
  const hush::style::watercolor wc(o_.gain);
  constexpr std::size_t kPigmentCount = sizeof kPigments / sizeof kPigments[0];
  for (std::size_t i = 0; i < w * h; ++i) {
    const double tone = tone_[i];
    const double n0 = images_.empty() ? 0.0 : images_[0][i];
    const double n1 = images_.size() > 1 ? images_[1][i] : 0.0;
    hush::dvec3 c{1, 1, 1};
    switch (o_.style) {
      case npr_style::none:
        break;
      case npr_style::hatching:
      case npr_style::stippling:
        c.x = c.y = c.z = binary.paper(n0, tone);
        break;
      case npr_style::crosshatch:
        c.x = c.y = c.z = cross.paper(n0, n1, tone);
        break;
      case npr_style::graphite:
        c.x = c.y = c.z = graphite.paper(n0, n1, tone);
        break;
      case npr_style::watercolor: {
        const std::uint32_t o = f.object_id(i % w, i / w);
        if (o == 0) break;
        const double* p = kPigments[(o - 1) % kPigmentCount];
        c = wc.colour({p[0] * tone, p[1] * tone, p[2] * tone}, n0);
        break;
      }
    }
    rgb[3 * i] = byte_of(c.x);
    rgb[3 * i + 1] = byte_of(c.y);
    rgb[3 * i + 2] = byte_of(c.z);
  }
}

}  // namespace hush_cli
