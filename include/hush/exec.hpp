// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Execution policies and batch evaluation: the caller picks the backend per
// call site, the noise object stays the same.
//
//   hush::perlin<3> p{7};
//   hush::evaluate(p, hush::exec::scalar, points, out);        // reference loop
//   hush::evaluate(p, hush::exec::simd, points, out);          // Highway kernels
//   hush::evaluate_grid(p, hush::exec::glsl{device}, g, out);  // GL compute shader
//
// Policies are empty tag types (Highway's sort/order.h style), except glsl,
// which carries the device it runs on (backends/glsl, hush/glsl/device.hpp).
//
// Contract of every overload:
//  - points: span of vec<float, D>; out.size() must equal points.size(), and
//    gradients (when given) too, else hush::invalid_argument naming the span.
//  - grids: grid<D> (origin and step in double); out has grid.count()
//    elements in C order, i fastest (core/views.hpp). The grid is validated.
//  - scalar: exactly noise(point) per element, in float. A noise may share
//    work between neighbouring points of a batch (detail::has_point_values:
//    bit for bit noise(point)) and between the samples of a grid
//    (detail::has_grid_values); a grid's results are point evaluation's, bit
//    for bit unless the compiler contracts multiply-adds (HUSH_STRICT_FP
//    forbids it), or within a stated bound of them where it says so (Perlin
//    and fBm 3D values with gradients: perlin.hpp grid_values; Gabor grids'
//    separable form: gabor.hpp grid_values, docs/gabor.md "Float accuracy").
//  - simd: the same values bit for bit under HUSH_STRICT_FP; otherwise within
//    the noise's float budget of the double reference (perlin, fractal:
//    hush/perlin/simd-inl.h, docs/design.md "Backends"). Without SIMD
//    configured (HUSH_CONFIG_SIMD == 0) it runs the scalar loop.
//  - glsl: within the GLSL tolerance stated by the backend
//    (backends/glsl/include/hush/glsl/device.hpp).
//  - samples (core/samples.hpp): positions plus optional per-sample
//    footprints, normals and surface maps. Each given span must have one
//    element per position, and only inputs the noise takes
//    (Noise::takes_footprint, Noise::takes_normal, Noise::takes_surface_map)
//    may be given, else hush::invalid_argument naming the span. scalar computes
//    noise.sample_value<float>(samples.at(i)); with positions only, exactly what the points
//    overload computes.
//  - parallel(inner, threads) / parallel(inner, pool): the batch split over
//    threads (started per call, or a hush::thread_pool's), each
//    running `inner` (scalar or simd) on a contiguous part: points and
//    samples in chunks, grids in slabs along the slowest axis (rows in 2D,
//    slices in 3D). Results are identical, bit for bit, to `inner` on the
//    whole batch (tests/simd/parallel_test.cpp).
//  - NaN/Inf coordinates give NaN, as in point evaluation; nothing throws
//    after validation, and no output element is left unwritten.
#ifndef HUSH_EXEC_HPP
#define HUSH_EXEC_HPP

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "hush/config.hpp"
#include "hush/core/error.hpp"
#include "hush/core/samples.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/simd/dispatch.hpp"  // detail::simd_kernel (each noise specialises it)
#include "hush/thread_pool.hpp"

