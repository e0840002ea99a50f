// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::glsl::noise_program<Noise>: what the GL runner needs to know about a
// noise type, so that later noises plug into hush::glsl::device without
// touching it. A specialisation provides
//   static constexpr int dimension;            D, the position's dimension
//   static constexpr const char* name;         program name, e.g. "perlin2"
//   static std::string uniforms();             GLSL uniform declarations of its params
//   static std::string point_call(bool grad);  expression of `p` (vecD): float, or
//                                              vec(D+1) (value, gradient) when grad
//   static std::string cells_call(bool grad);  the same of `i0`, `i1` (uvecD), `f` (vecD)
//   static std::uint32_t period(const Noise&, int axis);  lattice period (0 = none),
//                                              for the CPU-side split of grid axes
//   static void set_uniforms(const detail::gl_api&, detail::gl_uint program, const Noise&);
// A noise that takes per-sample inputs (core/samples.hpp: footprints, normals)
// also provides
//   static std::string sample_call(bool grad); the same of `p` (vecD), `fp` (matD,
//                                              the footprint matrix S; zero when
//                                              not given), `nrm` (vec3) and `has_nrm`
// for the samples layout (compute_source.hpp); banded noises see fp, nrm and
// has_nrm in band_begin, band_step and band_result instead.
// A *banded* noise (a sum over bands of a lattice noise, e.g. hush::fractal)
// declares `static constexpr bool banded = true` and, instead of point_call
// and cells_call and period:
//   static int band_count(const Noise&);
//   static std::uint32_t band_period(const Noise&, int band, int axis);
//   static vec<double, D> band_position(const Noise&, int band, const vec<double, D>& p);
//                                              the band's lattice position of p, in
//                                              double; component a depends on p[a] only
//   static std::string band_begin(bool grad);  GLSL statements before the band loop
//   static std::string band_step(bool grad);   statements of `b` (uint band),
//                                              `i0`, `i1` (uvecD), `f` (vecD)
//   static std::string band_result(bool grad); the result: float or vec(D+1)
// (In the samples layout HUSH_SAMPLES is #defined, so band_begin can tell
// whether fp, nrm and has_nrm exist; in the grid layout HUSH_GRID, so it can
// tell a grid's samples from points.)
// The runner then splits every band coordinate on the CPU in double
// (hush::lattice_split<float>) for points and grids alike (compute_source.hpp).
// A noise whose evaluation reads large precomputed data (wavelet tiles,
// anisotropic subband tiles) may also provide
//   static std::string preamble();             GLSL emitted before the function library
//                                              (e.g. its SSBO declarations and the
//                                              macros the library's bodies read them by)
//   static std::vector<data_buffer> data_buffers(const Noise&);
//                                              the SSBOs the program reads, at bindings
//                                              >= kFirstDataBinding (0 ... 4 are the
//                                              runner's): each with its bytes and an
//                                              owner identity (data_buffer below)
// hush::glsl::device uploads a data buffer the first time it sees its owner at a
// binding and keeps it there: evaluating any number of noises that share one
// tile uploads it once per device; a different owner (another tile, or a new
// one at a reused address after the old was freed) is uploaded again.
// A noise whose per-sample state is best formed on the CPU in double (e.g.
// quadratic forms that cancel in float) may provide, for the samples layout,
//   static constexpr unsigned sample_data_binding;  its SSBO binding: >= kFirstDataBinding
//                                              and none of its data_buffers' bindings
//   static std::size_t sample_data_floats(const Noise&);  floats per sample (> 0)
//   static void sample_data(const Noise&, const sample_input<D>& in, float* out);
//                                              sample `in`'s floats into out
// The device fills them per batch and uploads them to that binding, sample n's
// at [n * sample_data_floats, (n + 1) * sample_data_floats) (batches split so
// that the buffer fits GL_MAX_SHADER_STORAGE_BLOCK_SIZE); the points and grid
// layouts have none (HUSH_SAMPLES is not defined there). When that data carries
// all the program needs of the footprints, normals and maps, it declares
//   static constexpr bool reads_sample_inputs = false;
// and the device uploads none of them (bindings 2 to 4 hold a dummy), the runner
// reads none (fp, nrm and smap keep their defaults); has_nrm and has_smap still
// say whether they were given.
// A noise may instead (or also) provide
//   static std::vector<noise_texture> textures(const Noise&);
// 2D RGBA32F textures, sampled with hardware bilinear filtering and repeat
// wrapping, that the device uploads once per owner (cached while the owner
// lives) and binds to texture units 0, 1, ... before every dispatch, setting
// each sampler2D uniform to its unit.
// The runner validates nothing about a noise: noise objects are valid by construction.
// Every noise type with a specialisation is listed once, in program_noises (the GLSL
// layer's list of noises, hush/glsl/noises.hpp, included at the end of this file):
// `hush glsl-export` writes the runners of exactly those.
#ifndef HUSH_GLSL_NOISE_PROGRAM_HPP
#define HUSH_GLSL_NOISE_PROGRAM_HPP

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "hush/glsl/detail/gl.hpp"

