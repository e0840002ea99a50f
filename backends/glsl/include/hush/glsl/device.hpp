// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::glsl::device: batch evaluation of hush noises with GLSL 4.30 compute
// shaders, in any OpenGL >= 4.3 context current on the calling thread.
//
//   hush::glsl::osmesa_context ctx;                      // or the application's context
//   hush::glsl::device dev{ctx.loader()};                // or glfwGetProcAddress, ...
//   hush::evaluate(p, hush::exec::glsl{dev}, points, out);
//   hush::evaluate_grid(p, hush::exec::glsl{dev}, grid, out, gradients);
//
// GL functions come from the loader (name -> address); no GL library is linked.
// The device compiles one program per (noise, values or gradients, points, grid
// or samples) on first use and caches it, uploads the inputs to SSBOs, dispatches in
// chunks of at most GL_MAX_COMPUTE_WORK_GROUP_COUNT groups, splits batches
// larger than GL_MAX_SHADER_STORAGE_BLOCK_SIZE, and reads the results back
// (synchronously). It leaves the current program, the generic
// GL_SHADER_STORAGE_BUFFER binding and the active texture unit as it found
// them. It rebinds the indexed SSBO bindings 0 to 4 (the runner's), the
// bindings of the noises' own data (5 and up: noise_program::data_buffers,
// e.g. wavelet tiles, and noise_program::sample_data, e.g. the anisotropic
// weights' per-sample inputs) and, for noises with textures (noise_program::textures),
// the GL_TEXTURE_2D binding of texture units 0 ... n-1. Data buffers and
// textures are uploaded once per owner (e.g. a shared tile) and kept while it
// stays the same (data_uploads() counts the buffer uploads); their sizes are
// checked against GL_MAX_SHADER_STORAGE_BLOCK_SIZE and GL_MAX_TEXTURE_SIZE, the
// texture count against GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS
// (hush::invalid_argument when they do not fit).
//
// Accuracy (tests/glsl/glsl_test.cpp; see also hush/glsl/library.hpp):
//  - points: the float position as given, split exactly on the GPU; grids: each
//    axis position grid::coordinate(axis, i) is formed and split into cell and fraction
//    in double on the CPU (hush::lattice_split<float>, exactly as the scalar
//    grid path does), so far-from-origin grids (1e6, -1e9) and negative steps
//    lose nothing: cells and fractions equal the CPU's bit for bit.
//  - hashes are bit-identical to the CPU; the remaining float arithmetic
//    follows the CPU's order, with GLSL's freedom to fuse multiply-adds
//    (hush/glsl/library.hpp derives the bounds). Tolerance, tested on
//    llvmpipe: values within 2^-16 (1.5e-5) of the double reference and
//    2^-15 of the CPU float path; gradients within 2^-16 (1 + L), L the
//    noise's Lipschitz bound (L = 7.3 in 2D, 10.0 in 3D). On GPUs whose float
//    ops err by up to 2 ulp, twice that. Measured on llvmpipe (Mesa 22.3.6):
//    values max 1.8e-6 / RMS 2e-7 from the double reference, gradients max
//    4.8e-6; Perlin 3D equals the CPU float path bit for bit there, 2D within
//    2.1e-7 (fused multiply-adds). Measured on an NVIDIA H100 (driver
//    580.159.04, EGL, tools/gpu_rows.sh): values max 8.9e-7 from the double
//    reference and 1.6e-6 from the CPU float path, gradients 2.9e-6 and 5.4e-6.
//    GLSL lets a GPU flush subnormal floats to zero (NVIDIA does): a point
//    coordinate below 2^-126 in magnitude may then split as +-0 would, a move
//    of at most 2^-126 (the lattice split is otherwise bit for bit the CPU's).
//  - fractal sums (hush::fractal<hush::perlin<D>>, fBm and turbulence): every
//    band coordinate f_i x + o_i of every point and grid sample is formed and
//    split in double on the CPU (fractal::band_position, lattice_split<float>),
//    as the CPU float path does, and uploaded as (i0, i1, fraction) triples:
//    3 D words per band per point, nb (nx + ny [+ nz]) triples per grid.
//    The GPU sums the bands in the CPU's order with the CPU's float weights.
//    Tolerance (derived in tests/fractal/glsl_fractal_test.cpp), K = scale(),
//    w_i, f_i the raw weights and frequencies, nb the band count:
//      values    within K sum|w_i|     (2^-16 + (nb + 4) 2^-24) of the double reference,
//      gradients within K sum|w_i| f_i (2^-16 + (nb + 4) 2^-24) (1 + L),
//    and twice that of the CPU float path, at any position (no float band
//    position is formed on the GPU). Measured on llvmpipe: default fBm values
//    max 5.9e-6 from the double reference, 8.3e-7 from the CPU float path in
//    2D, equal to it bit for bit in 3D.
//  - samples (hush::samples: positions with per-sample footprints, normals
//    and surface maps, core/samples.hpp): positions as for points; footprints
//    (their stored float upper triangle), normals and surface maps (floats)
//    are uploaded as given, so the GPU sees the CPU's inputs bit for bit.
//    Each noise states its own tolerance for filtered evaluation.
//  - NaN or +-Inf in a point gives NaN in its value and gradient.
//
// Errors: the constructor throws std::runtime_error when an entry point is
// missing or the context is older than 4.3; evaluation throws
// std::runtime_error with the driver's log when a program does not compile or
// link, or with the GL error code when GL reports one, and
// hush::invalid_argument for a grid of 2^32 or more samples, or with more
// samples summed over its axes (times the bands of a fractal) than
// max_buffer_bytes() / 12 (11 million on llvmpipe), or when one sample's
// input or output does not fit max_buffer_bytes() (a device made with a tiny
// options::max_buffer_bytes).
// A GL error already pending when a call starts is reported by that call too.
// Not thread-safe; destroy the device while its context is still alive.
#ifndef HUSH_GLSL_DEVICE_HPP
#define HUSH_GLSL_DEVICE_HPP

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "hush/core/error.hpp"
#include "hush/core/footprint.hpp"
#include "hush/core/lattice.hpp"
#include "hush/core/samples.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/glsl/compute_source.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/noise_program.hpp"