namespace hush {
namespace exec {

// Plain C++ loop over the noise's point evaluation: the reference backend.
struct scalar_t {
  static constexpr const char* name = "scalar";
};
// Highway SIMD kernels, dynamically dispatched to the best compiled target
// (or statically, see hush/simd/dispatch.hpp); the scalar loop without SIMD.
struct simd_t {
  static constexpr const char* name = "simd";
};
inline constexpr scalar_t scalar{};
// Without SIMD compiled in (HUSH_CONFIG_SIMD == 0, hush/config.hpp), exec::simd runs
// the scalar loop, and naming it draws a deprecation warning that says so (code that
// never names it compiles as before, -Werror included). Defining HUSH_NO_SIMD (scalar
// on purpose) or HUSH_SIMD_ALLOW_SCALAR (exec::simd may fall back quietly) silences it.
#if HUSH_CONFIG_SIMD || defined(HUSH_NO_SIMD) || defined(HUSH_SIMD_ALLOW_SCALAR)
inline constexpr simd_t simd{};
#else
[[deprecated(
    "no SIMD compiled in: hush::exec::simd runs the scalar loop. Link hush::simd (CMake), or "
    "define HUSH_SIMD_STATIC and link Highway (-lhwy), or define HUSH_SIMD_DYNAMIC and compile "
    "hush/simd/dispatch_impl.hpp once; define HUSH_NO_SIMD or HUSH_SIMD_ALLOW_SCALAR to run "
    "scalar code without this warning")]] inline constexpr simd_t simd{};
#endif

// GLSL compute shaders on a GL device: hush::exec::glsl{device}. Device is
// any type with the batch members hush::glsl::device has; the core does not
// depend on GL.
template <class Device>
struct glsl {
  static constexpr const char* name = "glsl";
  Device& device;
};
template <class Device>
glsl(Device&) -> glsl<Device>;

// Multi-threaded batches: hush::exec::parallel(hush::exec::simd, threads)
// evaluates a batch on `threads` std::threads (0: one per hardware thread,
// std::thread::hardware_concurrency()), each running the inner policy on a
// contiguous part, and returns when all are done. Results are those of the
// inner policy on the whole batch, bit for bit: points and samples are
// evaluated independently of their neighbours, and a grid slab is the same
// rows of the same grid (the kernels take a row range, so every sample's
// position is formed exactly as in the whole-grid call). Batches too small to
// give every thread kParallelGrain samples use fewer threads.
// With a hush::thread_pool instead of a count, the pool's threads run the
// parts (no thread start per call: worth it for batches under ~1 ms; the pool
// must outlive the call, and batches on one pool run one at a time).
template <class Inner>
struct parallel_t {
  static_assert(std::is_same<Inner, scalar_t>::value || std::is_same<Inner, simd_t>::value,
                "hush::exec::parallel runs the scalar or simd policy");
  static constexpr const char* name = "parallel";
  static constexpr int kMaxThreads = 1024;
  static constexpr std::size_t kParallelGrain = 4096;  // samples per thread, at least
  Inner inner;
  unsigned threads;             // >= 1, resolved at construction
  thread_pool* pool = nullptr;  // null: threads started per call
};
// Throws hush::invalid_argument when threads is outside 0 ... 1024.
template <class Inner>
parallel_t<Inner> parallel(Inner inner, int threads = 0) {
  detail::require_in_range("hush::exec::parallel", "threads", threads, 0,
                           parallel_t<Inner>::kMaxThreads, "0 (one per hardware thread) ... 1024");
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  return {inner, threads == 0 ? hw : static_cast<unsigned>(threads), nullptr};
}
// The pool's threads (pool.size(), the calling thread included) run the parts.
template <class Inner>
parallel_t<Inner> parallel(Inner inner, thread_pool& pool) {
  return {inner, pool.size(), &pool};
}

}  // namespace exec

namespace detail {

template <class Noise>
using point_span = span<const vec<float, Noise::dimension>>;
template <class Noise>
using gradient_span = span<vec<float, Noise::dimension>>;

inline void require_same_size(const char* where, const char* name, std::size_t got,
                              std::size_t want) {
  if (got != want)
    throw_out_of_range(where, name, got,
                       ("exactly " + std::to_string(want) + " elements (one per sample)").c_str());
}

// The parallel policy's overloads (defined at the end of this namespace).
template <class Noise, class Inner>
void run_points(const Noise& n, const exec::parallel_t<Inner>& ex, point_span<Noise> pts,
                float* out, vec<float, Noise::dimension>* grad);
template <class Noise, class Inner>
void run_samples(const Noise& n, const exec::parallel_t<Inner>& ex,
                 const samples<Noise::dimension>& s, float* out,
                 vec<float, Noise::dimension>* grad);
template <class Noise, class Inner>
void run_grid(const Noise& n, const exec::parallel_t<Inner>& ex, const grid<Noise::dimension>& g,
              float* out, vec<float, Noise::dimension>* grad);

// Whether Noise evaluates batches of points itself: a member
//   void point_values(const vec<float, D>* pts, std::size_t count, float* out,
//                     vec<float, D>* grad) const;
// with exactly the values and gradients of its point evaluation, faster than the
// loop below by sharing work between neighbouring points (gabor.hpp).
template <class Noise, class = void>
struct has_point_values : std::false_type {};
template <class Noise>
struct has_point_values<
    Noise, std::void_t<decltype(std::declval<const Noise&>().point_values(
               std::declval<const vec<float, Noise::dimension>*>(), std::size_t{},
               std::declval<float*>(), std::declval<vec<float, Noise::dimension>*>()))>>
    : std::true_type {};

template <class Noise>
void scalar_points(const Noise& n, point_span<Noise> pts, float* out,
                   vec<float, Noise::dimension>* grad) {
  if constexpr (has_point_values<Noise>::value) {
    n.point_values(pts.data(), pts.size(), out, grad);
    return;
  }
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (grad) {
      const auto r = n.gradient(pts[i]);
      out[i] = r.value;
      grad[i] = r.gradient;
    } else {
      out[i] = n(pts[i]);
    }
  }
}

// Whether Noise evaluates grid slabs itself: a member
//   void grid_values(const grid<D>& g, std::size_t first, std::size_t count,
//                    float* out, vec<float, D>* grad) const;
// with the values and gradients of its point evaluation at every sample (bit
// for bit unless the compiler contracts multiply-adds, or within the bound the
// noise states: gabor.hpp), faster than the sample loop below by sharing work
// between samples (perlin.hpp).
template <class Noise, class = void>
struct has_grid_values : std::false_type {};
template <class Noise>
struct has_grid_values<
    Noise, std::void_t<decltype(std::declval<const Noise&>().grid_values(
               std::declval<const grid<Noise::dimension>&>(), std::size_t{}, std::size_t{},
               std::declval<float*>(), std::declval<vec<float, Noise::dimension>*>()))>>
    : std::true_type {};

// The grid's samples with slowest-axis index (j in 2D, k in 3D) in
// [first, first + count) into out, which starts at sample (0, 0[, 0]) of that slab.
template <class Noise>
void scalar_grid(const Noise& n, const grid<Noise::dimension>& g, std::size_t first,
                 std::size_t count, float* out, vec<float, Noise::dimension>* grad) {
  constexpr int D = Noise::dimension;
  if constexpr (has_grid_values<Noise>::value) {
    n.grid_values(g, first, count, out, grad);
  } else {
    g.for_each_in_slab(first, count, [&](std::size_t idx, const vec<double, D>& p) {
      if (grad) {
        const auto r = n.template value_and_gradient<float>(p);
        out[idx] = r.value;
        grad[idx] = r.gradient;
      } else {
        out[idx] = n.template value<float>(p);
      }
    });
  }
}
template <class Noise>
void scalar_grid(const Noise& n, const grid<Noise::dimension>& g, float* out,
                 vec<float, Noise::dimension>* grad) {
  scalar_grid(n, g, 0, g.size[Noise::dimension - 1], out, grad);
}

template <class Noise, class Exec>
void run_points(const Noise& n, const Exec& ex, point_span<Noise> pts, float* out,
                vec<float, Noise::dimension>* grad) {
  if constexpr (std::is_same<Exec, exec::scalar_t>::value) {
    scalar_points(n, pts, out, grad);
  } else if constexpr (std::is_same<Exec, exec::simd_t>::value) {
    if constexpr (simd_kernel<Noise>::available)
      simd_kernel<Noise>::points(n, pts.data(), pts.size(), out, grad);
    else
      scalar_points(n, pts, out, grad);
  } else {
    ex.device.evaluate_points(n, pts.data(), pts.size(), out, grad);
  }
}

// The scalar loop over samples with extra inputs (footprints, normals, maps).
template <class Noise>
void scalar_samples(const Noise& n, const samples<Noise::dimension>& s, float* out,
                    vec<float, Noise::dimension>* grad) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    const sample_input<Noise::dimension> in = s.at(i);
    if (grad) {
      const auto r = n.template sample_value_and_gradient<float>(in);
      out[i] = r.value;
      grad[i] = r.gradient;
    } else {
      out[i] = n.template sample_value<float>(in);
    }
  }
}

