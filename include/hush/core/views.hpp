// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Non-owning views for batch evaluation and per-pixel data:
//  - span<T>:        contiguous array (pointer + count); C++17 has no std::span.
//  - grid<N>:        a uniform sample grid: origin, step per axis, count per axis,
//                    and the index of its first sample in a larger grid it is a
//                    block of (0 for a whole grid). Sample (i, j, k) sits at
//                    origin + step * (first + (i, j, k)); its index in C order is
//                    (k * ny + j) * nx + i (i along x, fastest).
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
//
// A block of a larger grid (block(), for work split over threads, processes or
// machines) keeps the whole grid's origin and step and says where it starts in
// `first`: its sample (i, j, k) is the whole grid's sample first + (i, j, k),
// at the same position bit for bit, so every backend gives a block exactly the
// values the whole grid's call gives those samples. A block re-based as a grid
// of its own (origin + step * first as its origin) would round its positions
// differently.
template <int N>
struct grid {
  vec<double, N> origin;  // position of the whole grid's sample (0, 0[, 0])
  vec<double, N> step;    // spacing along each axis (may be negative, not zero)
  std::array<std::size_t, std::size_t{N}> size{};   // samples along each axis (nx, ny[, nz])
  std::array<std::size_t, std::size_t{N}> first{};  // index of this grid's sample 0 in the whole grid

  // Position along `axis` of this grid's sample `index` on that axis:
  // origin + step * (first + index), in double. Every backend forms grid
  // positions with it, so a block's samples sit where the whole grid's do.
  double coordinate(int axis, std::size_t index) const {
    return origin[axis] +
           step[axis] * static_cast<double>(first[static_cast<std::size_t>(axis)] + index);
  }

  // Number of samples; 0 when any axis is empty.
  std::size_t count() const {
    std::size_t n = 1;
    for (std::size_t a = 0; a < N; ++a) n *= size[a];
    return n;
  }
  // Position of the sample with index (i, j[, k]) of this grid (coordinate() per axis).
  vec<double, N> position(const std::array<std::size_t, std::size_t{N}>& ijk) const {
    vec<double, N> p;
    for (int a = 0; a < N; ++a) p[a] = coordinate(a, ijk[static_cast<std::size_t>(a)]);
    return p;
  }
  // The block of this grid whose samples are this grid's (first_index +
  // (i, j[, k])) for i < block_size[0], ...: same origin and step, `first`
  // advanced by first_index, sizes block_size. Throws hush::invalid_argument
  // naming the axis when the block does not lie inside this grid
  // (first_index[a] + block_size[a] > size[a]); an empty block (a size of 0)
  // is allowed anywhere inside. Evaluating the block gives, bit for bit, the
  // values (and gradients) that evaluating this grid gives those samples, on
  // every backend, with one exception that follows from the algorithm, not
  // the positions: 3D Perlin and fBm gradients take the affine-in-x form on
  // rows whose cells hold two columns on average (perlin.hpp grid_values), a
  // choice made per grid from its x extent, so their blocks are bit-identical
  // when they keep the whole grid's x extent (split along y and z) and
  // otherwise within that form's stated bound of point evaluation.
  grid block(const std::array<std::size_t, std::size_t{N}>& first_index,
             const std::array<std::size_t, std::size_t{N}>& block_size) const {
    grid b = *this;
    for (std::size_t a = 0; a < std::size_t{N}; ++a) {
      const std::string axis = "[" + std::to_string(a) + "]";
      if (first_index[a] > size[a])
        detail::throw_out_of_range("hush::grid::block", "first" + axis, first_index[a],
                                   ("0 ... " + std::to_string(size[a])).c_str());
      if (block_size[a] > size[a] - first_index[a])
        detail::throw_out_of_range(
            "hush::grid::block", "size" + axis, block_size[a],
            ("0 ... " + std::to_string(size[a] - first_index[a]) + " (first + size <= " +
             std::to_string(size[a]) + ")")
                .c_str());
      b.first[a] = first[a] + first_index[a];
      b.size[a] = block_size[a];
    }
    return b;
  }
  // f(idx, position) for the samples of the slab whose slowest-axis index (j in
  // 2D, k in 3D) is in [slab, slab + count), idx counting from 0 in C order.
  template <class F>
  void for_each_in_slab(std::size_t slab, std::size_t count, F f) const {
    static_assert(N == 2 || N == 3, "grid slabs are 2D or 3D");
    const std::size_t j0 = N == 2 ? slab : 0, ny = N == 2 ? slab + count : size[1];
    const std::size_t k0 = N == 3 ? slab : 0, nz = N == 3 ? slab + count : 1;
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
  // finite, step non-zero, first + size must fit in size_t on every axis, and the
  // total count must fit in the address space.
  void validate(const char* where) const {
    for (int a = 0; a < N; ++a) {
      if (!std::isfinite(origin[a]))
        detail::throw_out_of_range(where, "grid.origin[" + std::to_string(a) + "]", origin[a],
                                   "a finite number");
      if (!std::isfinite(step[a]) || step[a] == 0.0)
        detail::throw_out_of_range(where, "grid.step[" + std::to_string(a) + "]", step[a],
                                   "a finite non-zero number");
    }
    for (std::size_t a = 0; a < std::size_t{N}; ++a)
      if (first[a] > SIZE_MAX - size[a])
        detail::throw_out_of_range(where, "grid.first[" + std::to_string(a) + "]", first[a],
                                   "an index whose sum with grid.size fits in size_t");
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
