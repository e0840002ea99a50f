// hush — the `hush` program: the gallery's NPR Gabor noise entries (see gallery_npr.hpp).
#include "gallery_npr.hpp"

#if HUSH_CLI_HAVE_SCENE
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "hush/gabor.hpp"
#include "hush/npr_gabor.hpp"
#include "npr_styles.hpp"
#include "raster_cpu.hpp"
#include "scene.hpp"
#include "triangles.hpp"
#endif

namespace hush_cli {

#if HUSH_CLI_HAVE_SCENE
namespace {

namespace hs = hush_tools::scene;

constexpr std::size_t kW = 128, kH = 96;  // one panel
constexpr int kFrames = 24;               // 24 frames, 8 cs each (12.5 fps)
constexpr int kDelay = 8;
constexpr double kShown = 2.5;             // unit-variance noise shown over +-2.5
constexpr double kFrequency = 0.125;       // cycles per pixel (NPR Gabor's default)
constexpr double kBandwidth = 0.08;        // 1/pixel
constexpr std::uint8_t kLevelMask = 0xf8;  // 32 grey levels: smaller GIFs, same look

struct scene_frames {
  hs::scene s;
  std::vector<hs::gbuffer> g;
  std::vector<hs::triangle_frame> t;
};

scene_frames render_frames(const std::string& name) {
  scene_frames f{hs::make_scene(name), {}, {}};
  for (int i = 0; i < kFrames; ++i) {
    f.g.push_back(hs::render_cpu(f.s, i, int(kW), int(kH)));
    f.t.push_back(hs::project_triangles(f.s, i, int(kW), int(kH)));
  }
  return f;
}

gray_image shown(const std::vector<float>& v, const hs::gbuffer& g) {
  return noise_on_surfaces(v, g, kShown);
}

// Object-space units per pixel in the first frame: the median distance between the
// positions of horizontally adjacent pixels of one object (what makes the texture-mapped
// noise start at the same screen frequency as the others).
double units_per_pixel(const hs::gbuffer& g) {
  std::vector<double> d;
  for (std::size_t y = 0; y < kH; ++y)
    for (std::size_t x = 0; x + 1 < kW; ++x) {
      const std::size_t p = y * kW + x;
      if (!g.covered(p) || g.object_id[p] != g.object_id[p + 1]) continue;
      double s = 0;
      for (std::size_t c = 0; c < 3; ++c) {
        const double e = g.position[3 * (p + 1) + c] - g.position[3 * p + c];
        s += e * e;
      }
      if (s > 0) d.push_back(std::sqrt(s));
    }
  if (d.empty()) return 1.0;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

// Figure 1: shower door | texture mapping | NPR Gabor noise, isotropic, same screen frequency.
std::vector<gray_image> figure1(const std::string& name) {
  const scene_frames f = render_frames(name);
  hush::gabor<2>::params p2;
  p2.seed = 3;
  p2.frequency = kFrequency;
  p2.bandwidth = kBandwidth;
  const hush::gabor<2> door(p2);
  const double u = units_per_pixel(f.g[0]);
  hush::gabor<3>::params q;
  q.seed = 3;
  q.frequency = kFrequency / u;
  q.bandwidth = kBandwidth / u;
  const hush::gabor<3> texture(q);
  hush::npr_gabor::params pn;
  pn.seed = 3;
  pn.isotropic = true;
  const hush::npr_gabor npr(pn);
  std::vector<gray_image> frames;
  std::vector<float> a(kW * kH), b(kW * kH), c(kW * kH);
  for (int i = 0; i < kFrames; ++i) {
    const hs::gbuffer& g = f.g[std::size_t(i)];
    for (std::size_t y = 0; y < kH; ++y)
      for (std::size_t x = 0; x < kW; ++x) {
        const std::size_t px = y * kW + x;
        a[px] = door.value<float>({double(x) + 0.5, double(y) + 0.5});
        b[px] = texture.value<float>(
            {g.position[3 * px], g.position[3 * px + 1], g.position[3 * px + 2]});
      }
    npr.render(hush::exec::simd, hs::as_frame(g), f.t[std::size_t(i)].view(),
               hush::image_view<float>(c.data(), kW, kH));
    gray_image img = side_by_side(side_by_side(shown(a, g), shown(b, g)), shown(c, g));
    for (std::uint8_t& v : img.pixels) v &= kLevelMask;
    frames.push_back(std::move(img));
  }
  return frames;
}

// The styled entries' noise: F0 = 0.2 cycle/px, a = 0.12 /px, seed 7.
hush::npr_gabor::params style_params() {
  hush::npr_gabor::params p;
  p.seed = 7;
  p.frequency = 0.2;
  p.bandwidth = 0.12;
  return p;
}

hush::image_view<const hush::vec3> normals_of(const hs::gbuffer& g) {
  return {reinterpret_cast<const hush::vec3*>(g.normal.data()), kW, kH};
}

gray_image red_channel(const std::vector<std::uint8_t>& rgb) {
  gray_image img(kW, kH);
  for (std::size_t p = 0; p < kW * kH; ++p) img.pixels[p] = rgb[3 * p];
  return img;
}

// The four grey styles in a 2 x 2 grid: hatching | stippling; crosshatch | graphite. On the
// rotate scene only, to keep the gallery short (the walkthrough's huge ground triangles no
// longer cost points off screen: stage 1 culls their point trees).
// The layers are splatted by exec::simd (within the float budget of the scalar image). The
// anisotropic layers follow the principal curvature (npr_field::curvature): on the torus the
// strokes run along the tube everywhere, where the projected normal is undefined on the
// tube's camera-facing crest and there falls back to the constant orientation (horizontal
// strokes cutting across the tube); flat parts (the backdrop) fall back to the projected
// normal either way.
std::vector<gray_image> styles(const std::string& name) {
  const scene_frames f = render_frames(name);
  const hush::npr_gabor::params p = style_params();
  std::vector<npr_stylizer> st;
  for (npr_style s :
       {npr_style::hatching, npr_style::stippling, npr_style::crosshatch, npr_style::graphite}) {
    npr_style_options o;
    o.style = s;
    o.field = npr_field::curvature;
    st.emplace_back(p, o);
  }
  std::vector<gray_image> frames;
  std::vector<std::uint8_t> rgb;
  for (int i = 0; i < kFrames; ++i) {
    const hs::gbuffer& g = f.g[std::size_t(i)];
    std::vector<gray_image> panel;
    for (npr_stylizer& s : st) {
      s.draw(true, hs::as_frame(g), f.t[std::size_t(i)].view(), normals_of(g), rgb);
      panel.push_back(red_channel(rgb));
    }
    const gray_image top = side_by_side(panel[0], panel[1]);
    const gray_image bottom = side_by_side(panel[2], panel[3]);
    gray_image img(top.width, 2 * kH);
    std::copy(top.pixels.begin(), top.pixels.end(), img.pixels.begin());
    std::copy(bottom.pixels.begin(), bottom.pixels.end(),
              img.pixels.begin() + static_cast<std::ptrdiff_t>(top.pixels.size()));
    frames.push_back(std::move(img));
  }
  return frames;
}

// The watercolour style (one isotropic layer overlaid on each object's pigment times the
// tone), in colour: the GIF dithers it to a fixed palette (gif::encode_rgb).
std::vector<rgb_image> watercolour(const std::string& name) {
  const scene_frames f = render_frames(name);
  npr_style_options o;
  o.style = npr_style::watercolor;
  o.gain = 0.5;
  npr_stylizer st(style_params(), o);
  std::vector<rgb_image> frames;
  for (int i = 0; i < kFrames; ++i) {
    const hs::gbuffer& g = f.g[std::size_t(i)];
    rgb_image img(kW, kH);
    st.draw(true, hs::as_frame(g), f.t[std::size_t(i)].view(), normals_of(g), img.pixels);
    frames.push_back(std::move(img));
  }
  return frames;
}

}  // namespace

std::vector<gallery_item> npr_gallery_items() {
  return {
      {"npr_fig1_rotate.gif",
       "Benard et al. Fig. 1, rotate scene, 24 frames: 2D Gabor noise (shower door) | Gabor "
       "noise of the object-space position (texture mapping) | NPR Gabor noise; isotropic, "
       "F0 = 1/8 cycle/px",
       [] { return figure1("rotate"); }, kDelay},
      {"npr_fig1_walkthrough.gif", "the same comparison on the walkthrough scene",
       [] { return figure1("walkthrough"); }, kDelay},
      {"npr_styles_rotate.gif",
       "NPR Gabor styles, rotate scene: hatching | stippling; cross-hatching | graphite (tone "
       "from N.L, strokes along the principal curvature)",
       [] { return styles("rotate"); }, kDelay},
      {"npr_watercolor_rotate.gif",
       "NPR Gabor watercolour style, rotate scene (isotropic layer overlaid on each object's "
       "pigment times the N.L tone, gain 0.5; colour GIF: 6x7x6 palette, ordered dithering)",
       nullptr, kDelay, [] { return watercolour("rotate"); }},
  };
}

#else
std::vector<gallery_item> npr_gallery_items() { return {}; }
#endif

}  // namespace hush_cli