// Whether the SIMD kernels of Noise take per-sample inputs (simd_kernel<Noise>::samples).
template <class Kernel, class = void>
struct has_simd_samples : std::false_type {};
template <class Kernel>
struct has_simd_samples<Kernel, std::void_t<decltype(Kernel::has_samples)>>
    : std::integral_constant<bool, Kernel::has_samples> {};

// Samples with extra inputs on backend ex; positions-only batches go to run_points.
template <class Noise, class Exec>
void run_samples(const Noise& n, const Exec& ex, const samples<Noise::dimension>& s, float* out,
                 vec<float, Noise::dimension>* grad) {
  // Positions only (always so for a noise that takes no extras: validated) is a points batch.
  constexpr bool kExtras = takes_sample_inputs<Noise>::value;
  if (!kExtras || !s.has_extras()) {
    run_points(n, ex, s.positions, out, grad);
    return;
  }
  if constexpr (kExtras) {
    if constexpr (std::is_same<Exec, exec::scalar_t>::value) {
      scalar_samples(n, s, out, grad);
    } else if constexpr (std::is_same<Exec, exec::simd_t>::value) {
      if constexpr (has_simd_samples<simd_kernel<Noise>>::value)
        simd_kernel<Noise>::samples(n, s, out, grad);
      else
        scalar_samples(n, s, out, grad);
    } else {
      ex.device.evaluate_samples(n, s, out, grad);
    }
  }
}