namespace hush {
namespace glsl {

// The first SSBO binding free for a noise's data (bindings 0 ... 4 are the runner's
// input, output, footprints, normals and surface maps; compute_source.hpp).
constexpr unsigned kFirstDataBinding = 5;

// One SSBO a noise program reads (noise_program::data_buffers): `bytes` bytes at
// `data`, bound at `binding`. `owner` identifies the data and keeps it alive while
// the device may still upload it: the device compares owners, never contents.
struct data_buffer {
  unsigned binding = kFirstDataBinding;
  const void* data = nullptr;
  std::size_t bytes = 0;
  std::shared_ptr<const void> owner;
};

// A 16-byte buffer of zeros for a binding a program declares but does not read
// with these parameters (every declared SSBO must have a buffer bound).
inline data_buffer unused_data_buffer(unsigned binding) {
  static const auto zeros = std::make_shared<const std::array<float, 4>>();
  return {binding, zeros->data(), sizeof(*zeros), zeros};
}

// A texture a noise program samples (see the file comment).
struct noise_texture {
  std::string sampler;                       // name of the sampler2D uniform
  std::size_t width = 0, height = 0;         // in texels
  std::shared_ptr<const void> owner;         // the data's owner: cache identity and lifetime
  int index = 0;                             // which of the owner's textures this is
  std::function<std::vector<float>()> rgba;  // width * height * 4 floats, row-major
};

// Primary template: not a GLSL-capable noise (no specialisation).
template <class Noise>
struct noise_program;

// Whether noise_program<Noise> is banded (declares banded = true).
template <class Program, class = void>
struct is_banded : std::false_type {};
template <class Program>
struct is_banded<Program, std::void_t<decltype(Program::banded)>>
    : std::integral_constant<bool, Program::banded> {};

// Whether a program declares preamble() (GLSL before the library) and data_buffers().
template <class Program, class = void>
struct has_preamble : std::false_type {};
template <class Program>
struct has_preamble<Program, std::void_t<decltype(Program::preamble())>> : std::true_type {};
template <class Noise, class = void>
struct has_data_buffers : std::false_type {};
template <class Noise>
struct has_data_buffers<
    Noise, std::void_t<decltype(noise_program<Noise>::data_buffers(std::declval<const Noise&>()))>>
    : std::true_type {};

// Whether a program declares per-sample data (sample_data_floats, sample_data).
template <class Noise, class = void>
struct has_sample_data : std::false_type {};
template <class Noise>
struct has_sample_data<Noise, std::void_t<decltype(noise_program<Noise>::sample_data_floats(
                                  std::declval<const Noise&>()))>> : std::true_type {};

// Whether the runner uploads and reads the samples layout's footprints, normals and
// maps for Noise: unless its program declares reads_sample_inputs = false.
template <class Noise, class = void>
struct reads_sample_inputs : std::true_type {};
template <class Noise>
struct reads_sample_inputs<Noise, std::void_t<decltype(noise_program<Noise>::reads_sample_inputs)>>
    : std::bool_constant<noise_program<Noise>::reads_sample_inputs> {};

// Whether a program declares sample_call (per-sample footprints and normals).
template <class Program, class = void>
struct has_sample_call : std::false_type {};
template <class Program>
struct has_sample_call<Program, std::void_t<decltype(Program::sample_call(false))>>
    : std::true_type {};

// Whether a program declares textures(noise).
template <class Program, class Noise, class = void>
struct has_textures : std::false_type {};
template <class Program, class Noise>
struct has_textures<Program, Noise,
                    std::void_t<decltype(Program::textures(std::declval<const Noise&>()))>>
    : std::true_type {};

// True when the GLSL backend has a program for Noise (noise_program is
// specialised for it), e.g. to pick a backend at compile time.
template <class Noise, class = void>
struct has_program : std::false_type {};
template <class Noise>
struct has_program<Noise, std::void_t<decltype(sizeof(noise_program<Noise>))>> : std::true_type {};
template <class Noise>
inline constexpr bool has_program_v = has_program<Noise>::value;

}  // namespace glsl
}  // namespace hush

// The programs of the noises, each in its folder hush/glsl/<noise>/ (each includes this
// header first), and program_noises: the programs part of the GLSL layer's list of noises.
#define HUSH_GLSL_NOISES_PROGRAMS
#include "hush/glsl/noises.hpp"  // IWYU pragma: export
#undef HUSH_GLSL_NOISES_PROGRAMS

#endif  // HUSH_GLSL_NOISE_PROGRAM_HPP