namespace hush {
namespace glsl {

class device {
 public:
  using loader_fn = detail::loader_fn;

  // Limits below the GL ones, for tests and for sharing a GPU politely.
  struct options {
    // Work groups per glDispatchCompute; 0 = GL_MAX_COMPUTE_WORK_GROUP_COUNT[0].
    std::size_t max_groups_per_dispatch = 0;
    // Bytes per SSBO (input or output of one batch); 0 = GL_MAX_SHADER_STORAGE_BLOCK_SIZE.
    std::size_t max_buffer_bytes = 0;
  };

  // Loads the GL entry points through `loader` from the context current on
  // this thread and checks that it is OpenGL >= 4.3.
  explicit device(loader_fn loader) : device(loader, options{}) {}
  device(loader_fn loader, const options& opt) : gl_(std::make_unique<detail::gl_api>(loader)) {
    detail::gl_int major = 0, minor = 0;
    gl_->GetIntegerv(detail::kGlMajorVersion, &major);
    gl_->GetIntegerv(detail::kGlMinorVersion, &minor);
    while (gl_->GetError() != detail::kGlNoError) {
    }  // a pre-3.0 context rejects the version queries
    renderer_ = gl_->string(detail::kGlRenderer) + ", OpenGL " + gl_->string(detail::kGlVersion);
    if (major < 4 || (major == 4 && minor < 3))
      hush::detail::raise_error<std::runtime_error>(
          "hush::glsl::device: needs OpenGL >= 4.3 (compute shaders); the "
          "current context is " +
          renderer_);
    detail::gl_int groups = 0;
    gl_->GetIntegeri_v(detail::kGlMaxComputeWorkGroupCount, 0, &groups);
    long long block = 0;
    gl_->GetInteger64v(detail::kGlMaxShaderStorageBlockSize, &block);
    gl_->GetIntegerv(detail::kGlMaxShaderStorageBufferBindings, &max_bindings_);
    gl_->check("hush::glsl::device: querying limits");
    max_groups_ = static_cast<std::size_t>(groups);
    if (opt.max_groups_per_dispatch != 0)
      max_groups_ = std::min(max_groups_, opt.max_groups_per_dispatch);
    max_bytes_ = static_cast<std::size_t>(block);
    if (opt.max_buffer_bytes != 0) max_bytes_ = std::min(max_bytes_, opt.max_buffer_bytes);
    if (max_groups_ == 0 || max_bytes_ < 4 * sizeof(float))
      hush::detail::raise_error<std::runtime_error>("hush::glsl::device: the GL limits leave no room for a batch");
    gl_->GenBuffers(kBuffers, buffers_);
    gl_->check("hush::glsl::device: creating buffers");
  }
  device(const device&) = delete;
  device& operator=(const device&) = delete;
  ~device() {
    extensions_.clear();  // their GL objects go while the functions are loaded
    programs_.clear();
    gl_->DeleteBuffers(kBuffers, buffers_);
    for (const auto& d : data_) gl_->DeleteBuffers(1, &d.second.buffer);
    for (const texture_entry& t : textures_) gl_->DeleteTextures(1, &t.id);
  }