template <class Noise, class Exec>
void run_grid(const Noise& n, const Exec& ex, const grid<Noise::dimension>& g, float* out,
              vec<float, Noise::dimension>* grad) {
  if constexpr (std::is_same<Exec, exec::scalar_t>::value) {
    scalar_grid(n, g, out, grad);
  } else if constexpr (std::is_same<Exec, exec::simd_t>::value) {
    if constexpr (simd_kernel<Noise>::available)
      simd_kernel<Noise>::grid(n, g, out, grad);
    else
      scalar_grid(n, g, out, grad);
  } else {
    ex.device.evaluate_grid(n, g, out, grad);
  }
}

// ---- exec::parallel.

// Runs body(begin, end) over [0, n) split into at most `threads` contiguous
// parts of whole `unit`s (n is a multiple of unit), each at least `grain`
// long: on `pool`'s threads and the calling thread, whichever takes a part, or
// on threads started here when pool is null.
template <class Body>
void parallel_parts(std::size_t n, std::size_t unit, std::size_t grain, unsigned threads,
                    thread_pool* workers, const Body& body) {
  const std::size_t units = n / unit, grain_units = std::max<std::size_t>(1, grain / unit);
  const std::size_t parts =
      std::max<std::size_t>(1, std::min<std::size_t>(threads, units / grain_units));
  auto part = [&](std::size_t t) {
    body(t * units / parts * unit, (t + 1) * units / parts * unit);
  };
  if (workers) {
    workers->run(parts, part);
    return;
  }
  std::vector<std::thread> pool;
  pool.reserve(parts - 1);
  std::size_t started = 1;
#if HUSH_CONFIG_CXX_EXCEPTIONS
  try {
    for (; started < parts; ++started) pool.emplace_back(part, started);
  } catch (...) {  // no more threads to be had: the calling thread does the rest
  }
#else  // std::thread ends the program when the system refuses a thread
  for (; started < parts; ++started) pool.emplace_back(part, started);
#endif
  part(0);
  for (std::size_t t = started; t < parts; ++t) part(t);
  for (std::thread& th : pool) th.join();
}

// Whether simd_kernel<Noise> evaluates grid slabs (grid_slab(n, g, first, count, out, grad)).
template <class Kernel, class = void>
struct has_simd_grid_slab : std::false_type {};
template <class Kernel>
struct has_simd_grid_slab<Kernel, std::void_t<decltype(Kernel::has_grid_slab)>>
    : std::integral_constant<bool, Kernel::has_grid_slab> {};

template <class Noise, class Inner>
void run_points(const Noise& n, const exec::parallel_t<Inner>& ex, point_span<Noise> pts,
                float* out, vec<float, Noise::dimension>* grad) {
  parallel_parts(pts.size(), 1, ex.kParallelGrain, ex.threads, ex.pool,
                 [&](std::size_t b, std::size_t e) {
                   run_points(n, ex.inner, pts.subspan(b, e - b), out + b, grad ? grad + b : grad);
                 });
}

template <class Noise, class Inner>
void run_samples(const Noise& n, const exec::parallel_t<Inner>& ex,
                 const samples<Noise::dimension>& s, float* out,
                 vec<float, Noise::dimension>* grad) {
  parallel_parts(s.size(), 1, ex.kParallelGrain, ex.threads, ex.pool,
                 [&](std::size_t b, std::size_t e) {
                   run_samples(n, ex.inner, s.subrange(b, e - b), out + b, grad ? grad + b : grad);
                 });
}

