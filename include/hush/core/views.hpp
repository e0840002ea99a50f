// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Non-owning views for batch evaluation and per-pixel data:
//  - span<T>:        contiguous array (pointer + count); C++17 has no std::span.
//  - grid<N>:        a uniform sample grid: origin, step per axis, count per axis.
//                    Sample (i, j, k) sits at origin + step * (i, j, k); its index
//                    in C order is (k * ny + j) * nx + i (i along x, fastest).
//  - image_view<T>:  a 2D pixel array with a row stride, e.g. one G-buffer channel.
#ifndef HUSH_CORE_VIEWS_HPP
#define HUSH_CORE_VIEWS_HPP

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "hush/core/error.hpp"
#include "hush/core/vec.hpp"

namespace hush {

template <class T>
class span {
 public:
  using element_type = T;
  using value_type = std::remove_cv_t<T>;
  constexpr span() = default;
  constexpr span(T* data, std::size_t size) : data_(data), size_(size) {}
  template <std::size_t N>
  constexpr span(T (&a)[N]) : data_(a), size_(N) {}  // NOLINT: implicit like std::span
  template <class U, std::size_t N,
            class = std::enable_if_t<std::is_convertible<U (*)[], T (*)[]>::value>>
  constexpr span(std::array<U, N>& a) : data_(a.data()), size_(N) {}  // NOLINT
  template <class U, std::size_t N,
            class = std::enable_if_t<std::is_convertible<const U (*)[], T (*)[]>::value>>
  constexpr span(const std::array<U, N>& a) : data_(a.data()), size_(N) {}  // NOLINT
  template <class U, class A,
            class = std::enable_if_t<std::is_convertible<U (*)[], T (*)[]>::value>>
  span(std::vector<U, A>& v) : data_(v.data()), size_(v.size()) {}  // NOLINT
  template <class U, class A,
            class = std::enable_if_t<std::is_convertible<const U (*)[], T (*)[]>::value>>
  span(const std::vector<U, A>& v) : data_(v.data()), size_(v.size()) {}  // NOLINT
  // span<U> -> span<const U>
  template <class U, class = std::enable_if_t<std::is_convertible<U (*)[], T (*)[]>::value>>
  constexpr span(const span<U>& s) : data_(s.data()), size_(s.size()) {}  // NOLINT

  constexpr T* data() const { return data_; }
  constexpr std::size_t size() const { return size_; }
  constexpr bool empty() const { return size_ == 0; }
  constexpr T& operator[](std::size_t i) const { return data_[i]; }
  constexpr T* begin() const { return data_; }
  constexpr T* end() const { return data_ + size_; }
  constexpr span subspan(std::size_t offset, std::size_t count) const {
    return span(data_ + offset, count);
  }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

// A uniform grid of N-dimensional sample positions. Origin and step are double
// so that grids far from the origin keep their spacing exact; noises split each
// position into lattice cell and fraction in double before going to float.
template <int N>
struct grid {
  vec<double, N> origin;              // position of sample (0, 0[, 0])
  vec<double, N> step;                // spacing along each axis (may be negative, not zero)
  std::array<std::size_t, std::size_t{N}> size{};  // samples along each axis (nx, ny[, nz])

  // Number of samples; 0 when any axis is empty.
  std::size_t count() const {
    std::size_t n = 1;
    for (std::size_t a = 0; a < N; ++a) n *= size[a];
    return n;
  }
  // Position of the sample with index (i, j[, k]).
  vec<double, N> position(const std::array<std::size_t, std::size_t{N}>& ijk) const {
    vec<double, N> p;
    for (std::size_t a = 0; a < N; ++a) p[a] = origin[a] + step[a] * static_cast<double>(ijk[a]);
    return p;
  }
  // f(idx, position) for the samples of the slab whose slowest-axis index (j in
  // 2D, k in 3D) is in [first, first + count), idx counting from 0 in C order.
  template <class F>
  void for_each_in_slab(std::size_t first, std::size_t count, F f) const {
    static_assert(N == 2 || N == 3, "grid slabs are 2D or 3D");
    const std::size_t j0 = N == 2 ? first : 0, ny = N == 2 ? first + count : size[1];
    const std::size_t k0 = N == 3 ? first : 0, nz = N == 3 ? first + count : 1;
    std::size_t idx = 0;
    for (std::size_t k = k0; k < nz; ++k)
      for (std::size_t j = j0; j < ny; ++j)
        for (std::size_t i = 0; i < size[0]; ++i, ++idx) {
          std::array<std::size_t, std::size_t{N}> ijk{};
          ijk[0] = i;
          ijk[1] = j;
          if constexpr (N == 3) ijk[N - 1] = k;
          f(idx, position(ijk));
        }
  }
  // Throws hush::invalid_argument naming the first bad field: origin and step must be
  // finite, step non-zero, and the total count must fit in the address space.
  void validate(const char* where) const {
    for (int a = 0; a < N; ++a) {
      if (!std::isfinite(origin[a]))
        detail::throw_out_of_range(where, "grid.origin[" + std::to_string(a) + "]", origin[a],
                                   "a finite number");
      if (!std::isfinite(step[a]) || step[a] == 0.0)
        detail::throw_out_of_range(where, "grid.step[" + std::to_string(a) + "]", step[a],
                                   "a finite non-zero number");
    }
    std::size_t n = 1;
    for (std::size_t a = 0; a < N; ++a) {
      if (size[a] != 0 && n > SIZE_MAX / size[a])
        detail::throw_out_of_range(where, "grid.size[" + std::to_string(a) + "]", size[a],
                                   "a count whose product with the other axes fits in size_t");
      n *= size[a];
    }
  }
};

// A 2D array of pixels with a row stride in elements (stride >= width).
template <class T>
struct image_view {
  T* data = nullptr;
  std::size_t width = 0;
  std::size_t height = 0;
  std::size_t stride = 0;  // elements between the starts of consecutive rows

  image_view() = default;
  image_view(T* d, std::size_t w, std::size_t h) : data(d), width(w), height(h), stride(w) {}
  image_view(T* d, std::size_t w, std::size_t h, std::size_t s)
      : data(d), width(w), height(h), stride(s) {
    if (s < w) detail::throw_out_of_range("hush::image_view", "stride", s, "stride >= width");
  }
  T& operator()(std::size_t x, std::size_t y) const { return data[y * stride + x]; }
  T* row(std::size_t y) const { return data + y * stride; }
};

}  // namespace hush

#endif  // HUSH_CORE_VIEWS_HPP
