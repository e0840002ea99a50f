// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Per-sample inputs beyond the position (DESIGN.md "Per-sample inputs"):
//  - hush::sample_input<D>: one sample as a noise's scalar code sees it: the
//    position (double), the footprint (core/footprint.hpp; a point by default),
//    for surface noises in 3D the surface normal, and for 2D texture-space
//    noises on surfaces the surface map T (core/surface_map.hpp; texture <-
//    surface, identity by default);
//  - hush::samples<D>: a batch of them as spans beside the positions, what
//    hush::evaluate(noise, exec, samples, out[, gradients]) takes on every
//    backend (exec.hpp);
//  - hush::sample_noise<Derived, D>: the public overloads every noise that
//    uses these inputs offers, written once (like core/point_noise.hpp):
//      n.sample(p, footprint)                 -> float / double (by p's type)
//      n.sample(p, normal, footprint)         -> the same on a surface (3D noises
//                                                with takes_normal)
//      n.sample(p, footprint, map)            -> the same on a surface whose UV
//                                                mapping is T = map (2D noises
//                                                with takes_surface_map)
//      n.sample_gradient(p, footprint), n.sample_gradient(p, normal, footprint),
//      n.sample_gradient(p, footprint, map)   -> value and d/d(position) of
//                                                the filtered noise, footprint fixed
// A noise derives from sample_noise<Derived, D> (which derives from
// point_noise<Derived, D>: n(p) and n.gradient(p) stay the unfiltered point
// evaluation) and defines, besides point_noise's two templates,
//   static constexpr bool takes_footprint;  // uses sample_input::fp
//   static constexpr bool takes_normal;     // uses sample_input::normal (D == 3)
//   static constexpr bool takes_surface_map;  // uses sample_input::map (D == 2)
//   template <class T> T sample_value(const sample_input<D>& s) const;
//   template <class T> value_gradient<T, D> sample_value_and_gradient(const sample_input<D>& s)
//   const;
// with the same result class as point evaluation for NaN/Inf positions.
#ifndef HUSH_CORE_SAMPLES_HPP
#define HUSH_CORE_SAMPLES_HPP

#include <cstddef>
#include <string>
#include <type_traits>

#include "hush/core/error.hpp"
#include "hush/core/footprint.hpp"
#include "hush/core/point_noise.hpp"
#include "hush/core/surface_map.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"

namespace hush {

// One sample: position, footprint, optionally the surface normal (any
// length; a noise documents what it does with a zero or non-finite normal)
// and the surface map (a noise documents what it does with a singular one).
template <int D>
struct sample_input {
  vec<double, D> position{};
  footprint<D> fp{};
  vec<double, 3> normal{};
  bool has_normal = false;
  surface_map map{};
  bool has_map = false;
};

// A batch of samples: positions and, optionally, one footprint, one normal
// and one surface map per position. An empty span means "not given": point
// samples, no normal, the identity map. Normals are for 3D noises, surface
// maps for 2D texture-space noises.
template <int D>
struct samples {
  span<const vec<float, D>> positions;
  span<const footprint<D>> footprints;
  span<const vec<float, 3>> normals;
  span<const surface_map> surface_maps{};  // last, defaulted: {positions, footprints, normals}
                                           // still initialises a batch

  std::size_t size() const { return positions.size(); }
  bool has_footprints() const { return !footprints.empty(); }
  bool has_normals() const { return !normals.empty(); }
  bool has_surface_maps() const { return !surface_maps.empty(); }
  // True when anything beside the positions is given.
  bool has_extras() const {
    bool any = false;
    for_each_extra([&](const char*, const auto& in) { any = any || !in.empty(); });
    return any;
  }

  // Calls f(name, span) for each per-sample input beside the positions, given
  // or not, name being the member's ("footprints", ...). It and visit_extras
  // are the only code that lists the members, so what walks a batch
  // (subrange, has_extras, validate_samples) cannot miss one.
  template <class F>
  constexpr void for_each_extra(F&& f) const {
    visit_extras(*this, f);
  }
  // The number of per-sample inputs beside the positions.
  static constexpr std::size_t extra_count() {
    std::size_t n = 0;
    samples<D>{}.for_each_extra([&](const char*, const auto&) { ++n; });
    return n;
  }

