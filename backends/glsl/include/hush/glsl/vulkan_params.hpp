// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The Vulkan params block of a complete shader, laid out and filled by name. Under VULKAN the
// loose uniforms of every complete shader hush writes (`hush glsl-export`, export_files(); the
// rule is hush::glsl::dual_dialect, hush/glsl/dialect.hpp) are, in declaration order, the
// members of one std140 uniform block at binding kVulkanParamsBinding (16) of descriptor set
// 0. OpenGL sets them one by one with glUniform*; a Vulkan engine fills the block's bytes:
//
//   const std::string text = /* hush_perlin3_grid.comp, as exported */;
//   hush::glsl::vulkan_params params{hush::glsl::vulkan_params_layout_of(text)};  // once
//   params.set("hush_key", hush::seed_key(seed));                      // uint
//   params.set("hush_size", hush::vec<std::uint32_t, 3>{nx, ny, nz});  // uvec3
//   // copy params.bytes() into the uniform buffer at binding 16 of set 0 (at least
//   // params.bytes().size() bytes), then dispatch
//
// The values are those hush's own GL path sets with glUniform* (for the runners,
// noise_program<Noise>::set_uniforms; hush/glsl/device.hpp). The offsets follow std140 (GL 4.6
// sec. 7.6.2.2; Vulkan's standard uniform buffer layout): scalars align to 4 bytes, vec2 to 8,
// vec3 and vec4 to 16; each array element and each matrix column takes a 16-byte slot.
// tests/glsl/glslang_matrix.py compares every exported block with glslang's reflection.
#ifndef HUSH_GLSL_VULKAN_PARAMS_HPP
#define HUSH_GLSL_VULKAN_PARAMS_HPP

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "hush/core/error.hpp"
#include "hush/core/vec.hpp"
#include "hush/glsl/dialect.hpp"

