// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// One text, two dialects: every complete shader hush writes (the compute runners, coherent
// noise's pass, NPR Gabor noise's passes and splat program) compiles as OpenGL 4.3 core and,
// unchanged, as Vulkan GLSL (glslangValidator -V / shaderc, which predefine VULKAN).
//
// OpenGL sets loose uniforms one by one (glUniform*), hush's own device among them; Vulkan
// has no loose non-opaque uniforms and one binding space per descriptor set, where OpenGL
// has one per kind of resource. dual_dialect() turns a shader written for OpenGL into one
// that is both:
//   - the loose non-opaque uniforms stay as they are outside VULKAN (#ifndef VULKAN), and
//     under VULKAN are the members, in declaration order, of one std140 uniform block
//     `<block>` at binding kVulkanParamsBinding, declared where the first of them was (its
//     std140 layout, and a writer that fills it by name: hush/glsl/vulkan_params.hpp);
//   - storage buffers keep their bindings (all below kVulkanParamsBinding);
//   - a uniform block of the source at uniform-block binding b (OpenGL's own binding space)
//     is at binding kVulkanBlockBinding + b under VULKAN (b < 3);
//   - a sampler at texture unit u (its `layout(binding = u)`) is at binding
//     kVulkanTextureBinding + u under VULKAN, an image at image unit u at
//     kVulkanImageBinding + u; OpenGL sees the declaration as written;
//   - everything is in descriptor set 0;
//   - a comment after the file's first comment line states the file's Vulkan bindings.
// Under OpenGL the text compiles to the same program as before (the same declarations in the
// same order), so hush's GL results are the same bit for bit. User inputs and outputs between
// stages carry `layout(location = N)` in the sources themselves (valid in GL 4.3 as well).
#ifndef HUSH_GLSL_DIALECT_HPP
#define HUSH_GLSL_DIALECT_HPP

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "hush/core/error.hpp"

namespace hush {
namespace glsl {

// Descriptor bindings (set 0) of a complete shader under Vulkan (file comment).
constexpr unsigned kVulkanParamsBinding = 16;   // the std140 block of the loose uniforms
constexpr unsigned kVulkanBlockBinding = 17;    // + the source's own uniform block's binding
constexpr unsigned kVulkanTextureBinding = 20;  // + the sampler's GL texture unit
constexpr unsigned kVulkanImageBinding = 28;    // + the image's GL image unit

namespace detail {

// Whether a GLSL type name is opaque (a sampler, image or atomic counter): such uniforms
// stay loose in Vulkan too.
inline bool opaque_glsl_type(const std::string& type) {
  return type.find("sampler") != std::string::npos || type.find("image") != std::string::npos ||
         type.find("texture") != std::string::npos || type == "atomic_uint";
}

// The `binding = N` of a declaration's layout, or -1 when it has none.
inline int layout_binding(const std::string& line) {
  const std::string key = "binding = ";
  const std::size_t at = line.find(key);
  if (at == std::string::npos || line.find("layout(") == std::string::npos) return -1;
  return std::stoi(line.substr(at + key.size()));
}

// The line with its `binding = N` replaced by `binding = b`.
inline std::string with_binding(const std::string& line, unsigned b) {
  const std::string key = "binding = ";
  const std::size_t at = line.find(key) + key.size();
  std::size_t end = at;
  while (end < line.size() && line[end] >= '0' && line[end] <= '9') ++end;
  return line.substr(0, at) + std::to_string(b) + line.substr(end);
}

// The name of a `layout(...) uniform NAME {` block declaration line, or "" when the line is
// not one.
inline std::string uniform_block_name(const std::string& line) {
  if (line.compare(0, 7, "layout(") != 0 || line.find('{') == std::string::npos) return "";
  const std::size_t u = line.find(" uniform ", line.find(')'));
  if (u == std::string::npos) return "";
  const std::size_t at = u + 9, end = line.find_first_of(" {", at);
  return line.substr(at, end - at);
}

// The type of a `uniform TYPE NAME...` or `layout(...) [qualifiers] uniform TYPE NAME...`
// declaration line, or "" when the line declares no uniform at file scope.
inline std::string uniform_type(const std::string& line) {
  std::size_t at = std::string::npos;
  if (line.compare(0, 8, "uniform ") == 0)
    at = 8;
  else if (line.compare(0, 7, "layout(") == 0) {
    const std::size_t u = line.find(" uniform ", line.find(')'));
    if (u != std::string::npos && line.find(" buffer ") == std::string::npos) at = u + 9;
  }
  if (at == std::string::npos) return "";
  const std::size_t end = line.find(' ', at);
  return line.substr(at, end == std::string::npos ? std::string::npos : end - at);
}

// The lines of `text`, without their newlines.
inline std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t nl = text.find('\n', at);
    const std::size_t end = nl == std::string::npos ? text.size() : nl;
    lines.push_back(text.substr(at, end - at));
    at = end + 1;
  }
  return lines;
}

// A loose non-opaque uniform: a declaration dual_dialect moves into the Vulkan params block.
struct params_declaration {
  std::size_t line = 0;     // its line (0-based) in the text
  std::string declaration;  // the line after `uniform `: `TYPE NAME[, NAME...];` and any comment
  std::string type;         // TYPE
};

// The loose non-opaque uniforms of a shader's lines, in declaration order: the members of its
// Vulkan params block. The one reading of those declarations: dual_dialect writes the block
// from it and vulkan_params_layout_of (hush/glsl/vulkan_params.hpp) lays the block out from
// it, in dual_dialect's source and in its output alike (there the moved lines stay, OpenGL's
// branch; the block's members are indented, so not read again). Throws std::logic_error for a
// non-opaque uniform with a layout (its place in the block would be unknown).
inline std::vector<params_declaration> params_declarations(const std::vector<std::string>& lines) {
  std::vector<params_declaration> out;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!uniform_block_name(lines[i]).empty()) continue;
    std::string type = uniform_type(lines[i]);
    if (type.empty() || opaque_glsl_type(type)) continue;
    if (lines[i].compare(0, 8, "uniform ") != 0)
      hush::detail::raise_error<std::logic_error>(
          "hush::glsl::dual_dialect: a non-opaque uniform with a layout");
    out.push_back({i, lines[i].substr(8), std::move(type)});
  }
  return out;
}

}  // namespace detail

