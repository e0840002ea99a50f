// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::param_source: where a scene-driven noise takes one of its parameters
// (Benard, Lagae et al. 2010 sec. 4: "the noise parameters ... can be defined
// per object or per pixel", e.g. an orientation field along the principal
// curvature or the projected normal, a frequency driven by shading). Four
// kinds:
//  - constant (the default-constructed source): the noise's own params value;
//  - per object: table[object_id], the G-buffer's object ids (ids past the
//    table's end take the constant);
//  - per pixel: field(x, y) at a pixel, a view of a caller-owned image of the
//    frame's size (e.g. a G-buffer channel), valid for the call that reads it;
//  - per vertex: values[v] for vertex v of the frame's triangle list (the
//    indexing of triangle_list::screen), interpolated over a triangle with the
//    barycentric coordinates of the point read (attached to the surface: a
//    point keeps its value in every frame).
// No copy of the data is made. The noise decides where it reads (NPR Gabor
// noise: each point at its own pixel or barycentric position, see
// npr_gabor.hpp).
//
//   std::vector<double> freq = {0.125, 0.25};           // objects 0 and 1
//   hush::param_source f = hush::param_source::per_object(freq);
//   hush::param_source o = hush::param_source::per_pixel({angles, w, h});
//   hush::param_source a = hush::param_source::per_vertex(bandwidths);  // one per vertex
//
// Bad values: validate() throws hush::invalid_argument for a table entry
// outside the parameter's range, a field whose size is not the frame's or a
// vertex array whose size is not the triangle list's vertex count; field
// pixels and vertex values are never read there (they may be anything):
// value() gives the fallback for a non-finite one and the caller clamps finite
// ones.
#ifndef HUSH_CORE_PARAM_SOURCE_HPP
#define HUSH_CORE_PARAM_SOURCE_HPP

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "hush/core/error.hpp"
#include "hush/core/views.hpp"

namespace hush {

class param_source {
 public:
  enum class kind { constant, per_object, per_pixel, per_vertex };

  param_source() = default;  // constant
  static param_source per_object(span<const double> table) {
    param_source s;
    s.kind_ = kind::per_object;
    s.table_ = table;
    return s;
  }
  static param_source per_pixel(image_view<const float> field) {
    param_source s;
    s.kind_ = kind::per_pixel;
    s.field_ = field;
    return s;
  }

  static param_source per_vertex(span<const float> values) {
    param_source s;
    s.kind_ = kind::per_vertex;
    s.vertex_ = values;
    return s;
  }

  // Where a noise reads a value: the object, the position in screen pixels
  // (y down) and, for per-vertex sources, the triangle's three vertex indices
  // with the barycentric coordinates of the point (null vertices: none known).
  struct site {
    std::uint32_t object = 0;
    double x = 0, y = 0;
    const std::uint32_t* vertices = nullptr;
    double b[3] = {0, 0, 0};
  };

  kind which() const { return kind_; }
  bool is_constant() const { return kind_ == kind::constant; }
  // Entries of a per-object table (0 for the other kinds).
  std::size_t table_size() const { return kind_ == kind::per_object ? table_.size() : 0; }

  // The value for object `object` at pixel (x, y) (screen pixels, y down;
  // the pixel whose square holds the position): the table entry or the
  // field's pixel. `fallback` (the constant) when the source is constant, the
  // object is past the table's end, the position is outside the field or not
  // finite, or the pixel is not finite (NaN: "no value here"). Never throws.
  // Per vertex: sum_i b_i values[vertices[i]]; `fallback` without vertices, for
  // an index past the array or a non-finite result.
  double value(const site& at, double fallback) const {
    switch (kind_) {
      case kind::constant:
        return fallback;
      case kind::per_object:
        return at.object < table_.size() ? table_[at.object] : fallback;
      case kind::per_pixel: {
        if (!(at.x >= 0.0 && at.y >= 0.0 && at.x < static_cast<double>(field_.width) &&
              at.y < static_cast<double>(field_.height)))
          return fallback;  // also NaN positions
        const double v = static_cast<double>(
            field_(static_cast<std::size_t>(at.x), static_cast<std::size_t>(at.y)));
        return std::isfinite(v) ? v : fallback;
      }
      case kind::per_vertex: {
        if (!at.vertices) return fallback;
        double v = 0;
        for (int i = 0; i < 3; ++i) {
          if (at.vertices[i] >= vertex_.size()) return fallback;
          v += at.b[i] * static_cast<double>(vertex_[at.vertices[i]]);
        }
        return std::isfinite(v) ? v : fallback;
      }
    }
    return fallback;
  }
  double value(std::uint32_t object, double x, double y, double fallback) const {
    return value(site{object, x, y, nullptr, {0, 0, 0}}, fallback);
  }
  // The value a per-vertex source holds at one vertex (for bounds over a
  // triangle): `fallback` where it is not finite or past the array, and for
  // every other kind.
  double vertex_value(std::uint32_t vertex, double fallback) const {
    if (kind_ != kind::per_vertex || vertex >= vertex_.size()) return fallback;
    const double v = static_cast<double>(vertex_[vertex]);
    return std::isfinite(v) ? v : fallback;
  }

  // Throws hush::invalid_argument naming `where` and `name`: a per-object
  // entry outside [lo, hi] (named "name[i]", with `valid` the range's text),
  // a per-pixel field with null data, or a size other than width x height, a
  // per-vertex array whose size is not `vertices` ("name vertex values").
  void validate(const char* where, const char* name, double lo, double hi, const char* valid,
                std::size_t width, std::size_t height, std::size_t vertices) const {
    if (kind_ == kind::per_vertex && vertex_.size() != vertices)
      detail::throw_out_of_range(
          where, std::string(name) + " vertex values", vertex_.size(),
          ("one per vertex of the triangle list (" + std::to_string(vertices) + ")").c_str());
    if (kind_ == kind::per_object) {
      for (std::size_t i = 0; i < table_.size(); ++i)
        detail::require_in_range(where, std::string(name) + "[" + std::to_string(i) + "]",
                                 table_[i], lo, hi, valid);
    } else if (kind_ == kind::per_pixel) {
      if (!field_.data || field_.width != width || field_.height != height)
        detail::throw_out_of_range(
            where, std::string(name) + " field size",
            std::to_string(field_.width) + "x" + std::to_string(field_.height),
            ("the frame's size " + std::to_string(width) + "x" + std::to_string(height) +
             " (non-null)")
                .c_str());
    }
  }

 private:
  kind kind_ = kind::constant;
  span<const double> table_;
  image_view<const float> field_;
  span<const float> vertex_;
};

}  // namespace hush

#endif  // HUSH_CORE_PARAM_SOURCE_HPP