namespace hush {
namespace glsl {

// One member of a Vulkan params block.
struct vulkan_param {
  std::string name;  // its GLSL name
  std::string type;  // its GLSL type as declared: float, int, uint, bool, [i|u|b]vecN, matC[xR]
  std::size_t count = 0;   // array elements; 0: not an array
  std::size_t offset = 0;  // std140 byte offset from the block's start
  std::size_t stride =
      0;  // bytes from one array element to the next (16 per slot); 0: not an array
};

// The std140 layout of a shader's Vulkan params block.
struct vulkan_params_layout {
  std::string block;                        // the block's GLSL name, hush_<file>_params
  unsigned binding = kVulkanParamsBinding;  // its binding, in descriptor set 0
  std::vector<vulkan_param> members;        // in declaration order, offsets increasing
  // Bytes up to the end of the last member: the block's size as SPIR-V declares it (glslang's
  // reflection reports the same); 0 for a shader without loose uniforms. A larger buffer is fine.
  std::size_t size = 0;
  // The member named `name`, or nullptr.
  const vulkan_param* find(const std::string& name) const {
    for (const vulkan_param& m : members)
      if (m.name == name) return &m;
    return nullptr;
  }
};

namespace detail {

// A GLSL type a params block may hold, as std140 sees it: `rows` components of 4 bytes (float,
// int, uint or bool, which std140 stores as a uint 0 or 1) per column, `columns` columns (1 but
// for matrices, whose columns are vectors of `rows`).
enum class glsl_scalar { float_bits, int_bits, uint_bits, bool_bits };
struct std140_shape {
  glsl_scalar scalar = glsl_scalar::float_bits;
  int rows = 1;
  int columns = 1;
  bool operator==(const std140_shape& o) const {
    return scalar == o.scalar && rows == o.rows && columns == o.columns;
  }
  bool operator!=(const std140_shape& o) const { return !(*this == o); }
};

constexpr const char* kStd140Types =
    "float, int, uint, bool, their vectors (vecN, ivecN, uvecN, bvecN, N = 2 ... 4) and float "
    "matrices (matN, matCxR)";

// The shape of GLSL type `type`; false for a type std140_shape does not describe (double,
// structs). matN is N columns of N rows, matCxR C columns of R rows.
inline bool std140_shape_of(const std::string& type, std140_shape& shape) {
  const auto dim = [](char c) { return c >= '2' && c <= '4' ? c - '0' : 0; };
  static const char* const scalars[] = {"float", "int", "uint", "bool"};
  static const char* const prefixes[] = {"", "i", "u", "b"};
  for (int k = 0; k < 4; ++k) {
    const std::string vec = std::string(prefixes[k]) + "vec";
    const bool vector = type.size() == vec.size() + 1 && type.compare(0, vec.size(), vec) == 0 &&
                        dim(type.back()) != 0;
    if (type == scalars[k] || vector) {
      shape = {static_cast<glsl_scalar>(k), vector ? dim(type.back()) : 1, 1};
      return true;
    }
  }
  if (type.compare(0, 3, "mat") != 0) return false;
  if (type.size() == 4 && dim(type[3])) {
    shape = {glsl_scalar::float_bits, dim(type[3]), dim(type[3])};
    return true;
  }
  if (type.size() == 6 && type[4] == 'x' && dim(type[3]) && dim(type[5])) {
    shape = {glsl_scalar::float_bits, dim(type[5]), dim(type[3])};
    return true;
  }
  return false;
}

// The C++ type vulkan_params::set takes for a member of this shape, for error messages.
inline std::string std140_cpp_type(const std140_shape& s) {
  static const char* const names[] = {"float", "std::int32_t", "std::uint32_t", "bool"};
  const std::string scalar = names[static_cast<int>(s.scalar)];
  if (s.columns > 1)
    return "std::array<hush::vec<float, " + std::to_string(s.rows) + ">, " +
           std::to_string(s.columns) + "> (columns)";
  return s.rows == 1 ? scalar : "hush::vec<" + scalar + ", " + std::to_string(s.rows) + ">";
}

// A decimal array size, `8` or `8u`; 0 when `text` (spaces around allowed) is not one.
inline std::size_t decimal_size(const std::string& text) {
  const std::size_t a = text.find_first_not_of(' ');
  if (a == std::string::npos) return 0;
  std::size_t n = 0, i = a;
  for (; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i)
    n = n * 10 + static_cast<std::size_t>(text[i] - '0');
  if (i == a) return 0;
  if (i < text.size() && (text[i] == 'u' || text[i] == 'U')) ++i;
  return text.find_first_not_of(' ', i) == std::string::npos ? n : 0;
}

// The size of an array declared `[size]` in a shader of these lines: a decimal, or the name of
// a `const uint NAME = 8u;` (or int) or `#define NAME 8` line of the shader (hush's runners
// size their arrays so: HUSH_ANISO_MAX_SCALES, HUSH_COHERENT_FIELD_SLOTS); 0 when neither.
inline std::size_t array_size(const std::vector<std::string>& lines, const std::string& size) {
  if (const std::size_t n = decimal_size(size)) return n;
  const std::size_t a = size.find_first_not_of(' '), b = size.find_last_not_of(' ');
  if (a == std::string::npos) return 0;
  const std::string name = size.substr(a, b - a + 1);
  for (const std::string& line : lines) {
    for (const char* head : {"const uint ", "const int "}) {
      const std::string lead = head + name + " = ";
      if (line.compare(0, lead.size(), lead) == 0)
        return decimal_size(line.substr(lead.size(), line.find(';') - lead.size()));
    }
    const std::string define = "#define " + name + " ";
    if (line.compare(0, define.size(), define) == 0) {
      const std::string value = line.substr(define.size());
      return decimal_size(value.substr(0, value.find("//")));
    }
  }
  return 0;
}

inline std::size_t round_up(std::size_t n, std::size_t to) { return (n + to - 1) / to * to; }

// What vulkan_params::set accepts: T's std140 shape and the 32-bit word of component (column,
// row). The primary template: not a type of a params block.
template <class T>
struct std140_value {
  static constexpr bool supported = false;
};

template <class S>
struct std140_scalar {
  static constexpr bool supported = true;
  static constexpr glsl_scalar scalar =
      std::is_same<S, float>::value           ? glsl_scalar::float_bits
      : std::is_same<S, std::int32_t>::value  ? glsl_scalar::int_bits
      : std::is_same<S, std::uint32_t>::value ? glsl_scalar::uint_bits
                                              : glsl_scalar::bool_bits;
  static std::uint32_t bits(S v) {
    if constexpr (std::is_same<S, bool>::value) {
      return v ? 1u : 0u;  // std140 bool: a uint, 0 or 1
    } else {
      std::uint32_t w;
      std::memcpy(&w, &v, sizeof w);
      return w;
    }
  }
};
template <>
struct std140_value<float> : std140_scalar<float> {
  static std140_shape shape() { return {scalar, 1, 1}; }
  static std::uint32_t word(float v, int, int) { return bits(v); }
};
template <>
struct std140_value<std::int32_t> : std140_scalar<std::int32_t> {
  static std140_shape shape() { return {scalar, 1, 1}; }
  static std::uint32_t word(std::int32_t v, int, int) { return bits(v); }
};
template <>
struct std140_value<std::uint32_t> : std140_scalar<std::uint32_t> {
  static std140_shape shape() { return {scalar, 1, 1}; }
  static std::uint32_t word(std::uint32_t v, int, int) { return v; }
};
template <>
struct std140_value<bool> : std140_scalar<bool> {
  static std140_shape shape() { return {scalar, 1, 1}; }
  static std::uint32_t word(bool v, int, int) { return bits(v); }
};
template <class S, int N>
struct std140_value<vec<S, N>> : std140_scalar<S> {
  static_assert(std140_value<S>::supported,
                "hush::vec of float, std::int32_t, std::uint32_t, bool");
  static std140_shape shape() { return {std140_scalar<S>::scalar, N, 1}; }
  static std::uint32_t word(const vec<S, N>& v, int, int row) {
    return std140_scalar<S>::bits(v[row]);
  }
};
template <int R, std::size_t C>
struct std140_value<std::array<vec<float, R>, C>> : std140_scalar<float> {
  static std140_shape shape() { return {scalar, R, static_cast<int>(C)}; }
  static std::uint32_t word(const std::array<vec<float, R>, C>& m, int column, int row) {
    return bits(m[static_cast<std::size_t>(column)][row]);
  }
};

}  // namespace detail

// The std140 layout of the Vulkan params block of `shader`: a complete shader as
// export_files() returns it or any dual_dialect output (or a source before dual_dialect: the
// block it will have, `block` then ""). Members come from the same declarations dual_dialect
// moves into the block (detail::params_declarations), so the two cannot disagree. Array sizes
// are decimals or names of the shader's `const uint|int NAME = N;` or `#define NAME N`.
// Throws hush::invalid_argument naming the member for a type not in detail::kStd140Types, an
// array of arrays, or an array size it cannot read; std::logic_error as dual_dialect does.
inline vulkan_params_layout vulkan_params_layout_of(const std::string& shader) {
  static const char* const where = "hush::glsl::vulkan_params_layout_of: ";
  const std::vector<std::string> lines = detail::split_lines(shader);
  vulkan_params_layout out;
  for (const std::string& line : lines)
    if (!detail::uniform_block_name(line).empty() &&
        detail::layout_binding(line) == static_cast<int>(kVulkanParamsBinding))
      out.block = detail::uniform_block_name(line);
  std::size_t end = 0;
  for (const detail::params_declaration& d : detail::params_declarations(lines)) {
    detail::std140_shape s;
    const bool known = detail::std140_shape_of(d.type, s);
    // `TYPE a, b[N];`: the declarators between the type and the semicolon.
    const std::string list =
        d.declaration.substr(d.type.size(), d.declaration.find(';') - d.type.size());
    for (std::size_t at = 0; at <= list.size();) {
      std::size_t comma = list.find(',', at);
      if (comma == std::string::npos) comma = list.size();
      std::string item = list.substr(at, comma - at);
      at = comma + 1;
      const std::size_t a = item.find_first_not_of(' '), b = item.find_last_not_of(' ');
      item = a == std::string::npos ? "" : item.substr(a, b - a + 1);
      vulkan_param m;
      m.type = d.type;
      const std::size_t bracket = item.find('[');
      m.name = item.substr(0, bracket);
      if (!known)
        hush::detail::raise_error(where + m.name + " has type " + d.type +
                                  "; valid: " + detail::kStd140Types);
      if (bracket != std::string::npos) {
        const std::size_t close = item.find(']', bracket);
        m.count = close == std::string::npos
                      ? 0
                      : detail::array_size(lines, item.substr(bracket + 1, close - bracket - 1));
        if (m.count == 0 || close + 1 != item.size())
          hush::detail::raise_error(where + m.name + " is declared `" + item +
                                    "`; valid: one array size, a decimal or the name of a "
                                    "`const uint NAME = N;` or `#define NAME N` of the shader");
      }
      // std140: a column vector aligns to 4, 8 or 16 bytes; matrices, arrays and their
      // elements to 16, each element (matrix column) in its own 16-byte slot.
      const std::size_t column = s.rows == 1 ? 4u : s.rows == 2 ? 8u : 16u;
      const std::size_t element = s.columns > 1 ? 16u * static_cast<std::size_t>(s.columns)
                                                : 4u * static_cast<std::size_t>(s.rows);
      const bool slotted = m.count > 0 || s.columns > 1;
      m.offset = detail::round_up(end, slotted ? 16u : column);
      m.stride = m.count > 0 ? detail::round_up(element, 16u) : 0u;
      end = m.offset + (m.count > 0 ? m.count * m.stride : element);
      out.members.push_back(std::move(m));
    }
  }
  out.size = end;
  return out;
}

// The bytes of one Vulkan params block, filled member by member; zero where nothing was set.
// set(name, value) writes a member, set(name, element, value) an array member's element. value
// is float, std::int32_t, std::uint32_t or bool for the scalars, hush::vec<S, N> of those for
// the vectors, std::array<hush::vec<float, R>, C> (the columns) for a matCxR; other C++ types
// do not compile. Throws hush::invalid_argument naming the member for a name not in the block
// (listing the members), a value of another GLSL type (naming the one it takes), an array
// without an element, an element of a non-array, or an element beyond the array.
class vulkan_params {
 public:
  explicit vulkan_params(vulkan_params_layout layout)
      : layout_(std::move(layout)), bytes_(layout_.size, std::byte{0}) {}

