// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The GLSL layer's list of noises: the one shared file a noise's GLSL registers in
// (docs/design.md "Adding a noise"). A noise's folder hush/glsl/<noise>/ defines its GLSL;
// this file names it, a line or two in each list that applies:
//   library    its library functions (<noise>/glsl.hpp), in library order:
//              detail::noise_bodies(), which library_bodies() appends (library.hpp)
//   programs   its public header, its <noise>/program.hpp and its noise types: program_noises,
//              which `hush glsl-export` and the tests enumerate (noise_program.hpp)
//   renderers  a scene-driven noise's renderer sources (<noise>/glsl.hpp's exports), in export
//              order: detail::renderer_exports(), which export_files() appends (export.hpp)
//   shaders    its functions for the user's shader (<noise>/shader.hpp: shader_for(noise) and
//              the kit sources): detail::shader_exports(), which export_files() appends
//
// The three lists sit at three heights of the include graph: the library's bodies include
// nothing, a program.hpp includes noise_program.hpp first, and a renderer's sources include
// library.hpp and compute_source.hpp, which includes both. One include guard would put them
// all at the lowest height, and a cycle through the renderers' sources. So each list is a part
// with its own include guard (HUSH_GLSL_NOISES_<PART>_PART), which the header that derives the
// list selects: it defines HUSH_GLSL_NOISES_<PART>, includes this file and undefines it.
// Included with no part selected, this file includes export.hpp, which includes every part.

#if !defined(HUSH_GLSL_NOISES_LIBRARY) && !defined(HUSH_GLSL_NOISES_PROGRAMS) && \
    !defined(HUSH_GLSL_NOISES_RENDERERS) && !defined(HUSH_GLSL_NOISES_SHADERS)
#include "hush/glsl/export.hpp"
#endif

// ---- Library: each noise's GLSL library functions (hush/glsl/library.hpp).
#if defined(HUSH_GLSL_NOISES_LIBRARY) && !defined(HUSH_GLSL_NOISES_LIBRARY_PART)
#define HUSH_GLSL_NOISES_LIBRARY_PART

#include <string>

#include "hush/glsl/fractal/glsl.hpp"
#include "hush/glsl/gabor/glsl.hpp"
#include "hush/glsl/perlin/glsl.hpp"
#include "hush/glsl/wavelet/glsl.hpp"

namespace hush {
namespace glsl {
namespace detail {

// The noises' library functions, after hashing and the lattice split (library_bodies()).
inline std::string noise_bodies() {
  return std::string(kPerlinBody) + kFractalBody + wavelet_body() + kGaborBody;
}

}  // namespace detail
}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_NOISES_LIBRARY_PART

// ---- Programs: each noise's batch runner (hush/glsl/noise_program.hpp).
#if defined(HUSH_GLSL_NOISES_PROGRAMS) && !defined(HUSH_GLSL_NOISES_PROGRAMS_PART)
#define HUSH_GLSL_NOISES_PROGRAMS_PART

#include <tuple>

// The noises' public headers first: a program.hpp included first reaches this part through
// noise_program.hpp before it includes its noise's header.
#include "hush/anisotropic.hpp"
#include "hush/fractal.hpp"
#include "hush/gabor.hpp"
#include "hush/perlin.hpp"
#include "hush/wavelet.hpp"

#include "hush/glsl/anisotropic/program.hpp"
#include "hush/glsl/fractal/program.hpp"
#include "hush/glsl/gabor/program.hpp"  // IWYU pragma: export
#include "hush/glsl/perlin/program.hpp"
#include "hush/glsl/wavelet/program.hpp"

namespace hush {
namespace glsl {

// Every noise type that has a noise_program: the one list that `hush glsl-export`
// (export.hpp) and the tests enumerate, so that a new program is exported with it.
using program_noises = std::tuple<perlin<2>, perlin<3>, fractal<perlin<2>>, fractal<perlin<3>>,
                                  wavelet<2>, wavelet<3>, gabor<2>, gabor<3>, anisotropic>;

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_NOISES_PROGRAMS_PART

// ---- Renderers: each scene-driven noise's sources (hush/glsl/export.hpp).
#if defined(HUSH_GLSL_NOISES_RENDERERS) && !defined(HUSH_GLSL_NOISES_RENDERERS_PART)
#define HUSH_GLSL_NOISES_RENDERERS_PART

#include <string>
#include <utility>
#include <vector>

#include "hush/glsl/coherent/glsl.hpp"
#include "hush/glsl/npr_gabor/glsl.hpp"

namespace hush {
namespace glsl {
namespace detail {

// The files `hush glsl-export` writes for each scene-driven noise after the runners, as
// (file name, text), in export order.
inline std::vector<std::vector<std::pair<std::string, std::string>>> renderer_exports() {
  return {coherent_exports(), npr_gabor_exports()};
}

}  // namespace detail
}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_NOISES_RENDERERS_PART

// ---- Shaders: each noise's functions for the user's shader (hush/glsl/shader.hpp).
#if defined(HUSH_GLSL_NOISES_SHADERS) && !defined(HUSH_GLSL_NOISES_SHADERS_PART)
#define HUSH_GLSL_NOISES_SHADERS_PART

#include <string>
#include <utility>
#include <vector>

#include "hush/glsl/shader.hpp"
#include "hush/glsl/anisotropic/shader.hpp"
#include "hush/glsl/fractal/shader.hpp"
#include "hush/glsl/gabor/shader.hpp"
#include "hush/glsl/perlin/shader.hpp"
#include "hush/glsl/wavelet/shader.hpp"

namespace hush {
namespace glsl {
namespace detail {

// The files `hush glsl-export` writes for the user's shader, as (file name, text), in export
// order: each noise's <noise>_shader_exports() (hush_<noise>_shader.glsl files).
inline std::vector<std::vector<std::pair<std::string, std::string>>> shader_exports() {
  return {perlin_shader_exports(), fractal_shader_exports(), wavelet_shader_exports(),
          gabor_shader_exports(), anisotropic_shader_exports()};
}

}  // namespace detail
}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_NOISES_SHADERS_PART