  // GL_RENDERER and GL_VERSION of the context, e.g. "llvmpipe (LLVM 15.0.6,
  // 256 bits), OpenGL 4.5 (Core Profile) Mesa 22.3.6".
  const std::string& renderer() const { return renderer_; }
  // glDispatchCompute calls made so far (tests check the chunking with it).
  std::size_t dispatches() const { return dispatches_; }
  // Noise textures uploaded so far (tests check the caching with it), and
  // the bytes of those held now.
  std::size_t texture_uploads() const { return texture_uploads_; }
  std::size_t texture_bytes() const {
    std::size_t b = 0;
    for (const texture_entry& t : textures_) b += t.owner.expired() ? 0 : t.bytes;
    return b;
  }
  // Work groups per dispatch and bytes per buffer this device uses.
  std::size_t max_groups_per_dispatch() const { return max_groups_; }
  std::size_t max_buffer_bytes() const { return max_bytes_; }
  // Uploads of noise data buffers so far (noise_program::data_buffers): a tile shared
  // by many noises is uploaded once per device.
  std::size_t data_uploads() const { return data_uploads_; }
  // The loaded GL functions (for code that adds its own shaders to the context).
  const detail::gl_api& gl() const { return *gl_; }
  // State another GLSL program keeps on this device between calls (its compiled
  // programs, framebuffer, buffers; e.g. hush/glsl/npr_gabor/renderer.hpp): made by make(),
  // a std::shared_ptr<T>, on the first call with `key`, and destroyed with the device
  // (before its GL functions are unloaded). Every call with one key must name one T.
  template <class T, class Make>
  T& extension(const std::string& key, Make make) {
    std::shared_ptr<void>& p = extensions_[key];
    if (!p) p = make();
    return *static_cast<T*>(p.get());
  }

  // Values (and, when grad is not null, gradients) of `noise` at n float
  // points: what hush::evaluate(noise, hush::exec::glsl{dev}, ...) calls.
  template <class Noise>
  void evaluate_points(const Noise& noise, const vec<float, Noise::dimension>* pts, std::size_t n,
                       float* out, vec<float, Noise::dimension>* grad) {
    constexpr int D = Noise::dimension;
    static_assert(sizeof(vec<float, D>) == D * sizeof(float), "vec<float, D> is D packed floats");
    if (n == 0) return;
    if constexpr (is_banded<noise_program<Noise>>::value) {
      banded_points(noise, pts, n, out, grad);
      return;
    }
    const state_guard guard(*gl_);
    const detail::gl_uint prog = use_program<Noise>(noise, batch_layout::points, grad != nullptr);
    const std::size_t stride = grad ? D + 1 : 1;
    const std::size_t batch = batch_samples(std::max<std::size_t>(stride, D));
    for (std::size_t first = 0; first < n; first += batch) {
      const std::size_t m = std::min(batch, n - first);
      upload(0, pts + first, m * sizeof(vec<float, D>));
      run_batch<D>(prog, m, stride, out + first, grad ? grad + first : nullptr);
    }
  }

  // Values (and gradients) of `noise` at samples s (positions with optional
  // footprints, normals and surface maps, core/samples.hpp; validated by the
  // caller): what hush::evaluate(noise, hush::exec::glsl{dev}, samples, ...)
  // calls. Footprints go to binding 2 as their stored upper triangle, normals
  // to binding 3, surface maps to binding 4 (compute_source.hpp, samples layout).
  template <class Noise>
  void evaluate_samples(const Noise& noise, const samples<Noise::dimension>& s, float* out,
                        vec<float, Noise::dimension>* grad) {
    constexpr int D = Noise::dimension;
    constexpr std::size_t kEntries = footprint<D>::kEntries;
    static_assert(sizeof(footprint<D>) == kEntries * sizeof(float),
                  "footprint<D> is its kEntries packed floats");
    const std::size_t n = s.size();
    if (n == 0) return;
    static_assert(sizeof(surface_map) == 4 * sizeof(float), "surface_map is 4 packed floats");
    if constexpr (!has_samples_runner<Noise>()) {
      evaluate_points(noise, s.positions.data(), n, out, grad);  // no extras can be given
    } else {
      using np = noise_program<Noise>;
      const bool fps = s.has_footprints(), normals = s.has_normals(), maps = s.has_surface_maps();
      const state_guard guard(*gl_);
      const detail::gl_uint prog =
          use_program<Noise>(noise, batch_layout::samples, grad != nullptr);
      gl_->Uniform1ui(gl_->GetUniformLocation(prog, "hush_has_footprint"), fps ? 1u : 0u);
      gl_->Uniform1ui(gl_->GetUniformLocation(prog, "hush_has_normal"), normals ? 1u : 0u);
      gl_->Uniform1ui(gl_->GetUniformLocation(prog, "hush_has_map"), maps ? 1u : 0u);
      const std::size_t stride = grad ? D + 1 : 1;
      std::size_t words = std::max<std::size_t>({stride, kEntries, 4});
      int bands = 0;
      if constexpr (is_banded<np>::value) {
        bands = np::band_count(noise);
        words = std::max(words, std::size_t{3} * D * static_cast<std::size_t>(bands));
        gl_->Uniform1ui(gl_->GetUniformLocation(prog, "hush_bands"),
                        static_cast<detail::gl_uint>(bands));
      }
      std::size_t data_floats = 0;
      if constexpr (has_sample_data<Noise>::value) {
        data_floats = np::sample_data_floats(noise);
        words = std::max(words, data_floats);
      }
      const std::size_t batch = batch_samples(words);
      std::vector<std::uint32_t> triples;
      const float dummy[4] = {0, 0, 0, 0};
      for (std::size_t first = 0; first < n; first += batch) {
        const std::size_t m = std::min(batch, n - first);
        if constexpr (is_banded<np>::value) {
          split_bands(noise, bands, s.positions.data() + first, m, triples);
          upload(0, triples.data(), triples.size() * sizeof(std::uint32_t));
        } else {
          upload(0, s.positions.data() + first, m * sizeof(vec<float, D>));
        }
        // Bound, never read where not given (the presence uniform is 0) or where the
        // program reads them through its sample data (reads_sample_inputs).
        constexpr bool reads = reads_sample_inputs<Noise>::value;
        if (reads && fps)
          upload(2, s.footprints.data() + first, m * sizeof(footprint<D>));
        else
          upload(2, dummy, sizeof dummy);
        if (reads && normals)
          upload(3, s.normals.data() + first, m * sizeof(vec<float, 3>));
        else
          upload(3, dummy, sizeof dummy);
        if (reads && maps)
          upload(4, s.surface_maps.data() + first, m * sizeof(surface_map));
        else
          upload(4, dummy, sizeof dummy);
        if constexpr (has_sample_data<Noise>::value)
          upload_sample_data(noise, s, first, m, data_floats);
        run_batch<D>(prog, m, stride, out + first, grad ? grad + first : nullptr);
      }
    }
  }