// `source` (a complete shader for OpenGL 4.3 core: #version line, header comment, one
// declaration per line) made to compile under Vulkan too, as the file comment says; `block`
// names the uniform block (hush_<file>_params). A shader without loose uniforms, samplers or
// images is returned as it is. Throws std::logic_error for a sampler, image or uniform block
// without `layout(binding = u)` (its Vulkan binding would be unknown), a block binding above 2
// and a non-opaque loose uniform with a layout.
inline std::string dual_dialect(const std::string& source, const std::string& block) {
  std::vector<std::string> lines = detail::split_lines(source);
  // The block's members, then the Vulkan bindings of the source's blocks, samplers and images.
  const std::vector<detail::params_declaration> moved = detail::params_declarations(lines);
  std::string members, note;
  for (const detail::params_declaration& d : moved) members += "  " + d.declaration + "\n";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string block_name = detail::uniform_block_name(lines[i]);
    if (!block_name.empty()) {
      const int b = detail::layout_binding(lines[i]);
      if (b < 0 || kVulkanBlockBinding + static_cast<unsigned>(b) >= kVulkanTextureBinding)
        hush::detail::raise_error<std::logic_error>(
            "hush::glsl::dual_dialect: a uniform block without layout(binding = 0 ... 2)");
      const unsigned vk = kVulkanBlockBinding + static_cast<unsigned>(b);
      note += std::string(note.empty() ? "" : ", ") + block_name + " at " + std::to_string(vk) +
              " (uniform block binding " + std::to_string(b) + ")";
      lines[i] = "#ifdef VULKAN\n" + detail::with_binding(lines[i], vk) + "\n#else\n" + lines[i] +
                 "\n#endif";
      continue;
    }
    const std::string type = detail::uniform_type(lines[i]);
    if (type.empty() || !detail::opaque_glsl_type(type)) continue;  // moved, above
    const int unit = detail::layout_binding(lines[i]);
    if (unit < 0)
      hush::detail::raise_error<std::logic_error>(
          "hush::glsl::dual_dialect: a sampler or image without layout(binding = unit)");
    const bool image = type.find("image") != std::string::npos;
    const unsigned vk =
        (image ? kVulkanImageBinding : kVulkanTextureBinding) + static_cast<unsigned>(unit);
    const std::size_t name_at = lines[i].find(' ', lines[i].find(type)) + 1;
    const std::string name = lines[i].substr(name_at, lines[i].find(';') - name_at);
    note += std::string(note.empty() ? "" : ", ") + name + " at " + std::to_string(vk) + " (" +
            (image ? "image" : "texture") + " unit " + std::to_string(unit) + ")";
    lines[i] = "#ifdef VULKAN\n" + detail::with_binding(lines[i], vk) + "\n#else\n" + lines[i] +
               "\n#endif";
  }
  if (members.empty() && note.empty()) return source;

  // Each run of loose uniforms is OpenGL's only; the block stands before the first run.
  std::vector<char> loose(lines.size(), 0);
  for (const detail::params_declaration& d : moved) loose[d.line] = 1;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!loose[i]) continue;
    const bool run_start = i == 0 || !loose[i - 1];
    const bool run_end = i + 1 == lines.size() || !loose[i + 1];
    if (run_start) {
      std::string head;
      if (i == moved.front().line) {
        head = "#ifdef VULKAN\nlayout(std140, binding = ";
        head += std::to_string(kVulkanParamsBinding);
        head += ") uniform ";
        head += block;
        head += " {\n";
        head += members;
        head += "};\n#else\n";
      } else {
        head = "#ifndef VULKAN\n";
      }
      lines[i] = head + lines[i];
    }
    if (run_end) lines[i] += "\n#endif";
  }

  // The note, after the header comment's first line, as comment lines of at most 100 columns.
  std::string vulkan =
      "Vulkan (glslang -V and shaderc define VULKAN): descriptor set 0; storage buffers at their "
      "OpenGL bindings";
  if (!members.empty())
    vulkan += "; the uniforms are the members of the std140 block " + block + " at binding " +
              std::to_string(kVulkanParamsBinding);
  if (!note.empty()) vulkan += "; " + note;
  vulkan += " (hush/glsl/dialect.hpp).";
  std::string wrapped, line = "//";
  for (std::size_t at = 0; at < vulkan.size();) {
    std::size_t end = vulkan.find(' ', at);
    if (end == std::string::npos) end = vulkan.size();
    const std::string word = vulkan.substr(at, end - at);
    if (line.size() > 2 && line.size() + 1 + word.size() > 100) {
      wrapped += line + "\n";
      line = "//";
    }
    line += " " + word;
    at = end + 1;
  }
  wrapped += line;
  lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(2, lines.size())),
               wrapped);

  std::string out;
  for (std::size_t i = 0; i < lines.size(); ++i)
    out += lines[i] + (i + 1 < lines.size() ? "\n" : "");
  if (!source.empty() && source.back() == '\n' && (out.empty() || out.back() != '\n')) out += '\n';
  return out;
}

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_DIALECT_HPP