// Slabs along the slowest axis. A SIMD kernel without slab support gets the
// whole grid on one thread: a slab re-based as a grid of its own would form
// its positions with other roundings.
template <class Noise, class Inner>
void run_grid(const Noise& n, const exec::parallel_t<Inner>& ex, const grid<Noise::dimension>& g,
              float* out, vec<float, Noise::dimension>* grad) {
  constexpr int D = Noise::dimension;
  constexpr bool kSlabs = std::is_same<Inner, exec::scalar_t>::value ||
                          !simd_kernel<Noise>::available ||
                          has_simd_grid_slab<simd_kernel<Noise>>::value;
  if constexpr (!kSlabs) {
    run_grid(n, ex.inner, g, out, grad);
  } else {
    const std::size_t slab = g.count() / g.size[D - 1];  // samples per slowest-axis index
    parallel_parts(
        g.count(), slab, ex.kParallelGrain, ex.threads, ex.pool, [&](std::size_t b, std::size_t e) {
          float* o = out + b;
          vec<float, D>* gr = grad ? grad + b : grad;
          if constexpr (std::is_same<Inner, exec::simd_t>::value && simd_kernel<Noise>::available)
            simd_kernel<Noise>::grid_slab(n, g, b / slab, (e - b) / slab, o, gr);
          else
            scalar_grid(n, g, b / slab, (e - b) / slab, o, gr);
        });
  }
}

}  // namespace detail

// Values of `noise` at `points` into `out` (same size), on backend `ex`.
template <class Noise, class Exec>
void evaluate(const Noise& noise, const Exec& ex, detail::point_span<Noise> points,
              span<float> out) {
  detail::require_same_size("hush::evaluate", "out", out.size(), points.size());
  if (points.empty()) return;
  detail::run_points(noise, ex, points, out.data(), nullptr);
}

// Values and analytic gradients (d noise / d position) at `points`.
template <class Noise, class Exec>
void evaluate(const Noise& noise, const Exec& ex, detail::point_span<Noise> points, span<float> out,
              detail::gradient_span<Noise> gradients) {
  detail::require_same_size("hush::evaluate", "out", out.size(), points.size());
  detail::require_same_size("hush::evaluate", "gradients", gradients.size(), points.size());
  if (points.empty()) return;
  detail::run_points(noise, ex, points, out.data(), gradients.data());
}

// Values of `noise` at `s` (positions with optional footprints, normals and
// surface maps, core/samples.hpp) into `out` (one per position), on backend `ex`.
template <class Noise, class Exec>
void evaluate(const Noise& noise, const Exec& ex, const samples<Noise::dimension>& s,
              span<float> out) {
  detail::validate_samples<Noise>("hush::evaluate", s);
  detail::require_same_size("hush::evaluate", "out", out.size(), s.size());
  if (s.size() == 0) return;
  detail::run_samples(noise, ex, s, out.data(), nullptr);
}

// Values and gradients (d value / d position, the footprint held fixed) at `s`.
template <class Noise, class Exec>
void evaluate(const Noise& noise, const Exec& ex, const samples<Noise::dimension>& s,
              span<float> out, detail::gradient_span<Noise> gradients) {
  detail::validate_samples<Noise>("hush::evaluate", s);
  detail::require_same_size("hush::evaluate", "out", out.size(), s.size());
  detail::require_same_size("hush::evaluate", "gradients", gradients.size(), s.size());
  if (s.size() == 0) return;
  detail::run_samples(noise, ex, s, out.data(), gradients.data());
}

// Values of `noise` on the uniform grid `g` into `out` (g.count() elements,
// C order, i fastest).
template <class Noise, class Exec>
void evaluate_grid(const Noise& noise, const Exec& ex, const grid<Noise::dimension>& g,
                   span<float> out) {
  g.validate("hush::evaluate_grid");
  detail::require_same_size("hush::evaluate_grid", "out", out.size(), g.count());
  if (g.count() == 0) return;
  detail::run_grid(noise, ex, g, out.data(), nullptr);
}

// Values and analytic gradients on the uniform grid `g`.
template <class Noise, class Exec>
void evaluate_grid(const Noise& noise, const Exec& ex, const grid<Noise::dimension>& g,
                   span<float> out, detail::gradient_span<Noise> gradients) {
  g.validate("hush::evaluate_grid");
  detail::require_same_size("hush::evaluate_grid", "out", out.size(), g.count());
  detail::require_same_size("hush::evaluate_grid", "gradients", gradients.size(), g.count());
  if (g.count() == 0) return;
  detail::run_grid(noise, ex, g, out.data(), gradients.data());
}

}  // namespace hush

#endif  // HUSH_EXEC_HPP