  // Values (and gradients) of `noise` on grid g, C order (i fastest): what
  // hush::evaluate_grid(noise, hush::exec::glsl{dev}, ...) calls.
  template <class Noise>
  void evaluate_grid(const Noise& noise, const grid<Noise::dimension>& g, float* out,
                     vec<float, Noise::dimension>* grad) {
    constexpr int D = Noise::dimension;
    g.validate("hush::glsl::device::evaluate_grid");
    const std::size_t count = g.count();
    if (count == 0) return;
    if (count > UINT32_MAX)
      hush::detail::throw_out_of_range("hush::glsl::device::evaluate_grid", "grid.count()", count,
                                       "at most 4294967295 samples per call");
    // Each axis position split in double on the CPU, exactly as the scalar
    // grid path splits it: (i0, i1, fraction bits) per sample index, in one SSBO.
    std::size_t axis_samples = 0;
    for (int a = 0; a < D; ++a) axis_samples += g.size[a];
    if constexpr (is_banded<noise_program<Noise>>::value)
      banded_grid(noise, g, axis_samples, out, grad);
    else
      plain_grid(noise, g, axis_samples, out, grad);
  }

 private:
  // Plain noises: one (i0, i1, fraction) triple per sample index and axis.
  template <class Noise>
  void plain_grid(const Noise& noise, const grid<Noise::dimension>& g, std::size_t axis_samples,
                  float* out, vec<float, Noise::dimension>* grad) {
    constexpr int D = Noise::dimension;
    require_axis_table(axis_samples, "grid.size (summed over the axes)");
    std::vector<std::uint32_t> axes(3 * axis_samples);
    std::uint32_t* w = axes.data();
    for (int a = 0; a < D; ++a) {
      const std::uint32_t period = noise_program<Noise>::period(noise, a);
      for (std::size_t i = 0; i < g.size[a]; ++i, w += 3)
        split_into(w, g.coordinate(a, i), period);
    }
    const state_guard guard(*gl_);
    const detail::gl_uint prog = use_program<Noise>(noise, batch_layout::grid, grad != nullptr);
    upload(0, axes.data(), axes.size() * sizeof(std::uint32_t));
    run_grid<D>(prog, g, D == 3 ? g.size[D - 1] : 1, out, grad);
  }

  // Banded noises (noise_program::banded): every band's coordinate of every
  // point is formed and split on the CPU in double and uploaded as
  // (i0, i1, fraction bits) triples, point-major (compute_source.hpp).
  template <class Noise>
  void banded_points(const Noise& noise, const vec<float, Noise::dimension>* pts, std::size_t n,
                     float* out, vec<float, Noise::dimension>* grad) {
    using np = noise_program<Noise>;
    constexpr int D = Noise::dimension;
    const int bands = np::band_count(noise);
    const std::size_t words = std::size_t{3} * D * static_cast<std::size_t>(bands);  // per point
    const state_guard guard(*gl_);
    const detail::gl_uint prog = use_program<Noise>(noise, batch_layout::points, grad != nullptr);
    gl_->Uniform1ui(gl_->GetUniformLocation(prog, "hush_bands"),
                    static_cast<detail::gl_uint>(bands));
    const std::size_t stride = grad ? D + 1 : 1;
    const std::size_t batch = batch_samples(std::max(stride, words));
    std::vector<std::uint32_t> triples;
    for (std::size_t first = 0; first < n; first += batch) {
      const std::size_t m = std::min(batch, n - first);
      split_bands(noise, bands, pts + first, m, triples);
      upload(0, triples.data(), triples.size() * sizeof(std::uint32_t));
      run_batch<D>(prog, m, stride, out + first, grad ? grad + first : nullptr);
    }
  }

