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
//  - scalar: exactly noise(point) per element, in float.
//  - simd: the same values bit for bit under HUSH_STRICT_FP; otherwise within
//    the noise's float budget of the double reference (perlin, fractal:
//    hush/simd/perlin-inl.h, docs/design.md "Backends"). Without SIMD
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
//  - NaN/Inf coordinates give NaN, as in point evaluation; nothing throws
//    after validation, and no output element is left unwritten.
#ifndef HUSH_EXEC_HPP
#define HUSH_EXEC_HPP

#include <array>
#include <cstddef>
#include <string>
#include <type_traits>

#include "hush/config.hpp"
#include "hush/core/error.hpp"
#include "hush/core/samples.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/simd/dispatch.hpp"  // detail::simd_kernel and its specialisations

namespace hush {
namespace exec {

// Plain C++ loop over the noise's point evaluation: the reference backend.
struct scalar_t {
  static constexpr const char* name = "scalar";
};
// Highway SIMD kernels, dynamically dispatched to the best compiled target
// (or statically, see hush/simd/dispatch.hpp).
struct simd_t {
  static constexpr const char* name = "simd";
};
inline constexpr scalar_t scalar{};
inline constexpr simd_t simd{};

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

template <class Noise>
void scalar_points(const Noise& n, point_span<Noise> pts, float* out,
                   vec<float, Noise::dimension>* grad) {
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

template <class Noise>
void scalar_grid(const Noise& n, const grid<Noise::dimension>& g, float* out,
                 vec<float, Noise::dimension>* grad) {
  constexpr int D = Noise::dimension;
  const std::size_t nx = g.size[0], ny = g.size[1], nz = D == 3 ? g.size[D - 1] : 1;
  std::size_t idx = 0;
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i, ++idx) {
        std::array<std::size_t, D> ijk{};
        ijk[0] = i;
        ijk[1] = j;
        if constexpr (D == 3) ijk[D - 1] = k;
        const vec<double, D> p = g.position(ijk);
        if (grad) {
          const auto r = n.template value_and_gradient<float>(p);
          out[idx] = r.value;
          grad[idx] = r.gradient;
        } else {
          out[idx] = n.template value<float>(p);
        }
      }
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