  // Samples [offset, offset + count) of the batch: every given span cut to
  // that range, every empty one left empty. Throws hush::invalid_argument,
  // naming the parameter, when offset + count exceeds size() or a given span
  // does not have size() elements; nothing is read.
  samples subrange(std::size_t offset, std::size_t count) const {
    const char* where = "hush::samples::subrange";
    if (offset > size() || count > size() - offset) {
      const std::string valid = "offset + count <= size() = " + std::to_string(size());
      detail::throw_out_of_range(where, "offset = " + std::to_string(offset) + ", count",
                                 count, valid.c_str());
    }
    samples part = *this;
    part.positions = positions.subspan(offset, count);
    visit_extras(part, [&](const char* name, auto& in) {
      if (in.empty()) return;
      if (in.size() != size()) {
        const std::string valid = "0 (not given) or size() = " + std::to_string(size());
        detail::throw_out_of_range(where, std::string(name) + ".size()", in.size(),
                                   valid.c_str());
      }
      in = in.subspan(offset, count);
    });
    return part;
  }

  // Sample i as the scalar code sees it.
  sample_input<D> at(std::size_t i) const {
    sample_input<D> s;
    s.position = vec_cast<double>(positions[i]);
    if (has_footprints()) s.fp = footprints[i];
    if (has_normals()) {
      s.normal = vec_cast<double>(normals[i]);
      s.has_normal = true;
    }
    if (has_surface_maps()) {
      s.map = surface_maps[i];
      s.has_map = true;
    }
    return s;
  }

 private:
  // The members beside the positions, each once; Self is samples or const samples.
  template <class Self, class F>
  static constexpr void visit_extras(Self& s, F&& f) {
    f("footprints", s.footprints);
    f("normals", s.normals);
    f("surface_maps", s.surface_maps);
  }
};

namespace detail {
// Every member of samples<D> is the positions or an input visit_extras lists:
// a span added to the struct but not to that list fails here.
template <int D>
constexpr bool samples_lists_every_span() {
  return sizeof(samples<D>) == (1 + samples<D>::extra_count()) * sizeof(span<const float>);
}
static_assert(samples_lists_every_span<2>() && samples_lists_every_span<3>(),
              "hush::samples: a member is missing from samples::visit_extras");

// What a noise type takes per sample (false for noises that do not say).
template <class Noise, class = void>
struct takes_footprint : std::false_type {};
template <class Noise>
struct takes_footprint<Noise, std::void_t<decltype(Noise::takes_footprint)>>
    : std::integral_constant<bool, Noise::takes_footprint> {};
template <class Noise, class = void>
struct takes_normal : std::false_type {};
template <class Noise>
struct takes_normal<Noise, std::void_t<decltype(Noise::takes_normal)>>
    : std::integral_constant<bool, Noise::takes_normal> {};
template <class Noise, class = void>
struct takes_surface_map : std::false_type {};
template <class Noise>
struct takes_surface_map<Noise, std::void_t<decltype(Noise::takes_surface_map)>>
    : std::integral_constant<bool, Noise::takes_surface_map> {};
// Whether a noise takes any per-sample input beside the position.
template <class Noise>
struct takes_sample_inputs
    : std::integral_constant<bool, takes_footprint<Noise>::value || takes_normal<Noise>::value ||
                                       takes_surface_map<Noise>::value> {};

// Throws hush::invalid_argument naming the first span that does not fit:
// only inputs the noise takes may be given, and every given span must have
// one element per position. Which inputs a noise takes is per input; the
// sizes are checked over every span (samples::for_each_extra).
template <class Noise>
void validate_samples(const char* where, const samples<Noise::dimension>& s) {
  if (s.has_footprints() && !takes_footprint<Noise>::value)
    hush::detail::raise_error(std::string(where) +
                                 ": samples.footprints given, but this noise does not filter; "
                                 "valid: none (an empty span)");
  if (s.has_normals() && !takes_normal<Noise>::value)
    hush::detail::raise_error(std::string(where) +
                                 ": samples.normals given, but this noise takes no normal; "
                                 "valid: none (an empty span)");
  if (s.has_surface_maps() && !takes_surface_map<Noise>::value)
    hush::detail::raise_error(std::string(where) +
                                 ": samples.surface_maps given, but this noise takes no surface "
                                 "map; valid: none (an empty span)");
  const std::size_t n = s.positions.size();
  s.for_each_extra([&](const char* name, const auto& in) {
    if (in.empty() || in.size() == n) return;
    const std::string per = "exactly " + std::to_string(n) + " elements (one per position) or none";
    throw_out_of_range(where, std::string("samples.") + name + ".size()", in.size(), per.c_str());
  });
}

}  // namespace detail

template <class Derived, int D>
class sample_noise : public point_noise<Derived, D> {
 public:
  // The filtered value at p over footprint fp (float arithmetic, or the double reference).
  float sample(const vec<float, D>& p, const footprint<D>& fp) const {
    return self().template sample_value<float>(input(vec_cast<double>(p), fp));
  }
  double sample(const vec<double, D>& p, const footprint<D>& fp) const {
    return self().template sample_value<double>(input(p, fp));
  }
  value_gradient<float, D> sample_gradient(const vec<float, D>& p, const footprint<D>& fp) const {
    return self().template sample_value_and_gradient<float>(input(vec_cast<double>(p), fp));
  }
  value_gradient<double, D> sample_gradient(const vec<double, D>& p, const footprint<D>& fp) const {
    return self().template sample_value_and_gradient<double>(input(p, fp));
  }

