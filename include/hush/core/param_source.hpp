// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::param_source: where a scene-driven noise takes one of its parameters
// (Benard, Lagae et al. 2010 sec. 4: "the noise parameters ... can be defined
// per object or per pixel", e.g. an orientation field along the principal
// curvature or the projected normal, a frequency driven by shading). Three
// kinds:
//  - constant (the default-constructed source): the noise's own params value;
//  - per object: table[object_id], the G-buffer's object ids (ids past the
//    table's end take the constant);
//  - per pixel: field(x, y) at a pixel, a view of a caller-owned image of the
//    frame's size (e.g. a G-buffer channel), valid for the call that reads it.
// No copy of the data is made. The noise decides where it reads (NPR Gabor
// noise: each point at its own pixel, see npr_gabor.hpp).
//
//   std::vector<double> freq = {0.125, 0.25};           // objects 0 and 1
//   hush::param_source f = hush::param_source::per_object(freq);
//   hush::param_source o = hush::param_source::per_pixel({angles, w, h});
//
// Bad values: validate() throws hush::invalid_argument for a table entry
// outside the parameter's range or a field whose size is not the frame's;
// field pixels are never read there (per-pixel data may be anything): value()
// gives the fallback for a non-finite pixel and the caller clamps finite ones.
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
  enum class kind { constant, per_object, per_pixel };

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

  kind which() const { return kind_; }
  bool is_constant() const { return kind_ == kind::constant; }
  // Entries of a per-object table (0 for the other kinds).
  std::size_t table_size() const { return kind_ == kind::per_object ? table_.size() : 0; }

  // The value for object `object` at pixel (x, y) (screen pixels, y down;
  // the pixel whose square holds the position): the table entry or the
  // field's pixel. `fallback` (the constant) when the source is constant, the
  // object is past the table's end, the position is outside the field or not
  // finite, or the pixel is not finite (NaN: "no value here"). Never throws.
  double value(std::uint32_t object, double x, double y, double fallback) const {
    switch (kind_) {
      case kind::constant:
        return fallback;
      case kind::per_object:
        return object < table_.size() ? table_[object] : fallback;
      case kind::per_pixel: {
        if (!(x >= 0.0 && y >= 0.0 && x < static_cast<double>(field_.width) &&
              y < static_cast<double>(field_.height)))
          return fallback;  // also NaN positions
        const double v = static_cast<double>(
            field_(static_cast<std::size_t>(x), static_cast<std::size_t>(y)));
        return std::isfinite(v) ? v : fallback;
      }
    }
    return fallback;
  }

  // Throws hush::invalid_argument naming `where` and `name`: a per-object
  // entry outside [lo, hi] (named "name[i]", with `valid` the range's text),
  // a per-pixel field with null data, or a size other than width x height.
  void validate(const char* where, const char* name, double lo, double hi, const char* valid,
                std::size_t width, std::size_t height) const {
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
};

}  // namespace hush

#endif  // HUSH_CORE_PARAM_SOURCE_HPP