  // Every band coordinate of m points, formed and split on the CPU in double:
  // (i0, i1, fraction bits) per point, per band, per axis, into `triples`.
  template <class Noise>
  static void split_bands(const Noise& noise, int bands, const vec<float, Noise::dimension>* pts,
                          std::size_t m, std::vector<std::uint32_t>& triples) {
    using np = noise_program<Noise>;
    constexpr int D = Noise::dimension;
    const auto nb = static_cast<std::size_t>(bands);
    std::vector<std::array<std::uint32_t, std::size_t{D}>> period(nb);
    for (std::size_t b = 0; b < nb; ++b)
      for (int a = 0; a < D; ++a)
        period[b][static_cast<std::size_t>(a)] = np::band_period(noise, static_cast<int>(b), a);
    triples.resize(m * std::size_t{3} * D * nb);
    std::uint32_t* w = triples.data();
    for (std::size_t i = 0; i < m; ++i) {
      const vec<double, D> p = vec_cast<double>(pts[i]);
      for (std::size_t b = 0; b < nb; ++b) {
        const vec<double, D> q = np::band_position(noise, static_cast<int>(b), p);
        for (int a = 0; a < D; ++a, w += 3)
          split_into(w, q[a], period[b][static_cast<std::size_t>(a)]);
      }
    }
  }

  // Banded grids: the per-axis triples of every band, band after band.
  template <class Noise>
  void banded_grid(const Noise& noise, const grid<Noise::dimension>& g, std::size_t axis_samples,
                   float* out, vec<float, Noise::dimension>* grad) {
    using np = noise_program<Noise>;
    constexpr int D = Noise::dimension;
    const int bands = np::band_count(noise);
    require_axis_table(axis_samples * static_cast<std::size_t>(bands),
                       "grid.size (summed over the axes) * bands");
    std::vector<std::uint32_t> axes(3 * axis_samples * static_cast<std::size_t>(bands));
    std::uint32_t* w = axes.data();
    for (int b = 0; b < bands; ++b)
      for (int a = 0; a < D; ++a) {
        const std::uint32_t period = np::band_period(noise, b, a);
        for (std::size_t i = 0; i < g.size[a]; ++i, w += 3) {
          // Component a of the band position depends on component a of p only.
          vec<double, D> p;
          for (int c = 0; c < D; ++c) p[c] = g.coordinate(a, i);
          split_into(w, np::band_position(noise, b, p)[a], period);
        }
      }
    const state_guard guard(*gl_);
    const detail::gl_uint prog = use_program<Noise>(noise, batch_layout::grid, grad != nullptr);
    gl_->Uniform1ui(gl_->GetUniformLocation(prog, "hush_bands"),
                    static_cast<detail::gl_uint>(bands));
    upload(0, axes.data(), axes.size() * sizeof(std::uint32_t));
    // hush_size.z is the z axis' triple count: 0 in 2D (no z triples).
    run_grid<D>(prog, g, D == 3 ? g.size[D - 1] : 0, out, grad);
  }

  // Refuses a grid whose axis table (`triples` (i0, i1, fraction) triples)
  // does not fit one SSBO.
  void require_axis_table(std::size_t triples, const char* name) const {
    const std::size_t limit = max_bytes_ / (3 * sizeof(std::uint32_t));
    if (triples > limit)
      hush::detail::throw_out_of_range(
          "hush::glsl::device::evaluate_grid", name, triples,
          ("at most " + std::to_string(limit) + " on this device (its SSBO size limit)").c_str());
  }

  // Runs grid program `prog` (axis table uploaded) over every sample of g in
  // batches; z_size is hush_size.z as the program reads it.
  template <int D>
  void run_grid(detail::gl_uint prog, const grid<D>& g, std::size_t z_size, float* out,
                vec<float, D>* grad) {
    gl_->Uniform3ui(gl_->GetUniformLocation(prog, "hush_size"),
                    static_cast<detail::gl_uint>(g.size[0]),
                    static_cast<detail::gl_uint>(g.size[1]), static_cast<detail::gl_uint>(z_size));
    const detail::gl_int base = gl_->GetUniformLocation(prog, "hush_base");
    const std::size_t stride = grad ? D + 1 : 1;
    const std::size_t batch = batch_samples(stride);
    const std::size_t count = g.count();
    for (std::size_t first = 0; first < count; first += batch) {
      gl_->Uniform1ui(base, static_cast<detail::gl_uint>(first));
      run_batch<D>(prog, std::min(batch, count - first), stride, out + first,
                   grad ? grad + first : nullptr);
    }
  }