  const vulkan_params_layout& layout() const noexcept { return layout_; }
  // The block's layout_.size bytes, for the uniform buffer at layout().binding.
  const std::vector<std::byte>& bytes() const noexcept { return bytes_; }

  template <class T>
  vulkan_params& set(const std::string& name, const T& value) {
    return write(name, nullptr, value);
  }
  template <class T>
  vulkan_params& set(const std::string& name, std::size_t element, const T& value) {
    return write(name, &element, value);
  }

 private:
  template <class T>
  vulkan_params& write(const std::string& name, const std::size_t* element, const T& value) {
    using traits = detail::std140_value<T>;
    static_assert(traits::supported,
                  "hush::glsl::vulkan_params::set takes float, std::int32_t, std::uint32_t, bool, "
                  "hush::vec of them, or std::array<hush::vec<float, R>, C> (matrix columns)");
    static const char* const where = "hush::glsl::vulkan_params::set: ";
    const vulkan_param* m = layout_.find(name);
    if (m == nullptr) {
      std::string valid;
      for (const vulkan_param& p : layout_.members) valid += (valid.empty() ? "" : ", ") + p.name;
      hush::detail::raise_error(where + std::string("name = '") + name +
                                "' is not a member of the block " + layout_.block +
                                "; valid: " + (valid.empty() ? "none (no loose uniforms)" : valid));
    }
    detail::std140_shape want;
    detail::std140_shape_of(m->type, want);  // known: vulkan_params_layout_of checked it
    if (traits::shape() != want)
      hush::detail::raise_error(where + name + " is a " + m->type + ", not a " +
                                detail::std140_cpp_type(traits::shape()) +
                                "; valid: " + detail::std140_cpp_type(want));
    const std::string last = m->count > 0 ? std::to_string(m->count - 1) : "";
    if (m->count > 0 && element == nullptr)
      hush::detail::raise_error(where + name + " is an array, " + m->type + "[" +
                                std::to_string(m->count) + "]; valid: set(\"" + name +
                                "\", element 0 ... " + last + ", value)");
    if (m->count == 0 && element != nullptr)
      hush::detail::raise_error(where + name + " is not an array; valid: set(\"" + name +
                                "\", value)");
    if (element != nullptr && *element >= m->count)
      hush::detail::throw_out_of_range("hush::glsl::vulkan_params::set", name + " element",
                                       *element, ("0 ... " + last).c_str());
    const std::size_t at = m->offset + (element != nullptr ? *element * m->stride : 0u);
    for (int c = 0; c < want.columns; ++c)
      for (int r = 0; r < want.rows; ++r) {
        const std::uint32_t w = traits::word(value, c, r);
        std::memcpy(bytes_.data() + at + 16u * static_cast<std::size_t>(c) +
                        4u * static_cast<std::size_t>(r),
                    &w, sizeof w);
      }
    return *this;
  }

  vulkan_params_layout layout_;
  std::vector<std::byte> bytes_;
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_VULKAN_PARAMS_HPP
