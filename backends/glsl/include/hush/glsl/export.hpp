// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The files `hush glsl-export DIR` writes, for engines that compile their own
// shaders: the function library and the kits for the user's shader (no #version line,
// so the engine prepends its own: 330 core or later, Vulkan 450, ES 3.00 where the
// file says so) and the complete shaders hush::glsl::device and the renderers use
// (#version 430 core; each compiles for Vulkan too, its Vulkan bindings in its header
// comment, hush/glsl/dialect.hpp). The library and the complete shaders start with a
// comment naming the hush version and how to use them.
#ifndef HUSH_GLSL_EXPORT_HPP
#define HUSH_GLSL_EXPORT_HPP

#include <string>
#include <tuple>
#include <vector>

#include "hush/glsl/compute_source.hpp"
#include "hush/glsl/library.hpp"
#include "hush/glsl/noise_program.hpp"

// The scene-driven noises' renderer sources, detail::renderer_exports(): the renderers
// part of the GLSL layer's list of noises.
#define HUSH_GLSL_NOISES_RENDERERS
#include "hush/glsl/noises.hpp"
#undef HUSH_GLSL_NOISES_RENDERERS

// Each noise's functions for the user's shader, detail::shader_exports(): the shaders part.
#define HUSH_GLSL_NOISES_SHADERS
#include "hush/glsl/noises.hpp"
#undef HUSH_GLSL_NOISES_SHADERS

namespace hush {
namespace glsl {

// One file of the export: its name and its complete text.
struct export_file {
  std::string name;     // file name, no directory
  std::string content;  // the text, ending in a newline
};

namespace detail {

// The runners of Noise: every (layout, values or gradients) hush::glsl::device runs.
template <class Noise>
void add_runners(std::vector<export_file>& files) {
  static_assert(has_program_v<Noise>, "program_noises lists only noises with a noise_program");
  for (batch_layout layout : {batch_layout::points, batch_layout::grid, batch_layout::samples}) {
    if (layout == batch_layout::samples && !has_samples_runner<Noise>()) continue;
    for (bool gradient : {false, true})
      files.push_back({runner_name<Noise>(layout, gradient) + ".comp",
                       compute_source<Noise>(layout, gradient)});
  }
}

template <class... Noise>
void add_all_runners(std::vector<export_file>& files, const std::tuple<Noise...>*) {
  (add_runners<Noise>(files), ...);
}

}  // namespace detail

// hush_noise.glsl, then for every noise with a GLSL program (program_noises in the GLSL
// layer's list of noises, hush/glsl/noises.hpp: perlin2, perlin3, fractal_perlin2,
// fractal_perlin3, wavelet2, wavelet3, gabor2, gabor3, anisotropic) its runners
// hush_<noise>_<points|grid>[_gradient].comp and, for the noises that take
// per-sample inputs (wavelet, gabor, anisotropic),
// hush_<noise>_samples[_gradient].comp (positions with optional footprints, normals
// and surface maps, compute_source.hpp's samples layout: one runner for every
// combination, told apart by its uniforms), and then every scene-driven noise's sources
// (detail::renderer_exports, the same list's renderers):
// hush_coherent_pass.comp (one pass of coherent noise, hush/glsl/coherent/glsl.hpp), and
// hush_npr_gabor_splat.vert, .geom, .frag (NPR Gabor noise's point sprites, one program,
// hush/glsl/npr_gabor/glsl.hpp) and hush_npr_gabor_lods.comp, _scan.comp, _roots.comp,
// _expand.comp, _children.comp, _records.comp (its stage 1: the compute passes that walk
// each triangle's point sequence level by level and write the records the sprites draw) and
// _plan.comp (the GPU-resident walk's counts and indirect commands, frame.hpp).
inline std::vector<export_file> export_files() {
  std::vector<export_file> files;
  files.push_back(
      {"hush_noise.glsl",
       "// hush " HUSH_VERSION_STRING " GLSL noise library, written by `hush glsl-export`.\n"
       "//\n"
       "// Usage: prepend your own #version line (330 core or later, 450 for Vulkan, or\n"
       "// 300 es; any shader stage):\n"
       "//   #version 330 core\n"
       "//   #include or paste this file\n"
       "//   float n = hush_perlin3(p, hush_seed_key(7u), uvec3(0u));  // in [-1, 1]\n"
       "// Keys: hush_seed_key(seed) equals hush::seed_key(seed) on the CPU, so a\n"
       "// shader and hush::perlin<D>{seed} give the same field. Periods: uvecD,\n"
       "// 0 = not periodic. The *_gradient functions return (value, gradient).\n"
       "// Hashes equal the CPU bit for bit; values are within 2^-16 of hush's\n"
       "// double reference where float +, -, * are correctly rounded (tested on\n"
       "// llvmpipe), 2^-15 where they err by up to 2 ulp; hush/glsl/library.hpp\n"
       "// derives the bounds. The *.comp files beside this one are the batch runners of\n"
       "// hush::glsl::device (interface: hush/glsl/compute_source.hpp; #version 430 core,\n"
       "// and Vulkan with the bindings each states in its header comment); the\n"
       "// hush_fractal_perlin* runners (fBm, turbulence) read band coordinates split on\n"
       "// the CPU (hush::fractal::band_position, hush::lattice_split<float>); so do the\n"
       "// hush_wavelet* runners (hush::wavelet::band_position), which also read the tile at\n"
       "// SSBO binding 5 (and variants at 6, the distribution table at 7), the hush_gabor*\n"
       "// runners (hush::gabor, cells of p / r; in 3D also p / (r sqrt(3/2)), the surface\n"
       "// process) and the hush_anisotropic* runners (hush::anisotropic, a band per scale),\n"
       "// which sample the tiles as RGBA32F textures hush_tile0 and hush_tile1. Runner names:\n"
       "// hush_<noise>_<points|grid|samples>[_gradient].comp; the *_samples runners (noises\n"
       "// that filter or take normals) read per-sample footprints at SSBO binding 2,\n"
       "// normals at 3, surface maps at 4, each where its hush_has_* uniform is 1u\n"
       "// (anisotropic: the CPU-formed per-sample data at 5 instead). The wavelet\n"
       "// functions of this library exist where the shader defines HUSH_WAVELET_TILE(i)\n"
       "// before it (hush/glsl/wavelet/glsl.hpp).\n"
       "// Regenerate with the same hush version instead of editing by hand.\n"
       "// GLSL ES 3.00 has no default float precision in fragment shaders: highp here.\n"
       "#ifdef GL_ES\nprecision highp float;\nprecision highp int;\n#endif\n" +
           library()});
  detail::add_all_runners(files, static_cast<const program_noises*>(nullptr));
  // The scene-driven noises' renderer sources, from each noise's hush/glsl/<noise>/glsl.hpp.
  for (const auto& exports : detail::renderer_exports())
    for (const auto& [name, text] : exports) files.push_back({name, text});
  // The functions for the user's shader, from each noise's hush/glsl/<noise>/shader.hpp.
  for (const auto& exports : detail::shader_exports())
    for (const auto& [name, text] : exports) files.push_back({name, text});
  return files;
}

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_EXPORT_HPP