  // (i0, i1, fraction bits) of hush::lattice_split<float>(x, period) at w.
  static void split_into(std::uint32_t* w, double x, std::uint32_t period) {
    const lattice_coord<float> c = lattice_split<float>(x, period);
    w[0] = c.i0;
    w[1] = c.i1;
    std::memcpy(&w[2], &c.f, sizeof c.f);
  }

  // Restores the caller's program, generic SSBO binding and active texture unit on scope exit.
  class state_guard {
   public:
    explicit state_guard(const detail::gl_api& gl) : gl_(gl) {
      gl.GetIntegerv(detail::kGlCurrentProgram, &program_);
      gl.GetIntegerv(detail::kGlShaderStorageBufferBinding, &buffer_);
      gl.GetIntegerv(detail::kGlActiveTexture, &unit_);
    }
    state_guard(const state_guard&) = delete;
    state_guard& operator=(const state_guard&) = delete;
    ~state_guard() {
      gl_.UseProgram(static_cast<detail::gl_uint>(program_));
      gl_.BindBuffer(detail::kGlShaderStorageBuffer, static_cast<detail::gl_uint>(buffer_));
      gl_.ActiveTexture(static_cast<detail::gl_enum>(unit_));
    }

   private:
    const detail::gl_api& gl_;
    detail::gl_int program_ = 0, buffer_ = 0, unit_ = detail::kGlTexture0;
  };

  // A noise texture uploaded to GL, valid while its owner lives.
  struct texture_entry {
    std::weak_ptr<const void> owner;
    const void* key = nullptr;
    int index = 0;
    detail::gl_uint id = 0;
    std::size_t bytes = 0;
  };

  // The GL texture of t, uploaded on first use (or after its owner changed).
  detail::gl_uint texture_of(const noise_texture& t) {
    for (auto it = textures_.begin(); it != textures_.end();) {
      if (it->owner.expired()) {  // its owner is gone: free it (the key may be reused)
        gl_->DeleteTextures(1, &it->id);
        it = textures_.erase(it);
        continue;
      }
      if (it->key == t.owner.get() && it->index == t.index) return it->id;
      ++it;
    }
    detail::gl_int max_size = 0, max_units = 0;
    gl_->GetIntegerv(detail::kGlMaxTextureSize, &max_size);
    gl_->GetIntegerv(detail::kGlMaxCombinedTextureImageUnits, &max_units);
    if (t.width == 0 || t.height == 0 || t.width > static_cast<std::size_t>(max_size) ||
        t.height > static_cast<std::size_t>(max_size))
      hush::detail::throw_out_of_range(
          "hush::glsl::device", "noise texture " + t.sampler + " width", t.width,
          ("1 ... GL_MAX_TEXTURE_SIZE = " + std::to_string(max_size)).c_str());
    const std::vector<float> rgba = t.rgba();
    texture_entry e;
    e.owner = t.owner;
    e.key = t.owner.get();
    e.index = t.index;
    e.bytes = rgba.size() * sizeof(float);
    gl_->GenTextures(1, &e.id);
    gl_->BindTexture(detail::kGlTexture2d, e.id);
    gl_->PixelStorei(detail::kGlUnpackAlignment, 4);
    gl_->TexImage2D(detail::kGlTexture2d, 0, static_cast<detail::gl_int>(detail::kGlRgba32f),
                    static_cast<detail::gl_sizei>(t.width), static_cast<detail::gl_sizei>(t.height),
                    0, detail::kGlRgba, detail::kGlFloat, rgba.data());
    for (const detail::gl_enum p : {detail::kGlTextureMinFilter, detail::kGlTextureMagFilter})
      gl_->TexParameteri(detail::kGlTexture2d, p, static_cast<detail::gl_int>(detail::kGlLinear));
    for (const detail::gl_enum p : {detail::kGlTextureWrapS, detail::kGlTextureWrapT})
      gl_->TexParameteri(detail::kGlTexture2d, p, static_cast<detail::gl_int>(detail::kGlRepeat));
    gl_->check("hush::glsl::device: uploading a noise texture");
    ++texture_uploads_;
    textures_.push_back(e);
    return e.id;
  }