  // On a surface with the given normal (3D noises with takes_normal).
  template <int E = D, class = std::enable_if_t<E == 3>>
  float sample(const vec<float, 3>& p, const vec<float, 3>& normal,
               const footprint<3>& fp = footprint<3>{}) const {
    return self().template sample_value<float>(
        input(vec_cast<double>(p), fp, vec_cast<double>(normal)));
  }
  template <int E = D, class = std::enable_if_t<E == 3>>
  double sample(const vec<double, 3>& p, const vec<double, 3>& normal,
                const footprint<3>& fp = footprint<3>{}) const {
    return self().template sample_value<double>(input(p, fp, normal));
  }
  template <int E = D, class = std::enable_if_t<E == 3>>
  value_gradient<float, 3> sample_gradient(const vec<float, 3>& p, const vec<float, 3>& normal,
                                           const footprint<3>& fp = footprint<3>{}) const {
    return self().template sample_value_and_gradient<float>(
        input(vec_cast<double>(p), fp, vec_cast<double>(normal)));
  }
  template <int E = D, class = std::enable_if_t<E == 3>>
  value_gradient<double, 3> sample_gradient(const vec<double, 3>& p, const vec<double, 3>& normal,
                                            const footprint<3>& fp = footprint<3>{}) const {
    return self().template sample_value_and_gradient<double>(input(p, fp, normal));
  }

  // On a surface whose UV mapping is T = map (2D noises with takes_surface_map).
  template <int E = D, class = std::enable_if_t<E == 2>>
  float sample(const vec<float, 2>& p, const footprint<2>& fp, const surface_map& map) const {
    return self().template sample_value<float>(input(vec_cast<double>(p), fp, map));
  }
  template <int E = D, class = std::enable_if_t<E == 2>>
  double sample(const vec<double, 2>& p, const footprint<2>& fp, const surface_map& map) const {
    return self().template sample_value<double>(input(p, fp, map));
  }
  template <int E = D, class = std::enable_if_t<E == 2>>
  value_gradient<float, 2> sample_gradient(const vec<float, 2>& p, const footprint<2>& fp,
                                           const surface_map& map) const {
    return self().template sample_value_and_gradient<float>(input(vec_cast<double>(p), fp, map));
  }
  template <int E = D, class = std::enable_if_t<E == 2>>
  value_gradient<double, 2> sample_gradient(const vec<double, 2>& p, const footprint<2>& fp,
                                            const surface_map& map) const {
    return self().template sample_value_and_gradient<double>(input(p, fp, map));
  }

 private:
  const Derived& self() const { return static_cast<const Derived&>(*this); }
  static sample_input<D> input(const vec<double, D>& p, const footprint<D>& fp) {
    sample_input<D> s;
    s.position = p;
    s.fp = fp;
    return s;
  }
  static sample_input<D> input(const vec<double, D>& p, const footprint<D>& fp,
                               const vec<double, 3>& normal) {
    static_assert(detail::takes_normal<Derived>::value, "this noise takes no surface normal");
    sample_input<D> s = input(p, fp);
    s.normal = normal;
    s.has_normal = true;
    return s;
  }
  static sample_input<D> input(const vec<double, D>& p, const footprint<D>& fp,
                               const surface_map& map) {
    static_assert(detail::takes_surface_map<Derived>::value, "this noise takes no surface map");
    sample_input<D> s = input(p, fp);
    s.map = map;
    s.has_map = true;
    return s;
  }
};

}  // namespace hush

#endif  // HUSH_CORE_SAMPLES_HPP
