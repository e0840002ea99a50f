// hush's Python module: a G-buffer of numpy arrays as a hush::frame (core/frame.hpp), for the
// scene-driven noises (coherent, NPR Gabor). Arrays are (H, W) or (H, W, C) in C order; the
// float32 / uint32 ones are viewed without a copy, others converted once.
#ifndef HUSH_PYTHON_FRAME_HPP
#define HUSH_PYTHON_FRAME_HPP

#include <string>
#include <vector>

#include "bindings.hpp"

namespace hush_python {

// Owns the (possibly converted) arrays a frame views.
struct frame_arrays {
  hush::frame frame;
  std::vector<py::object> keep;  // the arrays the views point into

  // The image `a` as (H, W[, channels]) of T; raises ValueError naming `name`.
  template <class T>
  const T* image(const py::object& a, const char* name, py::ssize_t channels, std::size_t& w,
                 std::size_t& h) {
    const char kind = py::array::ensure(a) ? py::array::ensure(a).dtype().kind() : '?';
    const bool real = kind == 'f' || kind == 'i' || kind == 'u';
    auto arr = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(a);
    const py::ssize_t want_ndim = channels == 1 ? 2 : 3;
    if (!arr || !real || arr.ndim() != want_ndim || (channels > 1 && arr.shape(2) != channels))
      throw py::value_error(std::string(name) + ": valid: a real array of shape (H, W" +
                            (channels > 1 ? ", " + std::to_string(channels) : std::string()) + ")");
    h = static_cast<std::size_t>(arr.shape(0));
    w = static_cast<std::size_t>(arr.shape(1));
    keep.push_back(arr);
    return arr.data();
  }

  frame_arrays(const py::object& depth, const py::object& velocity,
               const py::object& forward_velocity, const py::object& object_id,
               const py::object& triangle_id) {
    std::size_t w = 0, h = 0;
    frame.depth = {image<float>(depth, "depth", 1, w, h), w, h};
    auto vec3_view = [&](const py::object& a, const char* name) {
      std::size_t vw = 0, vh = 0;
      const float* d = image<float>(a, name, 3, vw, vh);
      return hush::image_view<const hush::vec3>{reinterpret_cast<const hush::vec3*>(d), vw, vh};
    };
    auto id_view = [&](const py::object& a, const char* name) {
      std::size_t iw = 0, ih = 0;
      const std::uint32_t* d = image<std::uint32_t>(a, name, 1, iw, ih);
      return hush::image_view<const std::uint32_t>{d, iw, ih};
    };
    if (!velocity.is_none()) frame.velocity = vec3_view(velocity, "velocity");
    if (!forward_velocity.is_none())
      frame.forward_velocity = vec3_view(forward_velocity, "forward_velocity");
    if (!object_id.is_none()) frame.object_id = id_view(object_id, "object_id");
    if (!triangle_id.is_none()) frame.triangle_id = id_view(triangle_id, "triangle_id");
  }
};

}  // namespace hush_python

#endif  // HUSH_PYTHON_FRAME_HPP