  // Binds a noise's textures to units 0 ... n-1 and points its samplers at them.
  template <class Noise>
  void bind_textures(const Noise& noise, detail::gl_uint prog) {
    using np = noise_program<Noise>;
    if constexpr (has_textures<np, Noise>::value) {
      const std::vector<noise_texture> list = np::textures(noise);
      detail::gl_int max_units = 0;
      gl_->GetIntegerv(detail::kGlMaxCombinedTextureImageUnits, &max_units);
      if (list.size() > static_cast<std::size_t>(max_units))
        hush::detail::throw_out_of_range(
            "hush::glsl::device", "noise textures", list.size(),
            ("at most GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS = " + std::to_string(max_units)).c_str());
      // Upload first (an upload binds to the active unit), then bind.
      std::vector<detail::gl_uint> ids;
      ids.reserve(list.size());
      for (const noise_texture& t : list) ids.push_back(texture_of(t));
      for (std::size_t u = 0; u < list.size(); ++u) {
        gl_->ActiveTexture(detail::kGlTexture0 + static_cast<detail::gl_enum>(u));
        gl_->BindTexture(detail::kGlTexture2d, ids[u]);
        gl_->Uniform1i(gl_->GetUniformLocation(prog, list[u].sampler.c_str()),
                       static_cast<detail::gl_int>(u));
      }
    } else {
      (void)noise;
      (void)prog;
    }
  }

  // The cached program of (Noise, layout, gradient), made current with the noise's uniforms set.
  template <class Noise>
  detail::gl_uint use_program(const Noise& noise, batch_layout layout, bool gradient) {
    using np = noise_program<Noise>;
    const std::string key =
        std::string(np::name) + "/" + layout_name(layout) + (gradient ? "/gradient" : "/value");
    auto it = programs_.find(key);
    if (it == programs_.end()) {
      detail::gl_program prog = detail::link_program(
          *gl_, {{detail::kGlComputeShader, compute_source<Noise>(layout, gradient)}});
      it = programs_.emplace(key, std::move(prog)).first;
    }
    const detail::gl_uint id = it->second.id();
    gl_->UseProgram(id);
    np::set_uniforms(*gl_, id, noise);
    if constexpr (has_data_buffers<Noise>::value)
      for (const data_buffer& b : np::data_buffers(noise)) bind_data(b);
    bind_textures(noise, id);
    gl_->Uniform1ui(gl_->GetUniformLocation(id, "hush_first"), 0u);
    return id;
  }

  // Binds a noise's data buffer, uploading it unless this binding already holds the
  // same owner's data. Throws hush::invalid_argument when the binding is not one the
  // noises may use on this context or the data exceeds the SSBO size limit.
  void bind_data(const data_buffer& b) {
    const char* where = "hush::glsl::device";
    if (b.binding < kFirstDataBinding || b.binding >= static_cast<unsigned>(max_bindings_))
      hush::detail::throw_out_of_range(
          where, "data_buffer.binding", b.binding,
          (std::to_string(kFirstDataBinding) +
           " ... GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS - 1 = " + std::to_string(max_bindings_ - 1))
              .c_str());
    if (b.bytes > max_bytes_)
      hush::detail::throw_out_of_range(
          where, "data_buffer.bytes", b.bytes,
          ("at most " + std::to_string(max_bytes_) + " (this device's SSBO size limit)").c_str());
    data_slot& slot = data_[b.binding];
    if (slot.buffer == 0) gl_->GenBuffers(1, &slot.buffer);
    const bool same = !slot.owner.expired() && !slot.owner.owner_before(b.owner) &&
                      !b.owner.owner_before(slot.owner) && slot.bytes == b.bytes;
    gl_->BindBuffer(detail::kGlShaderStorageBuffer, slot.buffer);
    if (!same) {
      gl_->BufferData(detail::kGlShaderStorageBuffer, static_cast<detail::gl_sizeiptr>(b.bytes),
                      b.data, detail::kGlStaticDraw);
      slot.owner = b.owner;
      slot.bytes = b.bytes;
      ++data_uploads_;
    }
    gl_->BindBufferBase(detail::kGlShaderStorageBuffer, b.binding, slot.buffer);
  }

  // The noise's per-sample data of samples [first, first + m) of s
  // (noise_program::sample_data), formed on the CPU and bound at the program's
  // sample_data_binding, a binding no data buffer then holds.
  template <class Noise>
  void upload_sample_data(const Noise& noise, const samples<Noise::dimension>& s, std::size_t first,
                          std::size_t m, std::size_t floats) {
    using np = noise_program<Noise>;
    static_assert(np::sample_data_binding >= kFirstDataBinding,
                  "sample_data_binding is one of the noises' bindings");
    scratch_.resize(m * floats);
    for (std::size_t j = 0; j < m; ++j)
      np::sample_data(noise, s.at(first + j), scratch_.data() + j * floats);
    data_slot& slot = data_[np::sample_data_binding];
    if (slot.buffer == 0) gl_->GenBuffers(1, &slot.buffer);
    slot.owner.reset();  // per-batch data: a data buffer bound here later uploads again
    gl_->BindBuffer(detail::kGlShaderStorageBuffer, slot.buffer);
    gl_->BufferData(detail::kGlShaderStorageBuffer,
                    static_cast<detail::gl_sizeiptr>(scratch_.size() * sizeof(float)),
                    scratch_.data(), detail::kGlStreamDraw);
    gl_->BindBufferBase(detail::kGlShaderStorageBuffer, np::sample_data_binding, slot.buffer);
  }

