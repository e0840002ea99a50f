// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::frame: what a renderer already has for one frame, as views of its
// G-buffer channels, for the scene-driven noises (coherent noise, Kass &
// Pesare 2011; NPR Gabor noise, Benard et al. 2010). No scene graph, camera or
// file format: pointers to pixels the caller owns, valid for the call.
//
// Conventions (the same as examples/scene/gbuffer.hpp, which produces them):
//  - width x height pixels, row y at data + y * stride (elements), row 0 at
//    the TOP of the image; pixel (x, y) has its centre at (x + 0.5, y + 0.5)
//    in screen pixels, x right, y down.
//  - depth: linear view depth (distance from the camera plane along the view
//    axis), > 0 where a surface is seen. +inf (background), NaN, 0 or
//    negative values mean "no usable surface here": noises treat the pixel as
//    disoccluded (coherent noise gives it fresh noise).
//  - velocity (backward 3D velocity): (dx, dy) in pixels per frame and dz in
//    depth units per frame, such that the surface point seen at pixel centre p
//    in this frame was at p - (dx, dy) with depth depth - dz in the previous
//    frame. NaN or +-Inf in any component: no previous position (disoccluded).
//  - forward_velocity: the same towards the NEXT frame: the point seen at p
//    is at p + (dx, dy) with depth depth + dz in frame i + 1 (what a backward
//    pass over a sequence needs; examples/scene writes both).
//  - object_id: an id per pixel (examples/scene: 0 = background); two pixels
//    show the same object when their ids are equal.
//  - triangle_id: the triangle index within the object (NPR Gabor noise).
//  - uv: the surface's texture coordinates (u, v) at the pixel centre
//    (anisotropic noise evaluates there).
//  - uv_jacobian: d(u, v)/d(x, y) in uv units per pixel, as (du/dx, du/dy,
//    dv/dx, dv/dy): the screen-to-texture Jacobian J a filtering 2D noise
//    turns into its footprint (hush::footprint<2>::from_derivatives((du/dx,
//    dv/dx), (du/dy, dv/dy)); anisotropic noise).
// NPR Gabor noise reads its triangle list beside these views (core/triangles.hpp).
#ifndef HUSH_CORE_FRAME_HPP
#define HUSH_CORE_FRAME_HPP

#include <cstddef>
#include <cstdint>
#include <string>

#include "hush/core/error.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"

namespace hush {

// Which views of a frame a noise reads; combine with |.
enum class frame_view : unsigned {
  none = 0,
  depth = 1u << 0,
  velocity = 1u << 1,
  forward_velocity = 1u << 2,
  object_id = 1u << 3,
  triangle_id = 1u << 4,
  uv = 1u << 5,
  uv_jacobian = 1u << 6,
};
constexpr frame_view operator|(frame_view a, frame_view b) {
  return static_cast<frame_view>(static_cast<unsigned>(a) | static_cast<unsigned>(b));
}
constexpr bool has_view(frame_view set, frame_view v) {
  return (static_cast<unsigned>(set) & static_cast<unsigned>(v)) != 0;
}

struct frame {
  image_view<const float> depth;                // linear view depth
  image_view<const vec3> velocity;              // (dx, dy, dz) from the previous frame
  image_view<const vec3> forward_velocity;      // (dx, dy, dz) to the next frame
  image_view<const std::uint32_t> object_id;    // optional: same id = same object
  image_view<const std::uint32_t> triangle_id;  // optional
  image_view<const vec2> uv;                    // optional: texture coordinates
  image_view<const vec4> uv_jacobian;           // optional: (du/dx, du/dy, dv/dx, dv/dy)

  // The frame's size: the depth view's (every present view must match it).
  std::size_t width() const { return depth.width; }
  std::size_t height() const { return depth.height; }
  std::size_t pixels() const { return depth.width * depth.height; }

  // Which views are present (data non-null).
  frame_view present() const {
    frame_view p = frame_view::none;
    if (depth.data) p = p | frame_view::depth;
    if (velocity.data) p = p | frame_view::velocity;
    if (forward_velocity.data) p = p | frame_view::forward_velocity;
    if (object_id.data) p = p | frame_view::object_id;
    if (triangle_id.data) p = p | frame_view::triangle_id;
    if (uv.data) p = p | frame_view::uv;
    if (uv_jacobian.data) p = p | frame_view::uv_jacobian;
    return p;
  }

  // Throws hush::invalid_argument naming `where` and the view when a view in
  // `required` is missing, when the depth view is empty (0 pixels) or larger
  // than max_side pixels on a side, or when a present view's size differs from
  // the depth view's or its stride is below its width. Never reads a pixel.
  void validate(const char* where, frame_view required, std::size_t max_side) const {
    if (!depth.data) missing(where, "depth");
    if (depth.width == 0 || depth.height == 0 || depth.width > max_side || depth.height > max_side)
      detail::throw_out_of_range(
          where, "frame.depth size", size_text(depth),
          ("1 ... " + std::to_string(max_side) + " pixels per side").c_str());
    check(where, "depth", depth, frame_view::depth, required);
    check(where, "velocity", velocity, frame_view::velocity, required);
    check(where, "forward_velocity", forward_velocity, frame_view::forward_velocity, required);
    check(where, "object_id", object_id, frame_view::object_id, required);
    check(where, "triangle_id", triangle_id, frame_view::triangle_id, required);
    check(where, "uv", uv, frame_view::uv, required);
    check(where, "uv_jacobian", uv_jacobian, frame_view::uv_jacobian, required);
  }

 private:
  template <class T>
  static std::string size_text(const image_view<T>& v) {
    return std::to_string(v.width) + "x" + std::to_string(v.height);
  }
  [[noreturn]] static void missing(const char* where, const char* name) {
    hush::detail::raise_error(std::string(where) + ": frame." + name +
                                 " is required but missing (null data)");
  }
  template <class T>
  void check(const char* where, const char* name, const image_view<T>& v, frame_view which,
             frame_view required) const {
    if (!v.data) {
      if (has_view(required, which)) missing(where, name);
      return;
    }
    if (v.width != depth.width || v.height != depth.height)
      detail::throw_out_of_range(where, std::string("frame.") + name + " size", size_text(v),
                                 ("the depth view's size, " + size_text(depth)).c_str());
    if (v.stride < v.width)
      detail::throw_out_of_range(where, std::string("frame.") + name + ".stride", v.stride,
                                 ("at least its width, " + std::to_string(v.width)).c_str());
  }
};

}  // namespace hush

#endif  // HUSH_CORE_FRAME_HPP