  // Samples per batch: each buffer holds at most max_bytes_, and the
  // shader's sample indices are 32-bit.
  // Throws hush::invalid_argument when not even one sample fits a buffer
  // (a device made with a tiny options::max_buffer_bytes).
  std::size_t batch_samples(std::size_t floats_per_sample) const {
    const std::size_t bytes = floats_per_sample * sizeof(float);
    if (bytes > max_bytes_)
      hush::detail::throw_out_of_range(
          "hush::glsl::device", "max_buffer_bytes()", max_bytes_,
          ("at least " + std::to_string(bytes) + " (one sample's input or output)").c_str());
    return std::min<std::size_t>(max_bytes_ / bytes, UINT32_MAX);
  }

  void upload(int slot, const void* data, std::size_t bytes,
              detail::gl_enum usage = detail::kGlStreamDraw) {
    gl_->BindBuffer(detail::kGlShaderStorageBuffer, buffers_[slot]);
    gl_->BufferData(detail::kGlShaderStorageBuffer, static_cast<detail::gl_sizeiptr>(bytes), data,
                    usage);
    gl_->BindBufferBase(detail::kGlShaderStorageBuffer, static_cast<detail::gl_uint>(slot),
                        buffers_[slot]);
  }

  // Dispatches samples [0, m) of the current batch (input already bound) in
  // chunks of max_groups_ groups and reads the results into out (and grad).
  template <int D>
  void run_batch(detail::gl_uint prog, std::size_t m, std::size_t stride, float* out,
                 vec<float, D>* grad) {
    const std::size_t out_bytes = m * stride * sizeof(float);
    upload(1, nullptr, out_bytes, detail::kGlDynamicRead);  // leaves buffer 1 bound for reading
    gl_->Uniform1ui(gl_->GetUniformLocation(prog, "hush_count"), static_cast<detail::gl_uint>(m));
    const detail::gl_int first_loc = gl_->GetUniformLocation(prog, "hush_first");
    const std::size_t groups = (m + kLocalSize - 1) / kLocalSize;
    for (std::size_t g0 = 0; g0 < groups; g0 += max_groups_) {
      gl_->Uniform1ui(first_loc, static_cast<detail::gl_uint>(g0 * kLocalSize));
      gl_->DispatchCompute(static_cast<detail::gl_uint>(std::min(max_groups_, groups - g0)), 1u,
                           1u);
      ++dispatches_;
    }
    gl_->MemoryBarrier(detail::kGlBufferUpdateBarrierBit);
    if (!grad) {
      gl_->GetBufferSubData(detail::kGlShaderStorageBuffer, 0,
                            static_cast<detail::gl_sizeiptr>(out_bytes), out);
    } else {
      scratch_.resize(m * stride);
      gl_->GetBufferSubData(detail::kGlShaderStorageBuffer, 0,
                            static_cast<detail::gl_sizeiptr>(out_bytes), scratch_.data());
      for (std::size_t i = 0; i < m; ++i) {
        out[i] = scratch_[i * stride];
        for (int a = 0; a < D; ++a)
          grad[i][static_cast<std::size_t>(a)] =
              scratch_[i * stride + 1 + static_cast<std::size_t>(a)];
      }
    }
    gl_->check("hush::glsl::device: evaluating a batch");
  }

  std::unique_ptr<detail::gl_api> gl_;
  std::string renderer_;
  std::size_t max_groups_ = 0, max_bytes_ = 0, dispatches_ = 0;
  // SSBO bindings 0 (input), 1 (output), 2 (footprints), 3 (normals), 4 (surface maps).
  static constexpr int kBuffers = 5;
  detail::gl_uint buffers_[kBuffers] = {0, 0, 0, 0, 0};
  std::map<std::string, detail::gl_program> programs_;
  // Noise data buffers (bindings >= 5): the GL buffer and whose data it holds (none
  // for per-sample data).
  struct data_slot {
    detail::gl_uint buffer = 0;
    std::weak_ptr<const void> owner;
    std::size_t bytes = 0;
  };
  std::map<unsigned, data_slot> data_;
  std::size_t data_uploads_ = 0;
  detail::gl_int max_bindings_ = 0;
  std::vector<float> scratch_;
  std::vector<texture_entry> textures_;
  std::size_t texture_uploads_ = 0;
  std::map<std::string, std::shared_ptr<void>> extensions_;
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_DEVICE_HPP
